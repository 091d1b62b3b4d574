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
 *   go-motion    step mode with a shutter (plan/gomo.h), for each frame:
 *                MOVE to where its run-up starts -> SETTLE -> (ARMED, until
 *                told to go, when cfg.gomo_wait) -> GOMO_RUNUP (runup.h,
 *                at least the triggers' lead long) -> GOMO_EXPOSE (the
 *                scene's ticks of the exposure; the trigger rises at its
 *                first, moved by its offset) -> GOMO_RUNOUT (to rest at the
 *                acceleration limits, as the post-roll) -> EXPOSE
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
 *     the tick its edge (or asserted level) is seen, even when the contact
 *     is closed again by then; the run ends (latched:
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
 * When more than one of these happens, the report keeps the first, except
 * that an e-stop outranks every other reason (loop_fail, loop_safety.c).
 *
 * Real-time rules: loop_tick and loop_run allocate nothing, make no file or
 * terminal I/O and take no lock; telemetry leaves through an SPSC ring, the
 * journal is a mapping written in place (journal.h).
 *
 * Memory. A loop is one block: loop_init measures what the run needs (the
 * rig's outputs, devices and triggers), allocates exactly that once, carves
 * it with the core's arena (motion/arena.h) and seals it. struct loop is
 * private to the loop's files (loop_priv.h); what a run leaves behind is
 * read through loop_result().
 */
#ifndef STRAND_LOOP_H
#define STRAND_LOOP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "frames.h"
#include "hal/clock.h"
#include "hal/ring.h"
#include "journal/journal.h"
#include "latency.h"
#include "rig/rig.h"
#include "scene/source.h"

struct chase;

/*
 * Input edges the loop takes from one input device in one tick, at most:
 * what a tick spends on its inputs is bounded however many edges a line
 * makes. Edges beyond it stay queued in the device, in order, for the
 * next tick (a GPIO device whose ring fills faults, which halts the run:
 * hal/gpio/gpio.h). The e-stop does not wait for them: the loop checks it
 * by its level every tick as well, and a level is the newest the device
 * knows, edges still queued included (din.h). So an edge storm on another
 * line, ahead of the e-stop's own edge, delays the e-stop by nothing; it
 * only delays the edges of that storm.
 *
 * The value: 256 is the GPIO backend's ring (HAL_GPIO_RING_DEFAULT), so
 * everything the ring held when the tick began is taken in that tick;
 * edges that come in during the drain wait for the next. A bouncing
 * contact makes tens of edges in the few milliseconds it bounces (the
 * event thread passes each change on), so a bounce on every input at once
 * is still taken whole; more than 256 from one device within one tick is
 * a line that oscillates, whose edges may as well wait. Each edge costs a
 * table lookup and a store or two (loop_safety.c): the bound is a few
 * microseconds of work per device at most.
 */
#define LOOP_EDGES_PER_TICK 256

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
	LOOP_CUE,          /* --chase: at rest, waiting for the source (loop_chase.c) */
	/* live mode (loop_live.h) */
	LOOP_HOLD,
	LOOP_JOG,
	LOOP_MOVE,
	/* go-motion (loop.h, "Sequence") */
	LOOP_GOMO_ARMED,   /* at the run-up's start, settled, waiting for loop_gomo_go */
	LOOP_GOMO_RUNUP,
	LOOP_GOMO_EXPOSE,
	LOOP_GOMO_RUNOUT,
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
	LOOP_CAUSE_CHASE,       /* the chased source: detail is its enum chase_event */
	LOOP_CAUSE_BOARD,       /* another board of a lockstep run (play/lockstep) */
	LOOP_CAUSE_DISABLE,     /* live mode: the drives were disabled */
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
	/* step mode: go-motion with this shutter, a Q32.32 fraction of a frame
	 * (plan/gomo.h), 0: none. The exposures run on the timeline of frames
	 * from..to (the ends go on at their speed, plan/timeline.h) of
	 * gomo_src, or of the run's source when it is NULL (the same tick
	 * rate); gomo_wait: each frame waits, settled at its run-up's start,
	 * for loop_gomo_go(); gomo_runup_ticks: the run-up lasts this long at
	 * least (a front end that said how long it takes: DFMoco's bf) */
	mot_q32 shutter;
	struct play_source *gomo_src;
	bool gomo_wait;
	int64_t gomo_runup_ticks;
	int64_t settle_ticks, exposure_ticks;
	int64_t in_position_timeout_ticks, ready_timeout_ticks;
	bool force;        /* clamp setpoints beyond the limits instead of stopping */
	int64_t max_ticks; /* controlled stop after this many ticks, 0 = none */
	uint32_t status_every; /* ticks between status samples (>= 1) */
	bool wait_for_journal; /* virtual clock: wait for the journal's service */
	bool live;         /* no run planned: loop_live_init makes it a live loop */
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

/*
 * What a run leaves behind. The loop thread writes it while the run lasts
 * (code running on that thread, a simulated device's callback, may read it
 * then); anyone may read it once loop_run has returned.
 */
struct loop_result {
	struct loop_report rep; /* why the run ended; end NONE while it runs */
	int64_t total_frames;   /* triggers the run will fire, -1: no end */
	int64_t frames_fired;
	int64_t last_frame;     /* the last frame fired, -1 before the first */
	int64_t ticks_run;
	double ferr_worst;      /* worst |following error|, core units */
	int32_t ferr_worst_out; /* its output, -1 while no output has feedback */
	int64_t status_dropped; /* status samples the ring had no room for */
	int64_t cpu_ns;         /* the loop thread's CPU time over the run */
	const int64_t *limited; /* per output: ticks clamped under --force */
	int64_t edges;          /* input edges taken from the devices */
	int64_t edges_tick_max; /* ... the most from one device in one tick */
	int64_t edges_bound_ticks; /* times a device gave LOOP_EDGES_PER_TICK in a tick */
	struct lat_stats lat;   /* last: 40 KB of histogram */
};

struct loop;

/* [init] Prepare a run in *out: everything the loop touches is allocated
 * here, in one block, and the rig (started) is read for where it stands.
 * 0, or a negative errno with a message (*out is NULL then): -EINVAL for
 * options that contradict the scene, -EDOM for an output that stands
 * outside its position limits, -ERANGE for a run it cannot plan. */
int loop_init(struct loop **out, const struct loop_cfg *cfg, struct rig *rig,
	      struct play_source *src, struct hal_clock *clk, struct hal_ring *status,
	      char *err, size_t errsize);

/* [init] Record every frame fired in jr from now on (before loop_run; the
 * journal is sized from loop_result()->total_frames). */
void loop_set_journal(struct loop *L, struct journal *jr);

/* [init] Chase c's source (chase.h, loop_chase.c): the run waits in
 * LOOP_CUE for a lock, cues the frame the source names, plays it on the
 * source's time, and cues again after each stop the source causes.
 * Continuous mode without --loop or --ping-pong; before loop_run. */
void loop_set_chase(struct loop *L, struct chase *c);

/* [init] NULL: nothing to free. */
void loop_free(struct loop *L);

/* [rt] Run ticks until the run ends. t0: when tick 0 is due. */
void loop_run(struct loop *L, int64_t t0);

/* [rt] A go-motion frame waiting in LOOP_GOMO_ARMED runs up from this
 * tick on: 0, or -EAGAIN when none waits. The loop's thread only (a
 * front end reaches it through its commands). */
int loop_gomo_go(struct loop *L);

/* [rt] One tick: k is due at due_ns and the loop woke at now_ns; false
 * once the run has ended. */
bool loop_tick(struct loop *L, int64_t k, int64_t due_ns, int64_t now_ns);

/* [any thread, signal handlers] Ask for a controlled (level 1) or an
 * immediate (level 2) stop. Async-signal-safe. */
void loop_request_stop(struct loop *L, int level, enum loop_cause cause);

/* [any thread] The same, ending the run as end (exit code) rather than
 * LOOP_END_STOPPED: another board's e-stop (LOOP_END_ESTOP) or fault. */
void loop_request_end(struct loop *L, int level, enum loop_end end, enum loop_cause cause);

/* [any thread] The level of stop asked for so far: 0, 1 or 2. */
int loop_stop_requested(const struct loop *L);

/* [any thread] Why the run is ending, as the loop decided it (the report
 * as it stands, copied whole): false while it plays on. For a thread that
 * must act on the run's end as it happens (the lockstep's watch). */
bool loop_report_now(const struct loop *L, struct loop_report *out);

/* [init] The run tick at which play begins: the pre-roll and run-up's
 * ticks (continuous mode, after loop_init). */
int64_t loop_play_tick(const struct loop *L);

/* The nanosecond tick k is due at. */
int64_t loop_due(const struct loop *L, int64_t k);

/* The run's results (see struct loop_result for when they may be read). */
const struct loop_result *loop_result(const struct loop *L);

const char *loop_state_name(enum loop_state s);
const char *loop_cause_name(enum loop_cause c);

#endif /* STRAND_LOOP_H */
