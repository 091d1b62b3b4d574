/* SPDX-License-Identifier: MIT */
/*
 * test_export.c - `strand export` against the floating-point reference
 * (ref_scene.c) on a scene that uses every kind of key, node, method and
 * option (tests/scenes/every_key.yaml): every column of every row, parsed
 * back from the CSV the command prints, within stated bounds.
 */
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "load/load.h"
#include "ref_scene.h"

#define SCENE "tests/scenes/every_key.yaml"

static char *run_export(const char *every)
{
	char *argv[] = { "strand", "export", SCENE, "--at", "ticks", "--every", (char *)every,
			 NULL };
	char *buf = NULL, *ebuf = NULL;
	size_t len = 0, elen = 0;
	FILE *out = open_memstream(&buf, &len), *err = open_memstream(&ebuf, &elen);
	int rc = cli_main(7, argv, out, err);

	fclose(out);
	fclose(err);
	if (rc != 0)
		fail_msg("export exited %d: %s", rc, ebuf);
	free(ebuf);
	return buf;
}

/* Index of a column by name, or fail. */
static int col(char **names, int n, const char *name)
{
	int i;

	for (i = 0; i < n; i++)
		if (strcmp(names[i], name) == 0)
			return i;
	fail_msg("no column %s", name);
	return -1;
}

static void test_every_key(void **state)
{
	struct scene_file sf;
	struct load_err le;
	struct ref_scene *ref;
	struct ref_pose rp;
	struct mot_timing t;
	struct tu_worst wpos = { 0, 0 }, wang = { 0, 0 }, wlen = { 0, 0 }, wrpm = { 0, 0 },
			wcam = { 0, 0 }, wcamang = { 0, 0 }, wattr = { 0, 0 };
	char *csv = run_export("37"), *line, *save = NULL;
	char *names[256];
	int ncol = 0, rows = 0, c;
	uint32_t i;
	const struct scene_desc *d;

	assert_int_equal(scene_file_load(&sf, SCENE, &le), 0);
	d = &sf.desc;
	ref = ref_scene_new(d);
	assert_non_null(ref);
	assert_int_equal(ref_pose_new(&rp, d), 0);
	assert_int_equal(mot_timing_init(&t, d->rate_num, d->rate_den, d->tick_hz), 0);
	assert_true(d->has_camera && d->ncycles > 0 && d->nattrs > 0);

	line = strtok_r(csv, "\n", &save);
	assert_non_null(line);
	for (char *f = strtok(line, ","); f; f = strtok(NULL, ","))
		names[ncol++] = f;
	while ((line = strtok_r(NULL, "\n", &save)) != NULL) {
		double v[256];
		char *p = line, *end;
		int64_t tick;

		for (c = 0; c < ncol; c++) {
			v[c] = strtod(p, &end);
			assert_true(end != p);
			p = *end == ',' ? end + 1 : end;
		}
		tick = (int64_t)v[0];
		/* the frame column is the tick's exact frame time, to 10 digits */
		{
			double f = q2d(mot_timing_tick_frame(&t, tick));

			assert_true(fabs(v[1] - f) <= 1e-9 * fmax(1, fabs(f)));
		}
		ref_scene_eval(ref, mot_timing_tick_frame(&t, tick), &rp);
		for (i = 0; i < d->nnodes; i++) {
			const struct sd_node *n = &d->nodes[i];
			char name[128];
			int k;

			for (k = 0; k < 3; k++) {
				snprintf(name, sizeof(name), "%s.%c", n->name, 'x' + k);
				tu_worst_add(&wpos, v[col(names, ncol, name)] - rp.pos[i][k],
					     (double)tick);
			}
			if (n->kind == MOT_NODE_REVOLUTE) {
				double a;

				/* a spin reaches tens of thousands of degrees: ten printed
				 * digits leave 1e-9 of the value, plus the core's 1e-7 deg */
				snprintf(name, sizeof(name), "%s.angle", n->name);
				a = v[col(names, ncol, name)];
				tu_worst_add(&wang, (a - rp.value[i] * 360) / (1e-7 + 1e-9 * fabs(a)),
					     (double)tick);
				if (n->spin.nkeys) {
					snprintf(name, sizeof(name), "%s.rpm", n->name);
					tu_worst_add(&wrpm, v[col(names, ncol, name)] - rp.rpm[i],
						     (double)tick);
				}
			} else if (n->kind == MOT_NODE_PRISMATIC) {
				snprintf(name, sizeof(name), "%s.position", n->name);
				tu_worst_add(&wlen, v[col(names, ncol, name)] - rp.value[i],
					     (double)tick);
			}
		}
		for (c = 0; c < 3; c++) {
			static const char *const xyz[3] = { "camera.x", "camera.y", "camera.z" };

			tu_worst_add(&wcam, v[col(names, ncol, xyz[c])] - rp.eye[c], (double)tick);
		}
		{
			/* pan is continuous in the export and principal in the
			 * reference: compare modulo a full turn */
			double pan = v[col(names, ncol, "camera.pan")] / 360 - rp.pan;

			pan -= nearbyint(pan);
			tu_worst_add(&wcamang, pan * 360, (double)tick);
			tu_worst_add(&wcamang, v[col(names, ncol, "camera.tilt")] - rp.tilt * 360,
				     (double)tick);
			tu_worst_add(&wcamang, v[col(names, ncol, "camera.roll")] - rp.roll * 360,
				     (double)tick);
		}
		for (i = 0; i < d->ncycles; i++) {
			char name[128];

			snprintf(name, sizeof(name), "%s.index", d->cycles[i].name);
			assert_int_equal((int)v[col(names, ncol, name)], rp.cycle[i]);
		}
		for (i = 0; i < d->nattrs; i++)
			tu_worst_add(&wattr, v[col(names, ncol, d->attrs[i].name)] - rp.attr[i],
				     (double)tick);
		rows++;
	}
	/* frames -10 .. 130 at 30000/1001 fps and 1 kHz, every 37th tick */
	assert_true(rows > 120);
	/* printed with 10 significant digits: the bounds include the printing */
	tu_bound("export.every_key.position", &wpos, 1e-8, "units");
	tu_bound("export.every_key.angle", &wang, 1, "x (1e-7 deg + 1e-9 |angle|)");
	tu_bound("export.every_key.prismatic", &wlen, 1e-8, "units");
	tu_bound("export.every_key.rpm", &wrpm, 1e-6, "rpm");
	tu_bound("export.every_key.camera_eye", &wcam, 1e-8, "units");
	tu_bound("export.every_key.camera_angles", &wcamang, 1e-6, "deg");
	tu_bound("export.every_key.attributes", &wattr, 1e-9, "units");
	ref_pose_free(&rp);
	ref_scene_free(ref);
	scene_file_free(&sf);
	free(csv);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_every_key),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
