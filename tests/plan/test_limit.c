/* SPDX-License-Identifier: MIT */
/*
 * test_limit.c - the one limit predicate (plan/limit.c): its stencil at each
 * tick rate, its velocity and acceleration against a double-precision
 * reference on random cubic motions, the limits at their edge (within the
 * slack: kept; beyond: broken), the stopping point, and a meter's ring.
 */
#include <stdlib.h>

#include "plan/limit.h"
#include "plan/move.h"
#include "testutil.h"

static void test_stencil(void **state)
{
	static const uint32_t hz[][2] = { { 100, 1 },  { 1000, 1 },  { 1001, 2 },
					  { 2000, 2 }, { 10000, 10 }, { 1048576, 1049 } };
	size_t i;

	for (i = 0; i < sizeof(hz) / sizeof(hz[0]); i++) {
		struct lim_stencil s;

		lim_stencil_init(&s, hz[i][0]);
		assert_int_equal(s.h, hz[i][1]);
		assert_true(s.rate == (double)hz[i][0] / hz[i][1]);
	}
}

/*
 * x(t) = c0 + c1 t + c2 t^2 + c3 t^3 sampled at ticks and rounded to Q32.32:
 * the predicate's velocity is the exact mean speed over its h ticks and its
 * acceleration the exact second difference of the real curve, within what
 * the rounding of three samples makes of them (one step each: 2 and 4 steps
 * per difference).
 */
static void test_measure(void **state)
{
	static const uint32_t rates[] = { 100, 1000, 2000, 10000 };
	struct tu_worst wv = { 0 }, wa = { 0 };
	struct tu_rng r;
	size_t i;
	int trial;

	tu_seed(&r, 12);
	for (i = 0; i < sizeof(rates) / sizeof(rates[0]); i++) {
		struct lim_stencil s;
		mot_q32 ring[LIM_METER_LEN(10)];

		lim_stencil_init(&s, rates[i]);
		for (trial = 0; trial < 50; trial++) {
			double c[4] = { tu_uniform(&r, -1000, 1000), tu_uniform(&r, -50, 50),
					tu_uniform(&r, -20, 20), tu_uniform(&r, -5, 5) };
			double dt = 1.0 / rates[i], step = 1.0 / TU_Q32;
			struct lim_meter m;
			int64_t k;

#define X(t) (c[0] + c[1] * (t) + c[2] * (t) * (t) + c[3] * (t) * (t) * (t))
			lim_meter_reset(&m, &s, ring, d2q(X(0.0)), false);
			for (k = 1; k < 400; k++) {
				double t = k * dt, th = s.h * dt;
				mot_q32 x = d2q(X(t));
				struct lim_measure me;

				lim_measure(&m, &s, x, &me);
				if (me.has_v)
					tu_worst_add(&wv, (me.v - (X(t) - X(t - th)) / th) /
							     (step / th), t);
				if (me.has_a)
					tu_worst_add(&wa, (me.a - (X(t) - 2 * X(t - th) +
								   X(t - 2 * th)) / (th * th)) /
							     (step / (th * th)), t);
				lim_meter_push(&m, x);
			}
#undef X
		}
	}
	/* in steps of Q32.32 per difference: the three samples' rounding
	 * (half a step each) and the double's at these magnitudes */
	tu_bound("limit_velocity_vs_exact_mean_speed", &wv, 1.01, "steps per difference");
	tu_bound("limit_acceleration_vs_exact_second_difference", &wa, 2.01,
		 "steps per difference");
}

static uint32_t hits(const struct lim_stencil *s, const struct lim_bounds *b,
		     const struct lim_measure *me, enum lim_kind *first)
{
	struct lim_hit h[LIM_NKINDS];
	uint32_t n = lim_test(s, b, me, h);

	if (n)
		*first = h[0].kind;
	return n;
}

/* At the limit and within the slack: kept; a step beyond the slack: broken. */
static void test_edges(void **state)
{
	struct lim_stencil s;
	struct lim_bounds b = { .min = -1, .max = 1, .vel = 2, .acc = 100 };
	struct lim_measure me = { .noise = 1.0 / TU_Q32, .has_v = true, .has_a = true };
	enum lim_kind k = LIM_NKINDS;

	lim_stencil_init(&s, 1000);
	me.x = 1;
	me.v = 0;
	me.a = 0;
	assert_int_equal(hits(&s, &b, &me, &k), 0);
	me.x = 1 + 2.0 / TU_Q32;
	assert_int_equal(hits(&s, &b, &me, &k), 2); /* max, and the stopping point */
	assert_int_equal(k, LIM_MAX);
	me.x = 0;
	me.v = 2 + 4 * me.noise * s.rate;
	assert_int_equal(hits(&s, &b, &me, &k), 0);
	me.v = 2 + 5 * me.noise * s.rate;
	assert_int_equal(hits(&s, &b, &me, &k), 1);
	assert_int_equal(k, LIM_VEL);
	me.v = 0;
	me.a = -(100 + 5 * me.noise * s.rate * s.rate);
	assert_int_equal(hits(&s, &b, &me, &k), 1);
	assert_int_equal(k, LIM_ACC);
	/* braking from 1.9/s by 0.1/s a tick (100/s^2 at 1 kHz) covers
	 * (1.8 + 1.7 + ... + 0.1) / 1000 = 0.0171 */
	assert_true(fabs(move_stop_distance(1.9, 100, 1000) - 0.0171) < 1e-15);
	assert_true(move_stop_distance(-0.05, 100, 1000) == 0);
	me.a = 0;
	me.v = me.v1 = 1.9;
	me.x = 1 - 0.0172;
	assert_int_equal(hits(&s, &b, &me, &k), 0);
	me.x = 1 - 0.0170;
	assert_int_equal(hits(&s, &b, &me, &k), 1);
	assert_int_equal(k, LIM_STOP);
	/* a speed channel has no stopping point */
	b.vel_ch = true;
	assert_int_equal(hits(&s, &b, &me, &k), 0);
	/* none given: nothing to break */
	b = (struct lim_bounds){ -INFINITY, INFINITY, INFINITY, INFINITY, false };
	me.x = 1e9;
	me.v = 1e9;
	me.a = 1e12;
	assert_int_equal(hits(&s, &b, &me, &k), 0);
}

/* The ring over many wraps: the samples h and 2h back, whatever its head. */
static void test_ring(void **state)
{
	struct lim_stencil s;
	struct lim_meter m;
	mot_q32 ring[LIM_METER_LEN(10)];
	int64_t k;

	lim_stencil_init(&s, 10000);
	lim_meter_reset(&m, &s, ring, 0, true);
	for (k = 1; k < 1000; k++) {
		struct lim_measure me;
		mot_q32 x = k * k * (mot_q32)65536;

		lim_measure(&m, &s, x, &me);
		assert_true(me.has_v && me.has_a);
		if (k >= 20) {
			/* (k^2 - (k-10)^2) and (k^2 - 2(k-10)^2 + (k-20)^2) in steps of 2^-16 */
			assert_true(me.v == (double)(20 * k - 100) / 65536 * s.rate);
			assert_true(me.a == 200.0 / 65536 * s.rate * s.rate);
		}
		lim_meter_push(&m, x);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_stencil),
		cmocka_unit_test(test_measure),
		cmocka_unit_test(test_edges),
		cmocka_unit_test(test_ring),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
