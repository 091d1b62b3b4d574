/* SPDX-License-Identifier: MIT */
/* rig_auto.c - a simulated rig for a scene without one (see rig_auto.h). */
#include "rig_auto.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drv_sim.h"

/* The largest |speed| and |acceleration| (file units) of channel idx over
 * the span, by finite differences every `step` ticks. */
static int measure(struct play_source *src, uint32_t idx, bool turns, double *vmax, double *amax)
{
	const struct mot_timing *t = &src->timing;
	int64_t k0 = mot_timing_trigger_tick(t, src->frame_first);
	int64_t k1 = mot_timing_trigger_tick(t, src->frame_last), k, step = 1;
	double dt, prev = 0, v_prev = 0, scale = turns ? 360.0 : 1.0;
	mot_q32 val;
	uint32_t sat = 0;
	int rc = src_select(src, &idx, 1);

	if (rc)
		return rc;
	if (k1 - k0 > RIG_AUTO_TICKS)
		step = (k1 - k0) / RIG_AUTO_TICKS + 1;
	dt = (double)step / t->tick_hz;
	*vmax = *amax = 0;
	for (k = k0; k <= k1; k += step) {
		double x, v;

		src_eval(src, mot_timing_tick_frame(t, k), &val, &sat);
		x = (double)val / 4294967296.0 * scale;
		if (k > k0) {
			v = (x - prev) / dt;
			*vmax = fmax(*vmax, fabs(v));
			if (k > k0 + step)
				*amax = fmax(*amax, fabs(v - v_prev) / dt);
			v_prev = v;
		}
		prev = x;
	}
	return 0;
}

/* One output for channel `name` on the simulated drive, axis n. */
static int add(struct rig_auto *ra, const char *name, const struct sd_limits *lim, uint32_t n,
	       struct play_source *src)
{
	struct rig_output_desc *o = &ra->out[n];
	struct src_channel sc;
	bool turns;
	double v, a;
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
	/* a simulated rig stands where the scene begins: no long pre-roll */
	{
		uint32_t one = (uint32_t)idx, sat = 0;
		mot_q32 v0;

		rc = src_select(src, &one, 1);
		if (rc)
			return rc;
		src_eval(src, src->frame_first * MOT_Q32_ONE, &v0, &sat);
		o->home = (double)v0 / 4294967296.0 * (turns ? 360 : 1);
	}
	if (!o->limits.has_vel || !o->limits.has_acc) {
		rc = measure(src, (uint32_t)idx, turns, &v, &a);
		if (rc)
			return rc;
		if (!o->limits.has_vel) {
			o->limits.has_vel = true;
			o->limits.vel = fmax(v * RIG_AUTO_MARGIN, turns ? 1 : 1e-3);
		}
		if (!o->limits.has_acc) {
			/* and it reaches its top speed within half a second: a
			 * model turning at constant speed asks for no
			 * acceleration, but its run-up does */
			o->limits.has_acc = true;
			o->limits.acc = fmax(a * RIG_AUTO_MARGIN, 2 * o->limits.vel);
		}
	}
	return 0;
}

int rig_auto_build(struct rig_auto *ra, const struct scene_desc *d, struct play_source *src)
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
		rc = add(ra, name, &nd->limits, n++, src);
	}
	for (i = 0; !rc && d->has_camera && i < 6; i++)
		rc = add(ra, cam[i], NULL, n++, src);
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
