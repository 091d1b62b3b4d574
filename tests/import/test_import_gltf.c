/* SPDX-License-Identifier: MIT */
/*
 * test_import_gltf.c - `strand import` then `strand export` of the glTF
 * files Blender's own exporter wrote (tests/import/blender/, made by `make
 * blender-fixtures`), against
 *   - a double-precision evaluation of the same file per the glTF 2.0
 *     specification's appendix C (below: STEP, LINEAR with slerp the short
 *     way, CUBICSPLINE with the tangents scaled by the key interval and a
 *     rotation normalised; the end values held), on the file's float32 keys
 *     as gltf.c decodes them: every node's world position at every frame,
 *     within 1e-6 m;
 *   - Blender's own world positions of every object and bone at every frame
 *     (<scene>.blender.csv), for the sampled exports, which keep them: within
 *     what float32 keeps of them.
 * And the readers' errors: one line, FILE: JSON path: what is wrong, exit 2.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cliutil.h"
#include "import/gltf.h"
#include "ref_mat.h"
#include "testutil.h"

#include <cmocka.h>

#define DIR "tests/import/blender/"
#define FPS 24.0

/* ---- the specification's evaluation, in double ---------------------------------- */

/* Key interval of t in times[0..n-1]: *i and the fraction; false when t is
 * at or outside an end (then *i is that end). */
static int locate(const double *times, uint32_t n, double t, uint32_t *i, double *s)
{
	uint32_t k;

	if (t <= times[0]) {
		*i = 0;
		return 0;
	}
	if (t >= times[n - 1]) {
		*i = n - 1;
		return 0;
	}
	for (k = 0; t >= times[k + 1]; k++)
		;
	*i = k;
	*s = (t - times[k]) / (times[k + 1] - times[k]);
	return 1;
}

/* Channel c at t seconds, into out[dim] in the file's order (x, y, z, w). */
static void sample(const struct gltf_channel *c, double t, double *out)
{
	uint32_t dim = c->dim, i, k;
	double s = 0;
	bool inside = locate(c->time, c->n, t, &i, &s);

	if (c->interp == GLTF_CUBIC) {
		const double *v = c->v;
		/* element i: in-tangent a, value v, out-tangent b at 3 i dim */
		if (!inside) {
			for (k = 0; k < dim; k++)
				out[k] = v[(3 * i + 1) * dim + k];
		} else {
			double td = c->time[i + 1] - c->time[i], s2 = s * s, s3 = s2 * s;

			for (k = 0; k < dim; k++)
				out[k] = (2 * s3 - 3 * s2 + 1) * v[(3 * i + 1) * dim + k] +
					 td * (s3 - 2 * s2 + s) * v[(3 * i + 2) * dim + k] +
					 (-2 * s3 + 3 * s2) * v[(3 * (i + 1) + 1) * dim + k] +
					 td * (s3 - s2) * v[(3 * (i + 1)) * dim + k];
		}
	} else if (!inside || c->interp == GLTF_STEP) {
		for (k = 0; k < dim; k++)
			out[k] = c->v[i * dim + k];
	} else if (dim == 4) {
		/* slerp, a = acos |dot|, the shorter way (appendix C) */
		const double *a = c->v + i * 4, *b = c->v + (i + 1) * 4;
		double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
		double sg = d < 0 ? -1 : 1, ang = acos(fmin(fabs(d), 1.0)), wa, wb;

		if (ang < 1e-12) {
			wa = 1 - s;
			wb = s;
		} else {
			wa = sin(ang * (1 - s)) / sin(ang);
			wb = sin(ang * s) / sin(ang);
		}
		for (k = 0; k < 4; k++)
			out[k] = wa * a[k] + sg * wb * b[k];
	} else {
		for (k = 0; k < dim; k++)
			out[k] = (1 - s) * c->v[i * dim + k] + s * c->v[(i + 1) * dim + k];
	}
	if (dim == 4) {
		double n = sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] +
				out[3] * out[3]);

		for (k = 0; k < 4; k++)
			out[k] /= n;
	}
}

/* The key times as the import reads them: a float32 time that is the float
 * nearest to a whole frame's time is that frame's time (imp_gltf.c). */
static void snap_times(struct gltf *g)
{
	uint32_t c, i;

	for (c = 0; c < g->nchannels; c++)
		for (i = 0; i < g->channels[c].n; i++) {
			double *t = &g->channels[c].time[i], n = nearbyint(*t * FPS);

			if ((float)(n / FPS) == (float)*t)
				*t = n / FPS;
		}
}

/* The local matrix T . R . S of node i at t (column vectors). */
static void local(struct ref_mat *lm, const struct gltf *g, uint32_t i, double t)
{
	double(*m)[4] = lm->m;
	const struct gltf_node *n = &g->nodes[i];
	double tr[3], q[4], sc[3], x, y, z, w;
	uint32_t c, k;

	if (n->has_matrix) {
		for (k = 0; k < 16; k++)
			m[k % 4][k / 4] = n->matrix[k];
		return;
	}
	memcpy(tr, n->t, sizeof(tr));
	memcpy(q, n->r, sizeof(q));
	memcpy(sc, n->s, sizeof(sc));
	for (c = 0; c < g->nchannels; c++) {
		const struct gltf_channel *ch = &g->channels[c];

		if ((uint32_t)ch->node == i)
			sample(ch, t, ch->path == GLTF_T ? tr : ch->path == GLTF_R ? q : sc);
	}
	x = q[0], y = q[1], z = q[2], w = q[3];
	{
		double r[3][3] = {
			{ 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y) },
			{ 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x) },
			{ 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y) }
		};

		for (c = 0; c < 3; c++) {
			for (k = 0; k < 3; k++)
				m[c][k] = r[c][k] * sc[k];
			m[c][3] = tr[c];
			m[3][c] = 0;
		}
		m[3][3] = 1;
	}
}

/* World = parent . local (column vectors: ref_mul's product is the plain
 * one). */
static void world(struct ref_mat *m, const struct gltf *g, uint32_t i, double t)
{
	struct ref_mat l, p;

	local(&l, g, i, t);
	if (g->nodes[i].parent < 0) {
		*m = l;
		return;
	}
	world(&p, g, (uint32_t)g->nodes[i].parent, t);
	ref_mul(m, &p, &l);
}

/* ---- strand's side ------------------------------------------------------------- */

struct table {
	char **names;
	int ncols, nrows;
	double *v; /* nrows x ncols */
};

static void table_parse(struct table *tb, char *text)
{
	char *line = text, *next, *f;
	int cap = 0;

	memset(tb, 0, sizeof(*tb));
	for (; line && *line; line = next) {
		int k = 0;

		next = strchr(line, '\n');
		if (next)
			*next++ = 0;
		if (!tb->names) {
			for (f = strtok(line, ","); f; f = strtok(NULL, ","))
				tb->ncols++;
			tb->names = calloc((size_t)tb->ncols, sizeof(char *));
			for (f = line; k < tb->ncols; k++, f += strlen(f) + 1)
				tb->names[k] = strdup(f);
			continue;
		}
		if (tb->nrows == cap) {
			cap = cap ? cap * 2 : 64;
			tb->v = realloc(tb->v, (size_t)cap * (size_t)tb->ncols * sizeof(double));
		}
		for (f = line; k < tb->ncols; k++) {
			tb->v[tb->nrows * tb->ncols + k] = strtod(f, &f);
			if (*f == ',')
				f++;
		}
		tb->nrows++;
	}
}

static void table_free(struct table *tb)
{
	int k;

	for (k = 0; k < tb->ncols; k++)
		free(tb->names[k]);
	free(tb->names);
	free(tb->v);
}

static int column(const struct table *tb, const char *name)
{
	int k;

	for (k = 0; k < tb->ncols; k++)
		if (!strcmp(tb->names[k], name))
			return k;
	return -1;
}

/* A glTF or Blender name as a scene takes it (imp_names; the fixtures have
 * no clashes). */
static void scene_name(char *out, size_t size, const char *name)
{
	size_t k;

	snprintf(out, size, "%s", name);
	for (k = 0; out[k]; k++)
		if (!((out[k] >= 'a' && out[k] <= 'z') || (out[k] >= 'A' && out[k] <= 'Z') ||
		      (out[k] >= '0' && out[k] <= '9') || out[k] == '_' || out[k] == '-'))
			out[k] = '_';
}

static char *slurp_text(const char *path)
{
	FILE *f = fopen(path, "rb");
	char *text;
	long len;

	assert_non_null(f);
	fseek(f, 0, SEEK_END);
	len = ftell(f);
	fseek(f, 0, SEEK_SET);
	text = calloc(1, (size_t)len + 1);
	assert_int_equal(fread(text, 1, (size_t)len, f), (size_t)len);
	fclose(f);
	return text;
}

/* `strand import FILE` then `strand export` of it at every frame. */
static void import_export(const char *file, struct table *tb)
{
	char args[512], yaml[64];
	struct run r;

	tmp_file(yaml, sizeof(yaml), ".yaml", "", 0);
	snprintf(args, sizeof(args), "import %s -o %s", file, yaml);
	strand(&r, args);
	assert_int_equal(r.rc, 0);
	run_free(&r);
	snprintf(args, sizeof(args), "export %s", yaml);
	strand(&r, args);
	if (r.rc)
		fprintf(stderr, "%s", r.err);
	assert_int_equal(r.rc, 0);
	table_parse(tb, r.out);
	run_free(&r);
	unlink(yaml);
}

static void against_spec(const char *scene, const char *kind, const char *ext)
{
	char file[256], col[160], name[128], bname[96];
	uint8_t *buf;
	size_t len;
	struct gltf g;
	struct table tb;
	struct tu_worst w = { 0, 0 };
	char err[256];
	FILE *f;
	uint32_t i;
	int row;

	snprintf(file, sizeof(file), DIR "%s.%s.%s", scene, kind, ext);
	f = fopen(file, "rb");
	assert_non_null(f);
	fseek(f, 0, SEEK_END);
	len = (size_t)ftell(f);
	fseek(f, 0, SEEK_SET);
	buf = malloc(len);
	assert_int_equal(fread(buf, 1, len, f), len);
	fclose(f);
	assert_int_equal(gltf_read(&g, file, buf, len, NULL, err, sizeof(err)), 0);
	free(buf);
	snap_times(&g);
	import_export(file, &tb);
	assert_true(tb.nrows > 48);
	for (i = 0; i < g.nnodes; i++) {
		int cx;

		scene_name(name, sizeof(name), g.nodes[i].name);
		snprintf(col, sizeof(col), "%s.x", name);
		cx = column(&tb, col);
		assert_true(cx >= 0);
		for (row = 0; row < tb.nrows; row++) {
			double frame = tb.v[row * tb.ncols + 1];
			struct ref_mat m;
			int k;

			world(&m, &g, i, frame / FPS);
			for (k = 0; k < 3; k++)
				tu_worst_add(&w, tb.v[row * tb.ncols + cx + k] - m.m[k][3], frame);
		}
	}
	snprintf(bname, sizeof(bname), "gltf_%s_%s_vs_spec", scene, kind);
	tu_bound(bname, &w, 1e-6, "m");
	gltf_free(&g);
	table_free(&tb);
}

static void against_blender(const char *scene)
{
	char file[256], text_path[256], col[160], bname[96];
	struct table tb, bl;
	struct tu_worst w = { 0, 0 };
	char *text;
	int k, row, compared = 0;

	snprintf(file, sizeof(file), DIR "%s.sampled.glb", scene);
	import_export(file, &tb);
	snprintf(text_path, sizeof(text_path), DIR "%s.blender.csv", scene);
	text = slurp_text(text_path);
	table_parse(&bl, text);
	free(text);
	assert_int_equal(bl.nrows, tb.nrows);
	for (k = 1; k < bl.ncols; k++) {
		int c;

		scene_name(col, sizeof(col), bl.names[k]);
		/* scene_name turned the '.' of ".x" into '_': put it back */
		col[strlen(col) - 2] = '.';
		c = column(&tb, col);
		assert_true(c >= 0);
		for (row = 0; row < bl.nrows; row++)
			tu_worst_add(&w, tb.v[row * tb.ncols + c] - bl.v[row * bl.ncols + k],
				     bl.v[row * bl.ncols]);
		compared++;
	}
	assert_true(compared >= 12);
	snprintf(bname, sizeof(bname), "gltf_%s_sampled_vs_blender", scene);
	tu_bound(bname, &w, 2e-6, "m");
	table_free(&tb);
	table_free(&bl);
}

static void test_hierarchy(void **state)
{
	(void)state;
	against_spec("hierarchy", "keys", "gltf");
	against_spec("hierarchy", "sampled", "glb");
	against_blender("hierarchy");
}

static void test_armature(void **state)
{
	(void)state;
	against_spec("armature", "keys", "gltf");
	against_spec("armature", "sampled", "glb");
	against_blender("armature");
}

/* `strand import FILE --merge` a scene with one revolute joint: exit 2,
 * one line naming the file. */
static void onto_error(const char *joint, const char *axis, const char *file, const char *want)
{
	char scene[256], path[64], args[256];
	struct run r;

	snprintf(scene, sizeof(scene),
		 "timing: {frame_rate: 24, frames: [0, 10]}\n"
		 "nodes: [{name: %s, joint: {type: revolute, axis: %s}}]\n", joint, axis);
	tmp_file(path, sizeof(path), ".yaml", scene, strlen(scene));
	snprintf(args, sizeof(args), "import " DIR "%s --merge %s", file, path);
	strand(&r, args);
	unlink(path);
	if (r.rc != 2 || !strstr(r.err, want))
		fprintf(stderr, "exit %d: %s", r.rc, r.err);
	assert_int_equal(r.rc, 2);
	assert_non_null(strstr(r.err, want));
	run_free(&r);
}

/* tests/import/urdf/arm.urdf's joints driven by the empties of Blender's
 * robot scene, named after them (`strand import robot.sampled.glb --merge
 * arm.yaml`): every frame's joint values against Blender's own. */
static void test_onto_joints(void **state)
{
	static const char *const cols[] = { "pan.angle", "lift.angle", "reach.position" };
	char robot[64], args[256], *text;
	struct table tb, bl;
	struct tu_worst wa = { 0, 0 }, wp = { 0, 0 };
	struct run r;
	int k, row;

	(void)state;
	tmp_file(robot, sizeof(robot), ".yaml", "", 0);
	snprintf(args, sizeof(args), "import tests/import/urdf/arm.urdf -o %s", robot);
	strand(&r, args);
	assert_int_equal(r.rc, 0);
	run_free(&r);
	snprintf(args, sizeof(args), "import " DIR "robot.sampled.glb --merge %s -o %s", robot, robot);
	strand(&r, args);
	assert_int_equal(r.rc, 0);
	run_free(&r);
	snprintf(args, sizeof(args), "export %s", robot);
	strand(&r, args);
	assert_int_equal(r.rc, 0);
	table_parse(&tb, r.out);
	run_free(&r);
	text = slurp_text(DIR "robot.blender.csv");
	table_parse(&bl, text);
	free(text);
	assert_int_equal(tb.nrows, bl.nrows);
	for (k = 0; k < 3; k++) {
		int c = column(&tb, cols[k]), b = column(&bl, cols[k]);

		assert_true(c >= 0 && b >= 0);
		for (row = 0; row < tb.nrows; row++)
			tu_worst_add(k < 2 ? &wa : &wp,
				     tb.v[row * tb.ncols + c] - bl.v[row * bl.ncols + b], row);
	}
	tu_bound("gltf_onto_urdf_angles_vs_blender", &wa, 1e-4, "deg");
	tu_bound("gltf_onto_urdf_positions_vs_blender", &wp, 1e-6, "m");
	table_free(&tb);
	table_free(&bl);
	unlink(robot);
	/* refused, named: a node that turns about two axes, one about another
	 * axis than its joint's, a cubic rotation */
	onto_error("Kid", "z", "hierarchy.sampled.glb",
		   ": node 'Kid' turns about more than one axis, and revolute joint 'Kid' about one");
	onto_error("Spinner", "x", "hierarchy.sampled.glb",
		   ": node 'Spinner' turns about (0, 1, 0) in the file's axes, not about revolute joint 'Spinner''s axis (1, 0, 0)");
	onto_error("Base", "y", "hierarchy.keys.gltf",
		   ": node 'Base': a CUBICSPLINE rotation is no cubic in its angle");
}

/* Bad files: one line naming the file and the JSON path, exit 2
 * (cliutil's import_error). */
#define GLTF_HEAD "{\"asset\": {\"version\": \"2.0\"}, "
/* 8 bytes: the floats 0 and 1 (times) */
#define BUF8 "\"buffers\": [{\"byteLength\": 8, \"uri\": \"data:application/octet-stream;base64,AAAAAAAAgD8=\"}], "

static void test_errors(void **state)
{
	static const char cycle[] = GLTF_HEAD
		"\"nodes\": [{\"children\": [1]}, {\"children\": [2]}, {\"children\": [1]}]}";
	static const char past[] = GLTF_HEAD BUF8
		"\"bufferViews\": [{\"buffer\": 0, \"byteLength\": 8}], "
		"\"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"SCALAR\"},"
		" {\"bufferView\": 0, \"componentType\": 5126, \"count\": 2, \"type\": \"VEC3\"}], "
		"\"nodes\": [{}], \"animations\": [{\"samplers\": [{\"input\": 0, \"output\": 1}], "
		"\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}}]}]}";
	/* the times 0 and NaN */
	static const char nan_key[] = GLTF_HEAD
		"\"buffers\": [{\"byteLength\": 8, \"uri\": \"data:application/octet-stream;base64,AAAAAAAAwH8=\"}], "
		"\"bufferViews\": [{\"buffer\": 0, \"byteLength\": 8}], "
		"\"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 2, \"type\": \"SCALAR\"}], "
		"\"nodes\": [{}], \"animations\": [{\"samplers\": [{\"input\": 0, \"output\": 0}], "
		"\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}}]}]}";
	uint8_t glb[64] = "glTF";

	(void)state;
	import_error(".gltf", cycle, sizeof(cycle) - 1, ": /nodes/2/children/0: node 1 is already a child of node 0");
	import_error(".gltf", cycle, 60, ": not valid JSON");
	import_error(".gltf", past, sizeof(past) - 1,
		     ": /accessors/0: 4 elements of 4 bytes from byte 0 pass the end of bufferView 0 (8 bytes)");
	import_error(".gltf", nan_key, sizeof(nan_key) - 1, ": /accessors/0: element 1 is NaN");
	glb[4] = 2;
	glb[8] = 200; /* says 200 bytes, has 64 */
	import_error(".glb", glb, sizeof(glb), ": the .glb says 200 bytes but has 64 (truncated)");
	{
		static const char own[] = GLTF_HEAD
			"\"nodes\": [{\"children\": [1]}, {\"children\": [0]}]}";

		import_error(".gltf", own, sizeof(own) - 1, ": /nodes/0: the node is its own ancestor");
	}
}

/* Names: other characters become '_', a clash gets _2 and is said once on
 * stderr, 'camera' is taken; nodes come parents first whatever the file's
 * order; a node without a name is node<i>. */
static void test_names(void **state)
{
	static const char file[] = GLTF_HEAD
		"\"nodes\": [{\"name\": \"leaf\"}, {\"name\": \"a.b\", \"children\": [0]},"
		" {\"name\": \"a_b\"}, {\"name\": \"camera\"}, {}]}";
	char path[64], args[128];
	struct run r;

	(void)state;
	tmp_file(path, sizeof(path), ".gltf", file, sizeof(file) - 1);
	snprintf(args, sizeof(args), "import %s", path);
	strand(&r, args);
	unlink(path);
	assert_int_equal(r.rc, 0);
	assert_non_null(strstr(r.err, ": the name 'a_b' is taken: it is 'a_b_2' in the scene\n"));
	assert_non_null(strstr(r.err, ": the name 'camera' is taken: it is 'camera_2' in the scene\n"));
	assert_non_null(strstr(r.out, "nodes:\n  - name: a_b\n  - name: leaf\n    parent: a_b\n"
				      "  - name: a_b_2\n  - name: camera_2\n  - name: node4\n"));
	run_free(&r);
}

/* --animation NAME|N chooses a clip; the first by default. */
static void test_clips(void **state)
{
	/* times 0 and 1 s, then clip A's translations (0,0,0) (1,2,3), B's
	 * (0,0,0) (-1,-2,-3) */
	static const char file[] = GLTF_HEAD
		"\"buffers\": [{\"byteLength\": 56, \"uri\": \"data:application/octet-stream;base64,"
		"AAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAQAAAQEAAAAAAAAAAAAAAAAAAAIC/AAAAwAAAQMA=\"}], "
		"\"bufferViews\": [{\"buffer\": 0, \"byteLength\": 56}], "
		"\"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 2, \"type\": \"SCALAR\"},"
		" {\"bufferView\": 0, \"byteOffset\": 8, \"componentType\": 5126, \"count\": 2, \"type\": \"VEC3\"},"
		" {\"bufferView\": 0, \"byteOffset\": 32, \"componentType\": 5126, \"count\": 2, \"type\": \"VEC3\"}], "
		"\"nodes\": [{\"name\": \"n\"}], \"animations\": ["
		"{\"name\": \"A\", \"samplers\": [{\"input\": 0, \"output\": 1}], "
		"\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}}]},"
		"{\"name\": \"B\", \"samplers\": [{\"input\": 0, \"output\": 2, \"interpolation\": \"STEP\"}], "
		"\"channels\": [{\"sampler\": 0, \"target\": {\"node\": 0, \"path\": \"translation\"}}]}]}";
	static const struct {
		const char *opt, *comment, *key;
	} clips[] = {
		{ "", "animation 0 'A' of 2", "{frame: 24, translate: [1, 2, 3]}" },
		{ "--animation B", "animation 1 'B' of 2", "{frame: 24, translate: [-1, -2, -3]}" },
		{ "--animation 1", "animation 1 'B' of 2", "translate: step" },
	};
	char path[64], args[160];
	struct run r;
	size_t i;

	(void)state;
	tmp_file(path, sizeof(path), ".gltf", file, sizeof(file) - 1);
	for (i = 0; i < sizeof(clips) / sizeof(clips[0]); i++) {
		snprintf(args, sizeof(args), "import %s %s", path, clips[i].opt);
		strand(&r, args);
		assert_int_equal(r.rc, 0);
		assert_non_null(strstr(r.out, clips[i].comment));
		assert_non_null(strstr(r.out, clips[i].key));
		run_free(&r);
	}
	snprintf(args, sizeof(args), "import %s --animation C", path);
	strand(&r, args);
	assert_int_equal(r.rc, 2);
	assert_non_null(strstr(r.err, ": /animations: no animation named or numbered 'C' (the file has 2)"));
	run_free(&r);
	unlink(path);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_hierarchy),
		cmocka_unit_test(test_armature),
		cmocka_unit_test(test_errors),
		cmocka_unit_test(test_onto_joints),
		cmocka_unit_test(test_names),
		cmocka_unit_test(test_clips),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
