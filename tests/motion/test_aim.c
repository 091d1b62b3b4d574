/* SPDX-License-Identifier: MIT */
/*
 * test_aim.c - pan/tilt heads following a target (motion/aim.h): a target
 * circling a head three times is followed with a continuous pan, against
 * atan2 unwrapped in double precision, at random frames as in order; a
 * target above the head; a target too fast for the grid is refused.
 */
#include <stdlib.h>

#include "motion/aim.h"
#include "testutil.h"

/* A target circling the head at (1, 2, 3) at `turns` turns over 100
 * frames, 0.5 below it. */
static void target(double f, double turns, mot_q32 p[3])
{
	double ang = 2 * M_PI * turns * f / 100;

	p[0] = d2q(1 + 2 * sin(ang));
	p[1] = d2q(1.5);
	p[2] = d2q(3 + 2 * cos(ang));
}

static int prepare(struct mot_aim *a, double turns)
{
	struct mot_aim_march m = { 0, 0, false };
	uint32_t k, sat = 0;
	int err = 0;

	a->at[0] = MOT_Q32_INT(1);
	a->at[1] = MOT_Q32_INT(2);
	a->at[2] = MOT_Q32_INT(3);
	a->f0 = 0;
	a->sub = 4;
	a->nref = mot_aim_ref_count(0, MOT_Q32_INT(100), a->sub);
	a->pan_ref = calloc(a->nref, sizeof(*a->pan_ref));
	for (k = 0; !err && k < (a->nref - 1) * 4 + 1; k++) {
		mot_q32 p[3];

		target(q2d(mot_aim_fine_frame(a, k, &sat)), turns, p);
		err = mot_aim_march(a, &m, k, p, &sat);
	}
	return err;
}

static void test_circle(void **state)
{
	struct tu_worst wp = { 0, 0 }, wt = { 0, 0 };
	struct mot_aim a;
	struct tu_rng r;
	int i;

	assert_int_equal(prepare(&a, 3), MOT_OK);
	tu_seed(&r, 4);
	for (i = 0; i < 20000; i++) {
		/* in order, then at random */
		double f = i < 10000 ? i * 0.01 : tu_uniform(&r, -5, 105);
		mot_q32 p[3], pan, tilt;
		double ff, dx, dz, ref;
		uint32_t sat = 0;

		target(f, 3, p);
		mot_aim_eval(&a, p, d2q(f), &pan, &tilt, &sat);
		assert_int_equal(sat, 0);
		dx = q2d(p[0]) - 1;
		dz = q2d(p[2]) - 3;
		/* the pan of FORMULAS section 10, unwrapped: it starts at its
		 * principal value and turns with the target */
		ff = f < 0 ? 0 : f > 100 ? 100 : f;
		ref = atan2(-dx, -dz) / (2 * M_PI);
		ref += round(3 * ff / 100 + 0.5 - ref); /* the turn the target is on */
		tu_worst_add(&wp, q2d(pan) - ref, f);
		tu_worst_add(&wt, q2d(tilt) - atan2(-0.5, sqrt(dx * dx + dz * dz)) / (2 * M_PI), f);
	}
	tu_bound("aim_pan_turns", &wp, 1e-9, "turns");
	tu_bound("aim_tilt_turns", &wt, 1e-9, "turns");
	free(a.pan_ref);
}

/* 500 turns in 100 frames is 5/16 turn a fine step: refused. */
static void test_too_fast(void **state)
{
	struct mot_aim a;

	assert_int_equal(prepare(&a, 500), MOT_E_RANGE);
	free(a.pan_ref);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_circle),
		cmocka_unit_test(test_too_fast),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
