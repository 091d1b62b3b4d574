/* SPDX-License-Identifier: MIT */
/* rig_auto.c - a simulated rig for a scene without one (see rig_auto.h). */
#include "rig_auto.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drv_sim.h"
#include "plan/limit.h"
#include "plan/timeline.h"

/*
 * The acceleration a channel with position limits needs so that a stop
 * after this sample (move_stop_distance: at most v^2 / 2a) comes to rest
 * before the limit it moves toward: 0 when it moves away, or is beyond
 * it (the scene's own violation, reported as one).
 */
static double stop_need(const struct lim_bounds *b, const struct lim_measure *me, uint32_t hz)
{
	double m = me->v1 > 0 ? b->max - me->x : me->x - b->min;

	if (me->v1 == 0 || !isfinite(m) || m < 0)
		return 0;
	return m > 0 ? me->v1 * me->v1 / (2 * m) : fabs(me->v1) * hz;
}

/*
 * The acceleration the run-up into the span needs to start inside the
 * position limit behind the first pose (runup.h: a ramp of n ticks starts
 * v dt (n + 1) / 2 behind it): 0 when any will do, or when none can (a
 * span starting on its limit with a speed; refused as such).
 */
static double runup_need(const struct lim_bounds *b, double x0, double v0, uint32_t hz)
{
	double m = v0 > 0 ? x0 - b->min : b->max - x0, nmax;

	if (v0 == 0 || !isfinite(m))
		return 0;
	nmax = floor(2 * m * hz / fabs(v0)) - 1;
	return nmax >= 1 ? fabs(v0) * hz / nmax : 0;
}

/*
 * The largest |speed| and |acceleration| (core units) of the outputs'
 * channels over the span as a run plays it (plan/timeline.h: the ticks of
 * the span and the last frame's, just beyond), measured as the limit
 * predicate measures them (plan/limit.h), every tick, all channels in one
 * walk; and in need[] the acceleration their position limits ask for, so
 * that the run-up starts and every stop (the post-roll's too) ends inside
 * them.
 */
static int measure(struct rig_auto *ra, uint32_t n, struct play_source *src, double *vmax,
		   double *amax, double *need)
{
	const struct mot_timing *t = &src->timing;
	struct lim_stencil st;
	struct timeline tl;
	struct lim_meter *m = calloc(n, sizeof(*m));
	struct lim_bounds *b = calloc(n, sizeof(*b));
	uint32_t *sel = calloc(n, sizeof(*sel)), i, sat = 0;
	bool *extend = calloc(n, sizeof(*extend));
	mot_q32 *q;
	int64_t k, k1;
	int rc = -ENOMEM;

	lim_stencil_init(&st, t->tick_hz);
	q = calloc(n * (1 + TIMELINE_WORDS(1) + LIM_METER_LEN(st.h)), sizeof(*q));
	if (!m || !b || !sel || !extend || !q)
		goto out;
	for (i = 0; i < n; i++) {
		struct src_channel sc;
		int idx = src_lookup(src, ra->out[i].channel, &sc);

		if (idx < 0) {
			rc = idx;
			goto out;
		}
		sel[i] = (uint32_t)idx;
		extend[i] = timeline_extends(sc.unit);
		lim_meter_reset(&m[i], &st, q + n * (1 + TIMELINE_WORDS(1)) + i * LIM_METER_LEN(st.h),
				0, false);
		vmax[i] = amax[i] = need[i] = 0;
		b[i] = lim_bounds_of(&ra->out[i].limits, sc.unit);
	}
	rc = src_select(src, sel, n);
	if (rc)
		goto out;
	timeline_init(&tl, src, n, extend, src->frame_first, src->frame_last, q + n, &sat);
	for (i = 0; i < n; i++)
		need[i] = runup_need(&b[i], (double)tl.x0[i] / 4294967296.0,
				     (double)tl.d0[i] / 4294967296.0 * t->tick_hz, t->tick_hz);
	k1 = mot_timing_trigger_tick(t, src->frame_last);
	for (k = tl.k0; k <= k1; k++) {
		timeline_eval(&tl, k, q, &sat);
		for (i = 0; i < n; i++) {
			struct lim_measure me;

			lim_measure(&m[i], &st, q[i], &me);
			if (me.has_v)
				vmax[i] = fmax(vmax[i], fabs(me.v));
			if (me.has_a)
				amax[i] = fmax(amax[i], fabs(me.a));
			if (me.has_v)
				need[i] = fmax(need[i], stop_need(&b[i], &me, t->tick_hz));
			lim_meter_push(&m[i], q[i]);
		}
	}
	rc = 0;
out:
	free(m);
	free(b);
	free(sel);
	free(extend);
	free(q);
	return rc;
}

/* One output for channel `name` on the simulated drive, axis n, standing
 * at frame `home`'s pose. */
static int add(struct rig_auto *ra, const char *name, const struct sd_limits *lim, uint32_t n,
	       struct play_source *src, int64_t home)
{
	struct rig_output_desc *o = &ra->out[n];
	struct src_channel sc;
	uint32_t one, sat = 0;
	mot_q32 v0;
	bool turns;
	int idx = src_lookup(src, name, &sc), rc;

	if (idx < 0)
		return idx;
	turns = sc.unit == SRC_UNIT_TURNS;
	o->channel = name;
	o->device = "sim";
	o->axis = n;
	o->counts_per_unit = turns ? 1000 : 1000000; /* millidegrees, micrometres */
	if (lim)
		o->limits = *lim;
	/* a simulated rig stands where the run begins: no long pre-roll */
	one = (uint32_t)idx;
	rc = src_select(src, &one, 1);
	if (rc)
		return rc;
	src_eval(src, home * MOT_Q32_ONE, &v0, &sat);
	o->home = lim_file_units(sc.unit, (double)v0 / 4294967296.0);
	return 0;
}

/* Speed and acceleration limits where the scene gives none: the channels'
 * own, measured, with a margin (rig_auto.h). */
static int derive(struct rig_auto *ra, uint32_t n, struct play_source *src)
{
	double *v = calloc(n ? n : 1, sizeof(*v)), *a = calloc(n ? n : 1, sizeof(*a));
	double *need = calloc(n ? n : 1, sizeof(*need));
	uint32_t i;
	int rc = -ENOMEM;

	if (v && a && need)
		rc = measure(ra, n, src, v, a, need);
	for (i = 0; !rc && i < n; i++) {
		struct sd_limits *l = &ra->out[i].limits;
		struct src_channel sc;
		bool turns;

		src_lookup(src, ra->out[i].channel, &sc);
		turns = sc.unit == SRC_UNIT_TURNS;
		if (!l->has_vel) {
			l->has_vel = true;
			l->vel = fmax(lim_file_units(sc.unit, v[i]) * RIG_AUTO_MARGIN,
				      turns ? 1 : 1e-3);
		}
		if (!l->has_acc) {
			/* and it reaches its top speed within half a second: a
			 * model turning at constant speed asks for no
			 * acceleration, but its run-up does */
			l->has_acc = true;
			l->acc = fmax(lim_file_units(sc.unit, fmax(a[i], need[i])) * RIG_AUTO_MARGIN,
				      2 * l->vel);
		}
	}
	free(v);
	free(a);
	free(need);
	return rc;
}

int rig_auto_build(struct rig_auto *ra, const struct scene_desc *d, struct play_source *src,
		   int64_t home)
{
	static const char *const cam[] = { "camera.x",	 "camera.y",    "camera.z",
					   "camera.pan", "camera.tilt", "camera.roll" };
	uint32_t i, n = 0;
	int rc = 0;

	memset(ra, 0, sizeof(*ra));
	ra->out = calloc(d->nnodes + 6, sizeof(*ra->out));
	ra->names = calloc(d->nnodes ? d->nnodes : 1, sizeof(*ra->names));
	if (!ra->out || !ra->names) {
		rig_auto_free(ra);
		return -ENOMEM;
	}
	for (i = 0; !rc && i < d->nnodes; i++) {
		const struct sd_node *nd = &d->nodes[i];
		char *name;

		if (nd->kind == MOT_NODE_FREE)
			continue;
		name = malloc(strlen(nd->name) + 10);
		if (!name) {
			rc = -ENOMEM;
			break;
		}
		sprintf(name, "%s.%s", nd->name, nd->kind == MOT_NODE_REVOLUTE ? "angle" : "position");
		ra->names[ra->nnames++] = name;
		rc = add(ra, name, &nd->limits, n++, src, home);
	}
	for (i = 0; !rc && d->has_camera && i < 6; i++)
		rc = add(ra, cam[i], NULL, n++, src, home);
	if (!rc)
		rc = derive(ra, n, src);
	if (rc) {
		rig_auto_free(ra);
		return rc;
	}
	ra->dev[0].name = "sim";
	ra->dev[0].driver = &rig_drv_sim;
	ra->dev[1].name = "io";
	ra->dev[1].driver = &rig_drv_sim;
	ra->trig.name = "camera";
	ra->trig.device = "io";
	ra->trig.pulse_ms = 1000.0 / src->timing.tick_hz;
	ra->d.ndevices = 2;
	ra->d.devices = ra->dev;
	ra->d.noutputs = n;
	ra->d.outputs = ra->out;
	ra->d.ntriggers = 1;
	ra->d.triggers = &ra->trig;
	return 0;
}

void rig_auto_free(struct rig_auto *ra)
{
	uint32_t i;

	for (i = 0; i < ra->nnames; i++)
		free(ra->names[i]);
	free(ra->names);
	free(ra->out);
	memset(ra, 0, sizeof(*ra));
}
