/* SPDX-License-Identifier: MIT */
/*
 * gomo.h - go-motion: step mode that moves while the shutter is open.
 *
 * A stop-motion frame is sharp: the rig stands still at the frame's pose
 * while the camera exposes. A live camera sees motion blur instead: its
 * shutter stays open for a fraction s of each frame interval (a cine
 * shutter angle: 180 degrees is s = 1/2) while everything moves. Go-motion
 * gives a stop-motion frame that blur: for frame f the rig runs the
 * scene's own motion from f - s/2 to f + s/2, at the scene's speed, with
 * the shutter open while it runs; before it a run-up from rest reaches the
 * scene's speed exactly where the exposure begins (plan/runup.h), after it
 * a run-out brings the rig back to rest at its acceleration limit (the
 * braking of every stop, plan/move.h), and between frames the rig waits at
 * rest as step mode does.
 *
 * The exposure is the scene's ticks whose instant lies within [f - s/2,
 * f + s/2]: the first at or after its start (where the trigger rises, never
 * early, at most a tick late, as FORMULAS section 5 fires a frame) to the
 * last at or before its end. The run-up, the exposure and the run-out are a
 * continuous pass over those ticks (plan/timeline.h: the speeds at the ends
 * are those of the first and last tick), so strand check walks them with
 * the same code as it walks a pass (check/limit_check.c), and the loop
 * plays them as it plays a pass.
 *
 * The shutter is a Q32.32 fraction of a frame interval, 0 < s <= 1: an
 * angle / 360. Every function is [rt].
 */
#ifndef STRAND_GOMO_H
#define STRAND_GOMO_H

#include <stdbool.h>
#include <stdint.h>

#include "motion/fix.h"
#include "motion/timing.h"
#include "hal/rt.h"

/* The widest shutter: a whole frame interval (360 degrees). */
#define GOMO_SHUTTER_MAX MOT_Q32_ONE

/* The exposure of frame f with shutter s, in scene ticks: the first tick
 * at or after the instant of f - s/2 into *first, the last at or before
 * that of f + s/2 into *last. 0, or -EINVAL when the exposure holds fewer
 * than two ticks (no speed to run the scene at) or s is outside
 * (0, GOMO_SHUTTER_MAX]. */
int gomo_window(const struct mot_timing *t, int64_t f, mot_q32 s, int64_t *first,
		int64_t *last);

/* Whether every frame's exposure with shutter s holds two ticks or more:
 * 0, or -EINVAL when s is outside (0, GOMO_SHUTTER_MAX] or opens for less
 * than two tick periods (then some frame's would hold fewer). */
int gomo_shutter_check(const struct mot_timing *t, mot_q32 s);

/* A shutter angle in degrees as the Q32.32 fraction of a frame it opens
 * for (angle / 360, rounded to nearest); false outside (0, 360] or when
 * it rounds to nothing. */
bool gomo_shutter_of_angle(double angle, mot_q32 *s);

#endif /* STRAND_GOMO_H */
