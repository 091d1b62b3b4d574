/* SPDX-License-Identifier: MIT */
/*
 * play.h - one run of `strand play`, put together: the clock, the rig, the
 * journal, the loop on its strand-rt thread, and the ordinary thread that
 * serves them (journal chunks, telemetry lines, the status line) while the
 * loop runs.
 *
 *     play_prepare()   builds and starts everything (may allocate, block)
 *     play_run()       runs the loop to its end; returns the exit code
 *     play_free()      stops the rig, closes the journal, frees
 *
 * The loop thread is the only one that touches the rig while it runs; the
 * service thread reads the status ring and maps journal chunks. Signal
 * handlers reach the loop through play_signal() only (an atomic store),
 * and the start before it through the cancel request of o.rig.cancel
 * (hal/cancel.h): the program installs them before play_prepare().
 */
#ifndef STRAND_PLAY_H
#define STRAND_PLAY_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>

#include "hal/clock.h"
#include "hal/ring.h"
#include "journal/journal.h"
#include "chase.h"
#include "hal/extclk.h"
#include "lockstep/lockstep.h"
#include "loop.h"
#include "rig/rig.h"
#include "rt.h"
#include "scene/source.h"

#define PLAY_STATUS_RING 1024

struct sim_ltc_cfg;

/* --chase: an external clock the run follows (chase.h, rig/rig_chase.h). */
struct play_chase {
	const char *spec;          /* NULL: the loop's own time */
	const char *tc_offset;     /* the source's timecode of the scene's frame 0, or NULL */
	double freewheel_ms;       /* without the source this long: a controlled stop */
	const struct sim_ltc_cfg *sim; /* tests: the script of "ltc:sim" */
	struct hal_din *sim_din;   /* tests: the input of "gpio:sim", taken over */
};

/* --node: one of several boards playing the scene together
 * (lockstep/lockstep.h); the run's rig is this board's part of it. */
struct play_lockstep {
	const struct rig_desc *scene_rig; /* the whole rig: boards:, lockstep: */
	uint32_t board;                   /* this board, an index into boards: */
	const uint8_t *digest;            /* the scene file's SHA-256 */
	const char *ptp_socket;           /* ptp4l's uds_address */
	bool ptp_free_running;            /* lockstep/ls_ptp.h */
};

struct play_opts {
	struct loop_cfg loop;
	bool virtual_clock;
	struct rt_opts rt;
	const char *journal_path; /* NULL: no journal */
	const char *telemetry_path; /* JSON lines, NULL: none */
	FILE *status_tty;         /* a live status line there, or NULL */
	struct rig_opts rig;
	struct play_chase chase;
	const struct play_lockstep *lockstep; /* NULL: this board alone */
};

/* Where play_prepare failed, for the exit code. */
enum play_stage {
	PLAY_STAGE_NONE,
	PLAY_STAGE_RIG,     /* the rig description does not fit the scene */
	PLAY_STAGE_START,   /* a device would not start */
	PLAY_STAGE_OPTIONS, /* the run's options contradict each other or the scene */
	PLAY_STAGE_LOOP,    /* the run cannot be planned (a run-up outside the limits) */
	PLAY_STAGE_JOURNAL, /* the journal or telemetry file */
};

struct play {
	struct play_opts o;
	enum play_stage failed_at;
	struct hal_clock clk;
	struct rig rig;
	bool rig_built, rig_started;
	struct journal jr;
	bool has_journal;
	struct loop *L;           /* NULL until the loop is prepared */
	const struct mot_timing *tm; /* the source's timing */
	struct hal_ring status;
	struct loop_status *status_buf;
	FILE *telemetry;
	struct hal_thread thread; /* strand-rt */
	struct rt_plan plan;      /* every thread's scheduling */
	struct rt_result rt;
	_Atomic bool done;
	struct loop_status last; /* the newest status sample */
	int64_t start_wall_ns;
	int64_t status_shown_ns;
	int service_err;
	int64_t wall_ns;          /* the run's duration on the monotonic clock */
	struct hal_extclk *extclk; /* --chase: the source, NULL: none */
	struct chase chase;
	struct lockstep *ls;      /* --node: the other boards, NULL: none */
	struct ls_board *ls_boards;
	int64_t t0;               /* --node: tick 0, as the boards agreed */
	_Atomic bool press;       /* SIGUSR1: press the simulated e-stops */
};

/* [init] Build the rig for src (simulated where asked), start it, prepare
 * the loop, open the journal. 0 or a negative errno with a message in err;
 * -ECANCELED when o->rig.cancel was requested meanwhile (a signal while the
 * devices started): every device that had started is stopped by then,
 * no drive left enabled. */
int play_prepare(struct play *p, const struct rig_desc *rd, struct play_source *src,
		 const struct play_opts *o, char *err, size_t errsize);

/* [init] Run to the end (the calling thread serves the loop meanwhile):
 * 0, the outcome in the loop's report (loop_result(p->L)->rep), or a
 * negative errno when the loop's thread could not start. */
int play_run(struct play *p);

void play_free(struct play *p);

/* Async-signal-safe: the first SIGINT/SIGTERM a controlled stop, a second
 * SIGINT an immediate one. */
void play_signal(struct play *p, int sig, int count);

/* Async-signal-safe: SIGUSR1, the simulated devices' e-stops pressed (by
 * the service thread, at its next round). */
void play_press_estop(struct play *p);

/* The one-line description of why the run ended ("e-stop: input 'estop'
 * (line 0) at tick 5000, frame 119"), into buf. */
void play_describe(const struct play *p, char *buf, size_t size);
/* The same for a report (loop_report_now's, while the run stops). */
void play_describe_report(const struct play *p, const struct loop_report *r, char *buf,
			  size_t size);

/* [init] A journal at path for a run on rig of src (mode JOURNAL_MODE_*,
 * total: the frames it fires, -1 without an end), as strand play opens
 * its own. 0, or a negative errno with err. */
int play_journal_open(struct journal *jr, const char *path, const struct rig *rig,
		      const struct play_source *src, uint32_t mode, int64_t total,
		      int64_t wall_ns, char *err, size_t errsize);

/* The same for any run of the loop on rig, whose scene has timing tm
 * (report r of result res; ls: its lockstep, or NULL). */
void play_report_describe(const struct rig *rig, const struct mot_timing *tm,
			  const struct loop_result *res, const struct loop_report *r,
			  const struct lockstep *ls, char *buf, size_t size);

/* A summary of the run (frames, time, latency, following error), with
 * play_describe's line first when `reason`. */
void play_summary(const struct play *p, FILE *f, bool reason);

#endif /* STRAND_PLAY_H */
