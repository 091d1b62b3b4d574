/* SPDX-License-Identifier: MIT */
/*
 * rig_desc.c - the rules a rig description follows (see rig_desc.h), once:
 * the loader refuses a scene file by them, with the place in the file, and
 * rig_build() a description made in code, naming the entry. So `strand
 * check` and `strand play` can never disagree about what a rig may be.
 */
#include "rig_desc.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rig_driver.h"

int rig_output_check_scale(const struct rig_output_desc *o, bool turns, char *msg,
			   size_t size)
{
	double scale = fabs(o->counts_per_unit) * (turns ? 360 : 1);

	/* a scale is Q32.32 counts per core unit (scale.h) */
	if (!isfinite(scale) || o->counts_per_unit == 0 || scale >= 2147483648.0) {
		snprintf(msg, size, "counts_per_unit must be non-zero and below 2^31 counts per %s",
			 turns ? "turn" : "unit");
		return -ERANGE;
	}
	if (scale < RIG_SCALE_MIN) {
		snprintf(msg, size, "counts_per_unit %.6g is %.6g counts per %s, below %g",
			 o->counts_per_unit, scale, turns ? "turn" : "unit", RIG_SCALE_MIN);
		return -ERANGE;
	}
	return 0;
}

double rig_output_home_counts(const struct rig_output_desc *o)
{
	return o->home * o->counts_per_unit + o->offset;
}

int rig_output_check_home(const struct rig_output_desc *o, char *msg, size_t size)
{
	double counts = rig_output_home_counts(o);

	/* counts are int64_t (scale.h) */
	if (!isfinite(counts) || fabs(counts) > 9e18) {
		snprintf(msg, size, "home %.10g is %.6g counts, beyond +-9e18", o->home, counts);
		return -ERANGE;
	}
	return 0;
}

int rig_sim_check(const struct rig_sim_desc *s, const char **key, char *msg, size_t size)
{
	static const struct {
		const char *key;
		size_t at;
		double min, max;
		const char *unit;
	} r[] = {
		{ "bandwidth", offsetof(struct rig_sim_desc, bandwidth_hz), RIG_SIM_BANDWIDTH_MIN,
		  RIG_SIM_BANDWIDTH_MAX, " Hz" },
		{ "damping", offsetof(struct rig_sim_desc, damping), RIG_SIM_DAMPING_MIN,
		  RIG_SIM_DAMPING_MAX, "" },
		{ "feedforward", offsetof(struct rig_sim_desc, feedforward), 0, 1, "" },
		{ "limit_factor", offsetof(struct rig_sim_desc, limit_factor),
		  RIG_SIM_LIMIT_FACTOR_MIN, RIG_SIM_LIMIT_FACTOR_MAX, "" },
		{ "exposure_ms", offsetof(struct rig_sim_desc, exposure_ms), 0,
		  RIG_SIM_CAMERA_MS_MAX, " ms" },
		{ "readout_ms", offsetof(struct rig_sim_desc, readout_ms), 0, RIG_SIM_CAMERA_MS_MAX,
		  " ms" },
	};
	size_t i;

	for (i = 0; i < sizeof(r) / sizeof(r[0]); i++) {
		double v = *(const double *)((const char *)s + r[i].at);

		/* 0: not given, the twin's default */
		if (v == 0 || (v >= r[i].min && v <= r[i].max))
			continue;
		*key = r[i].key;
		snprintf(msg, size, "%s %.6g is %s %g%s", r[i].key, v, v > r[i].max ? "above" :
			 "below", v > r[i].max ? r[i].max : r[i].min, r[i].unit);
		return -ERANGE;
	}
	return 0;
}

int rig_output_check_offset(const struct rig_output_desc *o, char *msg, size_t size)
{
	/* counts are int64_t, with room for the motion on top */
	if (!isfinite(o->offset) || fabs(o->offset) > 9e18) {
		snprintf(msg, size, "offset out of range");
		return -ERANGE;
	}
	return 0;
}

int rig_output_check_ferror(const struct rig_output_desc *o, bool *at_min, char *msg,
			    size_t size)
{
	*at_min = false;
	if (o->ferror < 0 || o->min_ferror < 0 || o->in_position < 0) {
		snprintf(msg, size, "ferror, min_ferror and in_position cannot be negative");
		return -EINVAL;
	}
	/* the bound scales from min_ferror at rest to ferror at full speed */
	if (o->ferror > 0 && o->min_ferror > o->ferror) {
		*at_min = true;
		snprintf(msg, size, "min_ferror %.10g is above ferror %.10g", o->min_ferror,
			 o->ferror);
		return -EINVAL;
	}
	return 0;
}

void rig_output_limits(const struct sd_limits *own, const struct sd_limits *scene,
		       struct sd_limits *out)
{
	static const struct sd_limits none;
	const struct sd_limits *b = scene ? scene : &none;
	struct sd_limits l = *own;

	if (!l.has_min && b->has_min) {
		l.has_min = true;
		l.min = b->min;
	}
	if (!l.has_max && b->has_max) {
		l.has_max = true;
		l.max = b->max;
	}
	if (!l.has_vel && b->has_vel) {
		l.has_vel = true;
		l.vel = b->vel;
	}
	if (!l.has_acc && b->has_acc) {
		l.has_acc = true;
		l.acc = b->acc;
	}
	*out = l;
}

int rig_output_check_limits(const char *channel, const struct sd_limits *lim, bool node,
			    char *msg, size_t size)
{
	if (!lim->has_vel || !lim->has_acc || !(lim->vel > 0) || !(lim->acc > 0) ||
	    !isfinite(lim->vel) || !isfinite(lim->acc)) {
		snprintf(msg, size,
			 "output '%s' needs velocity and acceleration limits (here%s): the "
			 "pre-roll, the moves and every stop are planned with them", channel,
			 node ? " or on its node" : "");
		return -EINVAL;
	}
	if (lim->vel < RIG_LIMIT_RATE_MIN || lim->acc < RIG_LIMIT_RATE_MIN) {
		snprintf(msg, size, "%s limit %.6g is below %g a second%s (too slow to plan a "
			 "move with)", lim->vel < RIG_LIMIT_RATE_MIN ?
			 "velocity" : "acceleration", lim->vel < RIG_LIMIT_RATE_MIN ? lim->vel :
			 lim->acc, RIG_LIMIT_RATE_MIN, lim->vel < RIG_LIMIT_RATE_MIN ? "" :
			 " squared");
		return -ERANGE;
	}
	if (lim->has_min && lim->has_max && lim->min > lim->max) {
		snprintf(msg, size, "limit max %.10g is below min %.10g", lim->max, lim->min);
		return -EINVAL;
	}
	return 0;
}

int rig_trigger_check(const struct rig_trigger_desc *g, const struct mot_timing *t,
		      int64_t *width, int64_t *offset, bool *at_offset, char *msg, size_t size)
{
	/* the shortest gap between two frame ticks: floor(ticks per frame) */
	double gap = (double)(t->ticks_den / t->num);
	double frame_ms = 1000.0 * t->den / t->num, tick_ms = 1000.0 / t->tick_hz;
	/* whole ticks, at least one; in doubles until they are known to fit */
	double w = fmax(ceil(g->pulse_ms * t->tick_hz / 1000.0 - 1e-9), 1);
	double off = round(g->offset_ms * t->tick_hz / 1000.0);

	*at_offset = false;
	if (!(w < gap)) {
		snprintf(msg, size, "a %.10g ms pulse does not end before the next frame's (frames "
			 "are %.6g ms apart, ticks %.6g ms)", g->pulse_ms, frame_ms, tick_ms);
		return -EINVAL;
	}
	*at_offset = true;
	if (!(fabs(g->offset_ms) < frame_ms)) {
		snprintf(msg, size, "offset %.10g ms is a frame (%.6g ms) or more", g->offset_ms,
			 frame_ms);
		return -EINVAL;
	}
	/* less than a frame, but as many ticks as two frame ticks may be apart */
	if (!(fabs(off) < gap)) {
		snprintf(msg, size, "offset %.10g ms is %.0f ticks: frame ticks may be only %.0f "
			 "apart", g->offset_ms, fabs(off), gap);
		return -EINVAL;
	}
	*at_offset = false;
	*width = (int64_t)w;
	*offset = (int64_t)off;
	return 0;
}

int rig_desc_validate(const struct rig_desc *d, uint32_t tick_hz, struct rig_desc_err *e)
{
	const struct rig_driver *const *drv;
	int rc;

	e->output = e->device = -1;
	e->key = NULL;
	e->msg[0] = '\0';
	for (drv = rig_drivers; *drv; drv++)
		if ((*drv)->validate && (rc = (*drv)->validate(d, tick_hz, e)))
			return rc;
	return 0;
}

/* ---- one board's part of the rig ------------------------------------------ */

static bool on_board(const struct rig_desc *in, const struct rig_board_desc *b, const char *dev)
{
	uint32_t i;

	for (i = 0; i < b->ndevices; i++)
		if (!strcmp(in->devices[b->devices[i]].name, dev))
			return true;
	return false;
}

int rig_desc_board(const struct rig_desc *in, uint32_t b, struct rig_desc *out)
{
	const struct rig_board_desc *bd = &in->boards[b];
	struct rig_device_desc *dev;
	struct rig_output_desc *o;
	struct rig_trigger_desc *t;
	struct rig_input_desc *n;
	uint32_t i;

	*out = *in;
	dev = calloc(bd->ndevices + 1, sizeof(*dev));
	o = calloc(in->noutputs + 1, sizeof(*o));
	t = calloc(in->ntriggers + 1, sizeof(*t));
	n = calloc(in->ninputs + 1, sizeof(*n));
	out->devices = dev;
	out->outputs = o;
	out->triggers = t;
	out->inputs = n;
	if (!dev || !o || !t || !n) {
		rig_desc_board_free(out);
		return -ENOMEM;
	}
	out->ndevices = bd->ndevices;
	for (i = 0; i < bd->ndevices; i++)
		dev[i] = in->devices[bd->devices[i]];
	out->noutputs = out->ntriggers = out->ninputs = 0;
	for (i = 0; i < in->noutputs; i++)
		if (on_board(in, bd, in->outputs[i].device))
			o[out->noutputs++] = in->outputs[i];
	for (i = 0; i < in->ntriggers; i++)
		if (on_board(in, bd, in->triggers[i].device))
			t[out->ntriggers++] = in->triggers[i];
	for (i = 0; i < in->ninputs; i++)
		if (on_board(in, bd, in->inputs[i].device))
			n[out->ninputs++] = in->inputs[i];
	return 0;
}

void rig_desc_board_free(struct rig_desc *d)
{
	free((void *)d->devices);
	free((void *)d->outputs);
	free((void *)d->triggers);
	free((void *)d->inputs);
	memset(d, 0, sizeof(*d));
}
