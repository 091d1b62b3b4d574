/* SPDX-License-Identifier: MIT */
/*
 * runup.h - the run-up into a pass: when a pass starts where the scene is
 * already moving (--from in the middle of a pan, a strand that starts with
 * a speed), arriving at rest and jumping to the scene's speed would break
 * the acceleration limit. Each channel instead comes to rest a little
 * behind the pass's first pose and ramps up to the scene's speed there at
 * its acceleration limit: from rest, its speed grows by v / n each tick for
 * n = ceil(|v| tick_hz / amax) ticks, so that it reaches the first pose
 * with speed v on the pass's first tick. The ramps of all channels end
 * together; a channel with a shorter one waits at rest until it begins.
 *
 * Speeds v k / n for k = 1..n cover v dt (n + 1) / 2, which is how far
 * behind the first pose a ramp starts. Every function is [rt]: the loop
 * plans each pass's run-up when it gets there.
 */
#ifndef STRAND_RUNUP_H
#define STRAND_RUNUP_H

#include <stdint.h>

#include "motion/fix.h"
#include "hal/rt.h"

struct runup_ramp {
	double v;  /* the scene's speed at the first pose, units/s */
	int64_t n; /* ticks of the ramp; 0: no speed to come up to */
};

/*
 * The ramp of a channel whose pass starts at `end` and is at `next` one
 * tick later: its speed, its length, and where it starts into *start. 0,
 * or -ERANGE when the ramp would take NUM_TICKS_MAX ticks or more (a crawl
 * of an acceleration limit: *start is then where the longest ramp the run
 * counts would start, not a plan to play). amax > 0.
 */
int runup_plan(struct runup_ramp *r, mot_q32 end, mot_q32 next, uint32_t tick_hz, double amax,
	       mot_q32 *start);

/* The channel at step j of a run-up of `ticks` steps (the longest ramp's
 * n) ending at `end`: j = 0 at rest at its start (or waiting there), j =
 * ticks the first pose. */
mot_q32 runup_at(const struct runup_ramp *r, mot_q32 end, int64_t ticks, int64_t j,
		 uint32_t tick_hz);

#endif /* STRAND_RUNUP_H */
