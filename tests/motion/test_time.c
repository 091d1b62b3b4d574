/* SPDX-License-Identifier: MIT */
/*
 * test_time.c - frame/tick conversion and the trigger rule of FORMULAS
 * section 5, against exact __int128 rational arithmetic.
 */
#include "motion/timing.h"
#include "testutil.h"

typedef __int128 i128;

static i128 floordiv128(i128 n, i128 d)
{
	i128 q = n / d;

	if (n % d && (n < 0) != (d < 0))
		q--;
	return q;
}

static int64_t ref_trigger(int64_t f, const struct mot_timing *t)
{
	/* ceil(f * hz * den / num) */
	return (int64_t)-floordiv128(-(i128)f * t->tick_hz * t->den, t->num);
}

static void test_init(void **state)
{
	struct mot_timing t;

	assert_int_equal(mot_timing_init(&t, 0, 1, 1000), MOT_E_INVAL);
	assert_int_equal(mot_timing_init(&t, 24, 0, 1000), MOT_E_INVAL);
	assert_int_equal(mot_timing_init(&t, 24, 1, 0), MOT_E_INVAL);
	assert_int_equal(mot_timing_init(&t, 1001, 1, 1000), MOT_E_INVAL); /* > tick rate */
	assert_int_equal(mot_timing_init(&t, 1000, 1, 1000), MOT_OK);
	assert_int_equal(mot_timing_init(&t, 60000, 2002, 1000), MOT_OK);
	assert_int_equal(t.num, 30000);
	assert_int_equal(t.den, 1001);
}

/* Every tick of the first 10^6 (and around hour 24) fires exactly the frames
 * the rule says, once each, in order. */
static void check_rate(uint32_t num, uint32_t den, uint32_t hz, int64_t from, int64_t n)
{
	struct mot_timing t;
	int64_t k, expect, f;

	assert_int_equal(mot_timing_init(&t, num, den, hz), MOT_OK);
	expect = mot_timing_next_frame(&t, from);
	assert_true(ref_trigger(expect, &t) >= from);
	assert_true(ref_trigger(expect - 1, &t) < from);
	for (k = from; k < from + n; k++) {
		if (mot_timing_fires(&t, k, &f)) {
			assert_int_equal(f, expect);
			assert_int_equal(ref_trigger(f, &t), k);
			expect++;
		} else {
			assert_true(ref_trigger(expect, &t) > k);
		}
	}
}

static void test_fires(void **state)
{
	const int64_t day = 86400LL * 1000;

	check_rate(24, 1, 1000, 0, 1000000);
	check_rate(30000, 1001, 1000, 0, 1000000);
	check_rate(30000, 1001, 1000, day - 500000, 1000000);
	check_rate(25, 1, 4000, -10000, 200000);
	check_rate(1, 10, 1000, 0, 200000); /* time lapse: one frame per 10 s */
	check_rate(1000, 1, 1000, 0, 10000);  /* one frame per tick */
	check_rate(30000, 1001, 997, 0, 500000);
}

/* 24 hours at 1 kHz and 30000/1001 fps: frame count and last trigger tick. */
static void test_day(void **state)
{
	struct mot_timing t;
	const int64_t ticks = 86400LL * 1000; /* ticks 0 .. ticks-1 */
	int64_t nframes, last;

	assert_int_equal(mot_timing_init(&t, 30000, 1001, 1000), MOT_OK);
	nframes = mot_timing_next_frame(&t, ticks); /* frames 0 .. n-1 fire inside */
	/* 86400 s * 30000/1001 = 2589410.589... frames: 0 .. 2589410 fire */
	assert_int_equal(nframes, 2589411);
	last = mot_timing_trigger_tick(&t, nframes - 1);
	assert_int_equal(last, ref_trigger(2589410, &t));
	assert_int_equal(last, 86399981); /* ceil(2589410 * 1001 / 30) */
	assert_true(last < ticks);
	assert_true(mot_timing_trigger_tick(&t, nframes) >= ticks);
}

/* tick -> frame time within half an LSB of the exact rational. */
static void test_tick_frame(void **state)
{
	static const uint32_t rates[][3] = {
		{ 24, 1, 1000 }, { 30000, 1001, 1000 }, { 25, 1, 4000 }, { 1, 10, 1000 },
		{ 60, 1, 1000000 }, { 30000, 1001, 997 },
	};
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	size_t i;
	int n;

	tu_seed(&rng, 5);
	for (i = 0; i < sizeof(rates) / sizeof(rates[0]); i++) {
		struct mot_timing t;

		assert_int_equal(mot_timing_init(&t, rates[i][0], rates[i][1], rates[i][2]), 0);
		for (n = 0; n < 100000; n++) {
			int64_t k = (int64_t)(tu_u64(&rng) % (1ull << 31)) - (1ll << 30);
			i128 num = (i128)k * t.num * 4294967296ll;
			i128 d = (i128)t.ticks_den;
			mot_q32 got = mot_timing_tick_frame(&t, k);
			/* error in LSB, times 2 to stay integral: |2(got*d - num)| <= d */
			i128 e2 = 2 * ((i128)got * d - num);

			tu_worst_add(&w, (double)e2 / (double)d / 2.0, (double)k);
			/* frame time is exact at every frame's start tick when it divides */
		}
	}
	tu_bound("time.tick_frame", &w, 0.5, "LSB");
	{
		struct mot_timing t;

		mot_timing_init(&t, 24, 1, 1000);
		assert_int_equal(mot_timing_tick_frame(&t, 1000), MOT_Q32_INT(24));
		assert_int_equal(mot_timing_tick_frame(&t, -125), -MOT_Q32_INT(3));
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_init),
		cmocka_unit_test(test_fires),
		cmocka_unit_test(test_day),
		cmocka_unit_test(test_tick_frame),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
