/* SPDX-License-Identifier: MIT */
/*
 * loop_live.h - the loop's live mode: instead of one run planned before it
 * starts, the loop holds the rig where it stands and takes commands while
 * it ticks (strand serve, live/live.h):
 *
 *     HOLD   every output at rest, its pose sent every tick
 *     JOG    outputs at commanded fractions of their speed limits
 *     MOVE   a move to a pose (a frame's), as a pre-roll moves
 *     play   a segment of strand play (continuous or step, every option),
 *            back to HOLD when it ends
 *
 * Commands come in through an SPSC ring (struct loop_cmd), at most
 * LOOP_LIVE_CMDS_PER_TICK a tick, each answered through a second ring
 * (struct loop_ack) in the tick that takes it. The e-stop does not queue:
 * it is loop_request_stop(L, 2, LOOP_CAUSE_ESTOP), an atomic store the
 * next tick sees before anything else.
 *
 * The run ends (loop_tick returns false) on everything that leaves the
 * drives off or must leave them so: an e-stop, a device fault or limit
 * (once the others are at rest), a disable (once at rest), a signal. The
 * owner then stops the devices; a new run enables them again.
 *
 * Jog. Each output has its own commanded fraction f of its speed limit
 * (JOG sets one output's, JOG_VEC every output's at once: a jog of the
 * camera or a node, whose outputs move together); its speed follows
 * f * vmax at no more than amax a second, the outputs whose speeds change
 * together reaching theirs in the same tick (a vector jog keeps its
 * direction while it ramps), and never exceeds the speed from which it can
 * stop on its position limit within amax (the braking curve, in whole
 * ticks: see jog_vmax in loop_live.c), so it arrives on the limit and
 * stays there. A rig found outside a position limit holds there and may be
 * jogged or moved back, never further out (loop_safety.c: outside_ok). A jog lapses (f = 0) when no refresh came for
 * deadman_ticks.
 */
#ifndef STRAND_LOOP_LIVE_H
#define STRAND_LOOP_LIVE_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "frames.h"
#include "journal/journal.h"
#include "loop.h"

/* Outputs a live rig may have: a move's pose travels inside a command. */
#define LOOP_LIVE_OUT_MAX 32
/* Items of a step mode frame list, carried inside a command. */
#define LOOP_LIVE_FRAME_ITEMS 16
/* Commands taken in one tick, at most: the rest wait for the next. */
#define LOOP_LIVE_CMDS_PER_TICK 8

enum loop_cmd_kind {
	LOOP_CMD_JOG,     /* out, speed */
	LOOP_CMD_JOG_VEC, /* vec: every output's fraction at once (a space jog) */
	LOOP_CMD_MOVE,    /* pose (at rest only) */
	LOOP_CMD_PLAY,    /* cfg and frames (at rest only) */
	LOOP_CMD_STOP,    /* a controlled stop to HOLD */
	LOOP_CMD_DISABLE, /* a controlled stop, then the run ends */
	LOOP_CMD_SOURCE,  /* a new source (a taught scene), at rest only */
	LOOP_CMD_NOP,     /* answered, nothing done (a probe of the latency) */
	LOOP_CMD_GO,      /* a go-motion frame waiting armed runs up (loop_gomo_go) */
};

/* Why the loop refused a command (struct loop_ack.code), 0 when taken. */
enum loop_cmd_err {
	LOOP_CMD_OK = 0,
	LOOP_CMD_BUSY = 1,      /* the rig is not at rest */
	LOOP_CMD_LIMIT = 2,     /* a target outside its output's limits */
	LOOP_CMD_RUNUP = 3,     /* a run-up from outside the limits */
	LOOP_CMD_INVALID = 4,   /* an index or a value out of range */
	LOOP_CMD_STOPPING = 5,  /* the run is ending */
};

struct loop_cmd {
	uint64_t seq;
	int64_t arrival_ns;  /* hal_mono_ns() when it came in: for the latency */
	uint32_t kind;       /* enum loop_cmd_kind */
	uint32_t out;        /* JOG */
	double speed;        /* JOG: fraction of vmax, -1..1 */
	double vec[LOOP_LIVE_OUT_MAX]; /* JOG_VEC: each output's fraction, -1..1 */
	bool keep;           /* JOG_VEC: a new direction for a jog under way, not a
			      * refresh (its dead-man runs on); none under way: ignored */
	mot_q32 pose[LOOP_LIVE_OUT_MAX]; /* MOVE */
	int64_t frame;       /* MOVE: the frame whose pose it is, -1 */
	struct loop_cfg cfg; /* PLAY: mode, from, to, loop, ping_pong, passes, times, and
			      * go-motion's shutter, gomo_src, gomo_wait, gomo_runup_ticks */
	uint32_t nframes;    /* PLAY step: frames[0..nframes) */
	struct frame_item frames[LOOP_LIVE_FRAME_ITEMS];
	struct play_source *src; /* SOURCE */
	struct journal *jr;  /* PLAY: the segment's journal, or NULL (the owner's,
			      * open and serviced until the segment is over) */
};

struct loop_ack {
	uint64_t seq;
	int32_t code;        /* enum loop_cmd_err */
	int32_t out;         /* LIMIT, RUNUP: the output, else -1 */
	int64_t tick;        /* the tick that took it */
	int64_t latency_ns;  /* that tick's wake-up (hal_mono_ns) less arrival_ns */
};

/* One output in a status sample. */
struct loop_live_out {
	double sp;    /* setpoint, core units */
	double act;   /* actual position, core units (when has_act) */
	double fe;    /* following error, core units (when has_act) */
	double vel;   /* speed of the setpoints, core units/s */
	uint8_t has_act;
	uint8_t off;  /* its device is disabled */
	uint8_t jog;  /* being jogged */
	uint8_t pad[5];
};

/*
 * A live status sample: the loop's ordinary one, then what a console
 * shows, then one struct loop_live_out per output (the ring's element is
 * loop_live_status_size(n) bytes).
 */
struct loop_live_status {
	struct loop_status s;
	uint64_t cmd_seq;       /* the last command taken */
	int64_t seg_first;      /* the segment's first frame, -1 outside one */
	int64_t at_frame;       /* the frame the rig is at (the last fired in a
				 * segment, a move's frame), -1 off any */
	int64_t lat_n, lat_min_ns, lat_sum_ns; /* wake-ups so far */
	int64_t t_ns;           /* the tick's due time */
	struct loop_report rep; /* the last segment's end (end NONE: none yet) */
	uint32_t n;
	uint32_t pad;
	struct loop_live_out out[];
};

static inline uint32_t loop_live_status_size(uint32_t n)
{
	return (uint32_t)(sizeof(struct loop_live_status) + n * sizeof(struct loop_live_out));
}

struct loop_live_cfg {
	struct hal_ring *cmds;   /* struct loop_cmd, the owner's to push */
	struct hal_ring *acks;   /* struct loop_ack, the owner's to pop */
	int64_t deadman_ticks;   /* a jog lapses after this many ticks without a refresh */
	/* virtual clock: ticks paced at the wall's speed (a console's user
	 * watches, a client's jog refreshes keep up with the dead-man) at rest
	 * and in a jog, or in every state (pace_all) */
	bool pace, pace_all;
	/* the owner's requests, read at the start of every tick: an e-stop
	 * (the run halts: drives off at once) and a signal's stop level (1
	 * controlled, 2 immediate); never waiting behind a command */
	const _Atomic bool *estop;
	const _Atomic int *signal;
};

/* [init] Make L a live loop (after loop_init with cfg.live): it holds the
 * pose read from the rig. 0, or -ENOMEM / -EINVAL (too many outputs). */
int loop_live_init(struct loop *L, const struct loop_live_cfg *lc, char *err, size_t errsize);

/* [init] What loop_free frees of it. */
void loop_live_free(struct loop *L);

#endif /* STRAND_LOOP_LIVE_H */
