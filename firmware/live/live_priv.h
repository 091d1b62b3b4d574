/* SPDX-License-Identifier: MIT */
/*
 * live_priv.h - the session's state, shared by its files:
 *
 *     live.c        [init] open, close, a scene's version, the service round
 *     live_run.c    [init] a run of the loop: enable, its end, disable
 *     live_cmd.c    the commands that reach the loop
 *     live_teach.c  teach: keys from the rig's pose into the scene file
 *     live_space.c  jog the camera or a free node in its space or the world's
 */
#ifndef STRAND_LIVE_PRIV_H
#define STRAND_LIVE_PRIV_H

#include <limits.h>
#include <pthread.h>
#include <stdatomic.h>

#include "live.h"
#include "hal/cancel.h"
#include "hal/clock.h"
#include "hal/ring.h"
#include "hal/thread.h"
#include "journal/journal.h"
#include "check/limit_check.h"
#include "load/load.h"
#include "motion/mat.h"
#include "play/loop.h"
#include "rig/rig.h"
#include "rig/rig_auto.h"
#include "scene/source_path.h"
#include "scene/source_scene.h"

#define LIVE_CMD_RING 16
#define LIVE_STATUS_RING 64

/* One version of the scene: loaded, built, and two sources over it (the
 * loop's, and the session's own for poses it computes off the loop). */
struct live_scene {
	struct scene_file sf;
	struct scene_built b;
	struct source_scene src, twin;
	bool loaded, built, has_src, has_twin;
	char *text;          /* the file's bytes, for teach */
	size_t len;
	char path[PATH_MAX];
};

struct live {
	struct live_opts o;
	pthread_mutex_t mu;      /* the commands and the session's state */
	pthread_mutex_t snap_mu; /* snap */
	struct live_scene *sc;
	/* the scene the rig was built from: its names and devices' settings
	 * are the rig's, so it lives as long as the rig (a teach replaces sc
	 * alone: the same rig, other keys) */
	struct live_scene *rig_sc;
	struct rig_auto ra;
	const struct rig_desc *rd;
	struct rig rig;
	bool rig_built, rig_started;
	struct hal_clock clk;
	struct hal_cancel cancel; /* an e-stop or a signal gives a start up */
	struct rt_plan plan;
	struct rt_result rt;
	char data_dir[PATH_MAX];

	/* the run of the loop while the drives are enabled */
	struct loop *L;
	struct hal_thread thread;
	_Atomic bool running;     /* mu to change; any thread reads it */
	_Atomic bool done;        /* the loop's thread has returned */
	_Atomic bool estop_req;   /* live_estop: the loop halts, the state latches */
	_Atomic int signal_req;   /* live_signal's level */
	_Atomic bool finished;
	struct hal_ring cmds, acks, status;
	struct loop_cmd *cmd_buf;
	struct loop_ack *ack_buf;
	void *st_buf;
	struct loop_live_status *st; /* a sample being taken in */
	uint32_t st_size;
	uint64_t seq;
	uint64_t seq_run;        /* seq when the run began: all taken before it */
	_Atomic uint64_t cmd_sent; /* seq, for the snapshot */

	enum live_state state;   /* outside a run; a run's comes from its samples */
	char reason[LIVE_MSG];
	int64_t at_frame;        /* the frame the rig is at, -1 */
	int64_t goto_frame;      /* a move to this frame under way, -1 */
	uint64_t jog_client;
	uint64_t jog_seq[LOOP_LIVE_OUT_MAX];
	uint64_t space_seq;      /* the jog client's last jog of the camera or a node */
	/* a free node's world matrix as its jogs left it (no output says how
	 * it is turned: live_space.c), while nothing else moved the rig */
	struct live_space {
		bool valid;
		int32_t node;
		struct mot_mat w;
		int k;               /* the last jog's increment: axis, space */
		bool local;
		double rate[LOOP_LIVE_OUT_MAX]; /* its outputs' rates, core units */
		double at[LOOP_LIVE_OUT_MAX];   /* the outputs then, core units */
	} space;
	/* the jog of the camera or a node under way: its direction made again
	 * every few milliseconds (live_space_follow) until the dead-man's time
	 * after the client's last refresh */
	struct live_space_jog {
		bool active;
		int32_t node;
		int k;
		bool local;
		double sign, speed;
		int64_t last_ns, until_ns;
	} space_jog;
	_Atomic int64_t last_frame; /* the last frame the rig was at, -1: none yet */
	uint64_t generation;
	/* the journal of the play segment under way (--journal DIR) */
	struct journal jr;
	bool has_jr;
	uint64_t jr_seq;         /* the PLAY command that took it */
	uint32_t jr_n;           /* segments journaled */
	bool seg_active;         /* snap_mu: the newest sample is inside a segment */
	uint64_t seen_seq;       /* snap_mu: the newest sample's command */
	struct live_snap snap;   /* snap_mu */
	uint64_t serial;

	/* the session's journal (o.journal_file): every run's shots in it,
	 * handed to the loop with each play as a segment's is */
	struct journal sess_jr;
	bool has_sess_jr;
	/* go-motion through a front end's poses (live_gomo): the loop reads
	 * the path while it runs the segment, live_gomo writes it at rest */
	struct source_path path;
	const char *path_names[LOOP_LIVE_OUT_MAX];
	enum src_unit path_units[LOOP_LIVE_OUT_MAX];
	bool gomo_armed;         /* a live_gomo's segment, not yet told to go */
	uint64_t path_seq;       /* the command that runs the path: until a sample
				  * at rest has seen it, the loop may read it */
};

/* live.c */
/* The session's scene becomes s (the old one freed unless the rig holds
 * it). */
void live_scene_swap(struct live *lv, struct live_scene *s);
int live_scene_open(struct live_scene **out, const char *path, char *err, size_t errsize);
int live_scene_parse(struct live_scene **out, const char *path, const char *text, size_t len,
		     char *err, size_t errsize);
/* Both sources select the rig's channels. */
int live_scene_bind(struct live_scene *s, const struct rig *rig);
void live_scene_free(struct live_scene *s);
/* strand check of run over s on the session's rig (check/run_check.h), as
 * strand play makes it before anything moves: 0, or -EINVAL (the options
 * disagree), -EDOM (a violation, the first in msg; not with --force),
 * -ERANGE (saturated), -ENOMEM. */
int live_scene_check(struct live *lv, struct live_scene *s, struct lim_run *run, char *msg,
		     size_t size);

/* Build the rig for lv->sc, start its devices, disable the drives; and
 * the reverse (which frees rig_sc when it is no longer sc). */
int live_rig_up(struct live *lv, char *err, size_t errsize);
void live_rig_down(struct live *lv);

/* live_run.c (under mu) */
int live_run_start(struct live *lv, char *msg, size_t size);
/* The loop's thread has returned: join, stop the drives, the new state. */
void live_run_end(struct live *lv);
/* A command to the loop and its answer: 0, or a negative errno. */
int live_send(struct live *lv, struct loop_cmd *c, struct loop_ack *a, char *msg, size_t size);
/* The inputs' queued edges taken (no loop runs): their levels are now's. */
void live_drain_inputs(struct live *lv);
/* Where the e-stop inputs stand: true when one is asserted (named in msg). */
bool live_estop_input(struct live *lv, char *msg, size_t size);

/* The snapshot's facts of the scene (its frame rate), after a scene
 * changed. */
void live_publish_scene(struct live *lv);

/* live_space.c (mu held): a jog of the camera or a node under way turns
 * its direction as the rig turns. */
void live_space_follow(struct live *lv);

/* live_run.c (mu held): the segment's journal opened for a play (0 when
 * there is none to keep) into c->jr, and closed; with a session journal
 * (o.journal_file) that one goes into c->jr instead and stays open. */
int live_journal_open(struct live *lv, struct loop_cmd *c, char *msg, size_t size);
void live_journal_close(struct live *lv);

/* "no scene loaded: ..." into msg; -ENOENT. */
int live_no_scene(char *msg, size_t size);

/* file units of output i */
double live_file_units(const struct live *lv, uint32_t i, double v);

#endif /* STRAND_LIVE_PRIV_H */
