/* SPDX-License-Identifier: MIT */
/*
 * cmd_check.c - `strand check SCENE`: validate a scene file, then every
 * joint limit over the whole timeline at tick resolution (limit_check.c).
 */
#include <getopt.h>
#include <string.h>

#include "check/check_bus.h"
#include "check/limit_check.h"
#include "cli.h"
#include "exitcode.h"
#include "scene/channel.h"

/* What each particle system's pool held at most, and the steps a system
 * takes: the proof that the pool is enough. */
static void check_pools(FILE *out, const struct mot_scene *sc, const struct scene_desc *d)
{
	uint32_t i;

	for (i = 0; i < sc->nsys; i++) {
		const struct mot_system *s = &sc->sys[i];

		if (s->kind == MOT_SYS_PARTICLES && s->particles->emit)
			fprintf(out, "particles '%s': at most %lld of %u slots alive at once, %lld "
				"dropped; %lld steps at %g a second\n", sd_sys_name(&d->sys[i]),
				(long long)s->particles->peak, s->particles->npool,
				(long long)s->particles->dropped, (long long)s->particles->steps.nsteps,
				(double)s->particles->steps.rate_num / s->particles->steps.rate_den);
	}
}

struct report {
	FILE *out;
	const struct scene_desc *d;
};

static void print_violation(void *ctx, const struct lim_violation *v)
{
	const struct report *r = ctx;
	const char *unit = v->angle ? "deg" : "units";
	const char *per = v->kind == LIM_VEL ? "/s" : v->kind == LIM_ACC ? "/s^2" : "";

	/* 7 digits: a velocity or acceleration is a difference of quantised
	 * values, and more digits would print only that noise (limit_check.h) */
	if (v->kind == LIM_POOL) {
		fprintf(r->out,
			"%s: the pool of %.0f slots runs out at frame %.10g: %.0f particles "
			"dropped over the span (raise pool:)\n",
			v->channel, v->limit, v->frame_first, v->worst);
		return;
	}
	if (v->kind == LIM_STOP) {
		fprintf(r->out,
			"%s: a controlled stop would end at %.7g %s, beyond limit %.7g %s, "
			"frames %.10g to %.10g\n",
			v->channel, v->worst, unit, v->limit, unit, v->frame_first, v->frame_last);
		return;
	}
	fprintf(r->out, "%s: %s %.7g %s%s beyond limit %.7g %s%s, frames %.10g to %.10g\n",
		v->channel, lim_kind_name(v->kind), v->worst, unit, per, v->limit, unit, per,
		v->frame_first, v->frame_last);
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	static const struct option opts[] = { { "help", no_argument, NULL, 'h' }, { 0 } };
	struct scene_file sf;
	struct scene_built b;
	struct lim_result res;
	struct report r;
	uint32_t joints;
	const char *path;
	int rc;

	rc = cli_scene_args(cmd, argc, argv, out, err, opts, NULL, NULL, &path, &sf, &b);
	if (rc >= 0)
		return rc;
	r.out = out;
	r.d = &sf.desc;
	if (lim_check(&sf.desc, &b.sc, (int64_t)sf.desc.frame_first, (int64_t)sf.desc.frame_last,
		      print_violation, &r, &res)) {
		fprintf(err, "strand check: out of memory\n");
		rc = STRAND_EXIT_INTERNAL;
	} else if (res.sat) {
		fprintf(err, "%s: the core's arithmetic saturated at frame %.10g: values too large for its Q32.32 format\n",
			path, res.sat_frame);
		rc = STRAND_EXIT_INTERNAL;
	} else {
		joints = res.joints;
		fprintf(out, "%s: %u violation%s; %u joint%s", path, res.violations,
			res.violations == 1 ? "" : "s", joints, joints == 1 ? "" : "s");
		if (res.channels)
			fprintf(out, " and %u system channel%s", res.channels,
				res.channels == 1 ? "" : "s");
		fprintf(out, " with limits, frames %g to %g, %lld ticks\n", sf.desc.frame_first,
			sf.desc.frame_last, (long long)res.ticks);
		if (sf.desc.nsys)
			check_pools(out, &b.sc, &sf.desc);
		check_buses(out, &sf.rig, sf.desc.tick_hz);
		rc = res.violations ? STRAND_EXIT_VIOLATION : STRAND_EXIT_OK;
	}
	scene_built_free(&b);
	scene_file_free(&sf);
	return rc;
}

const struct cli_cmd cmd_check = {
	.name = "check",
	.summary = "validate a scene and verify every joint limit at tick resolution",
	.help = "usage: strand check SCENE.yaml\n\n"
		"Validate the scene file, then play its whole span (timing.frames) at\n"
		"tick resolution, as the controller will, and compare every joint with its\n"
		"limits: min and max value, velocity and acceleration. Each run of ticks\n"
		"breaking a limit is one line:\n"
		"  CHANNEL: KIND WORST UNIT beyond limit LIMIT UNIT, frames FIRST to LAST\n"
		"then a summary line.\n\n"
		"exit codes: 0 within limits, 1 limits violated, 2 invalid scene, 3 usage,\n"
		"            4 I/O, 8 the core's arithmetic saturated\n",
	.run = run,
};
