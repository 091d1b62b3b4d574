/* SPDX-License-Identifier: MIT */
/*
 * cmd_import.c - `strand import FILE`: a glTF 2.0 file (.gltf, .glb), a URDF
 * or a table (.csv) as a scene file (import/imp.h), on stdout or -o FILE.
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "exitcode.h"
#include "import/imp.h"

struct opts {
	struct imp_opts imp;
	const char *outpath, *merge;
	bool has_tick;
	const struct cli_cmd *cmd;
	FILE *err;
};

static int on_opt(void *ctx, int opt, const char *arg)
{
	static const char *const interps[] = { "step", "linear", "hermite" };
	struct opts *o = ctx;
	long long num, den = 1;
	char *slash;
	int k;

	switch (opt) {
	case 'o':
		o->outpath = arg;
		return -1;
	case 'm':
		o->merge = arg;
		return -1;
	case 'a':
		o->imp.anim = arg;
		return -1;
	case 'f':
		slash = strchr(arg, '/');
		if (slash) {
			char buf[64];

			snprintf(buf, sizeof(buf), "%.*s", (int)(slash - arg), arg);
			if (!opt_long(buf, 1, 16777216, &num) ||
			    !opt_long(slash + 1, 1, 16777216, &den))
				return cli_usage(o->cmd, o->err, "--fps takes N or N/D (1 to 16777216), not '%s'", arg);
		} else if (!opt_long(arg, 1, 16777216, &num)) {
			return cli_usage(o->cmd, o->err, "--fps takes N or N/D (1 to 16777216), not '%s'", arg);
		}
		o->imp.rate_num = (uint32_t)num;
		o->imp.rate_den = (uint32_t)den;
		return -1;
	case 't':
		if (!opt_long(arg, 1, 1048576, &num))
			return cli_usage(o->cmd, o->err, "--tick-hz takes 1 to 1048576, not '%s'", arg);
		o->imp.tick_hz = (uint32_t)num;
		o->has_tick = true;
		return -1;
	case 'i':
		for (k = 0; k < 3; k++)
			if (!strcmp(arg, interps[k]))
				break;
		if (k == 3)
			return cli_usage(o->cmd, o->err, "--interpolation takes step, linear or hermite, not '%s'", arg);
		o->imp.interp = k == 0 ? IMP_STEP : k == 1 ? IMP_LINEAR : IMP_HERMITE;
		return -1;
	}
	return STRAND_EXIT_USAGE;
}

static bool ends_with(const char *s, const char *tail)
{
	size_t a = strlen(s), b = strlen(tail);

	return a >= b && !strcasecmp(s + a - b, tail);
}

/* The whole file, NUL-terminated. */
static int slurp(const char *path, uint8_t **out, size_t *len)
{
	FILE *f = fopen(path, "rb");
	size_t cap = 1 << 16, n = 0;
	uint8_t *b = NULL, *nb;

	if (!f)
		return -errno;
	for (;;) {
		if (!(nb = realloc(b, cap + 1))) {
			free(b);
			fclose(f);
			return -ENOMEM;
		}
		b = nb;
		n += fread(b + n, 1, cap - n, f);
		if (n < cap)
			break;
		cap *= 2;
	}
	if (ferror(f)) {
		free(b);
		fclose(f);
		return -EIO;
	}
	fclose(f);
	b[n] = 0;
	*out = b;
	*len = n;
	return 0;
}

/* Whether the scene text has the top-level key `key` ("strands:"). */
static bool has_section(const char *text, const char *key)
{
	const char *line;

	for (line = text; line; line = strchr(line, '\n'), line = line ? line + 1 : NULL)
		if (!strncmp(line, key, strlen(key)))
			return true;
	return false;
}

/*
 * --merge SCENE.yaml: the existing scene's sections other than nodes follow
 * the imported nodes, as the file has them: its timing (when it has one),
 * strands, camera, cycles, attributes and rig. A top-level key starts a
 * line with no indentation; comments and the rest are kept.
 */
static int merge(FILE *out, const char *path, const char *text, const char *const *own)
{
	const char *line = text;
	bool keep = false;
	int k;

	fprintf(out, "# merged from %s: its sections but %s\n", path,
		!strcmp(own[0], "nodes:") ? "nodes" : "timing and strands");
	while (*line) {
		const char *end = strchr(line, '\n');
		size_t len = end ? (size_t)(end - line) + 1 : strlen(line);

		if (line[0] != ' ' && line[0] != '\t' && line[0] != '#' && line[0] != '\n' &&
		    line[0] != '-') {
			keep = true;
			for (k = 0; own[k]; k++)
				if (!strncmp(line, own[k], strlen(own[k])))
					keep = false;
		}
		if (keep)
			fwrite(line, 1, len, out);
		line += len;
	}
	return ferror(out) ? -EIO : 0;
}

/*
 * A glTF file merged into a scene whose joints its animated nodes name: the
 * animation drives those joints (import/imp_gltf_joint.c). *onto false when
 * no animated node has a joint's name, or the scene does not load on its
 * own (a take's strands and rig for another file's nodes): the file is then
 * imported as nodes, and the merged scene checked as a whole. 0, or a
 * negative errno with msg.
 */
static int onto_joints(struct imp_model *m, const char *path, const uint8_t *buf, size_t len,
		       const struct opts *o, FILE *warn, char *msg, size_t msgsize, bool *onto)
{
	struct scene_file sf;
	struct load_err le;
	struct imp_joint *joints;
	uint32_t i, n = 0, matched = 0;
	int rc;

	*onto = false;
	if (scene_file_load(&sf, o->merge, &le))
		return 0;
	joints = calloc(sf.desc.nnodes + 1, sizeof(*joints));
	if (!joints) {
		scene_file_free(&sf);
		return -ENOMEM;
	}
	for (i = 0; i < sf.desc.nnodes; i++) {
		const struct sd_node *sn = &sf.desc.nodes[i];
		double l = sqrt(sn->axis[0] * sn->axis[0] + sn->axis[1] * sn->axis[1] +
				sn->axis[2] * sn->axis[2]);
		int k;

		if (sn->kind == MOT_NODE_FREE || !(l > 0))
			continue;
		joints[n].name = sn->name;
		joints[n].kind = sn->kind == MOT_NODE_REVOLUTE ? IMP_REVOLUTE : IMP_PRISMATIC;
		for (k = 0; k < 3; k++)
			joints[n].axis[k] = sn->axis[k] / l;
		n++;
	}
	rc = imp_gltf_joints(m, path, buf, len, &o->imp, joints, n, &matched, warn, msg, msgsize);
	if (!rc && !matched)
		imp_model_free(m);
	*onto = !rc && matched;
	free(joints);
	scene_file_free(&sf);
	return rc;
}

/*
 * The scene written, read back by the loader and built, as check and play
 * will: a file whose numbers the core cannot hold (key times past 2^30
 * frames, a tangent beyond the core's range) is refused here, named, not
 * later. 0, or the exit code with one line on err: FILE: the scene it
 * makes ...
 */
static int check_scene(const char *path, const char *text, size_t len, FILE *err)
{
	struct scene_file sf;
	struct scene_built b;
	struct load_err e;
	int rc = scene_file_parse(&sf, "scene", text, len, &e);

	if (!rc) {
		rc = scene_file_build(&sf, &b, &e);
		if (!rc)
			scene_built_free(&b);
		scene_file_free(&sf);
	}
	if (!rc)
		return 0;
	if (e.line)
		fprintf(err, "%s: the scene it makes is refused at its line %u: %s\n", path, e.line,
			e.msg);
	else
		fprintf(err, "%s: the scene it makes is refused: %s\n", path, e.msg);
	return e.code == -ENOMEM ? STRAND_EXIT_INTERNAL : STRAND_EXIT_SCENE;
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	static const struct option opts[] = {
		{ "help", no_argument, NULL, 'h' },	    { "output", required_argument, NULL, 'o' },
		{ "fps", required_argument, NULL, 'f' },    { "tick-hz", required_argument, NULL, 't' },
		{ "animation", required_argument, NULL, 'a' },
		{ "interpolation", required_argument, NULL, 'i' },
		{ "merge", required_argument, NULL, 'm' },  { 0 } };
	struct opts o = { .imp = { 24, 1, 0, NULL, IMP_LINEAR }, .cmd = cmd, .err = err };
	struct imp_model m = { 0 };
	uint8_t *buf = NULL, *mbuf = NULL;
	size_t len, mlen;
	const char *path;
	char msg[512];
	FILE *f = out, *mem;
	char *text;
	size_t tlen;
	bool onto = false;
	int first, rc;

	rc = cli_options(cmd, argc, argv, out, err, "ho:", opts, on_opt, &o, &first);
	if (rc >= 0)
		return rc;
	if (argc - first != 1)
		return cli_usage(cmd, err, "expected one file to import");
	path = argv[first];
	if (o.imp.rate_num > (o.has_tick ? o.imp.tick_hz : 1048576) * (uint64_t)o.imp.rate_den)
		return cli_usage(cmd, err, "--fps %u/%u is above the tick rate", o.imp.rate_num,
				 o.imp.rate_den);
	if (!o.has_tick) {
		/* 1000 ticks a second, or the next multiple of a whole frame rate
		 * (24 fps: 1008), so that every frame falls on a tick */
		uint32_t r = o.imp.rate_num / o.imp.rate_den;

		o.imp.tick_hz = 1000;
		if (o.imp.rate_den == 1 && 1000 % r)
			o.imp.tick_hz = (1000 / r + 1) * r;
	}
	rc = slurp(path, &buf, &len);
	if (!rc && o.merge)
		rc = slurp(o.merge, &mbuf, &mlen);
	if (rc) {
		fprintf(err, "strand import: %s: %s\n", rc && !buf ? path : o.merge, strerror(-rc));
		free(buf);
		return STRAND_EXIT_IO;
	}
	if (ends_with(path, ".urdf") || ends_with(path, ".xml"))
		rc = imp_urdf(&m, path, buf, len, &o.imp, err, msg, sizeof(msg));
	else if (ends_with(path, ".csv"))
		rc = imp_csv(&m, path, buf, len, &o.imp, err, msg, sizeof(msg));
	else {
		rc = 0;
		if (o.merge)
			rc = onto_joints(&m, path, buf, len, &o, err, msg, sizeof(msg), &onto);
		if (!rc && !onto)
			rc = imp_gltf(&m, path, buf, len, &o.imp, err, msg, sizeof(msg));
	}
	free(buf);
	if (rc) {
		fprintf(err, "%s: %s\n", path, rc == -ENOMEM ? "out of memory" : msg);
		imp_model_free(&m);
		free(mbuf);
		return rc == -EIO ? STRAND_EXIT_IO : STRAND_EXIT_SCENE;
	}
	if (mbuf && !onto && imp_has_strands(&m) && has_section((const char *)mbuf, "strands:")) {
		fprintf(err, "strand import: both %s and %s have strands; merge the nodes of one with the strands of the other\n",
			path, o.merge);
		imp_model_free(&m);
		free(mbuf);
		return STRAND_EXIT_USAGE;
	}
	text = NULL;
	tlen = 0;
	mem = open_memstream(&text, &tlen);
	if (!mem) {
		imp_model_free(&m);
		free(mbuf);
		return STRAND_EXIT_INTERNAL;
	}
	if (onto) {
		/* the animation's timing and strands, the scene's nodes and rig */
		static const char *const drop[] = { "timing:", "strands:", "scene:", NULL };

		rc = imp_yaml_write(mem, &m, IMP_YAML_TIMING | IMP_YAML_STRANDS);
		if (!rc)
			rc = merge(mem, o.merge, (const char *)mbuf, drop);
	} else {
		static const char *const drop[] = { "nodes:", "scene:", NULL };
		bool timing = !mbuf || !has_section((const char *)mbuf, "timing:");

		rc = imp_yaml_write(mem, &m, IMP_YAML_ALL & ~(timing ? 0 : IMP_YAML_TIMING));
		if (!rc && mbuf)
			rc = merge(mem, o.merge, (const char *)mbuf, drop);
	}
	if (fclose(mem))
		rc = -ENOMEM;
	imp_model_free(&m);
	free(mbuf);
	if (!rc)
		rc = check_scene(path, text, tlen, err);
	if (rc) {
		free(text);
		return rc < 0 ? STRAND_EXIT_INTERNAL : rc;
	}
	if (o.outpath && !(f = fopen(o.outpath, "w"))) {
		fprintf(err, "strand import: %s: %s\n", o.outpath, strerror(errno));
		free(text);
		return STRAND_EXIT_IO;
	}
	if (fwrite(text, 1, tlen, f) != tlen || (f != out && fclose(f)))
		rc = -EIO;
	free(text);
	if (rc) {
		fprintf(err, "strand import: %s: cannot write\n", o.outpath ? o.outpath : "stdout");
		return STRAND_EXIT_IO;
	}
	return STRAND_EXIT_OK;
}

const struct cli_cmd cmd_import = {
	.name = "import",
	.summary = "a scene file from glTF 2.0 (Blender), a URDF or a table",
	.help = "usage: strand import FILE.gltf|FILE.glb|FILE.urdf|FILE.csv [-o SCENE.yaml]\n"
		"                     [--fps N|N/D] [--tick-hz N] [--animation NAME|N]\n"
		"                     [--interpolation step|linear|hermite] [--merge SCENE.yaml]\n"
		"\n"
		"Writes a scene file that check, export, plot and play take, with a comment at\n"
		"its top saying where it came from, to stdout or -o SCENE.yaml.\n"
		"\n"
		"  glTF 2.0  every node a free node, parents first; each channel of the animation\n"
		"            (--animation, default the first) its keys at time x fps frames;\n"
		"            STEP, LINEAR (slerp) and CUBICSPLINE (tangents) as the file has them\n"
		"  URDF      links and joints as nodes in the rest pose's coordinates; revolute,\n"
		"            continuous and prismatic joints with their axis and limits; mimic\n"
		"  CSV       a 'frame' column, then NODE.angle, NODE.position columns (one\n"
		"            joint each; NODE.rpm is refused) or plain names (attributes);\n"
		"            --interpolation (default linear)\n"
		"\n"
		"  --fps N|N/D      frames per second (default 24); key frames are seconds x fps\n"
		"  --tick-hz N      the scene's tick rate (default 1000, or the next multiple of\n"
		"                   a whole frame rate: 1008 at 24 fps)\n"
		"  --merge SCENE    the imported nodes with SCENE's other sections (its timing,\n"
		"                   strands, camera, rig): a URDF's robot under a scene's motion;\n"
		"                   a glTF whose animated nodes name SCENE's joints drives them\n"
		"                   (SCENE's nodes and rig, the animation's timing and strands)\n"
		"\n"
		"exit codes: 0 ok, 2 the file is invalid (one line: FILE: where: what), 3 usage,\n"
		"4 a file cannot be read or written.\n",
	.run = run,
};
