/* SPDX-License-Identifier: MIT */
/*
 * timing.h - exact time: frames, ticks and the frame trigger rule
 * (FORMULAS.md section 5).
 *
 * Time is never a float and never accumulated. The frame rate is a rational
 * num/den frames per second (24, 25, 30000/1001), the control loop runs at
 * tick_hz ticks per second, and every conversion is computed afresh from the
 * integer tick or frame number with 128-bit intermediates, so hour 24 is as
 * exact as second 1 and nothing drifts.
 *
 *   tick k starts at  k / tick_hz s
 *   frame f starts at f * den / num s
 *   frame f's trigger fires at tick ceil(f * den * tick_hz / num)
 *
 * The trigger rule means never early, at most one tick late. The frame rate
 * may not exceed the tick rate, so a tick fires at most one trigger.
 */
#ifndef MOT_TIMING_H
#define MOT_TIMING_H

#include "fix.h"

/* Limits that keep every intermediate inside 128 bits with room to spare. */
#define MOT_RATE_MAX ((uint32_t)1 << 24)    /* num, den */
#define MOT_TICK_HZ_MAX ((uint32_t)1 << 20) /* ~1 MHz */
#define MOT_TICK_MAX ((int64_t)1 << 52)     /* ~143 years at 1 MHz */

struct mot_timing {
	uint32_t num, den; /* frames per second = num / den, reduced */
	uint32_t tick_hz;
	uint64_t ticks_den; /* tick_hz * den: ticks per (num frames) */
	struct mot_udiv_inv per_turn; /* 60 num: a spin's turns (mot_spin_turns()) */
};

/*
 * Prepare a timing. num, den, tick_hz > 0 and within the limits above, and
 * num / den <= tick_hz (at most one frame per tick), else MOT_E_INVAL. The
 * fraction is reduced. Init only.
 */
int mot_timing_init(struct mot_timing *t, uint32_t num, uint32_t den, uint32_t tick_hz);

/* The exact frame time of tick k, k * num / (tick_hz * den), rounded to
 * Q32.32 frames. Real-time safe. */
mot_q32 mot_timing_tick_frame(const struct mot_timing *t, int64_t tick);

/* The tick at which frame f's trigger fires: ceil(f * tick_hz * den / num).
 * Real-time safe. */
int64_t mot_timing_trigger_tick(const struct mot_timing *t, int64_t frame);

/* The frame whose trigger fires at tick k, if any: true and *frame set, or
 * false. Exactly one tick per frame answers true. Real-time safe. */
bool mot_timing_fires(const struct mot_timing *t, int64_t tick, int64_t *frame);

/* The first frame whose trigger fires at or after tick k. */
int64_t mot_timing_next_frame(const struct mot_timing *t, int64_t tick);

/* The instant of a Q32.32 frame time in Q32.32 seconds. */
mot_q32 mot_timing_frame_seconds(const struct mot_timing *t, mot_q32 frame, uint32_t *sat);

#endif /* MOT_TIMING_H */
