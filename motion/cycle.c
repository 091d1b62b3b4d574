/* SPDX-License-Identifier: MIT */
/* cycle.c - cycled object index (see cycle.h). */
#include "cycle.h"

int mot_cycle_init(struct mot_cycle *c, int32_t first, int32_t last, int32_t skip,
		   enum mot_cycle_mode mode, int64_t frames_per_step, int64_t start_frame)
{
	if (skip <= 0 || last < first || frames_per_step <= 0 || mode > MOT_CYCLE_GROWTH)
		return MOT_E_INVAL;
	c->first = first;
	c->last = last;
	c->skip = skip;
	c->mode = mode;
	c->frames_per_step = frames_per_step;
	c->start_frame = start_frame;
	c->count = ((int64_t)last - first) / skip + 1;
	/* bounce runs first..last' and back without repeating either end:
	 * 2(count - 1) steps, or 1 when there is a single object */
	if (mode == MOT_CYCLE_BOUNCE)
		c->period = c->count > 1 ? 2 * (c->count - 1) : 1;
	else
		c->period = c->count;
	return MOT_OK;
}

int32_t mot_cycle_index(const struct mot_cycle *c, int64_t frame)
{
	int64_t step, pos;

	if (frame < c->start_frame)
		return c->first;
	/* frame - start_frame cannot overflow: both are frame numbers far
	 * inside int64 (the loader bounds them by the Q32.32 frame range) */
	step = (frame - c->start_frame) / c->frames_per_step;
	pos = step % c->period;
	if (c->mode == MOT_CYCLE_BOUNCE && pos >= c->count)
		pos = c->period - pos;
	return (int32_t)(c->first + pos * c->skip);
}
