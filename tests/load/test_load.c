/* SPDX-License-Identifier: MIT */
/*
 * test_load.c - valid scene files into struct scene_desc: the schema of
 * issue 3 field by field (tests/scenes/schema.yaml), defaults, matrix and
 * Euler keys, aliases, and every example. Then every prefix of every
 * example: a truncated file is a positioned error or a valid scene, never
 * a crash (the sanitizers watch).
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "load/affine.h"
#include "load/load.h"
#include "rig/drv_gpio.h"
#include "testutil.h"

const char *const examples[] = {
	"examples/robot_arm.yaml",  "examples/propeller.yaml", "examples/camera_move.yaml",
	"examples/cycled_data.yaml", "examples/curves.yaml",
};
#define NEXAMPLES (sizeof(examples) / sizeof(examples[0]))

static void load_ok(struct scene_file *sf, const char *path)
{
	struct load_err e;

	if (scene_file_load(sf, path, &e))
		fail_msg("%s:%u:%u: %s", path, e.line, e.col, e.msg);
}

static void parse_ok(struct scene_file *sf, const char *yaml)
{
	struct load_err e;

	if (scene_file_parse(sf, "t.yaml", yaml, strlen(yaml), &e))
		fail_msg("t.yaml:%u:%u: %s", e.line, e.col, e.msg);
}

static void test_schema(void **state)
{
	struct scene_file sf;
	const struct scene_desc *d;
	const struct sd_node *tool, *prop;
	int base;

	load_ok(&sf, "tests/scenes/schema.yaml");
	d = &sf.desc;
	assert_string_equal(d->name, "robot-arm");
	assert_int_equal(d->tick_hz, 1000);
	assert_int_equal(d->rate_num, 24);
	assert_int_equal(d->rate_den, 1);
	assert_true(d->frame_first == 0 && d->frame_last == 240);
	assert_int_equal(d->nnodes, 4);
	base = scene_file_node(&sf, "base");
	assert_int_equal(base, 0);
	assert_int_equal(d->nodes[0].kind, MOT_NODE_REVOLUTE);
	assert_int_equal(d->nodes[0].axis_id, MOT_AXIS_Y);
	assert_true(d->nodes[0].limits.has_min && d->nodes[0].limits.min == -170);
	assert_true(d->nodes[0].limits.has_acc && d->nodes[0].limits.acc == 360);
	assert_int_equal(d->nodes[1].parent, 0);
	assert_true(d->nodes[1].pivot[1] == 0.3);
	/* base: hermite angle keys with strand ease and a key ease */
	assert_int_equal(d->nodes[0].value.interp, MOT_INTERP_HERMITE);
	assert_int_equal(d->nodes[0].value.nkeys, 2);
	assert_true(d->nodes[0].value.keys[1].value == 400);
	assert_true(d->nodes[0].value.keys[1].ease_in == 0.3);
	assert_true(d->nodes[0].value.ease_in == 12 && d->nodes[0].value.ease_out == 12);
	/* tool: a free node with translate, rotate, scale, quat, shear and matrix keys */
	tool = &d->nodes[2];
	assert_int_equal(tool->kind, MOT_NODE_FREE);
	assert_true(tool->has_free);
	assert_int_equal(tool->free.ch[MOT_FREE_TX].interp, MOT_INTERP_BETA);
	assert_true(tool->free.ch[MOT_FREE_TX].beta1 == 1.5 && tool->free.ch[MOT_FREE_TX].beta2 == 4);
	assert_int_equal(tool->free.ch[MOT_FREE_TX].nkeys, 2);  /* frames 0 and 96 (matrix) */
	assert_true(tool->free.ch[MOT_FREE_TX].keys[1].value == 0.2);
	assert_int_equal(tool->free.ch[MOT_FREE_SX].nkeys, 2);  /* 0 and 96 */
	assert_int_equal(tool->free.ch[MOT_FREE_HXY].nkeys, 2); /* 48 and 96 */
	assert_true(tool->free.ch[MOT_FREE_HXY].keys[0].value == 0.1);
	assert_int_equal(tool->free.nrot, 3);
	assert_false(tool->free.squad);
	assert_true(tool->free.rot[1].q[0] == 0.92388 && tool->free.rot[1].q[2] == 0.38268);
	assert_true(fabs(tool->free.rot[2].q[0] - 1) < 1e-15);
	/* propeller: rpm keys become its spin curve */
	prop = &d->nodes[3];
	assert_int_equal(prop->spin.nkeys, 2);
	assert_int_equal(prop->value.nkeys, 0);
	assert_true(prop->spin.keys[1].value == 1200);
	assert_true(sf.strand[3].rpm);
	/* camera, cycles, attributes */
	assert_true(d->has_camera);
	assert_int_equal(d->camera.ch[MOT_CAM_EYE_Y].nkeys, 2);
	assert_true(d->camera.ch[MOT_CAM_EYE_Y].keys[0].value == 1.6);
	assert_true(d->camera.ease_in == 24 && d->camera.ch[0].ease_in == 0);
	assert_int_equal(d->ncycles, 1);
	assert_int_equal(d->cycles[0].mode, MOT_CYCLE_BOUNCE);
	assert_int_equal(d->cycles[0].skip, 2);
	assert_int_equal(d->nattrs, 1);
	assert_string_equal(d->attrs[0].name, "dye");
	assert_true(d->attrs[0].curve.keys[1].value == 1);
	scene_file_free(&sf);
}

/* What a file may leave out, and the NTSC rate as a ratio. */
static void test_defaults(void **state)
{
	struct scene_file sf;
	const struct scene_desc *d;

	parse_ok(&sf, "timing: {frame_rate: \"30000/1001\", frames: [-5, 10]}\n"
		      "nodes: [{name: a, joint: {type: prismatic, axis: [0, 2, 0]}, rest: 0.25}]\n"
		      "strands: [{node: a, keys: [{frame: 0.5, position: 1}]}]\n"
		      "cycles: [{name: c, first: 0, last: 3}]\n");
	d = &sf.desc;
	assert_string_equal(d->name, "");
	assert_int_equal(d->tick_hz, 1000);
	assert_int_equal(d->rate_num, 30000);
	assert_int_equal(d->rate_den, 1001);
	assert_true(d->frame_first == -5);
	assert_int_equal(d->nodes[0].kind, MOT_NODE_PRISMATIC);
	assert_int_equal(d->nodes[0].axis_id, MOT_AXIS_VEC);
	assert_true(d->nodes[0].axis[1] == 2 && d->nodes[0].rest == 0.25);
	assert_int_equal(d->nodes[0].value.interp, MOT_INTERP_HERMITE);
	assert_true(d->nodes[0].value.keys[0].frame == 0.5);
	assert_int_equal(d->cycles[0].skip, 1);
	assert_int_equal(d->cycles[0].mode, MOT_CYCLE_LOOP);
	assert_int_equal(d->cycles[0].frames_per_step, 1);
	assert_false(d->has_camera);
	scene_file_free(&sf);
}

/* A matrix key is decomposed (FORMULAS section 2) about the pivot; Euler
 * keys become the quaternion of Rx . Ry . Rz. */
static void test_matrix_key(void **state)
{
	struct scene_file sf;
	const struct sd_free *f;
	double q[4], deg[3] = { 10, 20, 30 }, m[3][3];

	parse_ok(&sf, "timing: {frame_rate: 24, frames: [0, 10]}\n"
		      "nodes: [{name: t, pivot: [1, 2, 3]}]\n"
		      "strands:\n"
		      "  - node: t\n"
		      "    keys:\n"
		      "      - {frame: 0, matrix: [[0, 2, 0, 0], [-3, 0, 0, 0], [0, 0, 4, 0], [5, 6, 7, 1]]}\n"
		      "      - {frame: 1, rotate: [10, 20, 30]}\n"
		      "      - {frame: 2, matrix: [[-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}\n");
	f = &sf.desc.nodes[0].free;
	/* rows (0,2,0), (-3,0,0), (0,0,4): scale 2, 3, 4, rotation Rz(90) */
	assert_true(fabs(f->ch[MOT_FREE_SX].keys[0].value - 2) < 1e-15);
	assert_true(fabs(f->ch[MOT_FREE_SY].keys[0].value - 3) < 1e-15);
	assert_true(fabs(f->ch[MOT_FREE_SZ].keys[0].value - 4) < 1e-15);
	assert_true(fabs(f->ch[MOT_FREE_HXY].keys[0].value) < 1e-15);
	assert_true(f->ch[MOT_FREE_TX].keys[0].value == 5 && f->ch[MOT_FREE_TZ].keys[0].value == 7);
	assert_true(fabs(f->rot[0].q[0] - cos(M_PI / 4)) < 1e-15);
	assert_true(fabs(f->rot[0].q[3] - sin(M_PI / 4)) < 1e-15);
	/* the Euler key */
	affine_euler_quat(q, deg);
	assert_memory_equal(q, f->rot[1].q, sizeof(q));
	/* a reflection diag(-1, 1, 1): every scale negated, and the rotation
	 * proper: diag(1, -1, -1), a half turn about x */
	assert_true(f->ch[MOT_FREE_SX].keys[1].value == -1 && f->ch[MOT_FREE_SY].keys[1].value == -1 &&
		    f->ch[MOT_FREE_SZ].keys[1].value == -1);
	affine_quat_mat(m, f->rot[2].q);
	assert_true(fabs(m[0][0] - 1) < 1e-15 && fabs(m[1][1] + 1) < 1e-15 && fabs(m[2][2] + 1) < 1e-15);
	/* translate, scale and shear channels exist only at the matrix keys */
	assert_int_equal(f->ch[MOT_FREE_TX].nkeys, 2);
	assert_int_equal(f->nrot, 3);
	scene_file_free(&sf);
}

static void test_examples(void **state)
{
	size_t i;

	for (i = 0; i < NEXAMPLES; i++) {
		struct scene_file sf;

		load_ok(&sf, examples[i]);
		assert_true(sf.desc.nnodes > 0);
		assert_true(sf.desc.frame_last > sf.desc.frame_first);
		scene_file_free(&sf);
	}
}

static char *slurp(const char *path, size_t *len)
{
	FILE *f = fopen(path, "rb");
	char *buf;

	assert_non_null(f);
	fseek(f, 0, SEEK_END);
	*len = (size_t)ftell(f);
	rewind(f);
	buf = malloc(*len + 1);
	assert_non_null(buf);
	assert_int_equal(fread(buf, 1, *len, f), *len);
	fclose(f);
	return buf;
}

/* Every prefix of every example. */
static void test_truncated(void **state)
{
	size_t i, n, len, ok = 0, errors = 0;

	for (i = 0; i < NEXAMPLES; i++) {
		char *buf = slurp(examples[i], &len);

		for (n = 0; n < len; n++) {
			struct scene_file sf;
			struct load_err e;
			/* a copy of exactly n bytes, so that ASan sees any read past it */
			char *cut = malloc(n ? n : 1);

			memcpy(cut, buf, n);
			if (scene_file_parse(&sf, "t.yaml", cut, n, &e) == 0) {
				ok++;
			} else {
				assert_true(e.code == -EINVAL || e.code == -EBADMSG || e.code == -ERANGE);
				assert_true(e.line > 0 && e.msg[0]);
				errors++;
			}
			scene_file_free(&sf);
			free(cut);
		}
		free(buf);
	}
	print_message("truncated examples: %zu parsed, %zu positioned errors\n", ok, errors);
	assert_true(errors > 0);
}

/* A GPIO device: its chip, whether it may sleep, its rig-ready line, lines
 * by offset and by name, each kept apart. */
static void test_gpio_lines(void **state)
{
	struct scene_file sf;
	const struct rig_desc *r;

	parse_ok(&sf, "timing: {frame_rate: 24, frames: [0, 10]}\n"
		      "devices: [{name: io, driver: gpio, chip: gpiochip2, allow_sleeping_chip: true},\n"
		      "          {name: any, driver: gpio, ready: {line: LAMP, active_low: true}}]\n"
		      "triggers: [{name: cam, device: io, line: 5, active_low: true},\n"
		      "           {name: cam2, device: any, line: CAM2_TRIG}]\n"
		      "inputs: [{name: estop, device: any, line: ESTOP-1, role: estop},\n"
		      "         {name: ready, device: io, line: 0, role: camera_ready}]\n");
	r = &sf.rig;
	assert_int_equal(r->ndevices, 2);
	assert_ptr_equal(r->devices[0].driver, rig_driver_find("gpio"));
	assert_ptr_equal(r->devices[1].driver, rig_driver_find("gpio"));
	assert_string_equal(((const struct rig_gpio_desc *)r->devices[0].priv)->chip, "gpiochip2");
	assert_null(((const struct rig_gpio_desc *)r->devices[1].priv)->chip);
	assert_true(((const struct rig_gpio_desc *)r->devices[0].priv)->allow_sleeping_chip);
	assert_false(((const struct rig_gpio_desc *)r->devices[1].priv)->allow_sleeping_chip);
	assert_false(r->devices[0].has_ready);
	assert_true(r->devices[1].has_ready);
	assert_string_equal(r->devices[1].ready_line_name, "LAMP");
	assert_true(r->devices[1].ready_active_low);
	assert_int_equal(r->triggers[0].line, 5);
	assert_null(r->triggers[0].line_name);
	assert_true(r->triggers[0].active_low);
	assert_string_equal(r->triggers[1].line_name, "CAM2_TRIG");
	assert_string_equal(r->inputs[0].line_name, "ESTOP-1");
	assert_true(r->inputs[0].active_low); /* an e-stop: normally closed */
	assert_int_equal(r->inputs[1].line, 0);
	assert_null(r->inputs[1].line_name);
	assert_false(r->inputs[1].active_low);
	scene_file_free(&sf);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_schema),	 cmocka_unit_test(test_defaults),
		cmocka_unit_test(test_matrix_key), cmocka_unit_test(test_examples),
		cmocka_unit_test(test_truncated), cmocka_unit_test(test_gpio_lines),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
