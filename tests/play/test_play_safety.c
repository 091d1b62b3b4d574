/* SPDX-License-Identifier: MIT */
/*
 * test_play_safety.c - the ways a run ends early, on the virtual clock: the
 * e-stop within one tick, a stop input, SIGINT (once: to rest within the
 * limits; twice: at once), a drive that trips, an axis that jams (following
 * error), a scene beyond its limits (refused, or clamped with --force),
 * and which reason the report keeps when there are two.
 */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/exitcode.h"
#include "playutil.h"
#include "sim/sim_camera.h"
#include "sim/sim_drive.h"
#include "sim/sim_gpio.h"
#include "testutil.h"

static struct play *g_play;

/* Prepare a run of the test arm (a on "arm" axis 0, b on "arm2" axis 0). */
static void prepare(struct play *p, struct pu_rig *r, struct pu_source *ps,
		    struct play_opts *o, unsigned inputs)
{
	char err[256];

	pu_arm_source(ps, 24, 1, 1000, 0, 240);
	pu_rig_init(r, ps, 1, inputs);
	r->out[1].device = "arm2";
	r->out[1].axis = 0;
	pu_opts(o, ps);
	pu_alloc_hook_install();
	if (play_prepare(p, &r->d, &ps->s, o, err, sizeof(err)))
		fail_msg("play_prepare: %s", err);
	g_play = p;
}

static const struct sim_drive_watch *watch(const struct play *p, uint32_t out)
{
	const struct rig_out *o = &p->rig.out[out];

	return sim_drive_watch(sim_drive_of(p->rig.axes[o->dev]), o->ch);
}

/* The last traced targets of an output: at rest (the last two equal). */
static void assert_at_rest(int64_t *trace, int64_t n, uint32_t nch, uint32_t ch)
{
	assert_true(n >= 2);
	assert_int_equal(trace[(n - 1) * nch + ch], trace[(n - 2) * nch + ch]);
}

static void no_exposure_from(struct play *p, int64_t tick)
{
	uint64_t i, n = sim_camera_count(rig_sim_camera(&p->rig, 0));

	for (i = 0; i < n; i++)
		assert_true(sim_camera_exposure(rig_sim_camera(&p->rig, 0), i)->tick < tick);
	assert_int_equal((int64_t)n, loop_result(p->L)->frames_fired);
}

/* The e-stop opens during tick 3000's period (or exactly as it begins):
 * tick 3000's setpoints never go out, every drive is disabled then, the
 * trigger line is deasserted, exit 6. */
static void test_estop(void **state)
{
	int64_t when[2] = { 0, -1 }; /* ns relative to tick 3000's start */
	int k;

	for (k = 0; k < 2; k++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;
		uint32_t i;

		prepare(&p, &r, &ps, &o, PU_ESTOP);
		assert_int_equal(sim_gpio_schedule(rig_sim_gpio(&p.rig, "io"), 0,
						   loop_due(p.L, 3000) + when[k], true), 0);
		assert_int_equal(pu_finish(&p, true), STRAND_EXIT_ESTOP);
		assert_int_equal(loop_result(p.L)->rep.cause, LOOP_CAUSE_ESTOP);
		assert_int_equal(loop_result(p.L)->rep.tick, 3000);
		for (i = 0; i < 2; i++) {
			assert_int_equal(watch(&p, i)->disabled_tick, 3000);
			assert_int_equal(watch(&p, i)->last_commit_tick, 2999);
			assert_false(watch(&p, i)->powered);
		}
		assert_false(sim_gpio_out_level(rig_sim_gpio(&p.rig, "io"), 0)); /* active high: low */
		no_exposure_from(&p, 3000);
		assert_true(loop_result(p.L)->frames_fired > 60);
		play_free(&p);
	}
}

/* An e-stop already open: nothing moves, nothing fires. */
static void test_estop_before_start(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;

	prepare(&p, &r, &ps, &o, PU_ESTOP);
	assert_int_equal(sim_gpio_schedule(rig_sim_gpio(&p.rig, "io"), 0, INT64_MIN, true), 0);
	assert_int_equal(pu_finish(&p, true), STRAND_EXIT_ESTOP);
	assert_int_equal(loop_result(p.L)->rep.tick, 0);
	assert_int_equal(watch(&p, 0)->commits, 0);
	assert_int_equal(sim_camera_count(rig_sim_camera(&p.rig, 0)), 0);
	play_free(&p);
}

/* An e-stop that opens for less than a tick and is closed again when the
 * loop looks: its edge stops the run all the same, in that tick. */
static void test_estop_short_pulse(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct sim_gpio *g;
	const struct loop_report *rep;
	int64_t opened;

	prepare(&p, &r, &ps, &o, PU_ESTOP);
	g = rig_sim_gpio(&p.rig, "io");
	opened = loop_due(p.L, 2999) + 1000;
	assert_int_equal(sim_gpio_schedule(g, 0, opened, true), 0);
	assert_int_equal(sim_gpio_schedule(g, 0, opened + 1000, false), 0);
	assert_int_equal(pu_finish(&p, true), STRAND_EXIT_ESTOP);
	rep = &loop_result(p.L)->rep;
	assert_int_equal(rep->cause, LOOP_CAUSE_ESTOP);
	assert_int_equal(rep->tick, 3000);
	assert_true(rep->has_edge);
	assert_int_equal(rep->edge_ns, opened);
	assert_string_equal(rep->device, "estop");
	assert_int_equal(watch(&p, 0)->disabled_tick, 3000);
	assert_int_equal(watch(&p, 0)->last_commit_tick, 2999);
	play_free(&p);
}

/* The simulated chip's level is the newest too: edges due but left for
 * the next poll count (din.h). */
static void test_sim_level_ahead_of_poll(void **state)
{
	struct hal_clock clk;
	struct sim_gpio *g;
	struct hal_edge ev[4];
	struct hal_din *d;
	char err[128];
	int i;

	hal_clock_init(&clk, true);
	assert_int_equal(sim_gpio_new(&g, "io", 0, 2, &clk, 16, err, sizeof(err)), 0);
	d = sim_gpio_din(g);
	for (i = 0; i < 4; i++)
		assert_int_equal(sim_gpio_schedule(g, 1, 100 + i, i % 2 == 0), 0);
	assert_int_equal(sim_gpio_schedule(g, 0, 200, true), 0);
	assert_int_equal(sim_gpio_schedule(g, 0, 900, false), 0); /* not due yet */
	assert_int_equal(hal_din_poll(d, 500, ev, 2), 2);
	assert_true(hal_din_level(d, 0));   /* its edge is still queued */
	assert_false(hal_din_level(d, 1));  /* after all four */
	assert_int_equal(hal_din_poll(d, 500, ev, 4), 3);
	assert_int_equal(ev[2].line, 0);
	assert_true(hal_din_level(d, 0));
	sim_gpio_free(g);
}

/*
 * An input device that queues far more edges than a tick takes: `n`
 * edges of a chattering line, then one asserted edge on line `last`, all
 * due at at_ns, handed out in that order, as a GPIO device's ring would.
 * It counts what each tick took; its level is the newest (din.h): every
 * edge due counts, handed out or not.
 */
struct storm {
	struct hal_din base; /* first */
	struct hal_din *orig;
	int64_t at_ns;
	uint32_t chatter, last, n, given;
	int64_t now_ns;           /* the tick being polled (virtual: its due time) */
	uint32_t tick_got, tick_max;
	int64_t ticks_with_edges;
	int64_t last_at_tick_ns;  /* when `last`'s own edge was handed out, or -1 */
};

static uint32_t storm_poll(struct hal_din *d, int64_t now_ns, struct hal_edge *ev, uint32_t max)
{
	struct storm *s = (struct storm *)d;
	uint32_t k = 0;

	if (now_ns != s->now_ns) {
		s->now_ns = now_ns;
		s->tick_got = 0;
	}
	while (now_ns >= s->at_ns && k < max && s->given <= s->n) {
		if (s->given < s->n)
			ev[k] = (struct hal_edge){ s->chatter, s->given % 2 == 0, s->at_ns };
		else
			ev[k] = (struct hal_edge){ s->last, true, s->at_ns + 1 };
		if (s->given == s->n)
			s->last_at_tick_ns = now_ns;
		s->given++;
		k++;
	}
	if (k && !s->tick_got)
		s->ticks_with_edges++;
	s->tick_got += k;
	if (s->tick_got > s->tick_max)
		s->tick_max = s->tick_got;
	return k;
}

static bool storm_level(struct hal_din *d, uint32_t line)
{
	struct storm *s = (struct storm *)d;

	/* n is even: the chattering line ends where it began, deasserted */
	return line == s->last && s->now_ns >= s->at_ns;
}

static int storm_fault(struct hal_din *d, struct hal_fault *f)
{
	return 0;
}

static int storm_nothing(struct hal_din *d)
{
	return 0;
}

static void storm_close(struct hal_din *d)
{
}

static const struct hal_din_ops storm_ops = {
	.start = storm_nothing, .poll = storm_poll, .level = storm_level,
	.fault = storm_fault, .stop = storm_nothing, .close = storm_close,
};

/* In place of device io's inputs from now on. */
static void storm_install(struct storm *s, struct play *p, uint32_t n, uint32_t chatter,
			  uint32_t last, int64_t at_ns)
{
	int32_t din = p->rig.dev[rig_device(&p->rig, "io")].din;

	assert_true(din >= 0);
	memset(s, 0, sizeof(*s));
	s->base = (struct hal_din){ .ops = &storm_ops, .name = "io", .nlines = 3 };
	s->orig = p->rig.dins[din];
	s->n = n;
	s->chatter = chatter;
	s->last = last;
	s->at_ns = at_ns;
	s->now_ns = INT64_MIN;
	s->last_at_tick_ns = -1;
	p->rig.dins[din] = &s->base;
}

static void storm_remove(struct storm *s, struct play *p)
{
	p->rig.dins[p->rig.dev[rig_device(&p->rig, "io")].din] = s->orig;
}

/* 4000 edges of a chattering camera-ready line, and the e-stop's edge
 * behind them, all due in tick 3000: the tick takes LOOP_EDGES_PER_TICK of
 * them and no more, and the e-stop, seen by its level, stops the run in
 * that very tick. */
static void test_estop_behind_edge_storm(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct storm s;
	const struct loop_result *res;

	prepare(&p, &r, &ps, &o, PU_ESTOP | PU_READY);
	storm_install(&s, &p, 4000, 1, 0, loop_due(p.L, 3000) - 1);
	assert_int_equal(pu_finish(&p, true), STRAND_EXIT_ESTOP);
	res = loop_result(p.L);
	assert_int_equal(res->rep.cause, LOOP_CAUSE_ESTOP);
	assert_int_equal(res->rep.tick, 3000);
	assert_false(res->rep.has_edge); /* its edge is still queued */
	assert_int_equal(s.tick_max, LOOP_EDGES_PER_TICK);
	assert_int_equal(s.ticks_with_edges, 1);
	assert_int_equal(res->edges, LOOP_EDGES_PER_TICK);
	assert_int_equal(res->edges_tick_max, LOOP_EDGES_PER_TICK);
	assert_int_equal(res->edges_bound_ticks, 1);
	assert_int_equal(watch(&p, 0)->disabled_tick, 3000);
	assert_int_equal(watch(&p, 0)->last_commit_tick, 2999);
	storm_remove(&s, &p);
	play_free(&p);
}

/* 1000 chattering edges and a stop input's edge behind them: each tick
 * takes LOOP_EDGES_PER_TICK, the rest wait for the next, in order, so the
 * stop edge (the 1001st) is acted on in the fourth tick, 3003. */
static void test_edges_beyond_the_bound_wait(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct storm s;
	const struct loop_result *res;
	char msg[1024];
	FILE *f;

	prepare(&p, &r, &ps, &o, PU_ESTOP | PU_READY | PU_STOP);
	storm_install(&s, &p, 1000, 1, 2, loop_due(p.L, 3000));
	assert_int_equal(pu_finish(&p, true), STRAND_EXIT_STOPPED);
	res = loop_result(p.L);
	assert_int_equal(res->rep.cause, LOOP_CAUSE_STOP_INPUT);
	assert_int_equal(res->rep.tick, 3003);
	assert_int_equal(s.last_at_tick_ns, loop_due(p.L, 3003));
	assert_int_equal(s.tick_max, LOOP_EDGES_PER_TICK);
	assert_int_equal(s.ticks_with_edges, 4);
	assert_int_equal(res->edges, 1001);
	assert_int_equal(res->edges_bound_ticks, 3);
	assert_int_equal(sim_camera_missed(rig_sim_camera(&p.rig, 0)), 0);
	f = fmemopen(msg, sizeof(msg), "w");
	play_summary(&p, f, false);
	fclose(f);
	printf("%s", msg);
	assert_non_null(strstr(msg, "input edges: 1001; on 3 ticks a device gave the most a tick "
				    "takes (256), the rest waited for the next tick"));
	storm_remove(&s, &p);
	play_free(&p);
}

/* A stop input: every axis to rest within its limits, no frame after. */
static void test_stop_input(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	int64_t trace[2][12000];

	prepare(&p, &r, &ps, &o, PU_STOP);
	sim_drive_trace(sim_drive_of(p.rig.axes[0]), trace[0], 12000);
	sim_drive_trace(sim_drive_of(p.rig.axes[1]), trace[1], 12000);
	assert_int_equal(sim_gpio_schedule(rig_sim_gpio(&p.rig, "io"), 0, loop_due(p.L, 3000), true), 0);
	assert_int_equal(pu_finish(&p, true), STRAND_EXIT_STOPPED);
	assert_int_equal(loop_result(p.L)->rep.cause, LOOP_CAUSE_STOP_INPUT);
	no_exposure_from(&p, 3001);
	/* a was moving fast: stopping took a while, and ended at rest */
	assert_true(loop_result(p.L)->ticks_run > 3010);
	assert_at_rest(trace[0], sim_drive_traced(sim_drive_of(p.rig.axes[0])), 1, 0);
	assert_at_rest(trace[1], sim_drive_traced(sim_drive_of(p.rig.axes[1])), 1, 0);
	play_free(&p);
}

static volatile sig_atomic_t sigints;

static void on_sigint(int sig)
{
	sigints++;
	play_signal(g_play, sig, sigints);
}

static int kills_wanted;

/* In the loop thread, at frame 100's exposure: SIGINT the process (the
 * service thread takes it) and wait until the loop has the request, so that
 * the stop lands on the next tick however fast the virtual clock runs. */
static void kill_at_100(void *ctx, const struct sim_exposure *e)
{
	struct play *p = ctx;
	int i;

	if (loop_result(p->L)->last_frame != 100)
		return;
	for (i = 0; i < kills_wanted; i++) {
		int want = i + 1;

		kill(getpid(), SIGINT);
		for (int spin = 0; spin < 5000 && loop_stop_requested(p->L) < want; spin++)
			usleep(1000);
	}
}

static void test_sigint(void **state)
{
	struct sigaction sa, old;
	int k;

	memset(&sa, 0, sizeof(sa));
	sa.sa_handler = on_sigint;
	sigaction(SIGINT, &sa, &old);
	for (k = 1; k <= 2; k++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;
		int64_t trace[12000];
		int64_t at;
		const struct loop_result *res;

		sigints = 0;
		kills_wanted = k;
		prepare(&p, &r, &ps, &o, 0);
		sim_drive_trace(sim_drive_of(p.rig.axes[0]), trace, 12000);
		sim_camera_on_exposure(rig_sim_camera(&p.rig, 0), kill_at_100, &p);
		assert_int_equal(pu_finish(&p, true), STRAND_EXIT_STOPPED);
		at = sim_camera_exposure(rig_sim_camera(&p.rig, 0), 100)->tick;
		res = loop_result(p.L);
		assert_int_equal(sim_camera_count(rig_sim_camera(&p.rig, 0)), 101);
		assert_int_equal(res->rep.tick, at + 1);
		if (k == 1) {
			assert_int_equal(res->rep.cause, LOOP_CAUSE_SIGNAL);
			/* a was moving at frame 100: it decelerated to rest */
			assert_true(res->ticks_run > at + 10);
			assert_at_rest(trace, sim_drive_traced(sim_drive_of(p.rig.axes[0])), 1, 0);
			assert_true(watch(&p, 0)->powered || watch(&p, 0)->disabled_tick > at + 10);
		} else {
			assert_int_equal(res->rep.cause, LOOP_CAUSE_IMMEDIATE);
			assert_int_equal(watch(&p, 0)->disabled_tick, at + 1);
			assert_int_equal(watch(&p, 1)->disabled_tick, at + 1);
		}
		play_free(&p);
	}
	sigaction(SIGINT, &old, NULL);
}

/* arm2 trips at tick 3000: it is disabled at once, a (on arm) comes to
 * rest, and the message names the device, the channel, the output and the
 * cause. */
static void test_drive_trip(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	int64_t trace[12000];
	char msg[512];
	const struct loop_report *rep;

	prepare(&p, &r, &ps, &o, 0);
	sim_drive_trace(sim_drive_of(p.rig.axes[0]), trace, 12000);
	sim_drive_inject(sim_drive_of(p.rig.axes[1]), 0, 3000, SIM_DRIVE_TRIP);
	assert_int_equal(pu_finish(&p, true), STRAND_EXIT_FAULT);
	rep = &loop_result(p.L)->rep;
	assert_int_equal(rep->cause, LOOP_CAUSE_DEVICE);
	assert_string_equal(rep->device, "arm2");
	assert_int_equal(rep->channel, 0);
	assert_int_equal(rep->out, 1);
	assert_int_equal(rep->tick, 3000);
	assert_int_equal(watch(&p, 1)->disabled_tick, 3000);
	no_exposure_from(&p, 3000);
	assert_at_rest(trace, sim_drive_traced(sim_drive_of(p.rig.axes[0])), 1, 0);
	play_describe(&p, msg, sizeof(msg));
	printf("%s\n", msg);
	assert_non_null(strstr(msg, "device 'arm2' channel 0 (b.position): overcurrent"));
	play_free(&p);
}

/* Two reasons to end: the first stands, but an e-stop outranks it. arm2
 * trips at tick 3000 and the run stops for it; a stop input at tick 3005
 * changes nothing, an e-stop at 3005 takes over (every drive off at once,
 * exit 6, the input named). */
static void test_first_reason_stands(void **state)
{
	int k;

	for (k = 0; k < 2; k++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;
		const struct loop_report *rep;
		uint32_t line = k == 0 ? 1 : 0; /* the stop input, the e-stop */

		prepare(&p, &r, &ps, &o, PU_ESTOP | PU_STOP);
		sim_drive_inject(sim_drive_of(p.rig.axes[1]), 0, 3000, SIM_DRIVE_TRIP);
		assert_int_equal(sim_gpio_schedule(rig_sim_gpio(&p.rig, "io"), line, loop_due(p.L, 3005),
						   true), 0);
		if (k == 0) {
			assert_int_equal(pu_finish(&p, true), STRAND_EXIT_FAULT);
			rep = &loop_result(p.L)->rep;
			assert_int_equal(rep->cause, LOOP_CAUSE_DEVICE);
			assert_string_equal(rep->device, "arm2");
			assert_int_equal(rep->out, 1);
			assert_int_equal(rep->tick, 3000);
			assert_true(loop_result(p.L)->ticks_run > 3005);
		} else {
			assert_int_equal(pu_finish(&p, true), STRAND_EXIT_ESTOP);
			rep = &loop_result(p.L)->rep;
			assert_int_equal(rep->cause, LOOP_CAUSE_ESTOP);
			assert_string_equal(rep->device, "estop");
			assert_int_equal(rep->channel, 0);
			assert_int_equal(rep->out, -1);
			assert_null(rep->what);
			assert_int_equal(rep->tick, 3005);
			assert_int_equal(watch(&p, 0)->disabled_tick, 3005);
		}
		assert_int_equal(watch(&p, 1)->disabled_tick, 3000);
		play_free(&p);
	}
}

/* a's axis jams while moving: the following error outgrows its bound
 * within a few ticks and the run stops, naming it. */
static void test_following_error(void **state)
{
	static const enum sim_drive_fault faults[] = { SIM_DRIVE_JAM, SIM_DRIVE_SLUGGISH };
	size_t k;

	for (k = 0; k < 2; k++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;
		char msg[512];
		const struct loop_report *rep;

		prepare(&p, &r, &ps, &o, 0);
		sim_drive_inject(sim_drive_of(p.rig.axes[0]), 0, 3000, faults[k]);
		assert_int_equal(pu_finish(&p, true), STRAND_EXIT_FAULT);
		rep = &loop_result(p.L)->rep;
		assert_int_equal(rep->cause, LOOP_CAUSE_FERROR);
		assert_string_equal(rep->device, "arm");
		assert_int_equal(rep->out, 0);
		assert_true(fabs(rep->value) > rep->bound);
		assert_true(rep->tick > 3000 && rep->tick < 3000 + 2000);
		play_describe(&p, msg, sizeof(msg));
		printf("%s\n", msg);
		assert_non_null(strstr(msg, "following error: device 'arm' channel 0 (a.angle)"));
		play_free(&p);
	}
}

/* A scene beyond a's limits: refused at the first offending tick (the
 * setpoint is never sent), or with --force clamped and counted. Either way
 * the drive never sees a command beyond the limits (run_checked). */
static void test_runtime_limits(void **state)
{
	static struct pu_smooth fast = { 10, 50, 300, 0 }; /* 300 deg in 40 frames */
	int force;

	for (force = 0; force < 2; force++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;
		char err[256];
		int code;
		const struct loop_result *res;

		pu_source_init(&ps, "too-fast", 24, 1, 1000, 0, 100);
		pu_source_add(&ps, "a.angle", SRC_UNIT_TURNS, pu_smooth, &fast, 60, 120);
		pu_rig_init(&r, &ps, 1, 0);
		r.out[0].limits.has_min = r.out[0].limits.has_max = true;
		r.out[0].limits.min = -10;
		r.out[0].limits.max = 400;
		pu_opts(&o, &ps);
		o.loop.force = force;
		pu_alloc_hook_install();
		assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), 0);
		code = pu_finish(&p, true);
		res = loop_result(p.L);
		if (!force) {
			assert_int_equal(code, STRAND_EXIT_FAULT);
			assert_true(res->rep.cause == LOOP_CAUSE_LIMIT_ACC ||
				    res->rep.cause == LOOP_CAUSE_LIMIT_VEL);
			assert_int_equal(res->rep.out, 0);
			play_describe(&p, err, sizeof(err));
			printf("%s\n", err);
		} else {
			assert_int_equal(code, STRAND_EXIT_OK);
			assert_true(res->limited[0] > 100);
			assert_int_equal(sim_camera_count(rig_sim_camera(&p.rig, 0)), 101);
		}
		play_free(&p);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_estop),
		cmocka_unit_test(test_estop_before_start),
		cmocka_unit_test(test_estop_short_pulse),
		cmocka_unit_test(test_sim_level_ahead_of_poll),
		cmocka_unit_test(test_estop_behind_edge_storm),
		cmocka_unit_test(test_edges_beyond_the_bound_wait),
		cmocka_unit_test(test_stop_input),
		cmocka_unit_test(test_sigint),
		cmocka_unit_test(test_drive_trip),
		cmocka_unit_test(test_first_reason_stands),
		cmocka_unit_test(test_following_error),
		cmocka_unit_test(test_runtime_limits),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
