/* SPDX-License-Identifier: MIT */
/* limits.c - the limit check of strand check and strand play (see limits.h). */
#include "limits.h"

#include <math.h>
#include <stdlib.h>

#include "check/channels.h"
#include "plan/gomo.h"
#include "cli.h"
#include "opt.h"

static void on_violation(void *ctx, const struct lim_violation *v)
{
	struct cli_limits *c = ctx;
	char line[512];

	if (c->res.violations == 1)
		c->first = *v;
	if (c->out) {
		cli_limits_line(line, sizeof(line), c, v);
		fprintf(c->out, "%s\n", line);
	}
}

int cli_limits_usage(const struct cli_cmd *cmd, FILE *err, const struct lim_run *r)
{
	if (r->step && (r->loop || r->ping_pong))
		return cli_usage(cmd, err, "--loop and --ping-pong are for continuous mode");
	if (r->loop && r->ping_pong)
		return cli_usage(cmd, err, "--loop or --ping-pong, not both");
	if (r->passes && !r->loop && !r->ping_pong)
		return cli_usage(cmd, err, "--passes goes with --loop or --ping-pong");
	if (r->shutter && !r->step)
		return cli_usage(cmd, err, "--shutter is go-motion, for --mode step");
	if (r->step)
		return -1;
	if (r->to < r->from)
		return cli_usage(cmd, err, "--from %lld is after --to %lld", (long long)r->from,
				 (long long)r->to);
	if (r->ping_pong && r->to == r->from)
		return cli_usage(cmd, err, "--ping-pong needs at least two frames");
	return -1;
}

int cli_shutter_arg(const struct cli_cmd *cmd, FILE *err, const char *arg, mot_q32 *s)
{
	double a;

	if (!opt_double(arg, 0, 360, &a) || !gomo_shutter_of_angle(a, s))
		return cli_usage(cmd, err, "--shutter %s: a shutter angle in degrees, above 0 and "
				 "at most 360", arg);
	return -1;
}

int cli_shutter_usage(const struct cli_cmd *cmd, FILE *err, const struct mot_timing *t,
		      mot_q32 s)
{
	double ms = (double)s / 4294967296.0 * t->den / t->num * 1000;

	if (!s || !gomo_shutter_check(t, s))
		return -1;
	return cli_usage(cmd, err, "--shutter: an exposure of %.6g ms is shorter than two ticks "
			 "(%.6g ms at tick_hz %u): go-motion needs the scene's speed", ms,
			 2000.0 / t->tick_hz, t->tick_hz);
}

int cli_limits_run(struct cli_limits *c, struct source_scene *ss, const struct rig_desc *rig,
		   struct lim_run *run)
{
	int rc = lim_channels(ss, rig, &c->ch, &c->n);

	if (rc)
		return rc;
	lim_run_triggers(rig, &ss->s.timing, &run->lead, &run->tail);
	return lim_check(&ss->s, c->ch, c->n, run, on_violation, c, &c->res);
}

void cli_limits_free(struct cli_limits *c)
{
	free(c->ch);
	c->ch = NULL;
}

uint32_t cli_limits_count(const struct cli_limits *c)
{
	uint32_t i, k = 0;

	for (i = 0; i < c->n; i++) {
		const struct lim_bounds *b = &c->ch[i].lim;

		k += isfinite(b->min) || isfinite(b->max) || isfinite(b->vel) || isfinite(b->acc);
	}
	return k;
}

static const char *unit_name(enum src_unit u)
{
	return u == SRC_UNIT_TURNS ? "deg" : u == SRC_UNIT_RPM ? "rpm" : "units";
}

void cli_limits_line(char *buf, size_t size, const struct cli_limits *c,
		     const struct lim_violation *v)
{
	const struct lim_channel *ch = &c->ch[v->channel];
	const char *unit = unit_name(ch->unit);
	const char *per = v->kind == LIM_VEL ? "/s" : v->kind == LIM_ACC ? "/s^2" : "";
	const char *back = v->dir < 0 ? " (backwards)" : "";
	const char *gomo = v->gomo ? "go-motion " : "";
	double worst = lim_file_units(ch->unit, v->worst);
	double limit = lim_file_units(ch->unit, v->limit);
	char where[160];

	/* 7 digits: a velocity or acceleration is a difference of quantised
	 * values, and more digits would print only that noise (plan/limit.h) */
	switch (v->seg) {
	case LIM_SEG_RUNUP:
		if (v->kind == LIM_MIN || v->kind == LIM_MAX) {
			snprintf(buf, size, "%s: the %srun-up into frame %.10g%s starts at %.7g %s, "
				 "beyond limit %.7g %s; %s", ch->name, gomo, v->frame_first, back,
				 worst, unit, limit, unit, v->gomo ?
				 "it moves too fast there to come up to its speed from rest inside "
				 "its limits" : "start from a frame where it moves slower");
			return;
		}
		snprintf(where, sizeof(where), "in the %srun-up into frame %.10g%s", gomo,
			 v->frame_first, back);
		break;
	case LIM_SEG_POSTROLL:
		snprintf(where, sizeof(where), "in the %s after frame %.10g%s",
			 v->gomo ? "go-motion run-out" : "post-roll", v->frame_last, back);
		break;
	case LIM_SEG_FRAME:
		snprintf(where, sizeof(where), "at frames %.10g to %.10g (step mode)", v->frame_first,
			 v->frame_last);
		break;
	default:
		snprintf(where, sizeof(where), "frames %.10g to %.10g%s%s", v->frame_first,
			 v->frame_last, back, v->gomo ? " (go-motion exposure)" : "");
		break;
	}
	if (v->kind == LIM_STOP)
		snprintf(buf, size, "%s: a controlled stop would end at %.7g %s, beyond limit %.7g "
			 "%s, %s", ch->name, worst, unit, limit, unit, where);
	else
		snprintf(buf, size, "%s: %s %.7g %s%s beyond limit %.7g %s%s, %s", ch->name,
			 lim_kind_name(v->kind), worst, unit, per, limit, unit, per, where);
}
