/* SPDX-License-Identifier: MIT */
/*
 * chase.h - the loop's tick clock disciplined by an external clock
 * (hal/extclk.h): LTC timecode or a frame pulse.
 *
 * Marks come in (each a source frame and the instant it began, already
 * filtered by the source's own DLL where it has one); a second DLL
 * (hal/dll.h) fits the source's frames to CLOCK_MONOTONIC: its rate
 * against ours and its phase. From that fit:
 *
 *   lock     CHASE_LOCK_MARKS marks in a row, each the frame after the last
 *            at about a frame's time: the source runs, and the fit knows it
 *   cue      (loop_chase.c) the frame the timecode names a lead time ahead,
 *            and the run tick at which the scene's tick for it is due
 *   due(k)   the tick schedule: each tick one scene tick of the source's
 *            time later (the fit's rate), plus a correction toward the fit's
 *            phase that is at most CHASE_SLEW of a tick. So the schedule
 *            never jumps: a tick is never due more than CHASE_SLEW sooner or
 *            later than the source's rate says, and the setpoints, which
 *            belong to ticks, never jump with it (the motion is stretched
 *            or squeezed by at most 1 + rate error + CHASE_SLEW).
 *   events   a mark that is not the frame expected at its time (a jump, a
 *            stop, reverse play), a rate beyond CHASE_RATE_MAX, no mark for
 *            the freewheel time: the loop stops under control and cues
 *            again when the source is back (loop_chase.c). Between marks,
 *            and for up to the freewheel time without any, the schedule
 *            runs on at the fitted rate (freewheel).
 *
 * Everything is [rt] but chase_init. Times are CLOCK_MONOTONIC ns.
 */
#ifndef STRAND_CHASE_H
#define STRAND_CHASE_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/dll.h"
#include "hal/extclk.h"
#include "scene/timecode.h"

/* Marks in a row that make a lock. */
#define CHASE_LOCK_MARKS 4
/* The source's rate may be off ours by this much and be chased (1%: ten
 * times a poor crystal; the scene must pass strand check with its speed
 * limits this much tighter, and its acceleration limits the square). */
#define CHASE_RATE_MAX 0.01
/* The schedule's phase correction, at most, per tick: 0.2% of a tick. */
#define CHASE_SLEW 0.002
/* ... and the fraction of the phase error corrected per tick below that. */
#define CHASE_GAIN 0.02
/* The source frames' DLL once its start-up fit has narrowed. */
#define CHASE_BW_HZ 0.05
/* Marks taken from the source in one tick, at most. */
#define CHASE_MARKS_PER_TICK 8

enum chase_event {
	CHASE_EV_NONE,
	CHASE_EV_JUMP,    /* a frame that is not the one expected */
	CHASE_EV_STOPPED, /* the same frame again: the source stands */
	CHASE_EV_REVERSE, /* played backwards */
	CHASE_EV_RATE,    /* the rate beyond CHASE_RATE_MAX */
	CHASE_EV_LOST,    /* no mark for the freewheel time */
	CHASE_EV_FORMAT,  /* drop-frame labels where the scene has none, or the reverse */
};

struct chase_cfg {
	struct hal_extclk *src;
	uint32_t num, den, tick_hz;  /* the scene's frame rate and tick */
	uint32_t mult;               /* scene frames per source frame (1, or 2 at 50/60) */
	int64_t offset;              /* the source frame that is the scene's frame 0 */
	int64_t freewheel_ns;        /* without marks this long: CHASE_EV_LOST */
};

struct chase_stats {
	int64_t marks, outliers;
	int64_t locks, events[CHASE_EV_FORMAT + 1];
	int64_t first_mark_ns, lock_ns; /* the first mark, the first lock */
	double rate;          /* the source's frames against ours, 1 = exact */
	double level_dbfs;
	int64_t freewheel_max_ns; /* the longest time without a mark while mapped */
	double phase_max_ns;  /* the schedule's worst distance from the fit while playing */
};

struct chase {
	struct chase_cfg cfg;
	struct timecode tc;   /* the source's labels */
	int64_t day;          /* frames in a day of them */
	double frame_ns;      /* a source frame's nominal length */
	double tick_frames;   /* source frames per scene tick */
	struct hal_dll dll;   /* source frame -> CLOCK_MONOTONIC */
	/* the marks */
	int good;             /* consistent marks in a row */
	bool locked;
	int64_t last_n;       /* the last mark's frame */
	double last_t;
	int64_t last_seen_ns; /* when the last mark came in (our clock) */
	enum chase_event event; /* the first since the loop last looked */
	/* the schedule: run tick k's scene tick is scene_begin + k - k_play */
	bool mapped;
	int64_t k_play, scene_begin;
	int64_t k_last;
	double due_last, step_ns;
	bool cued;            /* a cue is made: PREROLL begins at k_start */
	int64_t k_start;
	bool past_end;        /* the source names a frame past the range */
	int64_t recues;
	bool ended;           /* the source's fault: no cue again */
	struct chase_stats st;
	struct hal_mark buf[CHASE_MARKS_PER_TICK];
};

/* [init] */
void chase_init(struct chase *c, const struct chase_cfg *cfg);

/* [rt] Tick 0 is due at t0 (the schedule runs free at our rate until a
 * cue maps it onto the source). */
void chase_begin(struct chase *c, int64_t t0);

/* [rt] Take the marks known by now. */
void chase_poll(struct chase *c, int64_t now);

/* [rt] The event since the last call (and forget it), or CHASE_EV_NONE;
 * CHASE_EV_LOST when no mark came for the freewheel time while mapped. */
enum chase_event chase_take_event(struct chase *c, int64_t now);

/* [rt] When run tick k is due: k is the last tick asked for or the one after. */
int64_t chase_due(struct chase *c, int64_t k);

/* [rt] The source frame (fractional) the fit puts at time t. */
double chase_src_at(const struct chase *c, double t);
/* [rt] The time the fit puts source frame x at. */
double chase_time_of(const struct chase *c, double x);
/* [rt] The source frame of scene tick s. */
double chase_src_of_scene_tick(const struct chase *c, int64_t s);

const char *chase_event_name(enum chase_event e);

#endif /* STRAND_CHASE_H */
