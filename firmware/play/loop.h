/* SPDX-License-Identifier: MIT */
/*
 * loop.h - the real-time loop: one tick after another at the scene's
 * tick_hz, each doing
 *
 *     read inputs -> evaluate the tick's pose -> check runtime limits ->
 *     write outputs -> fire the trigger edges due -> record statistics
 *
 * on a rig built by rig.h from a source of channel values (source.h).
 *
 * Sequence. A run is a chain of segments, each producing one setpoint per
 * output per tick:
 *
 *   continuous   PREROLL (a move from where the rig stands to the start of
 *                the run-up) -> RUNUP -> PLAY (the scene, tick by tick) ->
 *                POSTROLL (to rest); with --loop or --ping-pong each pass
 *                is followed by BRIDGE (to rest, then a move to the next
 *                pass's run-up)
 *
 * The run-up exists because a range may start where the scene is already
 * moving (--from 100 in the middle of a pan): arriving there at rest and
 * jumping to the scene's speed would break the acceleration limit. So each
 * channel ramps its speed linearly up to the scene's first speed v, at its
 * acceleration limit, over n = ceil(|v| / (amax dt)) ticks, ending exactly
 * on the first pose; the pre-roll brings it to rest at the ramp's start,
 * v dt (n + 1) / 2 behind that pose. The ramps of all channels end on the
 * same tick. A ramp that would start outside a channel's position limits is
 * refused with the channel named.
 *   step         for each frame: MOVE to its exact pose -> SETTLE (every
 *                drive in position for the settle time) -> the trigger ->
 *                EXPOSE (exposure time, or the camera-ready edge)
 *
 * A move that covers no distance takes no tick. Frame f's trigger in PLAY
 * rises when the scene tick is FORMULAS.md section 5's tick for f plus the
 * trigger's offset (in the direction of play), and falls `width` ticks
 * later. Ping-pong never shows an end frame twice: F..T, T-1..F, F+1..T.
 *
 * Time. Tick k is due at t0 + k / tick_hz exactly (integer nanoseconds,
 * computed from k, never accumulated). The loop sleeps until a tick is due
 * (clock_nanosleep, TIMER_ABSTIME). When it wakes late, or a tick's work ends
 * after the next tick was due (an overrun, counted), the following ticks are
 * already due and run at once, back to back, each with its own tick number,
 * until the loop is on time again: nothing is skipped and nothing drifts.
 * A frame trigger therefore always belongs to its own tick and never
 * repeats; in wall time it goes out late by however late the loop is, and
 * the journal's due_ns and mono_ns columns show by how much. The motion is
 * not skipped either: the drives receive the missed ticks' setpoints in
 * quick succession, so a stall shows as a short burst, not a jump. The
 * statistics count such catch-up ticks apart from wake-up latency
 * (latency.h).
 *
 * Safety, checked every tick:
 *   - an e-stop input: every drive disabled, every trigger deasserted, in
 *     the tick its edge (or asserted level) is seen; the run ends (latched:
 *     nothing moves again until strand is started anew with the e-stop
 *     released; a run does not start while it is asserted);
 *   - a device fault, or a following error beyond its bound
 *     (max(min_ferror, ferror * |v| / vmax), LinuxCNC's speed scaling):
 *     the faulty device is disabled at once, every other output comes to
 *     rest within its limits, the run ends with the device, channel and
 *     cause named;
 *   - runtime limits (position, speed and acceleration by finite
 *     differences): a setpoint beyond them is not sent; the run stops as
 *     for a fault. With --force the setpoint is clamped instead and counted;
 *   - a stop request (SIGINT, SIGTERM, a stop input, --duration): no new
 *     triggers, every output to rest within its limits, a pulse under way
 *     ends normally; a second request of the immediate kind (second SIGINT)
 *     disables everything at once, as the e-stop does.
 *
 * Real-time rules: loop_tick and loop_run allocate nothing, make no file or
 * terminal I/O and take no lock; telemetry leaves through an SPSC ring, the
 * journal is a mapping written in place (journal.h).
 */
#ifndef STRAND_LOOP_H
#define STRAND_LOOP_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "frames.h"
#include "hal/clock.h"
#include "hal/ring.h"
#include "journal/journal.h"
#include "latency.h"
#include "move.h"
#include "rig/rig.h"
#include "scene/source.h"

enum loop_mode {
	LOOP_MODE_CONTINUOUS,
	LOOP_MODE_STEP,
};

enum loop_state {
	LOOP_PREROLL,
	LOOP_RUNUP,
	LOOP_PLAY,
	LOOP_BRIDGE_STOP,
	LOOP_BRIDGE_MOVE,
	LOOP_POSTROLL,
	LOOP_STEP_NEXT,
	LOOP_STEP_MOVE,
	LOOP_STEP_SETTLE,
	LOOP_STEP_EXPOSE,
	LOOP_STOPPING,
	LOOP_ENDED,
};

enum loop_end {
	LOOP_END_NONE,
	LOOP_END_DONE,     /* exit 0 */
	LOOP_END_STOPPED,  /* exit 5 */
	LOOP_END_ESTOP,    /* exit 6 */
	LOOP_END_FAULT,    /* exit 7 */
	LOOP_END_INTERNAL, /* exit 8 */
};

enum loop_cause {
	LOOP_CAUSE_NONE,
	LOOP_CAUSE_FINISHED,    /* the frames ran out */
	LOOP_CAUSE_DURATION,    /* --duration elapsed */
	LOOP_CAUSE_SIGNAL,      /* SIGINT/SIGTERM: controlled stop */
	LOOP_CAUSE_IMMEDIATE,   /* second SIGINT: drives off at once */
	LOOP_CAUSE_STOP_INPUT,  /* a stop input */
	LOOP_CAUSE_ESTOP,       /* the e-stop input */
	LOOP_CAUSE_DEVICE,      /* a device reported a fault */
	LOOP_CAUSE_FERROR,      /* following error beyond its bound */
	LOOP_CAUSE_LIMIT_POS,   /* a setpoint outside [min, max] */
	LOOP_CAUSE_LIMIT_VEL,
	LOOP_CAUSE_LIMIT_ACC,
	LOOP_CAUSE_IN_POSITION, /* step mode: drives not in position in time */
	LOOP_CAUSE_READY,       /* step mode: no camera-ready edge in time */
	LOOP_CAUSE_JOURNAL,     /* the journal could not take the frame */
	LOOP_CAUSE_SATURATION,  /* fixed-point arithmetic saturated */
};

/* What ended the run, for the message at the edge. */
struct loop_report {
	enum loop_end end;
	enum loop_cause cause;
	int code;           /* negative errno from a device, else 0 */
	const char *device; /* device or input name, or NULL */
	int32_t channel;    /* device channel or line, -1 if none */
	int32_t out;        /* output index, -1 if none */
	const char *what;   /* the device's cause text, or NULL */
	uint32_t detail;
	double value, bound; /* core units (ferror, limit) */
	int64_t tick;       /* run tick it happened at */
	int64_t frame;      /* last frame fired then, -1 if none */
	/* e-stop: the input edge's own time (the kernel's, for GPIO) and the
	 * clock when the loop acted; has_edge false when it was seen by its
	 * level alone (asserted before the run) */
	bool has_edge;
	int64_t edge_ns, acted_ns;
};

struct loop_cfg {
	enum loop_mode mode;
	int64_t from, to;  /* continuous: frames to fire, from <= to */
	bool loop, ping_pong;
	int64_t passes;    /* with loop or ping_pong: passes to play, 0 = no end */
	const struct frame_list *frames; /* step mode */
	int64_t settle_ticks, exposure_ticks;
	int64_t in_position_timeout_ticks, ready_timeout_ticks;
	bool force;        /* clamp setpoints beyond the limits instead of stopping */
	int64_t max_ticks; /* controlled stop after this many ticks, 0 = none */
	uint32_t status_every; /* ticks between status samples (>= 1) */
	bool wait_for_journal; /* virtual clock: wait for the journal's service */
};

/* A status sample, pushed into the status ring. */
struct loop_status {
	int64_t tick;
	int64_t frame;      /* last frame fired, -1 before the first */
	int64_t fired;      /* triggers fired so far */
	int64_t total;      /* frames the run will fire, -1 when it has no end */
	int64_t lat_max_ns; /* worst wake-up latency so far */
	int64_t overruns;
	double ferr;        /* worst following error so far, core units */
	int32_t ferr_out;
	uint8_t state;      /* enum loop_state */
	uint8_t end;        /* enum loop_end */
};

struct trig_state {
	int64_t next_frame; /* the next frame to fire in this pass */
	int64_t edge_k;     /* PLAY: the scene tick its edge rises at */
	int64_t fall_tick;  /* run tick the pulse ends at */
	bool pending;       /* a frame left in this pass */
	bool active;
};

#define LOOP_EDGES_MAX 32

struct loop {
	struct loop_cfg cfg;
	struct rig *rig;
	struct play_source *src;
	struct hal_clock *clk;
	struct journal *jr;     /* NULL: no journal */
	struct hal_ring *status; /* NULL: no status samples */
	const struct mot_timing *tm;
	uint32_t n;             /* outputs */
	int64_t t0;             /* monotonic ns of tick 0 */
	int64_t ns_whole, ns_frac; /* one tick: ns_whole + ns_frac / tick_hz ns */

	/* per output */
	mot_q32 *val, *prev;    /* setpoints: this tick, the last one */
	double *vel;            /* speed of the last setpoints, units/s */
	int64_t *sent;          /* counts sent last tick */
	struct hal_setpoint *sp; /* this tick's, in counts */
	mot_q32 *target;        /* a pose (the next pass's first, a frame's) */
	double *vmax, *amax;
	int64_t *limited;       /* ticks clamped under --force */
	struct move mv;
	struct move_ch *mv_ch;
	int64_t mv_j;
	mot_q32 *ru_end;        /* run-up: the pass's first pose */
	double *ru_v;           /* the scene's speed there, units/s */
	int64_t *ru_n;          /* ramp ticks per channel */
	int64_t ru_ticks, ru_j;
	bool *dev_off;          /* axis devices disabled */
	bool *dout_dirty;
	struct journal_rec **armed; /* ntrig */

	/* sequence */
	enum loop_state state;
	int64_t tick;           /* the tick being run */
	int64_t seg_j;          /* ticks into the present segment */
	int64_t pass;
	int dir;
	int64_t scene_k, scene_begin, scene_end;
	int64_t pass_first, pass_last; /* frames in firing order */
	int64_t lead, tail;     /* scene ticks before the first edge, after the last */
	struct trig_state *ts;
	struct frame_iter fit;
	int64_t step_frame, settled, fired_at;
	bool ready;             /* camera-ready asserted */
	bool ready_since_fire;
	bool has_ready_input;
	int64_t total_frames;   /* -1: no end */

	/* the current frame's journal record and worst following error */
	struct journal_rec *cur_rec;

	_Atomic int stop_req;   /* 0, 1 controlled, 2 immediate */
	enum loop_cause stop_cause;
	struct hal_edge edges[LOOP_EDGES_MAX];
	int64_t estop_edge_ns;  /* the last e-stop edge that asserted... */
	bool estop_edge;        /* ...if there was one during the run */

	/* results */
	struct loop_report rep;
	struct lat_stats lat;
	int64_t frames_fired;
	int64_t last_frame;
	double ferr_worst;
	int32_t ferr_worst_out;
	uint32_t sat;
	int64_t ticks_run;
	int64_t status_dropped;
	int64_t journal_waits;
	int64_t cpu_ns;         /* the loop thread's CPU time over the run */
};

/* [init] Prepare a run: everything the loop touches is allocated here, and
 * the rig (started) is read for where it stands. 0, or a negative errno
 * with a message. */
int loop_init(struct loop *L, const struct loop_cfg *cfg, struct rig *rig,
	      struct play_source *src, struct hal_clock *clk, struct journal *jr,
	      struct hal_ring *status, char *err, size_t errsize);
void loop_free(struct loop *L);

/* [rt] Run ticks until the run ends. t0: when tick 0 is due. */
void loop_run(struct loop *L, int64_t t0);

/* [rt] One tick: k is due at due_ns and the loop woke at now_ns; false
 * once the run has ended. */
bool loop_tick(struct loop *L, int64_t k, int64_t due_ns, int64_t now_ns);

/* [any thread, signal handlers] Ask for a controlled (level 1) or an
 * immediate (level 2) stop. Async-signal-safe. */
void loop_request_stop(struct loop *L, int level, enum loop_cause cause);

/* The nanosecond tick k is due at. */
int64_t loop_due(const struct loop *L, int64_t k);

const char *loop_state_name(enum loop_state s);
const char *loop_cause_name(enum loop_cause c);

#endif /* STRAND_LOOP_H */
