/* SPDX-License-Identifier: MIT */
/*
 * test_timeline.c - a range of the scene as the rig plays it (plan/timeline.c):
 * the last tick at or before a frame, the scene's values inside the range,
 * and beyond it each position going on at its last tick's speed (exactly,
 * in integers) while a speed holds; no velocity step at a range's end that
 * falls between two ticks.
 */
#include <stdlib.h>

#include "plan/timeline.h"
#include "playutil.h"
#include "testutil.h"

/* floor(f * tick_hz * den / num) against a double reference, for rates
 * whose frames fall on ticks and whose frames do not. */
static void test_tick_floor(void **state)
{
	static const uint32_t rates[][3] = {
		{ 24, 1, 1000 }, { 25, 1, 1000 }, { 30000, 1001, 1000 }, { 60000, 1001, 10000 },
		{ 24, 1, 100 },	 { 30, 1, 90 },	  { 24000, 1001, 977 },
	};
	size_t r;
	int64_t f;

	for (r = 0; r < sizeof(rates) / sizeof(rates[0]); r++) {
		struct mot_timing t;

		assert_int_equal(mot_timing_init(&t, rates[r][0], rates[r][1], rates[r][2]), 0);
		for (f = 0; f < 5000; f += 7) {
			/* ticks per frame times f, as an exact fraction */
			long double ticks = (long double)f * rates[r][2] * rates[r][1] / rates[r][0];
			int64_t want = (int64_t)floorl(ticks + 1e-12L);

			if (timeline_tick_floor(&t, f) != want)
				fail_msg("%u/%u fps at %u Hz, frame %lld: %lld, want %lld",
					 rates[r][0], rates[r][1], rates[r][2], (long long)f,
					 (long long)timeline_tick_floor(&t, f), (long long)want);
			assert_true(timeline_tick_floor(&t, f) <= mot_timing_trigger_tick(&t, f));
			assert_true(timeline_tick_floor(&t, f) >= mot_timing_trigger_tick(&t, f) - 1);
		}
	}
}

/* A channel that arrives at its last key moving: 3 deg per frame squared,
 * the frame's square, so that its speed at frame 10 is 60 deg per frame. */
static double square(const void *ctx, double frame)
{
	(void)ctx;
	return 3 * (frame < 10 ? frame * frame : 100);
}

static double rpm(const void *ctx, double frame)
{
	(void)ctx;
	return 100 + frame;
}

static void test_extension(void **state)
{
	struct pu_source ps;
	struct timeline tl;
	static const bool extend[] = { true, false };
	mot_q32 mem[TIMELINE_WORDS(2)], v[2], prev[2] = { 0, 0 };
	uint32_t sel[] = { 0, 1 }, sat = 0;
	int64_t k;

	/* 30000/1001 fps at 1 kHz: frame 10 at tick 333.67, between two */
	pu_source_init(&ps, "ext", 30000, 1001, 1000, 0, 10);
	pu_source_add(&ps, "a.angle", SRC_UNIT_TURNS, square, NULL, 0, 0);
	pu_source_add(&ps, "p.rpm", SRC_UNIT_RPM, rpm, NULL, 0, 0);
	assert_int_equal(src_select(&ps.s, sel, 2), 0);
	timeline_init(&tl, &ps.s, 2, extend, 2, 10, mem, &sat);
	assert_int_equal(tl.k0, mot_timing_trigger_tick(&ps.s.timing, 2));
	assert_int_equal(tl.k1, 333);
	assert_int_equal(mot_timing_trigger_tick(&ps.s.timing, 10), 334);
	for (k = tl.k0 - 5; k <= tl.k1 + 30; k++) {
		mot_q32 f = mot_timing_tick_frame(&ps.s.timing, k);

		timeline_eval(&tl, k, v, &sat);
		if (k >= tl.k0 && k <= tl.k1) {
			assert_true(v[0] == pu_value(&ps, 0, f));
			assert_true(v[1] == pu_value(&ps, 1, f));
		} else if (k > tl.k1) {
			/* on at the last tick's speed, exactly; the rpm holds */
			mot_q32 x1 = pu_value(&ps, 0, mot_timing_tick_frame(&ps.s.timing, tl.k1));
			mot_q32 x0 = pu_value(&ps, 0, mot_timing_tick_frame(&ps.s.timing, tl.k1 - 1));

			assert_true(v[0] == x1 + (k - tl.k1) * (x1 - x0));
			assert_true(v[1] == pu_value(&ps, 1, mot_timing_tick_frame(&ps.s.timing,
										  tl.k1)));
			/* the step from one tick to the next never drops */
			if (k > tl.k1 + 1)
				assert_true(v[0] - prev[0] == x1 - x0);
		} else {
			mot_q32 x0 = pu_value(&ps, 0, mot_timing_tick_frame(&ps.s.timing, tl.k0));
			mot_q32 x1 = pu_value(&ps, 0, mot_timing_tick_frame(&ps.s.timing, tl.k0 + 1));

			assert_true(v[0] == x0 - (tl.k0 - k) * (x1 - x0));
		}
		prev[0] = v[0];
		prev[1] = v[1];
	}
	assert_int_equal(sat, 0);
	/* beyond the core's range: saturated and said */
	timeline_eval(&tl, INT64_MAX / 2, v, &sat);
	assert_true(v[0] == MOT_Q32_MAX);
	assert_int_not_equal(sat & MOT_SAT_OVERFLOW, 0);
}

/* One frame between two ticks: the range is its trigger's tick, held. */
static void test_short_range(void **state)
{
	struct pu_source ps;
	struct timeline tl;
	static const bool extend[] = { true };
	mot_q32 mem[TIMELINE_WORDS(1)], v, at;
	uint32_t sel = 0, sat = 0;

	pu_source_init(&ps, "short", 24, 1, 1000, 0, 10);
	pu_source_add(&ps, "a.angle", SRC_UNIT_TURNS, square, NULL, 0, 0);
	assert_int_equal(src_select(&ps.s, &sel, 1), 0);
	timeline_init(&tl, &ps.s, 1, extend, 5, 5, mem, &sat);
	assert_int_equal(tl.k0, 209);
	assert_int_equal(tl.k1, 209);
	at = pu_value(&ps, 0, mot_timing_tick_frame(&ps.s.timing, 209));
	timeline_eval(&tl, 100, &v, &sat);
	assert_true(v == at);
	timeline_eval(&tl, 300, &v, &sat);
	assert_true(v == at);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_tick_floor),
		cmocka_unit_test(test_extension),
		cmocka_unit_test(test_short_range),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
