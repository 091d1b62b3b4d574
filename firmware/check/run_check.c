/* SPDX-License-Identifier: MIT */
/* run_check.c - the limit check of strand check, strand play and a live session
 * (run_check.h). */
#include "run_check.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "channels.h"
#include "plan/gomo.h"

static void on_violation(void *ctx, const struct lim_violation *v)
{
	struct run_check *c = ctx;
	char line[512];

	if (c->res.violations == 1)
		c->first = *v;
	if (c->out) {
		run_check_line(line, sizeof(line), c, v);
		fprintf(c->out, "%s\n", line);
	}
}

int run_check_options(const struct lim_run *r, char *msg, size_t size)
{
	const char *why = NULL;

	if (r->step && (r->loop || r->ping_pong))
		why = "--loop and --ping-pong are for continuous mode";
	else if (r->loop && r->ping_pong)
		why = "--loop or --ping-pong, not both";
	else if (r->passes && !r->loop && !r->ping_pong)
		why = "--passes goes with --loop or --ping-pong";
	else if (r->shutter && !r->step)
		why = "--shutter is go-motion, for --mode step";
	else if (!r->step && r->to < r->from)
		return snprintf(msg, size, "--from %lld is after --to %lld", (long long)r->from,
				(long long)r->to), -EINVAL;
	else if (!r->step && r->ping_pong && r->to == r->from)
		why = "--ping-pong needs at least two frames";
	if (!why)
		return 0;
	snprintf(msg, size, "%s", why);
	return -EINVAL;
}

int run_check_shutter(const struct mot_timing *t, mot_q32 s, char *msg, size_t size)
{
	if (!s || !gomo_shutter_check(t, s))
		return 0;
	snprintf(msg, size, "--shutter: an exposure of %.6g ms is shorter than two ticks (%.6g ms "
		 "at tick_hz %u): go-motion needs the scene's speed",
		 (double)s / 4294967296.0 * t->den / t->num * 1000, 2000.0 / t->tick_hz,
		 t->tick_hz);
	return -EINVAL;
}

int run_check(struct run_check *c, struct source_scene *ss, const struct rig_desc *rig,
	      struct lim_run *run)
{
	int rc = lim_channels(ss, rig, &c->ch, &c->n);

	if (rc)
		return rc;
	lim_run_triggers(rig, &ss->s.timing, &run->lead, &run->tail);
	return lim_check(&ss->s, c->ch, c->n, run, on_violation, c, &c->res);
}

void run_check_free(struct run_check *c)
{
	free(c->ch);
	c->ch = NULL;
}

uint32_t run_check_count(const struct run_check *c)
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

void run_check_line(char *buf, size_t size, const struct run_check *c,
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
