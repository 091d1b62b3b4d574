/* SPDX-License-Identifier: MIT */
/* play.c - one run of strand play (see play.h). */
#define _GNU_SOURCE
#include "play.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hal/rt.h"
#include "rig/drv_sim.h"
#include "rig/rig_chase.h"
#include "scene/timecode.h"

/* Records the journal keeps mapped ahead of the loop: ten seconds of
 * frames, at least 4096. What it holds in memory is sized by these, never
 * by the run's length (journal.h). */
#define JOURNAL_AHEAD_S 10

static uint32_t journal_unit(enum src_unit u)
{
	return u == SRC_UNIT_TURNS ? JOURNAL_UNIT_TURNS : JOURNAL_UNIT_PLAIN;
}

int play_journal_open(struct journal *jr, const char *path, const struct rig *rig,
		      const struct play_source *src, uint32_t mode, int64_t total,
		      int64_t wall_ns, char *err, size_t errsize)
{
	struct journal_info ji;
	const char **names;
	uint32_t *units, i, n = rig->nout;
	double fps = (double)src->timing.num / src->timing.den;
	int rc;

	names = calloc(n ? n : 1, sizeof(*names));
	units = calloc(n ? n : 1, sizeof(*units));
	if (!names || !units) {
		free(names);
		free(units);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	for (i = 0; i < n; i++) {
		names[i] = rig->out[i].channel;
		units[i] = journal_unit(rig->out[i].unit);
	}
	memset(&ji, 0, sizeof(ji));
	ji.scene = src->name;
	ji.rate_num = src->timing.num;
	ji.rate_den = src->timing.den;
	ji.tick_hz = src->timing.tick_hz;
	ji.mode = mode;
	ji.start_wall_ns = wall_ns;
	ji.nout = n;
	ji.out_name = names;
	ji.out_unit = units;
	/* a run with an end refuses a frame past it; one without grows its
	 * file until the run stops or the disk is full */
	ji.capacity = total >= 0 ? total : JOURNAL_UNBOUNDED;
	if (total == 0)
		ji.capacity = 1;
	ji.ahead = (int64_t)fmax(4096, JOURNAL_AHEAD_S * fps * (rig->ntrig ? rig->ntrig : 1));
	/* a tick's edges are FIRED after every one of them was armed */
	ji.behind = rig->ntrig ? rig->ntrig : 1;
	rc = journal_open(jr, path, &ji);
	free(names);
	free(units);
	if (rc)
		snprintf(err, errsize, "journal %s: %s", path, strerror(-rc));
	return rc;
}

static int open_journal(struct play *p, struct play_source *src, char *err, size_t errsize)
{
	int rc = play_journal_open(&p->jr, p->o.journal_path, &p->rig, src,
				   (p->o.loop.mode == LOOP_MODE_STEP ? JOURNAL_MODE_STEP : 0) |
				   (p->extclk ? JOURNAL_MODE_CHASE : 0) |
				   (p->o.loop.mode == LOOP_MODE_STEP && p->o.loop.shutter ?
				    JOURNAL_MODE_GOMO : 0),
				   loop_result(p->L)->total_frames, hal_clock_wall(&p->clk), err,
				   errsize);

	if (rc)
		return rc;
	p->has_journal = true;
	return 0;
}

/* A stop asked for while the run is prepared (a signal) once the devices
 * have started: they are stopped at once, as at the end of a run, and the
 * run does not begin. 0, or -ECANCELED. */
static int given_up(struct play *p, char *err, size_t errsize)
{
	if (!hal_cancelled(p->o.rig.cancel))
		return 0;
	snprintf(err, errsize, "start given up after every device had started");
	rig_stop(&p->rig);
	p->rig_started = false;
	return -ECANCELED;
}

/* --chase: the source opened and reading, the loop following it. The
 * source's labels count frames at the scene's rate, or at half of it
 * above 30 frames a second (LTC counts at most 30: 50 and 60000/1001
 * scenes chase 25 and 30000/1001 timecode, two frames per label). */
static int prepare_chase(struct play *p, const struct play_source *src, char *err,
			 size_t errsize)
{
	const struct play_chase *o = &p->o.chase;
	const struct mot_timing *tm = &src->timing;
	struct chase_cfg cc = { .num = tm->num, .den = tm->den, .tick_hz = tm->tick_hz,
				.mult = 1 };
	/* a frame pulse's edges are input events; LTC capture is I/O (rt.h) */
	struct rig_chase_cfg rc = { .spec = o->spec, .clk = &p->clk,
				    .sched = strncmp(o->spec, "ltc:", 4) ? p->plan.events : p->plan.io,
				    .gpio_sysfs = p->o.rig.gpio_sysfs, .sim = o->sim,
				    .sim_din = o->sim_din };
	struct timecode tc;
	int rc_;

	if (strncmp(o->spec, "gpio:", 5) && (double)tm->num / tm->den > 30.5) {
		if (tm->num % 2) {
			snprintf(err, errsize, "--chase %s: LTC counts at most 30 frames a second, "
				 "and %u/%u is not twice a rate it counts", o->spec, tm->num, tm->den);
			return -EINVAL;
		}
		cc.mult = 2;
	}
	rc.num = tm->num / cc.mult;
	rc.den = tm->den;
	timecode_init(&tc, rc.num, rc.den);
	if (o->tc_offset && timecode_parse(&tc, o->tc_offset, &cc.offset)) {
		snprintf(err, errsize, "--tc-offset %s: not a timecode at %u/%u frames a second "
			 "(HH:MM:SS:FF%s)", o->tc_offset, rc.num, rc.den,
			 tc.drop ? ", drop-frame: no label 00 or 01 in minutes not a tenth" : "");
		return -EINVAL;
	}
	cc.freewheel_ns = (int64_t)(o->freewheel_ms * 1e6);
	rc_ = rig_chase_open(&p->extclk, &rc, err, errsize);
	if (rc_)
		return rc_;
	cc.src = p->extclk;
	chase_init(&p->chase, &cc);
	loop_set_chase(p->L, &p->chase);
	rc_ = hal_extclk_start(p->extclk);
	if (rc_)
		snprintf(err, errsize, "--chase %s: cannot start reading: %s", o->spec,
			 strerror(-rc_));
	return rc_;
}

/* ---- --node: the other boards (lockstep/lockstep.h) ---- */

static int hook_local_end(void *ctx, int *level, char *text, size_t size)
{
	struct play *p = ctx;
	struct loop_report r;

	if (!loop_report_now(p->L, &r))
		return -1;
	if (r.cause == LOOP_CAUSE_BOARD)
		return -2;
	play_describe_report(p, &r, text, size);
	*level = r.end == LOOP_END_ESTOP || r.cause == LOOP_CAUSE_IMMEDIATE ? 2 : 1;
	switch (r.end) {
	case LOOP_END_ESTOP:
		return LS_STOP_ESTOP;
	case LOOP_END_DONE:
		/* the range played out: every board ends on the same tick */
		return r.cause == LOOP_CAUSE_FINISHED ? LS_STOP_FINISHED : LS_STOP_ASKED;
	case LOOP_END_STOPPED:
		return LS_STOP_ASKED;
	default:
		return LS_STOP_FAULT;
	}
}

static void hook_stop(void *ctx, int level, int kind)
{
	struct play *p = ctx;

	/* another board's e-stop is an e-stop here (exit 6), a stop asked for
	 * there a stop here (5), anything else a fault of the rig (7) */
	loop_request_end(p->L, level, kind == LS_STOP_ESTOP ? LOOP_END_ESTOP :
			 kind == LS_STOP_ASKED ? LOOP_END_STOPPED : LOOP_END_FAULT,
			 LOOP_CAUSE_BOARD);
}

static bool hook_ended(void *ctx)
{
	struct play *p = ctx;

	return atomic_load(&p->done);
}

/* The boards agree on an instant (ls_join), and the watch begins. Last of
 * the preparation: the start instant leaves start_ms for what follows
 * (the loop's thread, its memory locked). */
static int prepare_lockstep(struct play *p, char *err, size_t errsize)
{
	const struct play_lockstep *o = p->o.lockstep;
	const struct rig_desc *r = o->scene_rig;
	const struct rig_lockstep_desc *l = &r->lockstep;
	struct ls_hooks h = { .ctx = p, .local_end = hook_local_end, .stop = hook_stop,
			      .ended = hook_ended };
	struct ls_cfg c = {
		.nboards = r->nboards, .self = o->board, .tick_hz = p->tm->tick_hz,
		.need_ticks = loop_play_tick(p->L), .start_ms = l->start_ms,
		.heartbeat_ms = l->heartbeat_ms, .lost_ms = l->lost_ms, .join_ms = l->join_ms,
		.max_offset_us = l->max_offset_us, .ptp_offset_ns = l->ptp_offset_ns,
		.ptp_socket = o->ptp_socket, .ptp_free_running = o->ptp_free_running,
		.cancel = p->o.rig.cancel, .sched = p->plan.io, .log = p->o.rig.warn,
	};
	uint32_t i;
	int rc;

	p->ls_boards = calloc(r->nboards, sizeof(*p->ls_boards));
	if (!p->ls_boards) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	for (i = 0; i < r->nboards; i++) {
		p->ls_boards[i].name = r->boards[i].name;
		p->ls_boards[i].address = r->boards[i].address;
		p->ls_boards[i].port = r->boards[i].port ? r->boards[i].port : l->port;
		if (r->boards[i].lead)
			c.lead = i;
	}
	c.boards = p->ls_boards;
	memcpy(c.digest, o->digest, LS_DIGEST);
	rc = ls_open(&p->ls, &c, err, errsize);
	if (!rc)
		rc = ls_join(p->ls, &p->t0, err, errsize);
	if (!rc)
		rc = ls_watch(p->ls, &h);
	return rc;
}

int play_prepare(struct play *p, const struct rig_desc *rd, struct play_source *src,
		 const struct play_opts *o, char *err, size_t errsize)
{
	int rc;

	STRAND_ASSERT_NOT_RT();
	memset(p, 0, sizeof(*p));
	p->o = *o;
	atomic_init(&p->done, false);
	atomic_init(&p->press, false);
	hal_clock_init(&p->clk, o->virtual_clock);
	p->o.loop.wait_for_journal = o->virtual_clock;
	if (o->virtual_clock) {
		/* no deadline to meet: no need to starve others */
		p->o.rt.priority = 0;
		p->o.rt.pm_qos = false;
	}
	p->failed_at = PLAY_STAGE_RIG;
	/* one plan for every thread, before the devices start theirs */
	rt_plan_make(&p->plan, &p->o.rt);
	p->o.rig.events = p->plan.events;
	p->o.rig.io = p->plan.io;
	if (!p->o.rig.warn)
		p->o.rig.warn = stderr;
	rc = rig_build(&p->rig, rd, src, &p->clk, &p->o.rig, err, errsize);
	if (rc)
		return rc;
	p->rig_built = true;
	p->status_buf = calloc(PLAY_STATUS_RING, sizeof(*p->status_buf));
	if (!p->status_buf) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	hal_ring_init(&p->status, p->status_buf, PLAY_STATUS_RING, sizeof(*p->status_buf));
	p->failed_at = PLAY_STAGE_START;
	rc = rig_start(&p->rig, err, errsize);
	if (rc)
		return rc;
	p->rig_started = true;
	p->failed_at = PLAY_STAGE_LOOP;
	p->tm = &src->timing;
	rc = loop_init(&p->L, &p->o.loop, &p->rig, src, &p->clk, &p->status, err, errsize);
	if (rc == -EINVAL)
		p->failed_at = PLAY_STAGE_OPTIONS; /* --from after --to, and the like */
	if (rc == -EDOM)
		p->failed_at = PLAY_STAGE_START; /* an output stands outside its limits */
	if (!rc && o->chase.spec) {
		p->failed_at = PLAY_STAGE_START;
		rc = prepare_chase(p, src, err, errsize);
		if (rc == -EINVAL)
			p->failed_at = PLAY_STAGE_OPTIONS;
	}
	if (!rc)
		rc = given_up(p, err, errsize);
	if (rc)
		return rc;
	p->failed_at = PLAY_STAGE_JOURNAL;
	if (o->journal_path) {
		rc = open_journal(p, src, err, errsize);
		if (rc)
			return rc;
		loop_set_journal(p->L, &p->jr);
	}
	if (o->telemetry_path) {
		p->telemetry = fopen(o->telemetry_path, "w");
		if (!p->telemetry) {
			rc = -errno;
			snprintf(err, errsize, "telemetry %s: %s", o->telemetry_path, strerror(errno));
			return rc;
		}
	}
	p->failed_at = PLAY_STAGE_START;
	rc = given_up(p, err, errsize);
	if (!rc && o->lockstep)
		rc = prepare_lockstep(p, err, errsize);
	if (rc == -ECANCELED)
		rc = given_up(p, err, errsize) ? -ECANCELED : rc;
	if (rc)
		return rc;
	p->failed_at = PLAY_STAGE_NONE;
	return 0;
}

static void *rt_main(void *arg)
{
	struct play *p = arg;
	sigset_t all;
	int64_t t0 = 0;

	/* signals are the service thread's business */
	sigfillset(&all);
	pthread_sigmask(SIG_BLOCK, &all, NULL);
	rt_thread_setup(&p->o.rt, &p->rt);
	if (p->ls) {
		/* the instant the boards agreed on (lockstep.h) */
		t0 = p->t0;
	} else if (!p->clk.is_virtual) {
		/* tick 0 a millisecond from now, half a tick (half a
		 * millisecond at most) past a whole millisecond: no tick on the
		 * millisecond grid, where the kernel's own tick falls (HZ 1000,
		 * 250 or 100, on ktime multiples of its period). On this
		 * project's VM (HZ 250) whole-millisecond ticks met it every
		 * fourth tick: p50 +5 us, p99 113 us where cyclictest, whose
		 * phase is whatever its start makes it, had 75 (make
		 * bench-play). */
		int64_t tick_ns = 1000000000 / p->tm->tick_hz;

		t0 = (hal_clock_now(&p->clk) / 1000000 + 2) * 1000000 +
		     (tick_ns < 1000000 ? tick_ns : 1000000) / 2;
	} else {
		/* where starting the devices left virtual time (a CANopen
		 * start-up takes some), on a whole millisecond */
		t0 = (hal_clock_now(&p->clk) + 999999) / 1000000 * 1000000;
	}
	if (p->extclk)
		chase_begin(&p->chase, t0);
	strand_rt_enter();
	loop_run(p->L, t0);
	strand_rt_leave();
	atomic_store(&p->done, true);
	return NULL;
}

static const char *rig_out_name(const struct rig *r, int32_t i)
{
	return i >= 0 && (uint32_t)i < r->nout ? r->out[i].channel : "";
}

static double rig_out_file_units(const struct rig *r, int32_t i, double v)
{
	return i >= 0 && (uint32_t)i < r->nout ? rig_file_units(r->out[i].unit, v) : v;
}

static const char *rig_out_unit(const struct rig *r, int32_t i)
{
	return i >= 0 && (uint32_t)i < r->nout ? rig_unit_name(r->out[i].unit) : "";
}

static const char *out_name(const struct play *p, int32_t i)
{
	return rig_out_name(&p->rig, i);
}

static double out_file_units(const struct play *p, int32_t i, double v)
{
	return rig_out_file_units(&p->rig, i, v);
}

static const char *out_unit(const struct play *p, int32_t i)
{
	return rig_out_unit(&p->rig, i);
}

static void telemetry_line(struct play *p, const struct loop_status *s)
{
	fprintf(p->telemetry,
		"{\"tick\":%lld,\"t\":%.6f,\"state\":\"%s\",\"frame\":%lld,\"fired\":%lld,"
		"\"lat_max_us\":%.3f,\"overruns\":%lld,\"ferr\":%.6g,\"ferr_channel\":\"%s\"}\n",
		(long long)s->tick, (double)s->tick / p->tm->tick_hz,
		loop_state_name((enum loop_state)s->state), (long long)s->frame,
		(long long)s->fired, s->lat_max_ns / 1000.0, (long long)s->overruns,
		out_file_units(p, s->ferr_out, s->ferr), out_name(p, s->ferr_out));
}

static void status_line(struct play *p, const struct loop_status *s)
{
	double hz = p->tm->tick_hz, fps = (double)p->tm->num / p->tm->den;
	double el = s->tick / hz;
	char tc[24] = "--:--:--:--", rem[32] = "--";
	struct timecode tcr;

	timecode_init(&tcr, p->tm->num, p->tm->den);
	if (s->frame >= 0)
		timecode_format(&tcr, s->frame, tc, sizeof(tc));
	if (s->total >= 0) {
		double r = (double)(s->total - s->fired) / fps / (p->rig.ntrig ? p->rig.ntrig : 1);

		snprintf(rem, sizeof(rem), "%.1f s", r > 0 ? r : 0);
	}
	fprintf(p->o.status_tty,
		"\r\033[Kframe %lld %s  %lld/%lld fired  elapsed %.1f s  remaining %s  "
		"worst latency %.0f us  worst ferror %.4g %s  %s",
		(long long)s->frame, tc, (long long)s->fired, (long long)s->total, el, rem,
		s->lat_max_ns / 1000.0, out_file_units(p, s->ferr_out, s->ferr),
		out_unit(p, s->ferr_out), loop_state_name((enum loop_state)s->state));
	fflush(p->o.status_tty);
}

/* The service thread's round: journal chunks, telemetry, status line. */
static void serve(struct play *p, bool last)
{
	struct loop_status s;
	bool any = false;
	int64_t now = hal_mono_ns();

	if (p->has_journal) {
		int rc = journal_service(&p->jr, now);

		if (rc && !p->service_err)
			p->service_err = rc;
	}
	while (hal_ring_pop(&p->status, &s)) {
		any = true;
		p->last = s;
		if (p->telemetry)
			telemetry_line(p, &s);
	}
	if (atomic_exchange(&p->press, false))
		fprintf(stderr, "strand play: SIGUSR1: the simulated e-stops pressed (%u)\n",
			rig_sim_press_estop(&p->rig));
	if (p->o.status_tty && any && (last || now - p->status_shown_ns >= 100000000)) {
		p->status_shown_ns = now;
		status_line(p, &p->last);
	}
}

int play_run(struct play *p)
{
	struct timespec nap;
	int64_t start;
	int rc;

	STRAND_ASSERT_NOT_RT();
	rt_lock_memory(&p->o.rt, &p->rt);
	start = hal_mono_ns();
	rc = rt_thread_start(&p->thread, &p->o.rt, &p->plan, &p->rt, rt_main, p);
	if (rc) {
		rt_release(&p->rt);
		fprintf(stderr, "strand: cannot start the loop thread: %s\n", strerror(-rc));
		return rc;
	}
	/* every thread is up: what each runs at, once (none is real-time on
	 * the virtual clock) */
	if (!p->clk.is_virtual)
		rt_plan_report(&p->plan, stderr);
	/* The virtual clock may wait for the journal: serve it briskly. On the
	 * wall clock, 20 rounds a second keep the status line at 10 Hz and the
	 * journal's chunks ahead; waking more often measurably disturbed the
	 * loop's wake-ups on the test machine (make bench-play). */
	nap.tv_sec = 0;
	nap.tv_nsec = p->clk.is_virtual ? 1000000 : 50000000;
	while (!atomic_load(&p->done)) {
		serve(p, false);
		nanosleep(&nap, NULL);
	}
	hal_thread_join(&p->thread);
	p->wall_ns = hal_mono_ns() - start;
	rt_release(&p->rt);
	serve(p, true);
	if (p->o.status_tty)
		fputc('\n', p->o.status_tty);
	rt_report(&p->o.rt, &p->rt, stderr);
	/* drives disabled and lines deasserted before the journal is closed */
	rig_stop(&p->rig);
	p->rig_started = false;
	if (p->has_journal) {
		rc = journal_close(&p->jr);
		p->has_journal = false;
		if (rc && !p->service_err)
			p->service_err = rc;
	}
	if (p->telemetry) {
		fclose(p->telemetry);
		p->telemetry = NULL;
	}
	return 0;
}

void play_free(struct play *p)
{
	STRAND_ASSERT_NOT_RT();

	if (p->has_journal)
		journal_close(&p->jr);
	if (p->telemetry)
		fclose(p->telemetry);
	if (p->extclk) {
		hal_extclk_stop(p->extclk);
		hal_extclk_close(p->extclk);
	}
	/* before the loop is freed: the watch reads its report */
	ls_close(p->ls);
	free(p->ls_boards);
	loop_free(p->L);
	if (p->rig_built)
		rig_free(&p->rig);
	free(p->status_buf);
	memset(p, 0, sizeof(*p));
}

void play_signal(struct play *p, int sig, int count)
{
	if (!p->L)
		return;
	if (sig == SIGINT && count >= 2)
		loop_request_stop(p->L, 2, LOOP_CAUSE_IMMEDIATE);
	else
		loop_request_stop(p->L, 1, LOOP_CAUSE_SIGNAL);
}

void play_press_estop(struct play *p)
{
	atomic_store(&p->press, true);
}

void play_report_describe(const struct rig *rig, const struct mot_timing *tm,
			  const struct loop_result *res, const struct loop_report *r,
			  const struct lockstep *ls, char *buf, size_t size)
{
	int32_t o = r->out;
	const char *why;
	int level = 1;
	char when[96];

	snprintf(when, sizeof(when), "at tick %lld (%.3f s), last frame %lld", (long long)r->tick,
		 (double)r->tick / tm->tick_hz, (long long)r->frame);
	switch (r->cause) {
	case LOOP_CAUSE_FINISHED:
		snprintf(buf, size, "finished: %lld frames fired", (long long)res->frames_fired);
		break;
	case LOOP_CAUSE_DURATION:
	case LOOP_CAUSE_SIGNAL:
	case LOOP_CAUSE_STOP_INPUT:
		snprintf(buf, size, "%s %s; every axis brought to rest within its limits",
			 loop_cause_name(r->cause), when);
		break;
	case LOOP_CAUSE_IMMEDIATE:
		snprintf(buf, size, "%s %s; drives disabled at once", loop_cause_name(r->cause),
			 when);
		break;
	case LOOP_CAUSE_ESTOP:
		if (!r->device) /* no input's: a live session's e-stop command */
			snprintf(buf, size, "e-stop (commanded) %s; drives disabled, latched",
				 when);
		else if (r->has_edge)
			snprintf(buf, size, "e-stop: input '%s' (line %d) %s, acted on %.1f us after "
				 "the edge; drives disabled, latched", r->device ? r->device : "?",
				 r->channel, when, (r->acted_ns - r->edge_ns) / 1000.0);
		else
			snprintf(buf, size, "e-stop: input '%s' (line %d) %s; drives disabled, "
				 "latched", r->device ? r->device : "?", r->channel, when);
		break;
	case LOOP_CAUSE_DEVICE:
		if (r->channel < 0) { /* the device as a whole: a bus, a unit */
			snprintf(buf, size, "device fault: device '%s': %s (%s) %s",
				 r->device ? r->device : "?", r->what ? r->what : "fault",
				 strerror(r->code < 0 ? -r->code : r->code), when);
			break;
		}
		snprintf(buf, size, "device fault: device '%s' channel %d%s%s%s: %s (%s) %s",
			 r->device ? r->device : "?", r->channel, o >= 0 ? " (" : "",
			 rig_out_name(rig, o), o >= 0 ? ")" : "", r->what ? r->what : "fault",
			 strerror(r->code < 0 ? -r->code : r->code), when);
		break;
	case LOOP_CAUSE_FERROR:
	case LOOP_CAUSE_IN_POSITION:
		snprintf(buf, size, "%s: device '%s' channel %d (%s): %.6g %s beyond the bound %.6g %s %s",
			 loop_cause_name(r->cause), r->device ? r->device : "?", r->channel,
			 rig_out_name(rig, o), rig_out_file_units(rig, o, fabs(r->value)),
			 rig_out_unit(rig, o), rig_out_file_units(rig, o, r->bound),
			 rig_out_unit(rig, o), when);
		break;
	case LOOP_CAUSE_LIMIT_POS:
	case LOOP_CAUSE_LIMIT_VEL:
	case LOOP_CAUSE_LIMIT_ACC:
		snprintf(buf, size, "%s: %s (device '%s' channel %d): %.6g beyond %.6g %s%s %s",
			 loop_cause_name(r->cause), rig_out_name(rig, o),
			 r->device ? r->device : "?", r->channel,
			 rig_out_file_units(rig, o, r->value), rig_out_file_units(rig, o, r->bound),
			 rig_out_unit(rig, o),
			 r->cause == LOOP_CAUSE_LIMIT_VEL ? "/s" :
			 r->cause == LOOP_CAUSE_LIMIT_ACC ? "/s^2" : "", when);
		break;
	case LOOP_CAUSE_READY:
		snprintf(buf, size, "camera not ready: no camera-ready edge in time %s", when);
		break;
	case LOOP_CAUSE_JOURNAL:
		snprintf(buf, size, "journal cannot record the next frame (%s) %s; stopped before "
			 "firing it", r->code ? strerror(-r->code) : "not ready or full", when);
		break;
	case LOOP_CAUSE_SATURATION:
		snprintf(buf, size, "internal: fixed-point arithmetic saturated %s", when);
		break;
	case LOOP_CAUSE_CHASE:
		if (r->end == LOOP_END_FAULT)
			snprintf(buf, size, "chase: source '%s': %s (%s) %s; every axis brought to "
				 "rest within its limits", r->device ? r->device : "?",
				 r->what ? r->what : "fault", strerror(r->code < 0 ? -r->code : r->code),
				 when);
		else
			snprintf(buf, size, "chase: source '%s': %s %s; every axis brought to rest "
				 "within its limits", r->device ? r->device : "?",
				 chase_event_name((enum chase_event)r->detail), when);
		break;
	case LOOP_CAUSE_BOARD:
		why = ls ? ls_stop_reason(ls, &level) : NULL;
		snprintf(buf, size, "%s; here %s %s", why ? why : "another board stopped",
			 r->end == LOOP_END_ESTOP || level == 2 ? "every drive disabled at once" :
			 "every axis brought to rest within its limits", when);
		break;
	case LOOP_CAUSE_DISABLE:
		snprintf(buf, size, "drives disabled %s; every axis brought to rest first", when);
		break;
	default:
		snprintf(buf, size, "ended (%d)", (int)r->end);
		break;
	}
}

void play_describe(const struct play *p, char *buf, size_t size)
{
	play_describe_report(p, &loop_result(p->L)->rep, buf, size);
}

void play_describe_report(const struct play *p, const struct loop_report *r, char *buf,
			  size_t size)
{
	play_report_describe(&p->rig, p->tm, loop_result(p->L), r, p->ls, buf, size);
}

/* What the chase did: lock, rate, stops and cues, the schedule's phase. */
static void chase_summary(const struct play *p, FILE *f)
{
	const struct chase *c = &p->chase;
	const struct chase_stats *s = &c->st;
	uint32_t e;

	fprintf(f, "  chase %s: %lld marks", c->cfg.src->name, (long long)s->marks);
	if (s->lock_ns >= 0 && s->first_mark_ns >= 0)
		fprintf(f, ", locked %.1f ms after the first", (s->lock_ns - s->first_mark_ns) / 1e6);
	fprintf(f, ", rate %+.1f ppm, cued %lld time%s", (s->rate - 1) * 1e6,
		(long long)c->recues + (s->locks ? 1 : 0), c->recues ? "s" : "");
	if (s->phase_max_ns > 0)
		fprintf(f, ", schedule within %.1f us of the source", s->phase_max_ns / 1e3);
	if (s->freewheel_max_ns > 0)
		fprintf(f, ", longest without a mark %.1f ms", s->freewheel_max_ns / 1e6);
	fputc('\n', f);
	for (e = CHASE_EV_JUMP; e <= CHASE_EV_FORMAT; e++)
		if (s->events[e])
			fprintf(f, "  chase: %s: %lld time%s\n", chase_event_name((enum chase_event)e),
				(long long)s->events[e], s->events[e] == 1 ? "" : "s");
	if (s->outliers)
		fprintf(f, "  chase: %lld pulse%s between frames ignored\n", (long long)s->outliers,
			s->outliers == 1 ? "" : "s");
	if (c->past_end)
		fprintf(f, "  chase: the source named a frame past the range; nothing played then\n");
}

/* What the lockstep did: the start, the clocks, the heartbeats. */
static void lockstep_summary(const struct play *p, FILE *f)
{
	const struct play_lockstep *o = p->o.lockstep;
	const struct rig_desc *r = o->scene_rig;
	struct ls_stats st;

	ls_stats(p->ls, &st);
	fprintf(f, "  lockstep: board '%s' of %u%s, play began at %lld.%09lld on the PTP clock "
		"(CLOCK_REALTIME), tick 0 at %lld ns (CLOCK_MONOTONIC)", r->boards[o->board].name,
		r->nboards, r->boards[o->board].lead ? " (the leader)" : "",
		(long long)(st.play_ns / 1000000000), (long long)(st.play_ns % 1000000000),
		(long long)st.t0_ns);
	if (r->boards[o->board].lead)
		fprintf(f, "; the clocks within %.1f us (board '%s'; round trips up to %.1f us)",
			st.offset_us_max, r->boards[st.offset_board].name, st.delay_us_max);
	fprintf(f, "; heartbeats %lld sent, %lld heard, the longest wait %.1f ms",
		(long long)st.beats_sent, (long long)st.beats_got, st.beat_gap_max_ns / 1e6);
	if (st.dropped)
		fprintf(f, "; %lld datagrams refused", (long long)st.dropped);
	fputc('\n', f);
}

void play_summary(const struct play *p, FILE *f, bool reason)
{
	const struct loop_result *res = loop_result(p->L);
	const struct lat_stats *s = &res->lat;
	char why[512];
	uint32_t i;

	play_describe(p, why, sizeof(why));
	if (reason)
		fprintf(f, "strand play: %s\n", why);
	fprintf(f, "  frames fired %lld, ticks %lld (%.3f s of motion) in %.3f s, %s clock\n",
		(long long)res->frames_fired, (long long)res->ticks_run,
		(double)res->ticks_run / p->tm->tick_hz, p->wall_ns / 1e9,
		p->clk.is_virtual ? "virtual" : "wall");
	if (!p->clk.is_virtual && s->n)
		fprintf(f,
			"  wake-up latency us: min %.1f avg %.1f max %.1f (tick %lld) p50 %.0f "
			"p99 %.0f p99.9 %.0f; %s\n"
			"  overruns %lld, catch-up ticks %lld, latest tick start %.1f us, "
			"longest tick %.1f us\n",
			s->min_ns / 1e3, (double)s->sum_ns / s->n / 1e3, s->max_ns / 1e3,
			(long long)s->max_at_tick, lat_percentile_us(s, 0.5),
			lat_percentile_us(s, 0.99), lat_percentile_us(s, 0.999),
			p->rt.fifo ? "SCHED_FIFO" : "SCHED_OTHER", (long long)s->overruns,
			(long long)s->catchup, s->late_max_ns / 1e3, s->work_max_ns / 1e3);
	fprintf(f, "  cpu %.0f ns per tick\n",
		res->ticks_run ? (double)res->cpu_ns / res->ticks_run : 0.0);
	if (res->ferr_worst_out >= 0)
		fprintf(f, "  worst following error %.6g %s on %s\n",
			out_file_units(p, res->ferr_worst_out, res->ferr_worst),
			out_unit(p, res->ferr_worst_out), out_name(p, res->ferr_worst_out));
	for (i = 0; i < p->rig.nout; i++)
		if (res->limited[i])
			fprintf(f, "  --force: %s clamped to its limits on %lld ticks\n",
				p->rig.out[i].channel, (long long)res->limited[i]);
	if (res->edges_bound_ticks)
		fprintf(f, "  input edges: %lld; on %lld ticks a device gave the most a tick takes "
			"(%d), the rest waited for the next tick\n", (long long)res->edges,
			(long long)res->edges_bound_ticks, LOOP_EDGES_PER_TICK);
	if (p->extclk)
		chase_summary(p, f);
	if (p->ls)
		lockstep_summary(p, f);
	rig_report(&p->rig, f);
	if (res->status_dropped)
		fprintf(f, "  %lld status samples dropped (the service thread fell behind)\n",
			(long long)res->status_dropped);
	if (p->service_err)
		fprintf(f, "  journal: %s\n", strerror(-p->service_err));
	if (p->o.journal_path)
		fprintf(f, "  journal %s\n", p->o.journal_path);
}
