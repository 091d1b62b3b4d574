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
		cmocka_unit_test(test_stop_input),
		cmocka_unit_test(test_sigint),
		cmocka_unit_test(test_drive_trip),
		cmocka_unit_test(test_first_reason_stands),
		cmocka_unit_test(test_following_error),
		cmocka_unit_test(test_runtime_limits),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
