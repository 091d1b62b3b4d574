/* SPDX-License-Identifier: MIT */
/*
 * timeline.h - a range of the scene as the rig plays it, tick by tick, and
 * what it does just beyond the range's ends.
 *
 * A run plays frames [first, last] (the scene's span, or --from/--to). The
 * ticks whose instant lies within them, k0 = ceil(t_first * tick_hz) to
 * k1 = floor(t_last * tick_hz), are the scene's: every channel as the core
 * evaluates it there (a strand holds its last value after its last key,
 * FORMULAS section 5). Beyond them a run still has ticks to play: the
 * last frame's trigger fires at ceil(t_last * tick_hz), one tick after k1
 * when the frame does not fall on a tick; a trigger's offset_ms moves
 * edges a little before the first frame's tick or after the last one's;
 * and the run-up and post-roll join the range to rest. There the scene
 * says nothing a rig can follow: holding the value would stop a channel
 * that arrives at the range's end moving in one tick, a velocity step no
 * drive can make. So beyond k1 each position channel (an angle, a
 * position) goes on at the speed it has over the range's last tick,
 * x(k1) + (k - k1) (x(k1) - x(k1 - 1)), and before k0 it comes from the
 * speed of its first, x(k0) - (k0 - k) (x(k0 + 1) - x(k0)); a speed or
 * index channel (rpm, a cycle index, an attribute) holds its end value.
 * The post-roll then brakes from that speed within the limits (move.h),
 * and the run-up comes up to it.
 *
 * strand check, strand export, play's pre-check, an automatic rig's limits
 * and the loop all take a range's values from here, so that they agree
 * to the bit. The extension is exact integer arithmetic (saturating at the
 * ends of Q32.32, flagged in *sat).
 */
#ifndef STRAND_TIMELINE_H
#define STRAND_TIMELINE_H

#include <stdbool.h>
#include <stdint.h>

#include "motion/fix.h"
#include "motion/timing.h"
#include "hal/rt.h"
#include "scene/source.h"

struct timeline {
	struct play_source *src;
	uint32_t n;         /* the source's selected channels */
	int64_t k0, k1;     /* the scene's ticks of the range; k0 <= k1 */
	mot_q32 *x0, *d0;   /* at k0, and the step per tick before it */
	mot_q32 *x1, *d1;   /* at k1, and the step per tick after it */
	const bool *extend; /* per channel: goes on at its speed (else holds) */
};

/* Mot_q32 values a timeline of n channels keeps (its x0, d0, x1, d1). */
#define TIMELINE_WORDS(n) (4 * (size_t)(n))

/*
 * [rt] The range [first, last] (frames, first <= last) of src's selected
 * channels, n of them; extend[i]: channel i goes on at its speed beyond the
 * ends (a position), else it holds (kept, not copied). mem: TIMELINE_WORDS(n)
 * values, the caller's. Evaluates the scene at four ticks; its saturation
 * is ORed into *sat. A range shorter than a tick (first == last between two
 * ticks) is its frame's trigger tick alone, held at both ends.
 */
void timeline_init(struct timeline *tl, struct play_source *src, uint32_t n, const bool *extend,
		   int64_t first, int64_t last, mot_q32 *mem, uint32_t *sat);

/* [rt] Every channel at scene tick k, into out[n]. */
void timeline_eval(const struct timeline *tl, int64_t k, mot_q32 *out, uint32_t *sat);

/* The last tick at or before frame f's instant: floor(f * tick_hz * den / num). */
int64_t timeline_tick_floor(const struct mot_timing *t, int64_t f);

/* A channel of this unit goes on at its speed beyond a range's ends. */
static inline bool timeline_extends(enum src_unit u)
{
	return u == SRC_UNIT_TURNS || u == SRC_UNIT_LENGTH;
}

#endif /* STRAND_TIMELINE_H */
