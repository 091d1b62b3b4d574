/* SPDX-License-Identifier: MIT */
/*
 * limit_check.h - joint limits over a whole timeline, at tick resolution (the
 * work of `strand check`).
 *
 * Every tick of the span is evaluated, exactly as playback will, and each
 * joint's value, velocity and acceleration compared with its limits. A run
 * of consecutive ticks breaking the same limit is one violation: an
 * interval with its worst value.
 *
 * Velocity and acceleration are finite differences over h ticks, h =
 * ceil(tick_hz / 1000) (one tick at rates up to 1 kHz), attributed to the
 * tick they end at (velocity) or centre on (acceleration). A joint value is
 * quantised to one Q32.32 step (8.4e-8 degree), so differences carry noise
 * of a few steps per difference; a limit counts as broken only beyond that
 * noise (4 steps per difference), which at 1 kHz is 3.4e-4 deg/s and
 * 0.34 deg/s^2 - far below any servo's limits.
 */
#ifndef STRAND_LIMIT_CHECK_H
#define STRAND_LIMIT_CHECK_H

#include <stdint.h>

#include "scene/scene_desc.h"

/*
 * LIM_STOP: a controlled stop begun at that tick (every axis decelerating at
 * its acceleration limit, as SIGINT, a fault or a stop input do) would carry
 * the joint past its min or max. A joint with an acceleration limit and a
 * position limit is checked for it at every tick: its stopping point
 *     x + sign(v) (v^2 / (2 a) + |v| / tick_hz)
 * (the second term covers the tick the stop starts in) must stay inside the
 * limits, so that a stop anywhere on a timeline that passes `check` is safe.
 * worst is that stopping point, limit the bound it crosses.
 */
enum lim_kind { LIM_MIN, LIM_MAX, LIM_VEL, LIM_ACC, LIM_STOP, LIM_NKINDS,
		LIM_POOL = LIM_NKINDS /* a particle system's pool ran out (worst: particles
				       * dropped, limit: its slots; frames: the first drop) */ };

struct lim_violation {
	int32_t node;             /* the joint's node, or -1 (a system's channel, an aim) */
	const char *channel;      /* the channel's name (a pool's: the system's); valid
				   * during the report call only */
	bool angle;               /* degrees (else scene units or plain numbers) */
	enum lim_kind kind;
	double worst;             /* value, velocity or acceleration (signed), file units */
	double limit;             /* the limit it breaks (signed like worst) */
	int64_t tick_first, tick_last;
	double frame_first, frame_last; /* exact frame times of those ticks */
};

struct lim_result {
	uint32_t violations;
	uint32_t joints;      /* joints with limits */
	uint32_t channels;    /* other channels with limits (systems, aims) */
	int64_t ticks;        /* ticks evaluated */
	uint32_t sat;         /* the core's sticky saturation bits */
	double sat_frame;     /* the first frame where sat became non-zero */
};

typedef void (*lim_report_fn)(void *ctx, const struct lim_violation *v);

/*
 * Check frames [from, to] of a built scene against d's limits (every
 * channel with limits: joints, the systems' items, aims) and every
 * particle system's pool, calling
 * report for each violation as it closes (in time order per limit). 0, or
 * -ENOMEM. Not real-time: it allocates its state.
 */
int lim_check(const struct scene_desc *d, const struct mot_scene *sc, int64_t from, int64_t to,
	      lim_report_fn report, void *ctx, struct lim_result *res);

/* "min", "max", "velocity", "acceleration", "stopping distance", "pool" */
const char *lim_kind_name(enum lim_kind k);

#endif /* STRAND_LIMIT_CHECK_H */
