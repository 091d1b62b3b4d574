/* SPDX-License-Identifier: MIT */
/*
 * live.h - a rig under live control: the command API of strand serve, and
 * of any other front end (a motion-control protocol, a gamepad daemon).
 *
 * A live session owns the rig: it opens the scene's devices (or their
 * simulated twins), starts them with the drives disabled, and, while they
 * are enabled, runs the real-time loop in live mode (play/loop_live.h):
 * holding the pose at rest, taking commands between ticks. Every command
 * is a function here, answered with 0 or a negative errno and a message
 * that names what is wrong; none blocks longer than a tick or two of the
 * loop, but enable and disable, which start and stop devices.
 *
 * Machine states (struct live_snap.state), changed by commands only:
 *
 *   DISABLED   the devices open, the drives disabled; enable -> ENABLED
 *   ENABLED    the drives enabled, the rig at rest holding its pose
 *   MOVING     jog, move to a frame or a pose, play, step
 *   STOPPING   a controlled stop (stop, disable) under way
 *   ESTOPPED   latched by an e-stop (a command or the input): drives off
 *              until reset, which the e-stop input must allow
 *   FAULTED    a device fault, following error or limit, named in
 *              snap.reason, until reset clears it
 *
 * Threads. Any number of threads may call the commands; they take turns on
 * the session's lock, which the loop never takes. live_estop() takes no
 * lock at all: it reaches the loop through an atomic store, ahead of any
 * command queued or under way, and gives up a start of the drives under
 * way. live_service() and live_snapshot() never wait for a command either
 * (a front end calls them from the thread that must stay responsive):
 * live_service() is the owner's to call every few milliseconds: it takes
 * the loop's status samples in, services the journal and notices the end
 * of a run (at its next round, when a command holds the lock).
 */
#ifndef STRAND_LIVE_H
#define STRAND_LIVE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "play/loop_live.h"
#include "play/rt.h"

enum live_state {
	LIVE_DISABLED,
	LIVE_ENABLED,
	LIVE_MOVING,
	LIVE_STOPPING,
	LIVE_ESTOPPED,
	LIVE_FAULTED,
};

struct live_opts {
	bool sim;             /* every device by its simulated twin */
	bool virtual_clock;   /* virtual time, at the wall's pace at rest and in a jog */
	bool pace_all;        /* virtual time: at the wall's pace in every state */
	bool force;           /* play and teach what strand check rejects */
	struct rt_opts rt;
	const char *journal;  /* a folder for each play segment's journal, or NULL */
	const char *journal_file; /* one journal of the whole session's shots (strand
				   * dfmoco), or NULL; journal is then unused */
	bool journal_gomo;    /* journal_file's records hold go-motion's exposures
			       * (JOURNAL_MODE_GOMO) */
	const char *lat_hist; /* each run's wake-up latency histogram, or NULL */
	const char *data_dir; /* where load and save find scene files */
	double deadman_ms;    /* a jog lapses without a refresh (250) */
	uint32_t status_hz;   /* status samples a second (250) */
};

/* A step-mode or continuous segment, as strand play's options say it. */
struct live_play {
	bool step;
	bool has_from, has_to;
	int64_t from, to;
	const char *frames;   /* step: a --frames spec, or NULL */
	bool loop, ping_pong;
	int64_t passes;
	double duration_s;    /* 0: none */
	double settle_ms, exposure_ms, timeout_s; /* step mode (200, 100, 10) */
	double shutter;       /* step mode: go-motion, a shutter angle in degrees
			       * (plan/gomo.h); 0: none */
};

/*
 * Go-motion through poses a front end gives, rather than the scene's (a
 * motion-control protocol's: DFMoco's bf and go). The rig runs in a
 * straight line from where it would stand a fraction `shutter` of the way
 * back to the previous pose to as far towards the next, centred on `at`,
 * at a constant speed on each side, in exposure_ms: go-motion's exposure
 * (plan/gomo.h) on a path through the three poses (scene/source_path.h),
 * with its run-up and run-out, checked against the limits first.
 */
struct live_gomo {
	int64_t frame;        /* the journal's frame number, 1 to 2^31 - 2 */
	uint32_t exposure_ms; /* the shutter's time, 1 to 3600000: the motion takes this long */
	uint32_t shutter;     /* the fraction of a frame interval, in thousandths: 1 to 1000 */
	/* per output, its device's counts: the poses at the previous frame,
	 * this one and the next */
	const int64_t *prev, *at, *next;
};

/* Teach: which strands take a key from the rig's pose. */
enum live_teach_what {
	LIVE_TEACH_ALL,       /* every strand that drives an output */
	LIVE_TEACH_NODES,     /* the nodes named */
};

#define LIVE_MSG 512

struct live;

/* One output as a console shows it. */
struct live_out_info {
	const char *channel;
	const char *unit;     /* "deg", "rpm", "" */
	double min, max, vmax, amax; /* file units; +-inf when unlimited */
	bool jog;             /* may be jogged (a position channel) */
	bool teach;           /* a joint's value: teach keys it */
	int32_t node;         /* its node, -1 */
};

/* The newest status: the loop's last sample and the session's state. */
struct live_snap {
	enum live_state state;
	char reason[LIVE_MSG];  /* ESTOPPED, FAULTED: why; else the last end */
	int64_t tick, t_ns;
	int64_t frame;          /* where the rig is: the last frame fired or
				 * moved to, -1 off any frame (after a jog) */
	int64_t fired, total;
	const char *loop_state; /* the loop's: hold, jog, move, pre-roll, play, ... */
	int64_t lat_max_ns, lat_min_ns, lat_avg_ns, overruns;
	uint64_t lat_n;
	int64_t journal_frames; /* the session journal's records (journal_file), else
				 * the last segment's, -1: none */
	uint32_t nout;
	struct loop_live_out out[LOOP_LIVE_OUT_MAX]; /* file units */
	uint64_t serial;        /* counts the samples taken in */
	uint64_t cmd_sent;      /* the last command sent to the loop ... */
	uint64_t cmd_seen;      /* ... and the last the sample's tick had taken */
	uint64_t generation;    /* counts scene loads and teaches */
	uint32_t fps_num, fps_den; /* the scene's frame rate (0: no scene) */
	int64_t taken_ns;       /* hal_mono_ns() when the sample came in */
};

/* [init] Open SCENE (a path) for live control: load, check, build the rig,
 * start the devices, disable the drives. 0, or a negative errno with the
 * message in err (a scene's file:line:column: message). SCENE NULL: no
 * scene until live_load; the data folder is then o->data_dir or ".". */
int live_open(struct live **out, const char *scene, const struct live_opts *o, char *err,
	      size_t errsize);
void live_close(struct live *lv);

/* The owner's round: status in, journal, a run's end. Returns the
 * milliseconds until it wants the next round. */
int live_service(struct live *lv);

/* Copy out the newest status. */
void live_snapshot(struct live *lv, struct live_snap *s);

/* Output i's value in file units as its device's counts, and back
 * (rig/scale.h): what a protocol that counts steps speaks. */
int64_t live_counts(struct live *lv, uint32_t i, double v);
double live_units(struct live *lv, uint32_t i, int64_t counts);

/* The scene's outputs and frames, for a console. */
uint32_t live_outputs(struct live *lv, struct live_out_info *out, uint32_t max);
void live_span(struct live *lv, int64_t *first, int64_t *last, uint32_t *num, uint32_t *den,
	       uint32_t *tick_hz, const char **name, const char **path);

/* Key frames of every strand that drives an output (for the timeline):
 * calls fn for each (channel, frame). */
void live_keys(struct live *lv, void (*fn)(void *ctx, const char *channel, double frame),
	       void *ctx);

/* What live_jog_space takes: "camera" when the scene has one, then each
 * free node, into names (at most max): their number. */
uint32_t live_jog_targets(struct live *lv, const char **names, uint32_t max);

const char *live_state_name(enum live_state s);

/* ---- commands: 0 or a negative errno, the message in msg ---- */

int live_enable(struct live *lv, char *msg, size_t size);
int live_disable(struct live *lv, char *msg, size_t size);
/* out by index; speed a fraction of its velocity limit, -1..1; seq must
 * grow with each command of a client (a doubled or stale one is ignored,
 * 0 returned); client: who sends it (a new client restarts the count). */
int live_jog(struct live *lv, uint64_t client, uint32_t out, double speed, uint64_t seq,
	     char *msg, size_t size);
/* Jog the camera ("camera") or a free node in its own space ("local") or
 * the world's ("world") about its pivot (live_space.c): axis x, y, z
 * (translate) or rx, ry, rz (rotate), or the camera's names for them:
 * truck (x), boom (y), dolly (-z, where it looks), tilt (rx), pan (ry),
 * roll (rz). Every output the motion carries follows, the fastest at speed
 * (-1..1) of its velocity limit; seq as for live_jog. */
int live_jog_space(struct live *lv, uint64_t client, const char *node, const char *space,
		   const char *axis, double speed, uint64_t seq, char *msg, size_t size);
/* A client went away: its jogs end at once. */
void live_client_gone(struct live *lv, uint64_t client);
int live_goto(struct live *lv, int64_t frame, char *msg, size_t size);
int live_step(struct live *lv, int dir, char *msg, size_t size);
/* A pose in file units, one value per output (NaN: where it stands). */
int live_move(struct live *lv, const double *pose, uint32_t n, char *msg, size_t size);
int live_play(struct live *lv, const struct live_play *p, char *msg, size_t size);
int live_stop(struct live *lv, char *msg, size_t size);
/* Go-motion through g's poses: checked (every output within its limits
 * over the run-up, exposure and run-out: -EDOM, the first violation in
 * msg), then the rig moves to where the run-up starts and waits there,
 * armed, for live_gomo_go. *delay_ms: from the go to the exposure's first
 * tick (the run-up lasts exactly that, within a tick). At rest only. */
int live_gomo(struct live *lv, const struct live_gomo *g, int64_t *delay_ms, char *msg,
	      size_t size);
/* The armed go-motion runs: -EBUSY when none is armed (yet). */
int live_gomo_go(struct live *lv, char *msg, size_t size);
/* At once, from any thread, never waiting (async-signal-safe). */
void live_estop(struct live *lv);
int live_reset(struct live *lv, char *msg, size_t size);
/* A scene file of the data folder, by name (no path). */
int live_load(struct live *lv, const char *name, char *msg, size_t size);
/* Key the pose where the rig stands at frame (nodes: n names, or every
 * strand that drives an output when n is 0). */
int live_teach(struct live *lv, double frame, const char *const *nodes, uint32_t n,
	       char *msg, size_t size);
int live_teach_delete(struct live *lv, const char *node, double frame, char *msg, size_t size);
int live_teach_move(struct live *lv, const char *node, double from, double to, char *msg,
		    size_t size);
/* The scene as it is now into the data folder as name (NULL: its own file). */
int live_save(struct live *lv, const char *name, char *msg, size_t size);

/* A probe of the command path: a command that does nothing, answered by
 * the tick that takes it; *latency_ns from its arrival (hal_mono_ns() when
 * the front end received it; 0: now) to that tick's wake-up. */
int live_ping(struct live *lv, int64_t arrival_ns, int64_t *latency_ns, char *msg,
	      size_t size);

/* Ask the loop to stop as a signal does (async-signal-safe): controlled,
 * or immediate for level 2. */
void live_signal(struct live *lv, int level);
/* The session is done (a signal stopped it): the owner may close it. */
bool live_finished(struct live *lv);

#endif /* STRAND_LIVE_H */
