/* SPDX-License-Identifier: MIT */
/*
 * test_gomo.c - go-motion's exposure in ticks (plan/gomo.c): the first tick
 * at or after f - s/2 and the last at or before f + s/2, exact against a
 * 128-bit rational reference and within a tick of a long double one, for
 * rates whose frames fall on ticks and rates whose frames do not; the
 * shutter's lower bound (two ticks) and its angles.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "plan/gomo.h"
#include "testutil.h"

/* ceil or floor of n / d, d > 0, in 128 bits. */
static int64_t div128(__int128 n, __int128 d, int up)
{
	__int128 q = n / d, r = n % d;

	if (r != 0 && (r > 0) == up)
		q += up ? 1 : -1;
	return (int64_t)q;
}

static const uint32_t rates[][3] = {
	{ 24, 1, 1000 }, { 25, 1, 1000 }, { 30000, 1001, 1000 }, { 60000, 1001, 10000 },
	{ 24, 1, 100 },	 { 30, 1, 90 },	  { 24000, 1001, 977 }, { 24, 1, 48 },
};

static void test_window(void **state)
{
	static const double angles[] = { 360, 270, 180, 172.8, 90, 45, 11.25 };
	size_t r, a;
	int64_t f;
	unsigned checked = 0;

	for (r = 0; r < sizeof(rates) / sizeof(rates[0]); r++) {
		struct mot_timing t;

		assert_int_equal(mot_timing_init(&t, rates[r][0], rates[r][1], rates[r][2]), 0);
		for (a = 0; a < sizeof(angles) / sizeof(angles[0]); a++) {
			mot_q32 s;
			long double ticks_per_frame = (long double)t.ticks_den / t.num;

			assert_true(gomo_shutter_of_angle(angles[a], &s));
			if (gomo_shutter_check(&t, s))
				continue; /* shorter than two ticks at this rate */
			for (f = 0; f < 30000; f += 13) {
				__int128 d = (__int128)t.num << 32;
				mot_q32 half = s / 2;
				__int128 lo = ((__int128)f * MOT_Q32_ONE - half) * t.ticks_den;
				__int128 hi = ((__int128)f * MOT_Q32_ONE + (s - half)) * t.ticks_den;
				long double c = f * ticks_per_frame;
				long double w = (long double)s / 4294967296.0L * ticks_per_frame / 2;
				int64_t k0, k1;

				assert_int_equal(gomo_window(&t, f, s, &k0, &k1), 0);
				assert_int_equal(k0, div128(lo, d, 1));
				assert_int_equal(k1, div128(hi, d, 0));
				/* where the instants are, roughly: never early, never
				 * past the end, at least two ticks */
				assert_true(k0 >= c - w - 1e-6L && k0 < c - w + 1 + 1e-6L);
				assert_true(k1 <= c + w + 1e-6L && k1 > c + w - 1 - 1e-6L);
				assert_true(k1 > k0);
				checked++;
			}
		}
	}
	printf("BOUND go-motion windows: %u exact against 128-bit rationals\n", checked);
}

/* Two tick periods or more: every window holds two ticks; less, refused. */
static void test_shutter_bounds(void **state)
{
	struct mot_timing t;
	mot_q32 s, two;
	int64_t k0, k1, f;

	assert_int_equal(mot_timing_init(&t, 24, 1, 100), 0);
	/* two ticks at 100 Hz and 24 fps: 0.48 of a frame */
	two = (mot_q32)(0.48 * 4294967296.0) + 1;
	assert_int_equal(gomo_shutter_check(&t, two), 0);
	assert_int_equal(gomo_shutter_check(&t, two - 4), -EINVAL);
	for (f = 0; f < 2400; f++) {
		assert_int_equal(gomo_window(&t, f, two, &k0, &k1), 0);
		assert_true(k1 - k0 >= 1);
	}
	assert_int_equal(gomo_shutter_check(&t, 0), -EINVAL);
	assert_int_equal(gomo_shutter_check(&t, GOMO_SHUTTER_MAX + 1), -EINVAL);
	assert_int_equal(gomo_window(&t, 5, GOMO_SHUTTER_MAX + 1, &k0, &k1), -EINVAL);
	/* angles */
	assert_true(gomo_shutter_of_angle(180, &s) && s == MOT_Q32_ONE / 2);
	assert_true(gomo_shutter_of_angle(360, &s) && s == MOT_Q32_ONE);
	assert_false(gomo_shutter_of_angle(0, &s));
	assert_false(gomo_shutter_of_angle(360.001, &s));
	assert_false(gomo_shutter_of_angle(-90, &s));
	assert_false(gomo_shutter_of_angle(NAN, &s));
	assert_false(gomo_shutter_of_angle(1e-12, &s));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_window),
		cmocka_unit_test(test_shutter_bounds),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
