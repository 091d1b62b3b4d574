/* SPDX-License-Identifier: MIT */
/*
 * pass.h - which frames a pass of a continuous run plays, in which order,
 * and the scene ticks it covers. One pass plays frames from..to; --loop
 * plays that again and again; --ping-pong goes back and forth without
 * showing an end twice: from..to, to-1..from, from+1..to, ... A pass's
 * scene ticks run from its first frame's trigger tick to its last one's,
 * widened by the triggers' offsets (lead: edges before the first frame's
 * tick, tail: after the last one's), in the pass's direction.
 */
#ifndef STRAND_PASS_H
#define STRAND_PASS_H

#include <stdbool.h>
#include <stdint.h>

#include "motion/timing.h"
#include "hal/rt.h"

struct pass_span {
	int dir;               /* 1 forwards, -1 on a ping-pong's way back */
	int64_t first, last;   /* frames, in firing order */
	int64_t lo, hi;        /* the same frames in increasing order */
	int64_t begin, end;    /* scene ticks, in the pass's direction */
};

/* [rt] Pass p (from 0) of a run of frames from..to (from <= to). */
void pass_span(struct pass_span *s, const struct mot_timing *t, int64_t from, int64_t to,
	       bool ping_pong, int64_t p, int64_t lead, int64_t tail);

#endif /* STRAND_PASS_H */
