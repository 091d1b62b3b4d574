/* SPDX-License-Identifier: MIT */
/*
 * test_chase.c - strand play --chase on the virtual clock (play/chase.h,
 * play/loop_chase.c): LTC made by libltc's encoder behind the simulated
 * capture device (sim/sim_ltc.h) and a frame pulse on a simulated input,
 * each fired frame's due time held against the instant the source began
 * that frame (the simulation's log):
 *
 *   - the card's clock 0, +-100, +-1000 ppm off, the source's 1000 ppm
 *     fast, stamps up to 1 ms late: lock within 5 frames of the first mark,
 *     every trigger within 1 ms of its source frame's start, the source's
 *     rate within 10 ppm after 10 s;
 *   - a dropout shorter than --freewheel: no stop, the triggers still
 *     within 1 ms; a longer one: a controlled stop after the freewheel
 *     time, a new cue when the source is back, the run finished;
 *   - a jump, reverse play, a held frame: a controlled stop and a new cue;
 *   - a signal 40 dB down; drop-frame labels across minute boundaries at
 *     30000/1001 (the journal's source_tc the label the source sent);
 *   - genlock: pulses with 1 ms of jitter and some missing.
 *
 * Every run is also held to what pu_finish checks of every run: no
 * allocation in the loop, every command the drives saw within its
 * output's speed and acceleration limits (so no axis jumped), no trigger
 * the camera missed.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chaseutil.h"
#include "playutil.h"
#include "testutil.h"
#include "play/chase.h"
#include "scene/timecode.h"
#include "sim/sim_gpio.h"
#include "sim/sim_ltc.h"

static void test_clock_errors(void **state)
{
	static const double cap[] = { 0, 100, -100, 1000, -1000, 0 };
	static const double src[] = { 0, 0, 0, 0, 0, 1000 };
	char name[64];
	unsigned i;

	(void)state;
	for (i = 0; i < sizeof(cap) / sizeof(cap[0]); i++) {
		struct sim_ltc_cfg c = chase_ltc25(cap[i], src[i]);
		struct tu_worst lock = { 0 }, rate = { 0 };
		struct chase_outcome oc = { 0 };

		chase_run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
		assert_int_equal(oc.code, 0);
		assert_true(oc.matched > 150 && oc.matched == oc.fired && !oc.unplayed);
		assert_int_equal(oc.last_frame, 240);
		snprintf(name, sizeof(name), "chase_trigger_card%+.0f_src%+.0fppm", cap[i], src[i]);
		tu_bound(name, &oc.phase, 1000, "us");
		tu_worst_add(&lock, oc.lock_frames, 0);
		snprintf(name, sizeof(name), "chase_lock_card%+.0f_src%+.0fppm", cap[i], src[i]);
		tu_bound(name, &lock, 5, "frames");
		tu_worst_add(&rate, (oc.st.rate - (1 + src[i] * 1e-6)) * 1e6, 0);
		snprintf(name, sizeof(name), "chase_rate_card%+.0f_src%+.0fppm", cap[i], src[i]);
		tu_bound(name, &rate, 10, "ppm");
		/* the motion stretched by the source's rate and the schedule's
		 * slew at most */
		tu_bound("chase_frame_interval_vs_source", &oc.stretch,
			 src[i] * 1e-6 + CHASE_SLEW + 1e-3, "relative");
	}
}

static void test_dropouts(void **state)
{
	struct sim_ltc_event ev[1] = { { .at_s = 3.0, .ev = SIM_LTC_SILENCE, .until_s = 3.3 } };
	struct sim_ltc_cfg c = chase_ltc25(100, 0);
	struct tu_worst fw = { 0 };
	struct chase_outcome oc = { 0 };

	(void)state;
	/* 300 ms of silence, freewheel 500: played through */
	c.events = ev;
	c.nevents = 1;
	chase_run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.recues, 0);
	assert_int_equal(oc.st.events[CHASE_EV_LOST], 0);
	tu_bound("chase_trigger_after_300ms_dropout", &oc.phase, 1000, "us");
	/* 1.5 s of silence, freewheel 500: a stop after 500 ms without a
	 * mark, a new cue once it is back, the scene played to its end */
	ev[0].until_s = 4.5;
	chase_run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.st.events[CHASE_EV_LOST], 1);
	assert_int_equal(oc.recues, 1);
	assert_int_equal(oc.last_frame, 240);
	tu_worst_add(&fw, (double)oc.st.freewheel_max_ns / 1e6 - 500, 0);
	/* the stop comes in the first tick past the freewheel time */
	tu_bound("chase_freewheel_stop_after_ms", &fw, 1.5, "ms beyond 500");
	tu_bound("chase_trigger_after_recue", &oc.phase, 1000, "us");
}

static void test_jump_reverse_hold(void **state)
{
	static const struct sim_ltc_event jump[] = {
		{ .at_s = 3.0, .ev = SIM_LTC_JUMP, .ss = 6, .ff = 0 } };
	static const struct sim_ltc_event rev[] = {
		{ .at_s = 3.0, .ev = SIM_LTC_REVERSE }, { .at_s = 3.5, .ev = SIM_LTC_FORWARD } };
	static const struct sim_ltc_event hold[] = {
		{ .at_s = 3.0, .ev = SIM_LTC_HOLD, .until_s = 3.6 } };
	struct sim_ltc_cfg c = chase_ltc25(0, 0);
	struct chase_outcome oc = { 0 };

	(void)state;
	c.events = jump;
	c.nevents = 1;
	chase_run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.st.events[CHASE_EV_JUMP], 1);
	assert_int_equal(oc.recues, 1);
	assert_true(oc.unplayed <= 2);
	tu_bound("chase_trigger_after_jump", &oc.phase, 1000, "us");
	c.events = rev;
	c.nevents = 2;
	chase_run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_true(oc.st.events[CHASE_EV_REVERSE] >= 1);
	assert_true(oc.recues >= 1);
	assert_true(oc.unplayed <= 2);
	tu_bound("chase_trigger_after_reverse", &oc.phase, 1000, "us");
	c.events = hold;
	c.nevents = 1;
	chase_run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_true(oc.st.events[CHASE_EV_STOPPED] >= 1);
	assert_true(oc.recues >= 1);
	assert_true(oc.unplayed <= 2);
	tu_bound("chase_trigger_after_hold", &oc.phase, 1000, "us");
}

static void test_quiet(void **state)
{
	struct sim_ltc_cfg c = chase_ltc25(-100, 0);
	struct chase_outcome oc = { 0 };

	(void)state;
	c.volume_db = -40;
	chase_run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_true(oc.st.level_dbfs < -39 && oc.st.level_dbfs > -42);
	tu_bound("chase_trigger_quiet_-40dBFS", &oc.phase, 1000, "us");
}

/* 30000/1001, drop-frame: from 00:00:58;00 over the minute boundary (no
 * labels ;00 and ;01 at 00:01:00) and the scene's frame 0 at 00:00:57;00. */
static void test_drop_frame(void **state)
{
	struct sim_ltc_cfg c = chase_ltc25(200, 0);
	struct chase_outcome oc = { 0 };

	(void)state;
	c.fps_num = 30000;
	c.fps_den = 1001;
	c.ss = 58;
	c.end_s = 8;
	chase_run(&oc, "ltc:sim", &c, NULL, 30000, 1001, 200, "00:00:57;00", 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.last_frame, 200);
	/* frame 200 is 00:01:03;22: past the boundary, two labels dropped */
	assert_true(oc.matched > 100 && oc.matched == oc.fired);
	tu_bound("chase_trigger_drop_frame_29.97", &oc.phase, 1000, "us");
}

/* Label -> frame -> label over the first 20 minutes at every rule. */
static void test_timecode_frames(void **state)
{
	static const uint32_t rates[][2] = { { 24, 1 }, { 25, 1 }, { 30000, 1001 },
					     { 60000, 1001 }, { 30, 1 } };
	unsigned r;

	(void)state;
	for (r = 0; r < 5; r++) {
		struct timecode tc;
		int64_t f, g;
		char s[24];

		timecode_init(&tc, rates[r][0], rates[r][1]);
		for (f = 0; f < 20 * 60 * 60; f++) {
			timecode_format(&tc, f, s, sizeof(s));
			assert_int_equal(timecode_parse(&tc, s, &g), 0);
			assert_int_equal(g, f);
		}
		if (tc.drop) {
			assert_int_equal(timecode_parse(&tc, "00:01:00;00", &g), -EINVAL);
			assert_int_equal(timecode_parse(&tc, "00:10:00;00", &g), 0);
		}
		assert_int_equal(timecode_day(&tc), (int64_t)tc.nominal * 86400 -
						     (int64_t)tc.drop * 1296);
	}
}

/* A frame pulse (a camera's sync out) on a simulated input: 25 pulses a
 * second from 0.2 s, +-0.5 ms of jitter, pulses 100-102 missing (freewheel),
 * then none from pulse 200 on (a stop after the freewheel time). */
static void test_genlock(void **state)
{
	static int64_t truth[400];
	struct sim_gpio *g;
	struct hal_clock clk;
	struct tu_rng rng;
	struct chase_outcome oc = { 0 };
	char err[128];
	int i;

	(void)state;
	hal_clock_init(&clk, true);
	tu_seed(&rng, 3);
	assert_int_equal(sim_gpio_new(&g, "sync", 0, 1, &clk, 1024, err, sizeof(err)), 0);
	for (i = 0; i < 400; i++) {
		/* the true pulse, and its edge as the generator's jitter puts it */
		truth[i] = 200000000 + (int64_t)i * 40000000;
		if ((i >= 100 && i <= 102) || i >= 300)
			continue;
		int64_t at = truth[i] + (int64_t)tu_uniform(&rng, -5e5, 5e5);

		assert_int_equal(sim_gpio_schedule(g, 0, at, true), 0);
		assert_int_equal(sim_gpio_schedule(g, 0, at + 2000000, false), 0);
	}
	/* truth is by pulse count from the first: offset chosen at the cue */
	chase_run(&oc, "gpio:sim", NULL, sim_gpio_din(g), 25, 1, 240, NULL, 500, truth, 400);
	sim_gpio_free(g);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.last_frame, 240);
	tu_bound("genlock_trigger_vs_pulse", &oc.phase, 1000, "us");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_timecode_frames),
		cmocka_unit_test(test_clock_errors),
		cmocka_unit_test(test_dropouts),
		cmocka_unit_test(test_jump_reverse_hold),
		cmocka_unit_test(test_quiet),
		cmocka_unit_test(test_drop_frame),
		cmocka_unit_test(test_genlock),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
