/* SPDX-License-Identifier: MIT */
/*
 * limit.h - the one limit predicate: a channel's value, velocity and
 * acceleration against its limits, measured the same way by strand check,
 * play's check before the first tick, an automatic rig's limits and the
 * loop at every tick, so that a run enforces exactly what was verified.
 *
 * A meter keeps a channel's last 2h setpoints, h = ceil(tick_hz / 1000)
 * ticks per difference (one tick up to 1 kHz). Of a new sample x_k:
 *
 *     velocity      (x_k - x_{k-h}) / (h dt)                 ending at k
 *     acceleration  (x_k - 2 x_{k-h} + x_{k-2h}) / (h dt)^2  centred on k - h
 *
 * from exact differences of the Q32.32 values. Differences over h ticks
 * rather than one keep the quantisation of the values (one step, 2^-32 of
 * a unit) from swamping the acceleration at high tick rates: one step per
 * tick at 10 kHz is 0.0023 turns/s^2 over one tick but 2.3e-5 over ten.
 * A limit counts as broken only beyond that noise: four steps per
 * difference, and where a value is computed through a double (a planned
 * move far from zero) four of the double's steps at that magnitude too.
 *
 * A channel with a position limit and an acceleration limit is also held
 * to where a controlled stop begun after that sample would leave it, its
 * stopping point: every stop (SIGINT, a stop input, a fault, the post-roll)
 * brakes from the speed of the last tick at the acceleration limit
 * (plan/move.h, move_stop_distance gives how far exactly), so a timeline on
 * which this holds everywhere is safe to stop anywhere.
 *
 * Units are the core's (turns, scene units, rpm) per second and per
 * second squared; every function is [rt].
 */
#ifndef STRAND_PLAN_LIMIT_H
#define STRAND_PLAN_LIMIT_H

#include <stdbool.h>
#include <stdint.h>

#include "motion/fix.h"
#include "hal/rt.h"
#include "scene/scene_desc.h"
#include "scene/source.h"

enum lim_kind { LIM_MIN, LIM_MAX, LIM_VEL, LIM_ACC, LIM_STOP, LIM_NKINDS };

/* A channel's limits, core units; +-INFINITY where there is none. */
struct lim_bounds {
	double min, max;
	double vel, acc;
	bool vel_ch; /* a speed (rpm): no stopping point, a stop brings it to 0 */
};

struct lim_stencil {
	uint32_t h;      /* ticks per difference */
	uint32_t tick_hz;
	double rate;     /* differences per second: tick_hz / h */
};

/* The last 2h samples of one channel. */
struct lim_meter {
	mot_q32 *ring;  /* LIM_METER_LEN(h) values, the caller's */
	uint32_t len, head; /* head: where the next sample goes */
	int64_t seen;   /* samples pushed since the reset */
};

#define LIM_METER_LEN(h) (2 * (size_t)(h))

/* What a new sample measures against the meter's: the value, the velocity
 * ending at it and the acceleration centred h ticks before it (valid once
 * h and 2h samples came before it: has_v, has_a). */
struct lim_measure {
	double x, v, a;
	double v1;       /* the speed over the last tick alone, what a stop brakes from */
	double noise;    /* one sample's rounding at this magnitude, units */
	bool has_v, has_a;
};

/* One broken limit: its kind, the measure that breaks it (the stopping
 * point for LIM_STOP) and the limit, signed like the measure. */
struct lim_hit {
	enum lim_kind kind;
	double value, limit;
};

/* A channel's limits as a scene file gives them (an angle's in degrees)
 * in the core's units; what it leaves out is unlimited. */
struct lim_bounds lim_bounds_of(const struct sd_limits *l, enum src_unit unit);

/* A value in the core's units in a file's (an angle: turns to degrees). */
static inline double lim_file_units(enum src_unit unit, double v)
{
	return unit == SRC_UNIT_TURNS ? v * 360.0 : v;
}

void lim_stencil_init(struct lim_stencil *s, uint32_t tick_hz);

/* A channel standing still at x: every sample in the ring is x, as though
 * it had been there for 2h ticks (a run starts from rest); seen counts
 * them when `history`, else 0 (a range starting out of nowhere: velocity
 * and acceleration only once h and 2h samples were pushed). */
void lim_meter_reset(struct lim_meter *m, const struct lim_stencil *s, mot_q32 *ring, mot_q32 x,
		     bool history);

/* x becomes the newest of the meter's samples. */
void lim_meter_push(struct lim_meter *m, mot_q32 x);

/* What x measures as the sample after the meter's (which it leaves as they
 * are: the loop tests a tick's setpoint before it is final). */
void lim_measure(const struct lim_meter *m, const struct lim_stencil *s, mot_q32 x,
		 struct lim_measure *me);

/* The limits `me` breaks, into hit[] (at most LIM_NKINDS, in the order of
 * enum lim_kind): their number. */
uint32_t lim_test(const struct lim_stencil *s, const struct lim_bounds *b,
		  const struct lim_measure *me, struct lim_hit *hit);

#endif /* STRAND_PLAN_LIMIT_H */
