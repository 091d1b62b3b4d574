/* SPDX-License-Identifier: MIT */
/*
 * test_play.c - whole runs of the loop on the virtual clock: trigger ticks
 * exactly as FORMULAS.md section 5 says, the journal equal to what the
 * simulated camera saw, every commanded move within the limits, loops and
 * ping-pong, offsets and pulse widths, bit-reproducible runs, and not one
 * allocation by the loop thread.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "exitcode.h"
#include "playutil.h"
#include "sim_camera.h"
#include "sim_drive.h"
#include "sim_gpio.h"
#include "testutil.h"

static struct pu_smooth m_a = { 10, 200, 90, 0 };     /* degrees */
static struct pu_smooth m_b = { 0, 150, 0.25, 0.1 };  /* metres */

/* The arm of most tests: a revolute and a prismatic channel, 0..240 at
 * 24 fps on a 1 kHz tick. */
static void arm_source(struct pu_source *ps, uint32_t num, uint32_t den, uint32_t hz,
		       int64_t first, int64_t last)
{
	pu_source_init(ps, "test-arm", num, den, hz, first, last);
	pu_source_add(ps, "a.angle", SRC_UNIT_TURNS, pu_smooth, &m_a, 60, 120);
	pu_source_add(ps, "b.position", SRC_UNIT_LENGTH, pu_smooth, &m_b, 0.5, 2);
}

/* Run and check the things every run must satisfy: no allocation in the
 * loop, commanded speed and acceleration within every output's limits (as
 * the drive saw them), the camera never missing a trigger. */
static int run(struct play *p, struct pu_rig *r, struct pu_source *ps, struct play_opts *o)
{
	char err[256] = "";
	uint64_t before = pu_loop_allocations();
	int rc, code;
	uint32_t i;

	pu_alloc_hook_install();
	rc = play_prepare(p, &r->d, &ps->s, o, err, sizeof(err));
	if (rc)
		fail_msg("play_prepare: %s", err);
	code = play_run(p);
	if (code) {
		play_describe(p, err, sizeof(err));
		printf("run ended %d: %s\n", code, err);
	}
	assert_int_equal(pu_loop_allocations() - before, 0);
	for (i = 0; i < p->rig.nout; i++) {
		const struct rig_out *ro = &p->rig.out[i];
		const struct sim_drive_watch *w =
			sim_drive_watch(p->rig.sim_drive[ro->dev], ro->ch);
		double pu = fabs(ro->scale.per_unit_d);

		/* counts are integers: allow a count per tick of rounding */
		if (w->cmd_vel_max > ro->vmax * pu * (1 + 1e-6) + 1.0 * ps->s.timing.tick_hz ||
		    w->cmd_acc_max > ro->amax * pu * (1 + 1e-6) +
					     2.0 * ps->s.timing.tick_hz * ps->s.timing.tick_hz)
			fail_msg("%s: commanded %g counts/s, %g counts/s^2; limits %g, %g",
				 ro->channel, w->cmd_vel_max, w->cmd_acc_max, ro->vmax * pu,
				 ro->amax * pu);
	}
	for (i = 0; i < p->rig.ntrig; i++)
		assert_int_equal(sim_camera_missed(p->rig.camera[i]), 0);
	return code;
}

/* Every frame from..to fired once, at FORMULAS section 5's tick after the
 * pre-roll (the first frame fired at tick0; -1: take it from the camera).
 * Returns tick0. */
static int64_t check_frames(const struct play *p, const struct sim_camera *cam, int64_t from,
			    int64_t to, int64_t tick0)
{
	const struct mot_timing *t = p->L.tm;
	int64_t f, t_from = mot_timing_trigger_tick(t, from);

	assert_int_equal(sim_camera_count(cam), to - from + 1);
	if (tick0 < 0)
		tick0 = sim_camera_exposure(cam, 0)->tick;
	for (f = from; f <= to; f++) {
		const struct sim_exposure *e = sim_camera_exposure(cam, (uint64_t)(f - from));
		int64_t want = tick0 + mot_timing_trigger_tick(t, f) - t_from;

		if (e->tick != want)
			fail_msg("frame %lld: exposed at tick %lld, want %lld", (long long)f,
				 (long long)e->tick, (long long)want);
		/* virtual time: the edge's time is its tick's, exactly */
		assert_int_equal(e->ts_ns, loop_due(&p->L, e->tick));
	}
	return tick0;
}

static void test_whole_run(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;

	arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 1, PU_ESTOP);
	pu_opts(&o, &ps);
	assert_int_equal(run(&p, &r, &ps, &o), STRAND_EXIT_OK);
	assert_int_equal(p.L.rep.cause, LOOP_CAUSE_FINISHED);
	/* the rig stood at the first pose, where b is just starting to move:
	 * a one-tick move to the start of b's one-tick run-up, a tick at rest
	 * there, then frame 0 */
	assert_int_equal(check_frames(&p, p.rig.camera[0], 0, 240, -1), 2);
	assert_int_equal(p.L.frames_fired, 241);
	/* the drive followed: worst following error seen, and within bound */
	assert_true(p.L.ferr_worst > 0);
	play_free(&p);
}

/* A rig standing elsewhere: the pre-roll brings it to the first pose within
 * the limits, then the frames follow at their exact ticks. */
static void test_preroll(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	int64_t t0;

	arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 1, 0);
	r.out[0].home = -45; /* degrees away from the first pose */
	r.out[1].home = 0.3;
	pu_opts(&o, &ps);
	assert_int_equal(run(&p, &r, &ps, &o), STRAND_EXIT_OK);
	t0 = sim_camera_exposure(p.rig.camera[0], 0)->tick;
	printf("pre-roll %lld ticks\n", (long long)t0);
	assert_true(t0 > 0);
	/* 45 deg at 60 deg/s and 120 deg/s^2 takes at least 1.25 s from the
	 * last tick at rest (tick -1, where the rig stood) */
	assert_true(t0 + 1 >= 1250);
	check_frames(&p, p.rig.camera[0], 0, 240, t0);
	play_free(&p);
}

/* Trigger ticks exactly per section 5 at rates that do and do not divide
 * the tick rate, over a span that starts after frame 0. */
static void test_rates(void **state)
{
	static const uint32_t rates[][3] = {
		{ 24, 1, 1000 }, { 25, 1, 1000 }, { 30000, 1001, 1000 }, { 60, 1, 1000 },
		{ 24000, 1001, 997 }, { 30, 1, 250 }, { 60000, 1001, 240 },
	};
	size_t i;

	for (i = 0; i < sizeof(rates) / sizeof(rates[0]); i++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;

		arm_source(&ps, rates[i][0], rates[i][1], rates[i][2], 17, 230);
		pu_rig_init(&r, &ps, 1, 0);
		r.trig[0].pulse_ms = 1000.0 / rates[i][2]; /* one tick */
		pu_opts(&o, &ps);
		assert_int_equal(run(&p, &r, &ps, &o), STRAND_EXIT_OK);
		/* frame 17 is in the middle of a's move: a run-up first */
		assert_true(check_frames(&p, p.rig.camera[0], 17, 230, -1) > 2);
		play_free(&p);
	}
}

/* A day at 1 kHz and 30000/1001 fps: frames 0..2589410 begin within 24 h;
 * the last fires at tick ceil(2589410 * 1001 * 1000 / 30000) = 86399981.
 * Every trigger tick is checked. Triggers only, so the run measures the
 * loop itself. */
static void test_24h(void **state)
{
	const int64_t last = 2589410;
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	char err[256];
	uint64_t n;
	int64_t f;

	pu_source_init(&ps, "day", 30000, 1001, 1000, 0, last);
	pu_rig_init(&r, &ps, 1, 0);
	pu_opts(&o, &ps);
	o.rig.camera_cap = (uint64_t)last + 1;
	pu_alloc_hook_install();
	assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), 0);
	assert_int_equal(play_run(&p), STRAND_EXIT_OK);
	n = sim_camera_count(p.rig.camera[0]);
	assert_int_equal(n, (uint64_t)last + 1);
	assert_int_equal(sim_camera_exposure(p.rig.camera[0], n - 1)->tick, 86399981);
	for (f = 0; f <= last; f++)
		if (sim_camera_exposure(p.rig.camera[0], (uint64_t)f)->tick !=
		    mot_timing_trigger_tick(p.L.tm, f))
			fail_msg("frame %lld at the wrong tick", (long long)f);
	printf("24 h: %lld ticks in %.2f s wall, %.1f ns cpu per tick\n",
	       (long long)p.L.ticks_run, p.wall_ns / 1e9, (double)p.L.cpu_ns / p.L.ticks_run);
	play_free(&p);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_whole_run),
		cmocka_unit_test(test_preroll),
		cmocka_unit_test(test_rates),
		cmocka_unit_test(test_24h),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
