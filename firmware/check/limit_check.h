/* SPDX-License-Identifier: MIT */
/*
 * limit_check.h - a run's whole timeline against its channels' limits,
 * tick by tick, before anything moves (the work of `strand check` and of
 * `strand play` before its first tick).
 *
 * What a continuous pass plays is walked sample by sample, exactly as the
 * loop will play it, and every sample put to the loop's own predicate
 * (plan/limit.h) with the limits the run enforces:
 *
 *   run-up     from rest, each channel's ramp up to the scene's speed at the
 *              pass's first pose (plan/runup.h); it must start inside the
 *              position limits
 *   scene      every scene tick of the pass, the range and just beyond it
 *              (plan/timeline.h: the triggers' offsets, the last frame's
 *              tick when it falls after the last frame's instant)
 *   post-roll  from the speed of the last tick to rest, braking at each
 *              channel's acceleration limit (plan/move.h)
 *
 * A run of --loop repeats its first pass; one of --ping-pong has up to three
 * kinds (forwards, backwards, forwards from the second frame), each walked.
 * The pre-roll, the bridges between passes and step mode's moves go from
 * rest to rest within the limits by construction (move.h) between poses the
 * walk has checked; step mode's poses at the frames are checked for the
 * position limits. Go-motion (step mode with a shutter, plan/gomo.h) is a
 * short pass per frame: its run-up from rest (padded to the triggers' lead,
 * as the loop pads it), the scene's ticks of the exposure and the run-out
 * to rest, each walked as a pass is, on the timeline of the run's range
 * (its ends go on at their speed, timeline.h). A run of consecutive samples
 * breaking the same limit is one violation: an interval with its worst
 * value.
 */
#ifndef STRAND_LIMIT_CHECK_H
#define STRAND_LIMIT_CHECK_H

#include <stdbool.h>
#include <stdint.h>

#include "plan/limit.h"
#include "scene/source.h"

/* A channel the run drives, and the limits it is held to. */
struct lim_channel {
	const char *name;      /* as the scene names it: "base.angle" */
	uint32_t src;          /* the source's channel index */
	enum src_unit unit;
	struct lim_bounds lim; /* core units; INFINITY where none */
};

/* What the run plays. */
struct lim_run {
	int64_t from, to;      /* frames, from <= to */
	bool loop, ping_pong;
	int64_t passes;        /* with loop or ping_pong; 0: no end */
	int64_t lead, tail;    /* ticks: the triggers' earliest and latest offsets */
	bool step;             /* step mode: the frames' poses, at rest */
	mot_q32 shutter;       /* step mode: go-motion, this fraction of a frame (gomo.h);
				* 0: none */
	int64_t expose_first, expose_last; /* go-motion: the frames exposed; from..to is
					    * the range whose timeline they run on */
};

enum lim_segment { LIM_SEG_SCENE, LIM_SEG_RUNUP, LIM_SEG_POSTROLL, LIM_SEG_FRAME };

struct lim_violation {
	uint32_t channel;          /* index into the channels */
	enum lim_kind kind;
	enum lim_segment seg;
	int dir;                   /* the pass's direction (-1: a ping-pong's way back) */
	bool gomo;                 /* a go-motion frame's run-up, exposure or run-out */
	double worst;              /* value, velocity, acceleration or stopping point, core units */
	double limit;              /* the limit it breaks (signed like worst) */
	int64_t tick_first, tick_last;  /* scene ticks (LIM_SEG_SCENE), else steps of the segment */
	double frame_first, frame_last; /* exact frame times; run-up and post-roll: the pass's
					 * first and last frame */
};

struct lim_result {
	uint32_t violations;
	int64_t samples;      /* samples put to the predicate */
	uint32_t sat;         /* the core's sticky saturation bits */
	double sat_frame;     /* the first frame where sat became non-zero */
};

typedef void (*lim_report_fn)(void *ctx, const struct lim_violation *v);

/*
 * Walk the run over src (its channels are selected here: the caller selects
 * its own again afterwards) and report each violation as it closes. 0, or
 * -ENOMEM; -EINVAL for a go-motion frame whose exposure holds fewer than
 * two ticks (gomo_window). Not real-time: it allocates its state.
 */
int lim_check(struct play_source *src, const struct lim_channel *ch, uint32_t n,
	      const struct lim_run *run, lim_report_fn report, void *ctx, struct lim_result *res);

/* "min", "max", "velocity", "acceleration", "stopping distance" */
const char *lim_kind_name(enum lim_kind k);

#endif /* STRAND_LIMIT_CHECK_H */
