/* SPDX-License-Identifier: MIT */
/*
 * move.h - motion that the scene does not describe: the pre-roll to the
 * first pose, step mode's moves from frame to frame, the moves between
 * passes of --loop and --ping-pong, and every stop.
 *
 * A move takes n channels from rest at `from` to rest at `to` in the same
 * whole number of ticks, each along a trapezoidal speed profile within its
 * own speed and acceleration limits. The duration is the slowest channel's
 * shortest time, rounded up to a tick; every other channel gets the gentler
 * trapezoid that covers its distance in exactly that time,
 *
 *     cruise v = (a T - sqrt(a^2 T^2 - 4 a d)) / 2,  ramps of v / a,
 *
 * so all channels start and arrive together, as a camera operator expects
 * of a rig. Sampling a profile whose speed stays within vmax and whose
 * acceleration stays within amax at the ticks gives finite differences
 * within the same bounds (a difference quotient is a mean of the
 * derivative), which is what the loop's limit check measures. The last
 * sample is `to` exactly, so step mode lands on the frame's pose to the bit.
 *
 * A stop brings moving channels to rest: each one's speed shrinks by at most
 * amax * dt per tick, the fastest way its limit allows. A velocity channel
 * (a spin speed) is brought to zero instead, with its rate of change
 * limited the same way.
 *
 * move_plan is [rt] (the loop plans each step mode move when it gets there);
 * the caller owns the arrays.
 */
#ifndef STRAND_MOVE_H
#define STRAND_MOVE_H

#include <stdbool.h>
#include <stdint.h>

#include "motion/fix.h"
#include "hal/rt.h"
#include "scene/num.h"

struct move_ch {
	mot_q32 from, to;
	double d;  /* to - from, core units */
	double v;  /* cruise speed, units/s (>= 0) */
	double a;  /* acceleration, units/s^2 */
	double ta; /* ramp time, s */
};

struct move {
	uint32_t n;
	uint32_t tick_hz;
	int64_t ticks; /* duration; 0 when from == to */
	double t;      /* ticks / tick_hz */
	struct move_ch *ch;
};

/* Plan a move of n channels (ch: n entries owned by the caller). vmax and
 * amax must be positive and finite. 0, or -EINVAL; or -ERANGE when the
 * move would take more than NUM_TICKS_MAX ticks (a distance near the
 * core's range at a crawl): it is then planned over NUM_TICKS_MAX ticks,
 * a plan that is defined but faster than the limits allow, so the caller
 * must not play it. */
int move_plan(struct move *m, struct move_ch *ch, uint32_t n, const mot_q32 *from,
	      const mot_q32 *to, const double *vmax, const double *amax, uint32_t tick_hz);

/* Channel i at tick k of the move (0 <= k <= ticks; clamped). */
mot_q32 move_at(const struct move *m, uint32_t i, int64_t k);

/*
 * One tick of a stop for one channel. pos channels: v is the present speed
 * (units/s); it shrinks toward 0 by at most amax / tick_hz and the value
 * advances by the new speed over a tick. Velocity channels (vel_ch): the
 * value itself goes to 0 with its rate v bounded by vmax and changing by at
 * most amax / tick_hz per tick. Updates *value and *v; true when at rest.
 * The value saturates at the ends of Q32.32 rather than wrap.
 */
bool move_stop_step(mot_q32 *value, double *v, bool vel_ch, double vmax, double amax,
		    uint32_t tick_hz);

/* How far a stop from speed v (units/s, a position channel) goes before it
 * rests, exactly as move_stop_step brakes it: its speed shrinks by
 * amax / tick_hz a tick, each tick's advance its new speed over the tick,
 * dt (n |v| - dv n (n + 1) / 2), n = floor(|v| / dv) (the rounding of each
 * tick's advance to the core's step aside). Not signed. */
double move_stop_distance(double v, double amax, uint32_t tick_hz);

/* Q32.32 <-> double in core units. */
static inline double STRAND_RT move_q2d(mot_q32 x)
{
	return (double)x * (1.0 / 4294967296.0);
}

/* Saturating at the ends of Q32.32; NaN gives 0. */
mot_q32 move_d2q(double x);

#endif /* STRAND_MOVE_H */
