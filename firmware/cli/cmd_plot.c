/* SPDX-License-Identifier: MIT */
/*
 * cmd_plot.c - `strand plot SCENE -o FILE.svg`: a picture read at a glance.
 * Top and side views of every node's world path, then each channel against
 * frames with its keys marked. `--compare NODE` instead draws one strand's
 * keys through every interpolation method on one chart, as the seed paper's
 * Figure 8 compares splines (report/plot.c, report/plot_compare.c).
 */
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "exitcode.h"
#include "report/plot.h"

/* ---- the command ------------------------------------------------------------------ */

struct opts {
	const char *output, *compare;
};

static int on_opt(void *ctx, int opt, const char *arg)
{
	struct opts *o = ctx;

	if (opt == 'o')
		o->output = arg;
	else if (opt == 'c')
		o->compare = arg;
	return -1;
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	static const struct option opts[] = {
		{ "help", no_argument, NULL, 'h' },
		{ "output", required_argument, NULL, 'o' },
		{ "compare", required_argument, NULL, 'c' },
		{ 0 },
	};
	struct opts o = { NULL, NULL };
	struct plot_samples ps = { 0 };
	struct chan_list ch = { 0 };
	struct scene_file sf;
	struct scene_built b;
	const char *path;
	int rc, e = 0, node = -1;
	FILE *f;

	rc = cli_scene_args(cmd, argc, argv, out, err, opts, on_opt, &o, &path, &sf, &b);
	if (rc >= 0)
		return rc;
	if (!o.output)
		rc = cli_usage(cmd, err, "-o FILE.svg is required");
	else if (o.compare && (node = scene_file_node(&sf, o.compare)) < 0)
		rc = cli_usage(cmd, err, "--compare: no node '%s' in %s", o.compare, path);
	else if (o.compare && !sf.strand[node].present)
		rc = cli_usage(cmd, err, "--compare: node '%s' has no strand", o.compare);
	if (rc >= 0)
		goto out;
	f = fopen(o.output, "w");
	if (!f) {
		fprintf(err, "%s: cannot write: %s\n", o.output, strerror(errno));
		rc = STRAND_EXIT_IO;
		goto out;
	}
	if (o.compare) {
		e = plot_compare(f, &sf, (uint32_t)node);
	} else {
		e = chan_list_make(&ch, &sf.desc);
		if (!e)
			e = plot_samples_make(&ps, &sf, &b.sc, &ch, sf.desc.frame_first,
					      sf.desc.frame_last,
					      plot_sample_count(sf.desc.frame_first,
								sf.desc.frame_last));
		if (!e)
			e = plot_overview(f, &sf, &b.sc, &ch, &ps);
	}
	rc = STRAND_EXIT_OK;
	if (ferror(f) | fclose(f)) {
		fprintf(err, "%s: cannot write\n", o.output);
		rc = STRAND_EXIT_IO;
	}
	if (e) {
		fprintf(err, "strand plot: out of memory\n");
		rc = STRAND_EXIT_INTERNAL;
	}
	plot_samples_free(&ps);
	chan_list_free(&ch);
out:
	scene_built_free(&b);
	scene_file_free(&sf);
	return rc;
}

const struct cli_cmd cmd_plot = {
	.name = "plot",
	.summary = "draw a scene as SVG: node paths, channels, or one strand's methods",
	.help = "usage: strand plot SCENE.yaml -o FILE.svg [--compare NODE]\n\n"
		"Draw the scene to an SVG file that opens in any browser: top (x, z) and\n"
		"side (x, y) views of every node's world path, then every channel against\n"
		"frames, keys ringed.\n\n"
		"  -o, --output FILE.svg   where to write the picture (required)\n"
		"  --compare NODE          instead, draw NODE's keys through every\n"
		"                          interpolation method on one chart (step, linear,\n"
		"                          hermite, bspline, beta, bezier): its joint value\n"
		"                          against frames, or a free node's side-view path\n\n"
		"exit codes: 0 ok, 2 invalid scene, 3 usage, 4 I/O\n",
	.run = run,
};
