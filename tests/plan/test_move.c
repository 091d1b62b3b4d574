/* SPDX-License-Identifier: MIT */
/*
 * test_move.c - moves and stops: random multi-channel moves arrive on the
 * target to the bit, all channels on the same tick, with every finite
 * difference of speed and acceleration within each channel's limits (what
 * the loop's runtime check measures); stops come to rest within the
 * acceleration limit, a velocity channel to zero.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>

#include "plan/move.h"
#include "testutil.h"

#define NCH 4

static void test_random_moves(void **state)
{
	struct tu_rng rng;
	struct tu_worst wv = { 0 }, wa = { 0 };
	int round;

	tu_seed(&rng, 4);
	for (round = 0; round < 2000; round++) {
		struct move m;
		struct move_ch ch[NCH];
		mot_q32 from[NCH], to[NCH];
		double vmax[NCH], amax[NCH], prev[NCH], v_prev[NCH] = { 0 };
		uint32_t hz = (uint32_t)(250 + tu_u64(&rng) % 4000), i;
		int64_t k;

		for (i = 0; i < NCH; i++) {
			from[i] = d2q(tu_uniform(&rng, -100, 100));
			/* some channels do not move, some move a hair */
			to[i] = i == 3 ? from[i] : i == 2 ? from[i] + (int64_t)(tu_u64(&rng) % 1000)
							  : d2q(tu_uniform(&rng, -100, 100));
			vmax[i] = tu_uniform(&rng, 0.01, 500);
			amax[i] = tu_uniform(&rng, 0.01, 5000);
			prev[i] = q2d(from[i]);
		}
		assert_int_equal(move_plan(&m, ch, NCH, from, to, vmax, amax, hz), 0);
		for (k = 1; k <= m.ticks + 1; k++)
			for (i = 0; i < NCH; i++) {
				double p = q2d(move_at(&m, i, k)), v = (p - prev[i]) * hz;
				double a = (v - v_prev[i]) * hz;

				/* samples are rounded to Q32.32: a difference
				 * carries up to 2 steps per tick, as the loop's own
				 * check allows */
				tu_worst_add(&wv, fmax(0, (fabs(v) - 2.0 * hz / TU_Q32) / vmax[i] - 1),
					     (double)round);
				/* 8 Q32.32 steps of rounding per second difference */
				tu_worst_add(&wa, fmax(0, (fabs(a) - 8.0 * hz * hz / TU_Q32) / amax[i] - 1),
					     (double)round);
				prev[i] = p;
				v_prev[i] = v;
			}
		for (i = 0; i < NCH; i++)
			assert_int_equal(move_at(&m, i, m.ticks), to[i]);
	}
	tu_bound("move speed beyond vmax (relative)", &wv, 1e-6, "");
	tu_bound("move acceleration beyond amax (relative)", &wa, 1e-6, "");
}

static void test_zero_move(void **state)
{
	struct move m;
	struct move_ch ch[1];
	mot_q32 p = d2q(3.5);
	double v = 1, a = 1, bad = 0;

	assert_int_equal(move_plan(&m, ch, 1, &p, &p, &v, &a, 1000), 0);
	assert_int_equal(m.ticks, 0);
	assert_int_equal(move_at(&m, 0, 0), p);
	assert_int_equal(move_plan(&m, ch, 1, &p, &p, &bad, &a, 1000), -EINVAL);
}

/* Inputs each valid alone, together beyond anything: a crawl over the
 * core's range. The plan is capped at NUM_TICKS_MAX and refused, and every
 * sample is defined (the tests run with -fsanitize=float-cast-overflow). */
static void test_edges(void **state)
{
	struct move m;
	struct move_ch ch[2];
	mot_q32 from[2] = { MOT_Q32_MIN / 2, 0 }, to[2] = { MOT_Q32_MAX / 2, d2q(1) };
	double v[2] = { 1e-300, 1 }, a[2] = { 1e-300, 1 }, vs;
	mot_q32 x;
	int64_t k;

	assert_int_equal(move_plan(&m, ch, 2, from, to, v, a, 1048576), -ERANGE);
	assert_true(m.ticks == NUM_TICKS_MAX);
	for (k = -1; k <= m.ticks + 1; k += m.ticks / 7) {
		(void)move_at(&m, 0, k);
		(void)move_at(&m, 1, k);
	}
	assert_int_equal(move_at(&m, 0, m.ticks), to[0]);
	/* a stop at the end of the range saturates rather than wraps */
	x = MOT_Q32_MAX - 5;
	vs = 1e12;
	(void)move_stop_step(&x, &vs, false, 1e12, 1, 1000);
	assert_true(x == MOT_Q32_MAX);
	x = MOT_Q32_MIN + 5;
	vs = -1e12;
	(void)move_stop_step(&x, &vs, true, 1e12, 1e12, 1000);
	assert_true(x < 0);
	assert_true(move_d2q(NAN) == 0);
	assert_true(move_d2q(1e300) == MOT_Q32_MAX);
	assert_true(move_d2q(-1e300) == MOT_Q32_MIN);
}

/* Stops from random speeds: at rest within ceil(|v| / (a dt)) + 1 ticks,
 * every speed change within a dt; a velocity channel's value reaches 0. */
static void test_stops(void **state)
{
	struct tu_rng rng;
	int round;

	tu_seed(&rng, 11);
	for (round = 0; round < 2000; round++) {
		uint32_t hz = 1000;
		double amax = tu_uniform(&rng, 1, 1000), vmax = tu_uniform(&rng, 1, 500);
		double v = tu_uniform(&rng, -vmax, vmax), v0 = v;
		bool vel = round % 2;
		mot_q32 x = d2q(tu_uniform(&rng, -50, 50)), prev = x, x0 = x;
		int64_t k, limit = (int64_t)ceil(fabs(v) * hz / amax) + 2;

		if (vel) {
			/* a spin speed: its value runs at rate v toward 0 */
			/* at most: cover it at vmax, plus ramps at amax */
			limit = (int64_t)((fabs(q2d(x)) / vmax + 2 * (vmax + fabs(v)) / amax) * hz) +
				10;
		}
		for (k = 0; k < limit * 4; k++) {
			double before = v;
			bool rest = move_stop_step(&x, &v, vel, vmax, amax, hz);

			assert_true(fabs(v - before) <= amax / hz * (1 + 1e-9) ||
				    (vel && x == 0 && v == 0));
			if (!vel)
				assert_true(fabs(q2d(x - prev) * hz - v) < 1e-6);
			prev = x;
			if (rest)
				break;
		}
		if (k >= limit * 4)
			fail_msg("round %d: not at rest after %lld ticks (x0 %.17g v0 %.17g a %.17g "
				 "vmax %.17g, %s)", round, (long long)k, q2d(x0), v0, amax, vmax,
				 vel ? "velocity" : "position");
		if (vel)
			assert_int_equal(x, 0);
		else
			assert_true(k <= limit);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_random_moves),
		cmocka_unit_test(test_zero_move),
		cmocka_unit_test(test_edges),
		cmocka_unit_test(test_stops),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
