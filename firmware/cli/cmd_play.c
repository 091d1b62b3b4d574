/* SPDX-License-Identifier: MIT */
/*
 * cmd_play.c - `strand play SCENE`: the scene on its rig (or on simulated
 * twins with --sim) in real time, one trigger per frame; the options, the
 * signals, the refusal of a scene `strand check` rejects, the messages at
 * the edge and the exit codes (play.h does the run).
 */
#include <errno.h>
#include <float.h>
#include <getopt.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "check/pools.h"
#include "check/run_check.h"
#include "cli.h"
#include "exitcode.h"
#include "play/frames.h"
#include "play/play.h"
#include "rig/rig_auto.h"
#include "scene/num.h"
#include "scene/source_scene.h"

/*
 * The longest time an option may give, 1e9 s (31 years; --settle and
 * --exposure: 1e12 ms): longer than any shoot, and at the fastest tick
 * rate a scene may have (2^20 Hz) 1.05e15 ticks, far inside NUM_TICKS_MAX,
 * so no count of ticks the loop keeps against it can overflow.
 */
#define PLAY_TIME_MAX_S 1e9

enum {
	OPT_SIM = 256, OPT_MODE, OPT_FROM, OPT_TO, OPT_FRAMES, OPT_LOOP, OPT_PING_PONG,
	OPT_PASSES, OPT_DURATION, OPT_SETTLE, OPT_EXPOSURE, OPT_TIMEOUT, OPT_JOURNAL,
	OPT_NO_JOURNAL, OPT_TELEMETRY, OPT_CLOCK, OPT_PRIORITY, OPT_CPU, OPT_NO_MLOCK,
	OPT_FORCE, OPT_CAMERA_LOG, OPT_LAT_HIST, OPT_QUIET, OPT_CHASE, OPT_TC_OFFSET,
	OPT_FREEWHEEL, OPT_NODE, OPT_PTP_SOCKET, OPT_PTP_FREE, OPT_SHUTTER,
};

/* ptp4l's management socket where linuxptp puts it by default. */
#define PLAY_PTP_SOCKET "/var/run/ptp4l"

static const struct option play_options[] = {
	{ "sim", no_argument, NULL, OPT_SIM },
	{ "mode", required_argument, NULL, OPT_MODE },
	{ "from", required_argument, NULL, OPT_FROM },
	{ "to", required_argument, NULL, OPT_TO },
	{ "frames", required_argument, NULL, OPT_FRAMES },
	{ "loop", no_argument, NULL, OPT_LOOP },
	{ "ping-pong", no_argument, NULL, OPT_PING_PONG },
	{ "passes", required_argument, NULL, OPT_PASSES },
	{ "duration", required_argument, NULL, OPT_DURATION },
	{ "settle", required_argument, NULL, OPT_SETTLE },
	{ "exposure", required_argument, NULL, OPT_EXPOSURE },
	{ "timeout", required_argument, NULL, OPT_TIMEOUT },
	{ "journal", required_argument, NULL, OPT_JOURNAL },
	{ "no-journal", no_argument, NULL, OPT_NO_JOURNAL },
	{ "telemetry", required_argument, NULL, OPT_TELEMETRY },
	{ "clock", required_argument, NULL, OPT_CLOCK },
	{ "priority", required_argument, NULL, OPT_PRIORITY },
	{ "cpu", required_argument, NULL, OPT_CPU },
	{ "no-mlock", no_argument, NULL, OPT_NO_MLOCK },
	{ "force", no_argument, NULL, OPT_FORCE },
	{ "camera-log", required_argument, NULL, OPT_CAMERA_LOG },
	{ "latency-hist", required_argument, NULL, OPT_LAT_HIST },
	{ "quiet", no_argument, NULL, OPT_QUIET },
	{ "chase", required_argument, NULL, OPT_CHASE },
	{ "tc-offset", required_argument, NULL, OPT_TC_OFFSET },
	{ "freewheel", required_argument, NULL, OPT_FREEWHEEL },
	{ "node", required_argument, NULL, OPT_NODE },
	{ "ptp-socket", required_argument, NULL, OPT_PTP_SOCKET },
	{ "ptp-free-running", no_argument, NULL, OPT_PTP_FREE },
	{ "shutter", required_argument, NULL, OPT_SHUTTER },
	{ "help", no_argument, NULL, 'h' },
	{ NULL, 0, NULL, 0 },
};

struct cli {
	const struct cli_cmd *cmd;
	FILE *err;
	struct play_opts o;
	const char *frames, *lat_hist;
	bool have_from, have_to, no_journal, quiet, step, freewheel_given;
	long long from, to;
	double duration_s, settle_ms, exposure_ms, timeout_s;
	const char *duration_arg, *timeout_arg; /* as given, for their messages */
	const char *node, *ptp_socket;
	bool ptp_free_running;
	char journal[PATH_MAX];
};

static int play_time_bad(struct cli *c, const char *name, const char *arg)
{
	return cli_usage(c->cmd, c->err, "%s %s: a non-negative number", name, arg);
}

/* A time option against PLAY_TIME_MAX_S; per_s: its unit's count a second. */
static int play_time_max(struct cli *c, const char *name, const char *arg, double v, double per_s)
{
	if (v > PLAY_TIME_MAX_S * per_s)
		return cli_usage(c->cmd, c->err, "%s %s: at most %s (31 years)", name, arg,
				 per_s == 1 ? "1e9 seconds" : "1e12 ms");
	return -1;
}

/* A time option as ticks at hz, at least min: 1 for a duration or a
 * timeout, which would otherwise round to none (for a duration, none means
 * no limit at all). 0, or the usage error's exit code. */
static int play_ticks(struct cli *c, const char *name, const char *arg, double v, bool ms,
		      uint32_t hz, int64_t min, int64_t *out)
{
	int rc = ms ? num_ms_to_ticks(v, hz, NUM_ROUND_NEAREST, min, NUM_TICKS_MAX, out) :
		      num_s_to_ticks(v, hz, NUM_ROUND_NEAREST, min, NUM_TICKS_MAX, out);

	if (!rc)
		return 0;
	return cli_usage(c->cmd, c->err, "%s %s: shorter than a tick (%.6g ms at tick_hz %u)",
			 name, arg, 1000.0 / hz, hz);
}

static int on_opt(void *ctx, int opt, const char *arg)
{
	struct cli *c = ctx;
	long long v;

	switch (opt) {
	case OPT_SIM:
		c->o.rig.sim = true;
		return -1;
	case OPT_MODE:
		if (strcmp(arg, "continuous") && strcmp(arg, "step"))
			return cli_usage(c->cmd, c->err, "--mode %s: continuous or step", arg);
		c->step = !strcmp(arg, "step");
		return -1;
	case OPT_FROM:
	case OPT_TO:
		if (!opt_long(arg, 0, INT32_MAX, &v))
			return cli_usage(c->cmd, c->err, "%s %s: a frame number",
					 opt == OPT_FROM ? "--from" : "--to", arg);
		if (opt == OPT_FROM) {
			c->from = v;
			c->have_from = true;
		} else {
			c->to = v;
			c->have_to = true;
		}
		return -1;
	case OPT_FRAMES:
		c->frames = arg;
		return -1;
	case OPT_LOOP:
		c->o.loop.loop = true;
		return -1;
	case OPT_PING_PONG:
		c->o.loop.ping_pong = true;
		return -1;
	case OPT_PASSES:
		if (!opt_long(arg, 1, INT32_MAX, &v))
			return cli_usage(c->cmd, c->err, "--passes %s: a count of 1 or more", arg);
		c->o.loop.passes = v;
		return -1;
	case OPT_DURATION:
		c->duration_arg = arg;
		if (!opt_double(arg, 0, DBL_MAX, &c->duration_s) || c->duration_s == 0)
			return play_time_bad(c, "--duration", arg);
		return play_time_max(c, "--duration", arg, c->duration_s, 1);
	case OPT_SETTLE:
		if (!opt_double(arg, 0, DBL_MAX, &c->settle_ms))
			return play_time_bad(c, "--settle", arg);
		return play_time_max(c, "--settle", arg, c->settle_ms, 1000);
	case OPT_EXPOSURE:
		if (!opt_double(arg, 0, DBL_MAX, &c->exposure_ms))
			return play_time_bad(c, "--exposure", arg);
		return play_time_max(c, "--exposure", arg, c->exposure_ms, 1000);
	case OPT_TIMEOUT:
		c->timeout_arg = arg;
		if (!opt_double(arg, 0, DBL_MAX, &c->timeout_s) || c->timeout_s == 0)
			return play_time_bad(c, "--timeout", arg);
		return play_time_max(c, "--timeout", arg, c->timeout_s, 1);
	case OPT_JOURNAL:
		snprintf(c->journal, sizeof(c->journal), "%s", arg);
		return -1;
	case OPT_NO_JOURNAL:
		c->no_journal = true;
		return -1;
	case OPT_TELEMETRY:
		c->o.telemetry_path = arg;
		return -1;
	case OPT_CLOCK:
		if (strcmp(arg, "real") && strcmp(arg, "virtual"))
			return cli_usage(c->cmd, c->err, "--clock %s: real or virtual", arg);
		c->o.virtual_clock = !strcmp(arg, "virtual");
		return -1;
	case OPT_PRIORITY:
	case OPT_CPU:
	case OPT_NO_MLOCK:
		return cli_rt_option(c->cmd, c->err, opt == OPT_PRIORITY ? "priority" :
					      opt == OPT_CPU ? "cpu" : "no-mlock", arg, &c->o.rt);
	case OPT_FORCE:
		c->o.loop.force = true;
		return -1;
	case OPT_CAMERA_LOG:
		c->o.rig.camera_log = arg;
		return -1;
	case OPT_LAT_HIST:
		c->lat_hist = arg;
		return -1;
	case OPT_QUIET:
		c->quiet = true;
		return -1;
	case OPT_CHASE:
		c->o.chase.spec = arg;
		return -1;
	case OPT_TC_OFFSET:
		c->o.chase.tc_offset = arg;
		return -1;
	case OPT_FREEWHEEL:
		if (!opt_double(arg, 0, DBL_MAX, &c->o.chase.freewheel_ms) ||
		    c->o.chase.freewheel_ms > 3600000)
			return cli_usage(c->cmd, c->err, "--freewheel %s: 0 to 3600000 ms", arg);
		c->freewheel_given = true;
		return -1;
	case OPT_NODE:
		c->node = arg;
		return -1;
	case OPT_PTP_SOCKET:
		c->ptp_socket = arg;
		return -1;
	case OPT_PTP_FREE:
		c->ptp_free_running = true;
		return -1;
	case OPT_SHUTTER:
		return cli_shutter_arg(c->cmd, c->err, arg, &c->o.loop.shutter);
	default:
		return cli_usage(c->cmd, c->err, "unknown option");
	}
}

/*
 * The signals of a run, from before the first device starts to after the
 * last one stopped. Until the loop runs, a signal asks the start to give up
 * (g_cancel: the backends' waits and rig_start look at it, and the devices
 * started are stopped the ordinary way); once it runs, the loop is asked
 * to stop (play_signal). g_play is published after play_prepare returned,
 * and the request looked at once more after that, so that a signal in
 * between is seen by one or the other (both are sequentially consistent:
 * the handler stores the request, then loads g_play; the program stores
 * g_play, then loads the request).
 */
static struct hal_cancel g_cancel;
static struct play *_Atomic g_play;
static volatile sig_atomic_t g_sigints, g_signo;

static void on_signal(int sig)
{
	struct play *p;

	if (sig == SIGUSR1) { /* the simulated e-stops, pressed */
		p = atomic_load(&g_play);
		if (p)
			play_press_estop(p);
		return;
	}

	if (sig == SIGINT)
		g_sigints++;
	g_signo = sig;
	hal_cancel_request(&g_cancel);
	p = atomic_load(&g_play);
	if (p)
		play_signal(p, sig, sig == SIGINT ? g_sigints : 1);
}

struct saved_signals {
	struct sigaction sigint, sigterm, sigxfsz, sigusr1;
	bool installed;
};

static void signals_install(struct saved_signals *s)
{
	struct sigaction sa;

	memset(&sa, 0, sizeof(sa));
	sa.sa_handler = on_signal;
	sigemptyset(&sa.sa_mask);
	hal_cancel_init(&g_cancel);
	atomic_store(&g_play, NULL);
	g_sigints = 0;
	g_signo = 0;
	s->installed = !sigaction(SIGINT, &sa, &s->sigint) && !sigaction(SIGTERM, &sa, &s->sigterm) &&
		       !sigaction(SIGUSR1, &sa, &s->sigusr1);
	/* a file size limit (ulimit -f, LimitFSIZE=) reached by the journal's
	 * growth is then EFBIG, a clean stop the service reports, not a kill
	 * with the drives enabled */
	sa.sa_handler = SIG_IGN;
	s->installed = !sigaction(SIGXFSZ, &sa, &s->sigxfsz) && s->installed;
}

/* The handlers the program had before, once every device has stopped. */
static void signals_restore(struct saved_signals *s)
{
	if (!s->installed)
		return;
	atomic_store(&g_play, NULL);
	sigaction(SIGINT, &s->sigint, NULL);
	sigaction(SIGTERM, &s->sigterm, NULL);
	sigaction(SIGXFSZ, &s->sigxfsz, NULL);
	sigaction(SIGUSR1, &s->sigusr1, NULL);
	s->installed = false;
}

/* A signal came while the devices started: the run did not begin, and the
 * devices that had started are stopped (play_prepare saw to it). */
static int stopped_at_start(FILE *err, const char *where)
{
	fprintf(err, "strand play: stopped by a signal (%s) during start-up (%s); the devices "
		"that had started were stopped, their drives disabled\n",
		g_signo == SIGINT ? "SIGINT" : g_signo == SIGTERM ? "SIGTERM" : "?", where);
	return STRAND_EXIT_STOPPED;
}

static void default_journal(char *buf, size_t size, const char *scene)
{
	time_t now = time(NULL);
	struct tm tm;
	char when[32];

	localtime_r(&now, &tm);
	strftime(when, sizeof(when), "%Y%m%d-%H%M%S", &tm);
	snprintf(buf, size, "%s-%s.journal", scene, when);
}

/* The histogram as cyclictest -h writes its own: "us count" lines. */
/*
 * strand check's walk over what this run will play, with the limits its
 * rig holds each channel to (an automatic rig's derived ones included),
 * before any device starts: 0 clean, else the exit code, having said why.
 */
static int check_first(struct cli *c, const char *path, struct source_scene *ss,
		       const struct rig_desc *rig, struct frame_list *fl)
{
	struct run_check lc = { .out = NULL };
	struct lim_run run = {
		.from = c->o.loop.from, .to = c->o.loop.to, .loop = c->o.loop.loop,
		.ping_pong = c->o.loop.ping_pong, .passes = c->o.loop.passes, .step = c->step,
		.shutter = c->o.loop.shutter,
	};
	char line[512];
	uint32_t pools;
	int rc;

	if (c->step && fl->n) {
		/* step mode shoots the frames it lists: their poses, or their
		 * go-motion on the timeline the loop runs it on */
		run.from = frames_min(fl);
		run.to = frames_max(fl);
	}
	run.expose_first = run.from;
	run.expose_last = run.to;
	if (c->step && c->o.loop.shutter) {
		run.from = c->o.loop.from;
		run.to = c->o.loop.to;
	}
	rc = run_check(&lc, ss, rig, &run);
	if (rc) {
		fprintf(c->err, "strand play: %s\n", strerror(-rc));
		rc = STRAND_EXIT_INTERNAL;
	} else if (lc.res.sat) {
		fprintf(c->err, "%s: the core's arithmetic saturated at frame %.10g: values too "
			"large for its Q32.32 format\n", path, lc.res.sat_frame);
		rc = STRAND_EXIT_INTERNAL;
	} else if (!lc.res.violations && !c->o.loop.force &&
		   (pools = lim_pools(NULL, NULL, ss->d, ss->sc, run.to, line, sizeof(line)))) {
		/* check prints a pool's line after the walk's: the first when the
		 * walk finds none */
		fprintf(c->err,
			"%s: strand check finds %u violation%s, the first: %s.\n"
			"strand play refuses it ('strand check %s' with the same options lists "
			"them all); --force plays it,\nthe particles that find no slot left out.\n",
			path, pools, pools == 1 ? "" : "s", line, path);
		rc = STRAND_EXIT_VIOLATION;
	} else if (lc.res.violations && !c->o.loop.force) {
		run_check_line(line, sizeof(line), &lc, &lc.first);
		fprintf(c->err,
			"%s: strand check finds %u limit violation%s, the first: %s.\n"
			"strand play refuses it ('strand check %s' with the same options lists "
			"them all); --force plays it,\nclamping every setpoint to its limits.\n",
			path, lc.res.violations, lc.res.violations == 1 ? "" : "s", line, path);
		rc = STRAND_EXIT_VIOLATION;
	}
	run_check_free(&lc);
	return rc;
}

int cli_play_exit(const struct loop_report *r)
{
	switch (r->end) {
	case LOOP_END_DONE:
		return STRAND_EXIT_OK;
	case LOOP_END_STOPPED:
		return STRAND_EXIT_STOPPED;
	case LOOP_END_ESTOP:
		return STRAND_EXIT_ESTOP;
	case LOOP_END_FAULT:
		return r->cause == LOOP_CAUSE_JOURNAL ? STRAND_EXIT_IO : STRAND_EXIT_FAULT;
	default:
		return STRAND_EXIT_INTERNAL;
	}
}

/* The exit code of a run that could not start: by the stage it failed at. */
static int prepare_exit(const struct play *p, int rc)
{
	if (rc == -ENOMEM)
		return STRAND_EXIT_INTERNAL;
	switch (p->failed_at) {
	case PLAY_STAGE_START:
		return STRAND_EXIT_FAULT;
	case PLAY_STAGE_JOURNAL:
		return STRAND_EXIT_IO;
	case PLAY_STAGE_OPTIONS:
		return STRAND_EXIT_USAGE;
	default:
		return STRAND_EXIT_SCENE;
	}
}

/* The boards' names, "a, b, c", into buf. */
static const char *board_names(char *buf, size_t size, const struct rig_desc *r)
{
	size_t n = 0;
	uint32_t i;

	buf[0] = '\0';
	for (i = 0; i < r->nboards && n < size; i++)
		n += (size_t)snprintf(buf + n, size - n, "%s%s", i ? ", " : "", r->boards[i].name);
	return buf;
}

/* --node: this board's part of the rig in brig, the lockstep's settings in
 * ls. -1 when there is nothing to do or it is done, else the exit code. */
static int board_part(struct cli *c, const char *path, const struct scene_file *sf,
		      struct rig_desc *brig, struct play_lockstep *ls)
{
	const struct rig_desc *r = &sf->rig;
	char names[256];
	uint32_t b;

	if (!c->node && (c->ptp_socket || c->ptp_free_running))
		return cli_usage(c->cmd, c->err, "--ptp-socket and --ptp-free-running go with --node");
	if (c->node && !r->nboards)
		return cli_usage(c->cmd, c->err, "--node %s: the scene has no boards: section (one "
				 "board plays it)", c->node);
	if (!r->nboards)
		return -1;
	if (!c->node) {
		if (c->o.rig.sim)
			return -1; /* the whole rig, simulated, here */
		fprintf(c->err, "%s: the scene shares its rig among boards (%s); say which this is "
			"with --node NAME, or play the whole rig simulated here with --sim\n", path,
			board_names(names, sizeof(names), r));
		return STRAND_EXIT_USAGE;
	}
	for (b = 0; b < r->nboards && strcmp(r->boards[b].name, c->node); b++)
		;
	if (b == r->nboards)
		return cli_usage(c->cmd, c->err, "--node %s: no such board (boards: %s)", c->node,
				 board_names(names, sizeof(names), r));
	if (c->o.virtual_clock || c->step || c->o.chase.spec || c->o.rig.sim)
		return cli_usage(c->cmd, c->err, "--node plays on the PTP clock in continuous mode: "
				 "not with --clock virtual, --mode step, --chase or --sim (a board's "
				 "simulated devices are driver: sim)");
	if (rig_desc_board(r, b, brig)) {
		fprintf(c->err, "strand play: out of memory\n");
		return STRAND_EXIT_INTERNAL;
	}
	ls->scene_rig = r;
	ls->board = b;
	ls->digest = sf->digest;
	ls->ptp_socket = c->ptp_socket ? c->ptp_socket : PLAY_PTP_SOCKET;
	ls->ptp_free_running = c->ptp_free_running;
	c->o.lockstep = ls;
	return -1;
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	struct cli c;
	struct scene_file sf;
	struct scene_built b;
	struct source_scene src;
	struct rig_auto ra;
	struct frame_list fl = { 0 };
	const struct rig_desc *rig;
	struct saved_signals sigs = { .installed = false };
	struct rig_desc brig = { 0 };
	struct play_lockstep ls = { 0 };
	struct play p;
	const char *path;
	char msg[512];
	uint32_t hz;
	int rc;

	memset(&c, 0, sizeof(c));
	c.cmd = cmd;
	c.err = err;
	c.o.rt.priority = 80;
	c.o.rt.cpu = -1;
	c.o.rt.lock_memory = true;
	c.o.rt.pm_qos = true;
	c.o.rt.name = "strand-rt";
	c.settle_ms = 200;
	c.exposure_ms = 100;
	c.timeout_s = 10;
	c.timeout_arg = "10";
	c.o.chase.freewheel_ms = 500;
	rc = cli_scene_args(cmd, argc, argv, out, err, play_options, on_opt, &c, &path, &sf, &b);
	if (rc >= 0)
		return rc;
	memset(&src, 0, sizeof(src));
	memset(&ra, 0, sizeof(ra));
	memset(&p, 0, sizeof(p));
	rc = STRAND_EXIT_USAGE;
	if (c.frames && !c.step) {
		cli_usage(cmd, err, "--frames is for --mode step");
		goto out;
	}
	if (c.o.chase.spec && (c.step || c.o.loop.loop || c.o.loop.ping_pong)) {
		cli_usage(cmd, err, "--chase plays the scene as the source runs: not with --mode "
			  "step, --loop or --ping-pong");
		goto out;
	}
	if (!c.o.chase.spec && (c.o.chase.tc_offset || c.freewheel_given)) {
		cli_usage(cmd, err, "--tc-offset and --freewheel go with --chase");
		goto out;
	}
	rc = STRAND_EXIT_INTERNAL;
	if (source_scene_init(&src, &sf.desc, &b.sc)) {
		fprintf(err, "strand play: out of memory\n");
		goto out;
	}
	c.o.loop.from = c.have_from ? c.from : src.s.frame_first;
	c.o.loop.to = c.have_to ? c.to : src.s.frame_last;
	{
		struct lim_run r = { .from = c.o.loop.from, .to = c.o.loop.to,
				     .loop = c.o.loop.loop, .ping_pong = c.o.loop.ping_pong,
				     .passes = c.o.loop.passes, .step = c.step };

		r.shutter = c.o.loop.shutter;
		rc = cli_limits_usage(cmd, err, &r);
		if (rc < 0)
			rc = cli_shutter_usage(cmd, err, &src.s.timing, c.o.loop.shutter);
		if (rc >= 0)
			goto out;
	}
	rig = &sf.rig;
	rc = board_part(&c, path, &sf, &brig, &ls);
	if (rc >= 0)
		goto out;
	if (c.o.lockstep)
		rig = &brig;
	if (!rig->noutputs && !rig->ntriggers && !c.o.lockstep) {
		rc = STRAND_EXIT_SCENE;
		if (!c.o.rig.sim) {
			fprintf(err, "%s: the scene describes no rig (devices:, outputs:, triggers:); "
				"play it on a simulated one with --sim\n", path);
			goto out;
		}
		rc = STRAND_EXIT_INTERNAL;
		if (rig_auto_build(&ra, &sf.desc, &src.s, c.o.loop.from)) {
			fprintf(err, "strand play: out of memory\n");
			goto out;
		}
		rig = &ra.d;
	}
	hz = src.s.timing.tick_hz;
	/* in range since on_opt: only a timeout or a duration below a tick is
	 * refused (--settle and --exposure may round to none) */
	rc = STRAND_EXIT_USAGE;
	if (play_ticks(&c, "--settle", "", c.settle_ms, true, hz, 0, &c.o.loop.settle_ticks) ||
	    play_ticks(&c, "--exposure", "", c.exposure_ms, true, hz, 0,
		       &c.o.loop.exposure_ticks) ||
	    play_ticks(&c, "--timeout", c.timeout_arg, c.timeout_s, false, hz, 1,
		       &c.o.loop.in_position_timeout_ticks) ||
	    (c.duration_s > 0 && play_ticks(&c, "--duration", c.duration_arg, c.duration_s,
					    false, hz, 1, &c.o.loop.max_ticks)))
		goto out;
	c.o.loop.ready_timeout_ticks = c.o.loop.in_position_timeout_ticks;
	c.o.loop.status_every = hz / 10 ? hz / 10 : 1;
	if (c.step) {
		c.o.loop.mode = LOOP_MODE_STEP;
		rc = c.frames ? frames_parse(&fl, c.frames, msg, sizeof(msg)) :
				frames_range(&fl, c.o.loop.from, c.o.loop.to);
		if (rc) {
			fprintf(err, "strand play: %s\n", c.frames ? msg : strerror(-rc));
			rc = STRAND_EXIT_USAGE;
			goto out;
		}
		c.o.loop.frames = &fl;
		/* go-motion runs the scene's own motion over its span and the
		 * frames shot, and beyond them at the speed of their ends
		 * (plan/timeline.h); check_first walks the same */
		c.o.loop.from = frames_min(&fl) < src.s.frame_first ? frames_min(&fl) :
								      src.s.frame_first;
		c.o.loop.to = frames_max(&fl) > src.s.frame_last ? frames_max(&fl) :
								   src.s.frame_last;
	}
	rc = check_first(&c, path, &src, rig, &fl);
	if (rc)
		goto out;
	if (!c.no_journal) {
		if (!c.journal[0])
			default_journal(c.journal, sizeof(c.journal), src.s.name);
		c.o.journal_path = c.journal;
	}
	c.o.status_tty = !c.quiet && isatty(fileno(err)) ? err : NULL;
	/* before any device starts: a CANopen start-up takes seconds, and a
	 * SIGTERM then must not leave drives enabled with nothing behind */
	signals_install(&sigs);
	c.o.rig.cancel = &g_cancel;
	rc = play_prepare(&p, rig, &src.s, &c.o, msg, sizeof(msg));
	if (rc == -ECANCELED) {
		rc = stopped_at_start(err, msg);
		goto out;
	}
	if (rc) {
		fprintf(err, "%s: %s\n", path, msg);
		rc = prepare_exit(&p, rc);
		goto out;
	}
	atomic_store(&g_play, &p);
	if (hal_cancelled(&g_cancel)) {
		/* in the window before the loop could be told */
		atomic_store(&g_play, NULL);
		rc = stopped_at_start(err, "before the loop began");
		goto out;
	}
	rc = play_run(&p);
	rc = rc ? STRAND_EXIT_INTERNAL : cli_play_exit(&loop_result(p.L)->rep);
	/* the loop has ended: from now on a signal only sets g_cancel, which
	 * the stop of the devices (rig_stop) does not give up for */
	atomic_store(&g_play, NULL);
	if (rc != STRAND_EXIT_OK) {
		play_describe(&p, msg, sizeof(msg));
		fprintf(err, "strand play: %s\n", msg);
	}
	if (c.lat_hist && lat_write_hist(c.lat_hist, &loop_result(p.L)->lat))
		fprintf(err, "strand play: %s: %s\n", c.lat_hist, strerror(errno));
	/* the reason is on err already when the run did not finish */
	if (!c.quiet)
		play_summary(&p, out, rc == STRAND_EXIT_OK);
out:
	play_free(&p);
	signals_restore(&sigs);
	if (c.o.lockstep)
		rig_desc_board_free(&brig);
	frames_free(&fl);
	rig_auto_free(&ra);
	source_scene_free(&src);
	scene_built_free(&b);
	scene_file_free(&sf);
	return rc;
}

const struct cli_cmd cmd_play = {
	.name = "play",
	.summary = "play a scene on its rig in real time, one camera trigger per frame",
	.help = "usage: strand play SCENE.yaml [options]\n"
		"\n"
		"Plays the scene on its rig (devices:, outputs:, triggers:, inputs:) in real time\n"
		"and fires one camera trigger per frame, at the tick FORMULAS section 5 gives.\n"
		"A scene that strand check rejects is refused unless --force.\n"
		"\n"
		"  --sim                 every device by its simulated twin (a scene without a rig\n"
		"                        gets a simulated drive per joint and a camera)\n"
		"  --mode MODE           continuous (default) or step (shoot-move-shoot)\n"
		"  --from F, --to F      the frames to fire (default: the scene's span)\n"
		"  --frames SPEC         step mode: 0..240, 1,5,9, 12x5 (a reshoot), combined\n"
		"  --loop                play the range again and again\n"
		"  --ping-pong           forwards, then backwards, ... (F..T, T-1..F, F+1..T)\n"
		"  --passes N            with --loop or --ping-pong: stop after N passes\n"
		"  --duration S          a controlled stop after S seconds\n"
		"  --settle MS           step mode: in position this long before a shot (200)\n"
		"  --exposure MS         step mode: hold still this long after it (100), unless a\n"
		"                        camera_ready input paces the shots\n"
		"  --timeout S           step mode: for in position and camera ready (10)\n"
		"  --shutter ANGLE       step mode: go-motion. Each frame f runs the scene's motion\n"
		"                        from f - s/2 to f + s/2 (s = ANGLE/360 of a frame) with\n"
		"                        the trigger at its start, after a run-up from rest and\n"
		"                        before a run-out to rest, both within the limits\n"
		"  --journal FILE        the frame journal (default SCENE-YYYYmmdd-HHMMSS.journal)\n"
		"  --no-journal          no journal\n"
		"  --telemetry FILE      JSON lines of the loop's state, ten a second\n"
		"  --clock real|virtual  the wall clock (default), or virtual time as fast as the\n"
		"                        machine computes (bit-reproducible)\n"
		"  --priority N          SCHED_FIFO priority of the loop thread (80; 0: none)\n"
		"  --cpu N               pin the loop thread to CPU N\n"
		"  --no-mlock            do not lock memory\n"
		"  --force               play a scene strand check rejects, clamping setpoints\n"
		"  --camera-log FILE     the first simulated camera logs its trigger edges there\n"
		"  --latency-hist FILE   the wake-up latency histogram (us count lines)\n"
		"  --quiet               no status line, no summary\n"
		"  --chase SPEC          follow an external clock: ltc:DEVICE (LTC on an ALSA\n"
		"                        capture device), ltc:sim[:K=V,...] (simulated), or\n"
		"                        gpio:CHIP:LINE (a frame pulse): wait for it, lock, play\n"
		"                        from the frame it names (see README \"Time from outside\")\n"
		"  --tc-offset TC        the source's timecode of the scene's frame 0 (00:00:00:00)\n"
		"  --freewheel MS        run on without the source this long, then a controlled\n"
		"                        stop and a new cue when it is back (500)\n"
		"  --node NAME           this is board NAME of the scene's boards: it drives its\n"
		"                        devices, in lockstep with the others over UDP and PTP\n"
		"                        (see README \"Several boards, one scene\")\n"
		"  --ptp-socket PATH     ptp4l's management socket (" PLAY_PTP_SOCKET ")\n"
		"  --ptp-free-running    ptp4l measures but does not steer this clock (boards\n"
		"                        that share one clock): its offset alone says locked\n"
		"\n"
		"SIGINT or SIGTERM: every axis comes to rest within its limits (exit 5); a second\n"
		"SIGINT disables the drives at once. During the devices' start-up it is given up\n"
		"and every device started is stopped (exit 5). SIGUSR1 presses the e-stops of the\n"
		"simulated devices (exit 6).\n"
		"\n"
		"exit codes: 0 done, 1 strand check rejects the scene, 2 invalid scene or rig,\n"
		"3 usage, 4 journal or file, 5 stopped by SIGINT/SIGTERM or a stop input, 6 e-stop,\n"
		"7 device fault, following error or limit, 8 internal.\n",
	.run = run,
};
