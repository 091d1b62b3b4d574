/* SPDX-License-Identifier: MIT */
/*
 * cycle.h - cycled objects (FORMULAS.md section 9; the seed paper section 6).
 *
 * A set of objects first..last, stepping by skip, shown one step every
 * frames_per_step frames from start_frame. The channel `<cycle>.index` is
 * the object shown (loop, bounce) or the last object of the growing set
 * (growth). Before start_frame the first object is shown. A pure function
 * of the integer frame number: random access and playback agree.
 */
#ifndef MOT_CYCLE_H
#define MOT_CYCLE_H

#include "fix.h"

enum mot_cycle_mode {
	MOT_CYCLE_LOOP,   /* first, first+skip, ..., last', first, ... */
	MOT_CYCLE_BOUNCE, /* first ... last', back ... first+skip, first, ... */
	MOT_CYCLE_GROWTH, /* first..k shown together; restarts after last' */
};

struct mot_cycle {
	int32_t first, last, skip; /* skip > 0, last >= first */
	uint32_t mode;             /* enum mot_cycle_mode */
	int64_t frames_per_step;   /* > 0 */
	int64_t start_frame;
	int64_t count;             /* objects in one pass: (last - first) / skip + 1 */
	int64_t period;            /* steps before the sequence repeats */
};

/* Validate and prepare: skip > 0, last >= first, frames_per_step > 0,
 * mode known, else MOT_E_INVAL. Init only. */
int mot_cycle_init(struct mot_cycle *c, int32_t first, int32_t last, int32_t skip,
		   enum mot_cycle_mode mode, int64_t frames_per_step, int64_t start_frame);

/* The channel value at integer frame n. Real-time safe. */
int32_t mot_cycle_index(const struct mot_cycle *c, int64_t frame);

#endif /* MOT_CYCLE_H */
