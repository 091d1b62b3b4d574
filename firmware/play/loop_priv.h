/* SPDX-License-Identifier: MIT */
/*
 * loop_priv.h - the loop's state, shared by its files and by nobody else:
 *
 *     loop_setup.c   [init] the block, loop_init, loop_free
 *     loop_tick.c    [rt]   loop_run, loop_tick, the sequence, the outputs,
 *                           the status samples
 *     loop_plan.c    [rt]   passes, the run-up into them, moves and stops
 *     loop_trig.c    [rt]   trigger pulses, their journal records, step
 *                           mode's gates (in position, exposed)
 *     loop_safety.c  [rt]   inputs, feedback, limits, why the run ends
 *
 * The state is split by concern: one struct loop_out per output, the
 * sequence, the triggers, step mode and safety each in their own struct,
 * and the result, which is all that the rest of the program reads
 * (loop_result()). Every pointer below points into the loop's one block
 * (loop_setup.c carves it): struct loop first, then what a tick touches in
 * the order it touches it, then the result with its 40 KB latency histogram
 * at the end, away from the rest.
 *
 * Poses (one value per output) are vectors, not fields of struct loop_out:
 * the source evaluates a whole pose into an array, the move planner plans
 * from one array to another, and the journal copies the pose of each frame.
 */
#ifndef STRAND_LOOP_PRIV_H
#define STRAND_LOOP_PRIV_H

#include <stdatomic.h>

#include "loop.h"
#include "plan/limit.h"
#include "plan/move.h"
#include "plan/pass.h"
#include "plan/runup.h"
#include "plan/timeline.h"
#include "hal/rt.h"

/* Input edges taken per poll of a device; a device with more polls again,
 * up to LOOP_EDGES_PER_TICK in a tick (loop.h). */
#define LOOP_EDGES_MAX 32
_Static_assert(LOOP_EDGES_PER_TICK % LOOP_EDGES_MAX == 0, "whole polls per tick");

/* One output: what a tick reads and writes for it, besides its setpoints. */
struct loop_out {
	double vel;             /* speed of the last two setpoints, units/s */
	double vel_now;         /* this tick's, once its setpoint stands */
	/* a stop's speed, carried exactly from tick to tick as move_stop_step
	 * brakes it (re-deriving it from the rounded setpoints would feed
	 * their rounding back into the braking, a bias of up to half a step
	 * a tick: at 10 kHz beyond the acceleration limit's slack); the last
	 * tick's speed until a stop begins */
	double stop_v;
	int64_t sent;           /* counts sent last tick */
	/* this tick's feedback, as loop_feedback read it after the devices'
	 * input (a CANopen drive's answer to the last SYNC is current only
	 * until the next is sent): where the drive is, in counts, and the
	 * following error, core units */
	int64_t act;
	double fe;
	bool has_fb;
	struct hal_setpoint sp; /* this tick's, in counts */
	struct runup_ramp ru;   /* its ramp into the pass */
	struct lim_bounds lim;  /* its limits, as the predicate takes them */
	struct lim_meter meter; /* its last setpoints, for the limit check */
};

/* The segments of loop.h's "Sequence", the passes and the move under way. */
struct loop_seq {
	enum loop_state state;
	int dir;                /* 1, or -1 on a ping-pong's way back */
	int64_t seg_j;          /* ticks into the present segment */
	int64_t pass;
	int64_t scene_k;        /* PLAY: the scene tick being played */
	int64_t scene_begin, scene_end; /* the scene ticks the pass covers */
	int64_t pass_first, pass_last;  /* its frames, in firing order */
	struct pass_span span;  /* the pass: the same, and its frames in order */
	struct timeline tl;     /* the pass's range of the scene, and beyond */
	mot_q32 *tl_mem;        /* TIMELINE_WORDS(n) */
	bool *extend;           /* n: the output goes on at its speed beyond the range */
	int64_t lead, tail;     /* scene ticks before the first edge, after the last */
	struct move mv;         /* its channels are in the block */
	int64_t mv_j;
	int64_t ru_ticks, ru_j; /* the run-up: the longest ramp, the step it is at */
	bool braked;            /* this tick was a stop's step (loop_rest_step) */
	/* go-motion: the frame's exposure in scene ticks, the run ticks it
	 * opened and closed at (-1: not yet), and its poses there */
	int64_t gomo_first, gomo_last;
	int64_t gomo_open_tick, gomo_close_tick;
	mot_q32 *gomo_open, *gomo_close;
	mot_q32 *target;        /* a pose: where a move goes (a ramp's start, a frame) */
	mot_q32 *ru_end;        /* a pose: the pass's first, where the ramps end */
	double *vmax, *amax;    /* per output, as the move planner takes them */
};

/* One trigger line. */
struct loop_pulse {
	int64_t next_frame;        /* the next frame to fire in this pass */
	int64_t edge_k;            /* PLAY: the scene tick its edge rises at */
	int64_t fall_tick;         /* run tick the pulse ends at */
	struct journal_rec *armed; /* this tick's record, until it is FIRED */
	struct journal_rec *rec;   /* go-motion: this frame's, for its exposure */
	bool pending;              /* a frame left in this pass */
	bool active;               /* the line is asserted */
};

struct loop_trig {
	struct loop_pulse *pulse;     /* rig->ntrig */
	bool *dout_dirty;             /* rig->ndouts: a line changed this tick */
	struct journal *jr;           /* NULL: no journal */
	struct journal_rec *cur_rec;  /* the current frame's, for its worst ferror */
};

/* Step mode: MOVE, SETTLE and EXPOSE of one frame after another. */
struct loop_step {
	struct frame_iter fit;
	int64_t frame;          /* the frame being shot */
	int64_t settled;        /* ticks every drive has been in position */
	int64_t fired_at;       /* the tick its trigger rose */
	bool has_ready_input;   /* a camera-ready input says when it is exposed */
	bool ready;             /* camera-ready asserted */
	bool ready_since_fire;  /* ...at some tick since the trigger rose */
};

/*
 * What each line of each input device is for, made at [init] so that an
 * edge costs one lookup: input device d's lines are in_of[in_first[d]] to
 * in_of[in_first[d + 1] - 1], each the index of its input in rig->in, or
 * -1 for a line no input has.
 */
struct loop_safety {
	_Atomic int stop_req;   /* level (0, 1 controlled, 2 immediate) | cause << 2 | end << 10 */
	/* the report published for other threads (loop_report_now): a
	 * sequence count, odd while the loop writes the copy */
	_Atomic uint32_t rep_seq;
	struct loop_report rep_pub;
	bool *dev_off;          /* rig->naxes: axis devices disabled */
	uint32_t *in_first;     /* rig->ndins + 1 */
	int32_t *in_of;         /* in_first[ndins] */
	int32_t estop_in;       /* this tick: the input of the first asserted e-stop edge, or -1... */
	int64_t estop_edge_ns;  /* ...and its time */
	struct hal_edge edges[LOOP_EDGES_MAX]; /* the input poll's buffer */
};

struct loop {
	struct loop_cfg cfg;
	struct rig *rig;
	struct play_source *src;
	struct hal_clock *clk;
	struct hal_ring *status;  /* NULL: no status samples */
	const struct mot_timing *tm;
	uint32_t n;               /* outputs */
	uint32_t sat;             /* the core's saturation flags, sticky */
	struct lim_stencil stencil; /* the limit predicate's differences */
	int64_t t0;               /* monotonic ns of tick 0 */
	int64_t tick;             /* the tick being run */

	struct loop_out *out;     /* n */
	mot_q32 *val, *prev;      /* poses: this tick's setpoints, the last tick's */
	struct loop_seq seq;
	struct loop_trig trig;
	struct loop_step step;
	int64_t *limited;         /* n: the result's, written here */
	struct loop_result *res;
	struct loop_live *live;   /* NULL but in live mode (loop_live.c) */
	struct chase *chase;      /* NULL: the loop's own time */
	struct loop_safety safety; /* last: the edge buffer is large and seldom used */
};

/* Where the trouble is, for the report (struct loop_report's fields of
 * the same names). */
struct loop_where {
	const char *device;
	int32_t channel;
	int32_t out;
	const char *what;
	int code;
	uint32_t detail;
	double value, bound;
	bool has_edge;
	int64_t edge_ns, acted_ns;
};

/* [rt] Output i's speed from the last setpoint to this tick's, units/s. */
static inline double STRAND_RT loop_speed(const struct loop *L, uint32_t i)
{
	return (move_q2d(L->val[i]) - move_q2d(L->prev[i])) * L->tm->tick_hz;
}

/* [rt] Output i's following error this tick (what was sent last tick minus
 * where the drive is, as loop_feedback read it), core units, into *fe;
 * false when there is none to measure: a velocity channel, a disabled
 * device, no feedback this tick. */
static inline bool STRAND_RT loop_ferror(const struct loop *L, uint32_t i, double *fe)
{
	if (!L->out[i].has_fb || L->safety.dev_off[L->rig->out[i].dev])
		return false;
	*fe = L->out[i].fe;
	return true;
}

/* ---- loop_safety.c ---- */

/*
 * [rt] Record why the run ends, and where (NULL: nowhere in particular).
 * The first reason stands, except that an e-stop outranks them all: every
 * failure goes through here, and nothing else writes the report. What to
 * do about it is the caller's: loop_halt or loop_stop, which call this.
 */
void loop_fail(struct loop *L, enum loop_end end, enum loop_cause cause,
	       const struct loop_where *w);
/* [rt] E-stop and the immediate stop: drives off, triggers off, the run
 * ends in this tick. */
void loop_halt(struct loop *L, enum loop_end end, enum loop_cause cause,
	       const struct loop_where *w);
/* [rt] A controlled stop: no new triggers, every output to rest. */
void loop_stop(struct loop *L, enum loop_end end, enum loop_cause cause,
	       const struct loop_where *w);
/* [rt] Where a device's latched fault is (on no output in particular). */
struct loop_where loop_where_fault(const char *device, const struct hal_fault *f);
/* [rt] Where output i is, for a fault on it (value and bound in core units). */
struct loop_where loop_where_out(const struct loop *L, uint32_t i, double value, double bound);
/* [rt] Axis device dev reported f: it is disabled at once, the rest stops. */
void loop_fault_device(struct loop *L, uint32_t dev, const struct hal_fault *f);

/* [rt] The tick's steps, in the order loop_tick takes them. */
void loop_inputs(struct loop *L, int64_t now);
void loop_feedback(struct loop *L, double *worst, int32_t *worst_out);
void loop_limits(struct loop *L);

/* ---- loop_plan.c ---- */

/* [rt] The pose at a scene tick, into out. */
void loop_eval_at(struct loop *L, int64_t scene_tick, mot_q32 *out);
/* [rt] The frames of pass seq.pass, in firing order, the scene ticks it
 * covers, and every trigger's first edge in it. */
void loop_pass_setup(struct loop *L);
/* [rt] The way into the pass: 0, or -1 with the output in *bad when its
 * ramp would start outside its position limits. */
int loop_entry_plan(struct loop *L, int32_t *bad);
/* [rt] Output i at step j of the run-up. */
mot_q32 loop_runup_at(const struct loop *L, uint32_t i, int64_t j);
/* [rt] A move from `from` (at rest) to `to`. */
void loop_move_plan(struct loop *L, const mot_q32 *from, const mot_q32 *to);
/* [rt] Another pass after this one. */
bool loop_more_passes(const struct loop *L);
/* [rt] Every output one tick closer to rest; true when all are there. */
bool loop_rest_step(struct loop *L);
/* [init or rt] Go-motion's timeline: frames cfg.from..cfg.to of its source. */
void loop_gomo_setup(struct loop *L);
/* [rt] Go-motion frame step.frame: its exposure, the run-up into it, and in
 * seq.target where the run-up starts: 0, or -1 with the output in *bad when
 * that is outside its position limits. */
int loop_gomo_plan(struct loop *L, int32_t *bad);
/* [rt] The run-up begins at run tick t0, every trigger's edge set. */
void loop_gomo_start(struct loop *L, int64_t t0);

/* ---- loop_chase.c ---- */

/* [rt] The source's marks, its events (a controlled stop), the cue. */
void loop_chase_tick(struct loop *L, int64_t now);
/* [rt] After a tick: a run the source stopped waits for it again. */
void loop_chase_after(struct loop *L);
/* [rt] The source's frame at time t, plus one, for the journal (0: none). */
uint32_t loop_chase_frame(struct loop *L, int64_t t);

/* ---- loop_trig.c ---- */

/* [rt] Pulses ending, edges due, step mode's gates, the journal's FIRED. */
void loop_triggers(struct loop *L, int64_t due);
/* [rt] Every trigger deasserted in this tick, none pending. */
void loop_triggers_off(struct loop *L);
/* [rt] A pulse is under way. */
bool loop_pulses_active(const struct loop *L);
/* [rt] A trigger's edge still to come in this frame or pass. */
bool loop_pulses_pending(const struct loop *L);
/* [rt] Go-motion: the exposure's ticks and poses into this frame's
 * records, once the exposure has ended and they exist. */
void loop_gomo_journal(struct loop *L);

/* ---- loop_tick.c ---- */

/* [rt] The ordinary status sample of this tick into *s. */
void loop_status_fill(const struct loop *L, struct loop_status *s);

/* ---- loop_live.c (live mode only) ---- */

/* [rt] The commands waiting, at the start of a tick. */
void loop_live_commands(struct loop *L);
/* [rt] This tick's setpoints in HOLD, JOG and MOVE. */
void loop_live_sequence(struct loop *L);
/* [rt] A segment that ended goes back to HOLD; what ends the run stays. */
void loop_live_tick_end(struct loop *L);
/* [rt] The live status sample. */
void loop_live_status(struct loop *L);

#endif /* STRAND_LOOP_PRIV_H */
