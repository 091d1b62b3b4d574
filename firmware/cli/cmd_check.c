/* SPDX-License-Identifier: MIT */
/*
 * cmd_check.c - `strand check SCENE`: validate a scene file, then walk what
 * a run would play, tick by tick, against every limit the run would hold
 * its channels to (check/run_check.h), and its CAN buses' load.
 */
#include <getopt.h>
#include <string.h>

#include "check/check_bus.h"
#include "check/pools.h"
#include "check/run_check.h"
#include "cli.h"
#include "exitcode.h"
#include "opt.h"
#include "rig/rig_auto.h"

enum { OPT_SIM = 256, OPT_MODE, OPT_FROM, OPT_TO, OPT_LOOP, OPT_PING_PONG, OPT_PASSES,
       OPT_SHUTTER };

static const struct option check_options[] = {
	{ "sim", no_argument, NULL, OPT_SIM },
	{ "mode", required_argument, NULL, OPT_MODE },
	{ "from", required_argument, NULL, OPT_FROM },
	{ "to", required_argument, NULL, OPT_TO },
	{ "loop", no_argument, NULL, OPT_LOOP },
	{ "ping-pong", no_argument, NULL, OPT_PING_PONG },
	{ "passes", required_argument, NULL, OPT_PASSES },
	{ "shutter", required_argument, NULL, OPT_SHUTTER },
	{ "help", no_argument, NULL, 'h' },
	{ NULL, 0, NULL, 0 },
};

struct opts {
	const struct cli_cmd *cmd;
	FILE *err;
	struct lim_run run;
	bool sim, have_from, have_to;
};

static int on_opt(void *ctx, int opt, const char *arg)
{
	struct opts *o = ctx;
	long long v;

	switch (opt) {
	case OPT_SIM:
		o->sim = true;
		return -1;
	case OPT_MODE:
		if (strcmp(arg, "continuous") && strcmp(arg, "step"))
			return cli_usage(o->cmd, o->err, "--mode %s: continuous or step", arg);
		o->run.step = !strcmp(arg, "step");
		return -1;
	case OPT_FROM:
	case OPT_TO:
		if (!opt_long(arg, 0, INT32_MAX, &v))
			return cli_usage(o->cmd, o->err, "%s %s: a frame number",
					 opt == OPT_FROM ? "--from" : "--to", arg);
		if (opt == OPT_FROM) {
			o->run.from = v;
			o->have_from = true;
		} else {
			o->run.to = v;
			o->have_to = true;
		}
		return -1;
	case OPT_LOOP:
		o->run.loop = true;
		return -1;
	case OPT_PING_PONG:
		o->run.ping_pong = true;
		return -1;
	case OPT_PASSES:
		if (!opt_long(arg, 1, INT32_MAX, &v))
			return cli_usage(o->cmd, o->err, "--passes %s: a count of 1 or more", arg);
		o->run.passes = v;
		return -1;
	case OPT_SHUTTER:
		return cli_shutter_arg(o->cmd, o->err, arg, &o->run.shutter);
	default:
		return cli_usage(o->cmd, o->err, "unknown option");
	}
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	struct opts o = { .cmd = cmd, .err = err };
	struct run_check lc = { .out = out };
	struct scene_file sf;
	struct scene_built b;
	struct source_scene ss;
	struct rig_auto ra;
	const struct rig_desc *rig;
	const char *path;
	int64_t ticks;
	uint32_t pools;
	int rc;

	rc = cli_scene_args(cmd, argc, argv, out, err, check_options, on_opt, &o, &path, &sf, &b);
	if (rc >= 0)
		return rc;
	memset(&ra, 0, sizeof(ra));
	rc = STRAND_EXIT_INTERNAL;
	if (source_scene_init(&ss, &sf.desc, &b.sc)) {
		fprintf(err, "strand check: out of memory\n");
		goto out_scene;
	}
	if (!o.have_from)
		o.run.from = ss.s.frame_first;
	if (!o.have_to)
		o.run.to = ss.s.frame_last;
	o.run.expose_first = o.run.from;
	o.run.expose_last = o.run.to;
	if (o.run.step && o.run.shutter) {
		/* go-motion runs the scene's own motion over its span and the
		 * frames shot (strand play's loop.from and loop.to) */
		int64_t lo = o.run.from < o.run.to ? o.run.from : o.run.to;
		int64_t hi = o.run.from ^ o.run.to ^ lo;

		o.run.from = lo < ss.s.frame_first ? lo : ss.s.frame_first;
		o.run.to = hi > ss.s.frame_last ? hi : ss.s.frame_last;
	}
	rc = cli_limits_usage(cmd, err, &o.run);
	if (rc < 0)
		rc = cli_shutter_usage(cmd, err, &ss.s.timing, o.run.shutter);
	if (rc >= 0)
		goto out;
	rig = &sf.rig;
	if (o.sim && !rig->noutputs && !rig->ntriggers) {
		/* the rig strand play --sim makes for a scene without one,
		 * standing at the first frame asked for, as play's does */
		rc = STRAND_EXIT_INTERNAL;
		if (rig_auto_build(&ra, &sf.desc, &ss.s, o.run.expose_first)) {
			fprintf(err, "strand check: out of memory\n");
			goto out;
		}
		rig = &ra.d;
	}
	rc = run_check(&lc, &ss, rig, &o.run);
	if (rc) {
		fprintf(err, "strand check: %s\n", strerror(-rc));
		rc = STRAND_EXIT_INTERNAL;
	} else if (lc.res.sat) {
		fprintf(err, "%s: the core's arithmetic saturated at frame %.10g: values too large "
			"for its Q32.32 format\n", path, lc.res.sat_frame);
		rc = STRAND_EXIT_INTERNAL;
	} else {
		/* the frames asked for (go-motion's range reaches further) */
		int64_t from = o.run.shutter ? o.run.expose_first : o.run.from;
		int64_t to = o.run.shutter ? o.run.expose_last : o.run.to;

		ticks = mot_timing_trigger_tick(&ss.s.timing, to) -
			mot_timing_trigger_tick(&ss.s.timing, from) + 1;
		/* a particle pool that runs out is a violation too */
		pools = lim_pools(out, NULL, &sf.desc, &b.sc, o.run.to, NULL, 0);
		fprintf(out, "%s: %u violation%s; %u channel%s with limits, frames %lld to %lld, "
			"%lld ticks\n", path, lc.res.violations + pools,
			lc.res.violations + pools == 1 ? "" : "s",
			run_check_count(&lc), run_check_count(&lc) == 1 ? "" : "s",
			(long long)from, (long long)to, (long long)ticks);
		check_buses(out, rig, sf.desc.tick_hz);
		lim_pools(NULL, out, &sf.desc, &b.sc, o.run.to, NULL, 0);
		rc = lc.res.violations || pools ? STRAND_EXIT_VIOLATION : STRAND_EXIT_OK;
	}
out:
	run_check_free(&lc);
	rig_auto_free(&ra);
	source_scene_free(&ss);
out_scene:
	scene_built_free(&b);
	scene_file_free(&sf);
	return rc;
}

const struct cli_cmd cmd_check = {
	.name = "check",
	.summary = "validate a scene and verify every limit over what a run plays",
	.help = "usage: strand check SCENE.yaml [--from F] [--to F] [--loop | --ping-pong]\n"
		"                   [--passes N] [--mode continuous|step] [--shutter ANGLE]\n"
		"                   [--sim]\n\n"
		"Validate the scene file, then walk what strand play would play, tick by tick,\n"
		"as the controller will: the run-up into each pass, the scene's ticks, the\n"
		"post-roll to rest. Every channel the rig drives is held to its output's limits\n"
		"(its node's where the output gives none), every other joint to its node's:\n"
		"min and max value, velocity, acceleration, and where a controlled stop would\n"
		"leave it; every particle system's pool, that its slots suffice. Each run of\n"
		"ticks breaking a limit is one line:\n"
		"  CHANNEL: KIND WORST UNIT beyond limit LIMIT UNIT, frames FIRST to LAST\n"
		"then a summary line. The options are strand play's, and check what such a run\n"
		"plays (default: the scene's span, once); --mode step --shutter ANGLE walks\n"
		"go-motion: each frame's run-up from rest, its exposure of ANGLE/360 of a frame\n"
		"centred on it, and its run-out to rest; --sim checks a scene without a rig\n"
		"against the simulated rig strand play --sim makes for it.\n\n"
		"exit codes: 0 within limits, 1 limits violated, 2 invalid scene, 3 usage,\n"
		"            4 I/O, 8 the core's arithmetic saturated\n",
	.run = run,
};
