/* SPDX-License-Identifier: MIT */
/*
 * test_num.c - the checked conversions of numbers from outside (scene/num.h)
 * and the saturating one, with its users' contract: every input, NaN and
 * the infinities included, gives a defined result (the tests run with
 * -fsanitize=float-cast-overflow), in range or refused; and
 * hal_scale_rate() reports its saturation as hal_scale_counts() does.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>

#include "rig/scale.h"
#include "scene/num.h"
#include "testutil.h"

static void test_to_i64(void **state)
{
	static const double bad[] = { NAN, INFINITY, -INFINITY, 1e300, -1e300,
				      9223372036854775808.0, -9223372036854777856.0 };
	int64_t v = 42;
	size_t i;

	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		assert_int_equal(num_to_i64(bad[i], NUM_ROUND_NEAREST, INT64_MIN, INT64_MAX, &v),
				 -ERANGE);
		assert_int_equal(v, 42); /* untouched */
	}
	/* the ends of int64_t that a double holds */
	assert_int_equal(num_to_i64(-9223372036854775808.0, NUM_ROUND_NEAREST, INT64_MIN,
				    INT64_MAX, &v), 0);
	assert_true(v == INT64_MIN);
	assert_int_equal(num_to_i64(9223372036854774784.0, NUM_ROUND_NEAREST, INT64_MIN,
				    INT64_MAX, &v), 0);
	assert_true(v == INT64_C(9223372036854774784));
	/* rounding as llround, ceil and floor */
	assert_int_equal(num_to_i64(2.5, NUM_ROUND_NEAREST, 0, 10, &v), 0);
	assert_int_equal(v, 3);
	assert_int_equal(num_to_i64(-2.5, NUM_ROUND_NEAREST, -10, 10, &v), 0);
	assert_int_equal(v, -3);
	assert_int_equal(num_to_i64(2.1, NUM_ROUND_UP, 0, 10, &v), 0);
	assert_int_equal(v, 3);
	assert_int_equal(num_to_i64(2.9, NUM_ROUND_DOWN, 0, 10, &v), 0);
	assert_int_equal(v, 2);
	/* the range is of the result */
	assert_int_equal(num_to_i64(10.4, NUM_ROUND_NEAREST, 0, 10, &v), 0);
	assert_int_equal(num_to_i64(10.5, NUM_ROUND_NEAREST, 0, 10, &v), -ERANGE);
	assert_int_equal(num_to_i64(-0.4, NUM_ROUND_NEAREST, 0, 10, &v), 0);
	assert_int_equal(v, 0);
}

static void test_ticks(void **state)
{
	int64_t v = 0;

	/* what cmd_play did with llround, the same */
	assert_int_equal(num_ms_to_ticks(200, 1000, NUM_ROUND_NEAREST, 0, NUM_TICKS_MAX, &v), 0);
	assert_int_equal(v, 200);
	assert_int_equal(num_ms_to_ticks(0.7, 1000, NUM_ROUND_NEAREST, 0, NUM_TICKS_MAX, &v), 0);
	assert_int_equal(v, 1);
	assert_int_equal(num_s_to_ticks(10, 1048576, NUM_ROUND_NEAREST, 1, NUM_TICKS_MAX, &v), 0);
	assert_int_equal(v, 10485760);
	/* the issue's: --duration 1e16, --timeout 1e17 came out negative */
	assert_int_equal(num_s_to_ticks(1e16, 1000, NUM_ROUND_NEAREST, 1, NUM_TICKS_MAX, &v),
			 -ERANGE);
	assert_int_equal(num_s_to_ticks(1e17, 1048576, NUM_ROUND_NEAREST, 1, NUM_TICKS_MAX, &v),
			 -ERANGE);
	/* shorter than a tick, where one is needed */
	assert_int_equal(num_s_to_ticks(1e-4, 1000, NUM_ROUND_NEAREST, 1, NUM_TICKS_MAX, &v),
			 -ERANGE);
	/* exposure_ms: 1e300 */
	assert_int_equal(num_ms_to_ns(1e300, NUM_ROUND_DOWN, 0, INT64_C(1) << 60, &v), -ERANGE);
	assert_int_equal(num_ms_to_ns(16, NUM_ROUND_DOWN, 0, INT64_C(1) << 60, &v), 0);
	assert_int_equal(v, 16000000);
}

static void test_sat(void **state)
{
	uint32_t sat = 0;

	assert_true(num_sat_i64(1e300, INT64_MIN, INT64_MAX, &sat) == INT64_MAX);
	assert_int_equal(sat, MOT_SAT_OVERFLOW);
	sat = 0;
	assert_true(num_sat_i64(-INFINITY, INT64_MIN, INT64_MAX, &sat) == INT64_MIN);
	assert_int_equal(sat, MOT_SAT_OVERFLOW);
	sat = 0;
	assert_int_equal(num_sat_i64(NAN, INT64_MIN, INT64_MAX, &sat), 0);
	assert_int_equal(sat, MOT_SAT_OVERFLOW);
	sat = 0;
	assert_int_equal(num_sat_i64(7.5, 0, 5, &sat), 5);
	assert_int_equal(sat, MOT_SAT_OVERFLOW);
	sat = 0;
	assert_int_equal(num_sat_i64(-2.5, -10, 10, &sat), -3);
	assert_int_equal(sat, 0);
	assert_int_equal(num_sat_i64(1e300, 0, 5, NULL), 5); /* sat may be NULL */
}

/* hal_scale_rate: NaN and huge speeds saturate and say so, as counts do */
static void test_scale_rate(void **state)
{
	struct hal_scale s = { .per_unit = INT64_C(1000) << 32, .per_unit_d = 1000 };
	uint32_t sat = 0;

	assert_int_equal(hal_scale_rate(&s, 1.5, &sat), 1500);
	assert_int_equal(hal_scale_rate(&s, -0.0025, &sat), -3);
	assert_int_equal(sat, 0);
	assert_true(hal_scale_rate(&s, 1e300, &sat) == INT64_MAX);
	assert_int_equal(sat, MOT_SAT_OVERFLOW);
	sat = 0;
	assert_true(hal_scale_rate(&s, -1e17, &sat) == INT64_MIN);
	assert_int_equal(sat, MOT_SAT_OVERFLOW);
	sat = 0;
	assert_int_equal(hal_scale_rate(&s, NAN, &sat), 0);
	assert_int_equal(sat, MOT_SAT_OVERFLOW);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_to_i64),
		cmocka_unit_test(test_ticks),
		cmocka_unit_test(test_sat),
		cmocka_unit_test(test_scale_rate),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
