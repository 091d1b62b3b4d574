/* SPDX-License-Identifier: MIT */
/*
 * test_import_urdf.c - `strand import` of generated robots (chains, branches,
 * every joint type, mimic joints):
 *   - the tree of links against check_urdf's (liburdfdom-tools, the peer);
 *   - every joint's type, axis and limits against what the generator wrote
 *     (check_urdf prints the tree only);
 *   - every link's position at random joint values against a double-precision
 *     forward kinematics written here from the URDF's definitions (origins
 *     x, y, z then roll, pitch, yaw about fixed axes; the joint's motion about
 *     or along its axis in its own frame), within 1e-6 m;
 * and the reader's errors (a joint whose parent link does not exist, a
 * cycle, not XML): one line with the XML line, exit 2.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cliutil.h"
#include "load/load.h"
#include "ref_mat.h"
#include "testutil.h"

#include <cmocka.h>

#define MAXL 24

struct robot {
	int n;                 /* links; joint j connects parent[j] -> link j (j >= 1) */
	int parent[MAXL];
	int type[MAXL];        /* 0 revolute, 1 continuous, 2 prismatic, 3 fixed */
	double xyz[MAXL][3], rpy[MAXL][3], axis[MAXL][3];
	double lo[MAXL], hi[MAXL], vel[MAXL];
	int mimic[MAXL];       /* master joint or -1 */
	double mult[MAXL], off[MAXL];
};

static const char *const types[] = { "revolute", "continuous", "prismatic", "fixed" };

static void generate(struct robot *r, struct tu_rng *g, int n)
{
	int j, k;

	r->n = n;
	for (j = 1; j < n; j++) {
		/* a chain mostly, branches now and then */
		r->parent[j] = (tu_u64(g) % 3) ? j - 1 : (int)(tu_u64(g) % (uint64_t)j);
		r->type[j] = (int)(tu_u64(g) % 4);
		for (k = 0; k < 3; k++) {
			r->xyz[j][k] = tu_uniform(g, -0.4, 0.4);
			r->rpy[j][k] = tu_uniform(g, -3.1, 3.1);
			r->axis[j][k] = tu_uniform(g, -1, 1);
		}
		r->lo[j] = tu_uniform(g, -2, 0);
		r->hi[j] = tu_uniform(g, 0.1, 2);
		r->vel[j] = tu_uniform(g, 0.1, 5);
		r->mimic[j] = -1;
	}
	/* at most one mimic, of an earlier moving joint of the same type */
	for (j = n - 1; j > 1; j--)
		for (k = 1; k < j; k++)
			if (r->type[j] != 3 && r->type[k] == r->type[j] && tu_u64(g) % 2) {
				r->mimic[j] = k;
				r->mult[j] = tu_uniform(g, -2, 2);
				r->off[j] = tu_uniform(g, -0.2, 0.2);
				return;
			}
}

static void write_urdf(const struct robot *r, const char *path)
{
	FILE *f = fopen(path, "w");
	int j;

	assert_non_null(f);
	fprintf(f, "<?xml version=\"1.0\"?>\n<robot name=\"gen\">\n");
	for (j = 0; j < r->n; j++)
		fprintf(f, "  <link name=\"l%d\"/>\n", j);
	for (j = 1; j < r->n; j++) {
		fprintf(f, "  <joint name=\"j%d\" type=\"%s\">\n", j, types[r->type[j]]);
		fprintf(f, "    <parent link=\"l%d\"/>\n    <child link=\"l%d\"/>\n", r->parent[j], j);
		fprintf(f, "    <origin xyz=\"%.17g %.17g %.17g\" rpy=\"%.17g %.17g %.17g\"/>\n",
			r->xyz[j][0], r->xyz[j][1], r->xyz[j][2], r->rpy[j][0], r->rpy[j][1],
			r->rpy[j][2]);
		fprintf(f, "    <axis xyz=\"%.17g %.17g %.17g\"/>\n", r->axis[j][0], r->axis[j][1],
			r->axis[j][2]);
		fprintf(f, "    <limit lower=\"%.17g\" upper=\"%.17g\" effort=\"1\" velocity=\"%.17g\"/>\n",
			r->lo[j], r->hi[j], r->vel[j]);
		if (r->mimic[j] >= 0)
			fprintf(f, "    <mimic joint=\"j%d\" multiplier=\"%.17g\" offset=\"%.17g\"/>\n",
				r->mimic[j], r->mult[j], r->off[j]);
		fprintf(f, "  </joint>\n");
	}
	fprintf(f, "</robot>\n");
	fclose(f);
}

/* check_urdf's tree: each "child(k):  NAME" line, its parent by indentation. */
static void peer_tree(const char *path, int *parent, int n)
{
	char cmd[512], line[512];
	int stack[MAXL + 2], seen = 0;
	FILE *p;

	snprintf(cmd, sizeof(cmd), "check_urdf %s 2>&1", path);
	p = popen(cmd, "r");
	assert_non_null(p);
	while (fgets(line, sizeof(line), p)) {
		char *c = strstr(line, "child("), *name;
		int depth, l;

		if (!strncmp(line, "root Link: ", 11)) {
			assert_int_equal(atoi(line + 12), 0);
			stack[0] = 0;
			continue;
		}
		if (!c)
			continue;
		depth = (int)(c - line) / 4; /* four spaces a level */
		name = strstr(c, ":  ");
		assert_non_null(name);
		l = atoi(name + 4);
		assert_true(depth >= 1 && depth <= MAXL && l > 0 && l < n);
		parent[l] = stack[depth - 1];
		stack[depth] = l;
		seen++;
	}
	assert_int_equal(pclose(p), 0);
	assert_int_equal(seen, n - 1);
}

/* URDF forward kinematics in double: link frames, column vectors (ref_mul
 * is the plain product). */
static void mul(double o[4][4], double a[4][4], double b[4][4])
{
	struct ref_mat x, y, r;

	memcpy(x.m, a, sizeof(x.m));
	memcpy(y.m, b, sizeof(y.m));
	ref_mul(&r, &x, &y);
	memcpy(o, r.m, sizeof(r.m));
}

static void rot_axis(double m[4][4], const double a[3], double th)
{
	double c = cos(th), s = sin(th), C = 1 - c;
	double x = a[0], y = a[1], z = a[2];
	double r[4][4] = { { c + x * x * C, x * y * C - z * s, x * z * C + y * s, 0 },
			   { y * x * C + z * s, c + y * y * C, y * z * C - x * s, 0 },
			   { z * x * C - y * s, z * y * C + x * s, c + z * z * C, 0 },
			   { 0, 0, 0, 1 } };

	memcpy(m, r, sizeof(r));
}

static void fk(const struct robot *r, const double *q, double pos[MAXL][3])
{
	double f[MAXL][4][4];
	int j, k;

	memset(f[0], 0, sizeof(f[0]));
	for (k = 0; k < 4; k++)
		f[0][k][k] = 1;
	for (j = 1; j < r->n; j++) {
		const double *p = r->rpy[j];
		double cr = cos(p[0]), sr = sin(p[0]), cp = cos(p[1]), sp = sin(p[1]);
		double cy = cos(p[2]), sy = sin(p[2]), n, a[3], mo[4][4];
		double o[4][4] = {
			{ cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, r->xyz[j][0] },
			{ sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr, r->xyz[j][1] },
			{ -sp, cp * sr, cp * cr, r->xyz[j][2] },
			{ 0, 0, 0, 1 }
		};

		n = sqrt(r->axis[j][0] * r->axis[j][0] + r->axis[j][1] * r->axis[j][1] +
			 r->axis[j][2] * r->axis[j][2]);
		for (k = 0; k < 3; k++)
			a[k] = r->axis[j][k] / n;
		mul(f[j], f[r->parent[j]], o);
		if (r->type[j] <= 1) {
			rot_axis(mo, a, q[j]);
			mul(f[j], f[j], mo);
		} else if (r->type[j] == 2) {
			memset(mo, 0, sizeof(mo));
			for (k = 0; k < 4; k++)
				mo[k][k] = 1;
			for (k = 0; k < 3; k++)
				mo[k][3] = a[k] * q[j];
			mul(f[j], f[j], mo);
		}
	}
	for (j = 0; j < r->n; j++)
		for (k = 0; k < 3; k++)
			pos[j][k] = f[j][k][3];
}

static int node_of(const struct scene_desc *d, const char *name)
{
	uint32_t i;

	for (i = 0; i < d->nnodes; i++)
		if (!strcmp(d->nodes[i].name, name))
			return (int)i;
	return -1;
}

static void one_robot(struct tu_rng *g, int n, struct tu_worst *wpos)
{
	char urdf[64], yaml[64], args[256], name[16];
	struct robot r;
	struct run run;
	struct scene_file sf;
	struct scene_built b;
	struct load_err le;
	struct mot_eval ev;
	struct mot_pose pose;
	int peer[MAXL], j, trial;

	generate(&r, g, n);
	/* import decides by the name's end: .urdf */
	tmp_file(urdf, sizeof(urdf), ".urdf", "", 0);
	tmp_file(yaml, sizeof(yaml), ".yaml", "", 0);
	write_urdf(&r, urdf);
	peer_tree(urdf, peer, n);
	snprintf(args, sizeof(args), "import %s -o %s", urdf, yaml);
	strand(&run, args);
	if (run.rc)
		fprintf(stderr, "%s", run.err);
	assert_int_equal(run.rc, 0);
	run_free(&run);
	unlink(urdf);
	assert_int_equal(scene_file_load(&sf, yaml, &le), 0);
	unlink(yaml);
	for (j = 1; j < n; j++) {
		const struct sd_node *jn, *ln;
		int ji, li;

		snprintf(name, sizeof(name), "j%d", j);
		ji = node_of(&sf.desc, name);
		snprintf(name, sizeof(name), "l%d", j);
		li = node_of(&sf.desc, name);
		assert_true(ji >= 0 && li >= 0);
		jn = &sf.desc.nodes[ji];
		ln = &sf.desc.nodes[li];
		/* the tree: l(j) under j(j) under l(peer's parent) */
		assert_int_equal(ln->parent, ji);
		snprintf(name, sizeof(name), "l%d", peer[j]);
		assert_int_equal(jn->parent, node_of(&sf.desc, name));
		/* type and limits as the generator wrote them */
		assert_int_equal(jn->kind, r.type[j] <= 1 ? MOT_NODE_REVOLUTE :
					   r.type[j] == 2 ? MOT_NODE_PRISMATIC : MOT_NODE_FREE);
		if (r.type[j] != 3) {
			double s = r.type[j] == 2 ? 1 : 180 / M_PI;

			assert_int_equal(jn->limits.has_min, r.type[j] != 1);
			if (r.type[j] != 1) {
				assert_true(fabs(jn->limits.min - r.lo[j] * s) < 1e-9);
				assert_true(fabs(jn->limits.max - r.hi[j] * s) < 1e-9);
			}
			assert_true(fabs(jn->limits.vel - r.vel[j] * s) < 1e-9);
		}
	}
	for (trial = 0; trial < 20; trial++) {
		double q[MAXL] = { 0 }, pos[MAXL][3];
		struct sd_node *nodes = (struct sd_node *)sf.desc.nodes;

		for (j = 1; j < n; j++)
			q[j] = r.type[j] == 2 ? tu_uniform(g, -0.3, 0.3) : tu_uniform(g, -3, 3);
		for (j = 1; j < n; j++)
			if (r.mimic[j] >= 0)
				q[j] = r.mult[j] * q[r.mimic[j]] + r.off[j];
		for (j = 1; j < n; j++) {
			snprintf(name, sizeof(name), "j%d", j);
			if (r.type[j] != 3)
				nodes[node_of(&sf.desc, name)].rest =
					r.type[j] == 2 ? q[j] : q[j] * 180 / M_PI;
		}
		assert_int_equal(scene_file_build(&sf, &b, &le), 0);
		assert_int_equal(scene_eval_new(&ev, &b.sc), 0);
		assert_int_equal(scene_pose_new(&pose, &b.sc), 0);
		mot_scene_eval(&b.sc, &ev, 0, &pose);
		assert_int_equal(ev.sat, 0);
		fk(&r, q, pos);
		for (j = 0; j < n; j++) {
			int k, li;

			snprintf(name, sizeof(name), "l%d", j);
			li = node_of(&sf.desc, name);
			for (k = 0; k < 3; k++)
				tu_worst_add(wpos, pose.pos[li][k] / 4294967296.0 - pos[j][k], j);
		}
		scene_pose_free(&pose);
		scene_eval_free(&ev);
		scene_built_free(&b);
	}
	scene_file_free(&sf);
}

static void test_generated(void **state)
{
	struct tu_rng g;
	struct tu_worst w = { 0, 0 };
	int i;

	(void)state;
	tu_seed(&g, 1515);
	for (i = 0; i < 12; i++)
		one_robot(&g, 2 + (int)(tu_u64(&g) % (MAXL - 2)), &w);
	tu_bound("urdf_fk_positions", &w, 1e-6, "m");
}

/* One line, FILE: line N: what, exit 2. */
static void expect_error(const char *xml, const char *want)
{
	import_error(".urdf", xml, strlen(xml), want);
}

static void test_errors(void **state)
{
	(void)state;
	expect_error("<robot name=\"r\">\n<link name=\"a\"/>\n<joint name=\"j\" type=\"fixed\">\n"
		     "<parent link=\"nope\"/><child link=\"a\"/></joint>\n</robot>\n",
		     ": line 4: joint 'j': its parent link 'nope' does not exist");
	expect_error("<robot name=\"r\">\n<link name=\"a\"/><link name=\"b\"/>\n"
		     "<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
		     "<joint name=\"k\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint>\n"
		     "</robot>\n", "no root link: every link is some joint's child (a cycle)");
	expect_error("<robot name=\"r\">\n<link name=\"a\">\n</robot>\n", ": not well-formed XML");
	expect_error("<robot name=\"r\">\n<link name=\"a\"/><link name=\"b\"/>\n"
		     "<joint name=\"j\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>\n"
		     "<origin xyz=\"0 nan 0\"/></joint>\n</robot>\n",
		     ": line 4: 'xyz' takes 3 finite numbers");
	expect_error("<robot name=\"r\">\n<link name=\"a\"/><link name=\"b\"/>\n"
		     "<joint name=\"j\" type=\"ball\"><parent link=\"a\"/><child link=\"b\"/></joint>\n"
		     "</robot>\n", "type 'ball' is not revolute");
}

/* --merge: the robot's nodes under a scene's timing, strands and rig; a
 * scene with strands cannot take a glTF's strands too. */
static void test_merge(void **state)
{
	static const char scene[] =
		"scene: take\n"
		"timing: {tick_hz: 1000, frame_rate: 25, frames: [0, 100]}\n"
		"nodes:\n  - {name: pan, joint: {type: revolute, axis: z}}\n"
		"strands:\n  - node: pan\n"
		"    keys: [{frame: 0, angle: 0}, {frame: 50, angle: 90}, {frame: 100, angle: 0}]\n"
		"  - {node: grip_l, interpolation: linear,\n"
		"     keys: [{frame: 0, position: 0}, {frame: 100, position: 0.04}]}\n"
		"devices:\n  - {name: drives, driver: sim}\n"
		"outputs:\n  - {channel: pan.angle, device: drives, counts_per_unit: 100,\n"
		"     limits: {velocity: 100, acceleration: 500}}\n";
	char path[64], yaml[64], args[256];
	struct run r;

	(void)state;
	tmp_file(path, sizeof(path), ".yaml", scene, strlen(scene));
	tmp_file(yaml, sizeof(yaml), ".yaml", "", 0);
	snprintf(args, sizeof(args), "import tests/import/urdf/arm.urdf --merge %s -o %s", path, yaml);
	strand(&r, args);
	assert_int_equal(r.rc, 0);
	run_free(&r);
	snprintf(args, sizeof(args), "export %s --every 50", yaml);
	strand(&r, args);
	assert_int_equal(r.rc, 0);
	/* frame 50 at 25 fps and 1 kHz is tick 2000: pan at 90 degrees, the
	 * robot's other joints at rest */
	assert_non_null(strstr(r.out, "pan.angle,lift.angle,reach.position"));
	assert_non_null(strstr(r.out, "\n2000,50,"));
	/* pan at 90 degrees, grip_l half open and grip_r, its mimic, with it */
	assert_non_null(strstr(r.out, ",twist.angle,grip_l.position,grip_r.position\n"));
	assert_non_null(strstr(r.out, ",90,0,0,0,0.02000000002,0.02000000002\n"));
	run_free(&r);
	snprintf(args, sizeof(args), "play %s --sim --clock virtual --no-journal --quiet", yaml);
	strand(&r, args);
	if (r.rc)
		fprintf(stderr, "%s", r.err);
	assert_int_equal(r.rc, 0);
	run_free(&r);
	snprintf(args, sizeof(args), "import tests/import/blender/armature.keys.gltf --merge %s", path);
	strand(&r, args);
	assert_int_equal(r.rc, 3);
	assert_non_null(strstr(r.err, "have strands"));
	run_free(&r);
	unlink(path);
	unlink(yaml);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_generated),
		cmocka_unit_test(test_errors),
		cmocka_unit_test(test_merge),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
