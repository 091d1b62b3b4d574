/* SPDX-License-Identifier: MIT */
/*
 * test_ease.c - the slow-in/slow-out profile of motion/ease.c against the
 * formula of FORMULAS.md section 7 (tests/ref_curve.c, long double): values,
 * ends, continuity and monotonicity at the joins, the plateau speed, the
 * identity, and the argument checks.
 */
#include "motion/curve_priv.h"
#include "motion/ease.h"
#include "ref_curve.h"
#include "testutil.h"

#define Q62 4611686018427387904.0L /* 2^62 */
#define N 200000

static ref_t q62_to_ref(int64_t x)
{
	return (ref_t)x / Q62;
}

/* A random valid profile: fractions in [0, 1] with a + b <= 1, sometimes 0,
 * sometimes at the extremes (a + b = 1, a tiny fraction). */
static void random_ab(struct tu_rng *r, mot_q32 *a, mot_q32 *b)
{
	unsigned mode = (unsigned)(tu_u64(r) % 8);

	*a = (mot_q32)(tu_u64(r) % (uint64_t)(MOT_Q32_ONE + 1));
	*b = (mot_q32)(tu_u64(r) % (uint64_t)(MOT_Q32_ONE - *a + 1));
	if (mode == 0)
		*a = 0;
	else if (mode == 1)
		*b = 0;
	else if (mode == 2)
		*b = MOT_Q32_ONE - *a; /* no plateau */
	else if (mode == 3)
		*a = 1 + (mot_q32)(tu_u64(r) % 1000); /* a few LSB */
	if (*b > MOT_Q32_ONE - *a)
		*b = MOT_Q32_ONE - *a;
}

/* Against the formula, in units of 2^-62, for s over [0, 1] and densely
 * around both joins. The prepared fractions are exact here (Q32.32 inputs),
 * so this is the error of the apply alone. */
static void test_ease_vs_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int i;

	tu_seed(&rng, 11);
	for (i = 0; i < N; i++) {
		struct mot_ease e;
		mot_q32 a, b;
		int64_t s, got;
		unsigned where = (unsigned)(tu_u64(&rng) % 4);

		random_ab(&rng, &a, &b);
		assert_int_equal(mot_ease_init(&e, a, b, NULL), MOT_OK);
		s = (int64_t)(tu_u64(&rng) % (uint64_t)(MOT_Q62_ONE + 1));
		if (where == 1)
			s = e.a + (int64_t)(tu_u64(&rng) % 2001) - 1000;
		else if (where == 2)
			s = MOT_Q62_ONE - e.b + (int64_t)(tu_u64(&rng) % 2001) - 1000;
		s = s < 0 ? 0 : s > MOT_Q62_ONE ? MOT_Q62_ONE : s;
		got = mot_ease_apply62(&e, s);
		tu_worst_add(
			&w,
			(double)((q62_to_ref(got) - ref_ease(ref_q(a), ref_q(b), q62_to_ref(s))) *
				 Q62),
			(double)i);
	}
	tu_bound("ease.apply62_vs_ref", &w, 3.0, "units of 2^-62");
}

/* The Q32.32 entry point: one rounding on top of the above. */
static void test_ease_q32(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int i;

	tu_seed(&rng, 12);
	for (i = 0; i < N; i++) {
		struct mot_ease e;
		mot_q32 a, b, s = (mot_q32)(tu_u64(&rng) % (uint64_t)(MOT_Q32_ONE + 1));

		random_ab(&rng, &a, &b);
		assert_int_equal(mot_ease_init(&e, a, b, NULL), MOT_OK);
		tu_worst_add(&w,
			     (double)((ref_q(mot_ease_apply(&e, s, NULL)) -
				       ref_ease(ref_q(a), ref_q(b), ref_q(s))) *
				      4294967296.0L),
			     (double)i);
	}
	tu_bound("ease.apply_q32_vs_ref", &w, 0.51, "LSB");
}

/* Fractions given as frames over a span (a strand's ease): against the
 * exact ratio, so this includes the rounding of a and b to Q2.62. */
static void test_ease_ratio(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int i;

	tu_seed(&rng, 13);
	for (i = 0; i < N; i++) {
		struct mot_ease e;
		int64_t den = 1 + (int64_t)(tu_u64(&rng) >> (1 + tu_u64(&rng) % 40));
		int64_t an = (int64_t)(tu_u64(&rng) % ((uint64_t)den + 1));
		int64_t bn = (int64_t)(tu_u64(&rng) % ((uint64_t)(den - an) + 1));
		int64_t s = (int64_t)(tu_u64(&rng) % (uint64_t)(MOT_Q62_ONE + 1));

		assert_int_equal(mot_ease_init_ratio(&e, an, bn, den, NULL), MOT_OK);
		tu_worst_add(&w,
			     (double)((q62_to_ref(mot_ease_apply62(&e, s)) -
				       ref_ease((ref_t)an / den, (ref_t)bn / den, q62_to_ref(s))) *
				      Q62),
			     (double)den);
	}
	tu_bound("ease.ratio_vs_ref", &w, 4.0, "units of 2^-62");
}

/* s'(0) = 0 and s'(1) = 1 exactly; a = b = 0 is the identity bit for bit. */
static void test_ease_ends_identity(void **state)
{
	struct tu_rng rng;
	struct mot_ease e;
	int i;

	tu_seed(&rng, 14);
	for (i = 0; i < N / 10; i++) {
		mot_q32 a, b;

		random_ab(&rng, &a, &b);
		assert_int_equal(mot_ease_init(&e, a, b, NULL), MOT_OK);
		assert_int_equal(mot_ease_apply62(&e, 0), 0);
		assert_int_equal(mot_ease_apply62(&e, MOT_Q62_ONE), MOT_Q62_ONE);
		assert_int_equal(mot_ease_apply(&e, 0, NULL), 0);
		assert_int_equal(mot_ease_apply(&e, MOT_Q32_ONE, NULL), MOT_Q32_ONE);
	}
	assert_int_equal(mot_ease_init(&e, 0, 0, NULL), MOT_OK);
	assert_true(mot_ease_is_identity(&e));
	for (i = 0; i < N / 10; i++) {
		int64_t s = (int64_t)(tu_u64(&rng) % (uint64_t)(MOT_Q62_ONE + 1));
		mot_q32 sq = (mot_q32)(tu_u64(&rng) % (uint64_t)(MOT_Q32_ONE + 1));

		assert_int_equal(mot_ease_apply62(&e, s), s);
		assert_int_equal(mot_ease_apply(&e, sq, NULL), sq);
	}
	/* all acceleration: s' = s^2 (v = 2, v / 2a = 1) */
	assert_int_equal(mot_ease_init(&e, MOT_Q32_ONE, 0, NULL), MOT_OK);
	assert_int_equal(mot_ease_apply(&e, MOT_Q32_HALF, NULL), MOT_Q32_ONE / 4);
	/* triangle a = b = 1/2: s'(1/2) = 1/2, s'(1/4) = 1/8 */
	assert_int_equal(mot_ease_init(&e, MOT_Q32_HALF, MOT_Q32_HALF, NULL), MOT_OK);
	assert_int_equal(mot_ease_apply(&e, MOT_Q32_HALF, NULL), MOT_Q32_HALF);
	assert_int_equal(mot_ease_apply(&e, MOT_Q32_ONE / 4, NULL), MOT_Q32_ONE / 8);
	assert_int_equal(mot_ease_apply(&e, 3 * (MOT_Q32_ONE / 4), NULL), 7 * (MOT_Q32_ONE / 8));
}

/* Continuity and monotonicity: walking 2000 units of 2^-62 across each join
 * one unit at a time, no step goes down and none jumps by more than the
 * peak speed (<= 2 units) plus the roundings. Then the whole range in
 * 2^20 Q32.32 steps. */
static void test_ease_joins_monotone(void **state)
{
	struct tu_rng rng;
	struct tu_worst jump = { 0, 0 }, down = { 0, 0 };
	int i, j;

	tu_seed(&rng, 15);
	for (i = 0; i < 2000; i++) {
		struct mot_ease e;
		mot_q32 a, b;
		int64_t at[2];
		int t;

		random_ab(&rng, &a, &b);
		assert_int_equal(mot_ease_init(&e, a, b, NULL), MOT_OK);
		at[0] = e.a;
		at[1] = MOT_Q62_ONE - e.b;
		for (t = 0; t < 2; t++) {
			int64_t s = at[t] - 1000, prev;

			s = s < 0 ? 0 : s;
			prev = mot_ease_apply62(&e, s);
			for (j = 0; j < 2000 && s < MOT_Q62_ONE; j++) {
				int64_t cur = mot_ease_apply62(&e, ++s);

				tu_worst_add(&jump, (double)(cur - prev), (double)i);
				if (cur < prev)
					tu_worst_add(&down, (double)(prev - cur), (double)i);
				prev = cur;
			}
		}
		if (i < 20) {
			mot_q32 prevq = 0;

			for (j = 0; j <= 1 << 20; j++) {
				mot_q32 cur = mot_ease_apply(&e, (mot_q32)j << 12, NULL);

				if (cur < prevq)
					tu_worst_add(&down, (double)(prevq - cur), (double)i);
				prevq = cur;
			}
		}
	}
	tu_bound("ease.join_jump", &jump, 4.0, "units of 2^-62 per unit step");
	tu_bound("ease.decrease", &down, 0.0, "units of 2^-62");
}

/* The plateau runs at v = 1 / (1 - a/2 - b/2): a difference quotient over
 * 2^-20 in the middle of it, relative to v. */
static void test_ease_plateau_speed(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int i;

	tu_seed(&rng, 16);
	for (i = 0; i < N / 10; i++) {
		struct mot_ease e;
		mot_q32 a, b;
		int64_t s0, s1, d = (int64_t)1 << 42;
		ref_t v, got;

		random_ab(&rng, &a, &b);
		if (MOT_Q32_ONE - a - b < ((mot_q32)1 << 23))
			continue; /* no plateau to measure */
		assert_int_equal(mot_ease_init(&e, a, b, NULL), MOT_OK);
		s0 = e.a + (MOT_Q62_ONE - e.a - e.b) / 2 - d / 2;
		s1 = s0 + d;
		v = 1 / (1 - ref_q(a) / 2 - ref_q(b) / 2);
		got = (ref_t)(mot_ease_apply62(&e, s1) - mot_ease_apply62(&e, s0)) / (ref_t)d;
		tu_worst_add(&w, (double)((got - v) / v), (double)i);
		/* and the prepared v itself, Q3.61 */
		assert_true(fabsl((ref_t)e.v / (Q62 / 2) - v) * (Q62 / 2) <= 0.6L);
	}
	tu_bound("ease.plateau_speed", &w, 1e-12, "relative");
}

/* The profile over a span in its own units (a strand's ease in Q32.32
 * frames, ease.h): against the exact piecewise formula in long double
 * (A, B, W and x exact in its 64-bit mantissa), in units of the span;
 * spans below 2^52 (2^20 frames) and up to 2^63 apart. Then no step down
 * walking 2000 units across each join. */
static ref_t ref_span(int64_t a, int64_t b, int64_t w, int64_t x)
{
	ref_t A = (ref_t)a, B = (ref_t)b, W = (ref_t)w, X = (ref_t)x;
	ref_t v = 2 * W / (2 * W - A - B);

	if (X < A)
		return v * X * X / (2 * A);
	if (X > W - B)
		return W - v * (W - X) * (W - X) / (2 * B);
	return v * (2 * X - A) / 2;
}

static void test_ease_span(void **state)
{
	struct tu_rng rng;
	struct tu_worst small = { 0, 0 }, big = { 0, 0 }, down = { 0, 0 };
	int i, j, t;

	tu_seed(&rng, 17);
	for (i = 0; i < N; i++) {
		struct mot_ease_span e;
		bool huge = i % 4 == 0;
		int64_t w = 2 + (int64_t)(tu_u64(&rng) >> (huge ? 1 + tu_u64(&rng) % 62 :
								 12 + tu_u64(&rng) % 50));
		int64_t a = (int64_t)(tu_u64(&rng) % (uint64_t)(w + 1)), b, x, at[2];
		unsigned mode = (unsigned)(tu_u64(&rng) % 8);
		int64_t g;

		b = (int64_t)(tu_u64(&rng) % (uint64_t)(w - a + 1));
		if (mode == 0)
			a = 0;
		else if (mode == 1)
			b = 0;
		else if (mode == 2)
			b = w - a;
		assert_int_equal(mot_ease_span_init(&e, a, b, w, NULL), MOT_OK);
		x = 1 + (int64_t)(tu_u64(&rng) % (uint64_t)(w - 1));
		g = mot_ease_span_apply_in(&e, x);
		assert_true(g >= 0 && g <= w);
		tu_worst_add(huge ? &big : &small, (double)((ref_t)g - ref_span(a, b, w, x)),
			     (double)w);
		if (huge || i % 64)
			continue;
		at[0] = a;
		at[1] = w - b;
		for (t = 0; t < 2; t++) {
			int64_t y = at[t] - 1000, prev;

			y = y < 1 ? 1 : y;
			prev = mot_ease_span_apply_in(&e, y);
			for (j = 0; j < 2000 && y + 1 < w; j++) {
				int64_t cur = mot_ease_span_apply_in(&e, ++y);

				if (cur < prev)
					tu_worst_add(&down, (double)(prev - cur), (double)w);
				prev = cur;
			}
		}
	}
	tu_bound("ease.span_vs_ref", &small, 0.51, "units, spans below 2^52");
	tu_bound("ease.span_huge_vs_ref", &big, 3.0, "units, spans up to 2^63");
	tu_bound("ease.span_decrease", &down, 0.0, "units");
	assert_int_equal(mot_ease_span_init(&(struct mot_ease_span){ 0 }, 2, 3, 4, NULL),
			 MOT_E_INVAL);
	assert_int_equal(mot_ease_span_init(&(struct mot_ease_span){ 0 }, -1, 0, 4, NULL),
			 MOT_E_INVAL);
	assert_int_equal(mot_ease_span_init(&(struct mot_ease_span){ 0 }, 0, 0, 0, NULL),
			 MOT_E_INVAL);
}

/* An eased piece's parameter (curve_priv.h's eased_u()): on the plateau
 * fused with the fraction of the width, elsewhere frac62 and the profile;
 * against the formula at x / w in long double, in units of 2^-62, over
 * widths of 2 to 2^62 units, uniformly and around the joins. */
static void test_ease_fused(void **state)
{
	struct tu_rng rng;
	struct tu_worst on = { 0, 0 }, off = { 0, 0 }, two = { 0, 0 };
	int i;

	tu_seed(&rng, 18);
	for (i = 0; i < N; i++) {
		struct mot_curve_seg s;
		mot_q32 a, b;
		int64_t w = 2 + (int64_t)(tu_u64(&rng) >> (2 + tu_u64(&rng) % 61)), x, xs;
		unsigned where = (unsigned)(tu_u64(&rng) % 4);
		ref_t want;
		int64_t got;

		random_ab(&rng, &a, &b);
		s = (struct mot_curve_seg){ 0 };
		assert_int_equal(mot_ease_init(&s.ease, a, b, NULL), MOT_OK);
		assert_int_equal(mot_recip_init(&s.inv_w, w), MOT_OK);
		mot_ease_fused_init(&s.ef, &s.ease, &s.inv_w);
		x = (int64_t)(tu_u64(&rng) % (uint64_t)w);
		if (where == 1)
			x = (int64_t)((ref_t)w * ref_q(a)) + (int64_t)(tu_u64(&rng) % 5) - 2;
		else if (where == 2)
			x = (int64_t)((ref_t)w * (1 - ref_q(b))) + (int64_t)(tu_u64(&rng) % 5) - 2;
		x = x < 0 ? 0 : x >= w ? w - 1 : x;
		got = eased_u(&s, x);
		want = ref_ease(ref_q(a), ref_q(b), (ref_t)x / (ref_t)w);
		xs = x << (93 - s.inv_w.shift);
		tu_worst_add(xs >= s.ef.xa && xs <= s.ef.xd ? &on : &off,
			     (double)((q62_to_ref(got) - want) * Q62), (double)w);
		/* the two steps everywhere, for comparison */
		tu_worst_add(&two,
			     (double)((q62_to_ref(mot_ease_apply62(&s.ease, frac62(x, &s.inv_w))) -
				       want) *
				      Q62),
			     (double)w);
	}
	tu_bound("ease.fused_plateau_vs_ref", &on, 3.5, "units of 2^-62");
	tu_bound("ease.fused_off_plateau_vs_ref", &off, 4.0, "units of 2^-62");
	tu_bound("ease.frac_then_profile_vs_ref", &two, 4.0, "units of 2^-62");
}

static void test_ease_errors(void **state)
{
	struct mot_ease e;
	uint32_t sat = 0;

	assert_int_equal(mot_ease_init(&e, -1, 0, NULL), MOT_E_INVAL);
	assert_true(mot_ease_is_identity(&e));
	assert_int_equal(mot_ease_init(&e, 0, -1, NULL), MOT_E_INVAL);
	assert_int_equal(mot_ease_init(&e, MOT_Q32_ONE + 1, 0, NULL), MOT_E_INVAL);
	assert_int_equal(mot_ease_init(&e, 0, MOT_Q32_ONE + 1, NULL), MOT_E_INVAL);
	assert_int_equal(mot_ease_init(&e, MOT_Q32_HALF, MOT_Q32_HALF + 1, NULL), MOT_E_INVAL);
	assert_int_equal(mot_ease_init(&e, MOT_Q32_MAX, MOT_Q32_MAX, NULL), MOT_E_INVAL);
	assert_int_equal(mot_ease_init_ratio(&e, 1, 1, 0, NULL), MOT_E_INVAL);
	assert_int_equal(mot_ease_init_ratio(&e, 0, 0, -5, NULL), MOT_E_INVAL);
	assert_int_equal(mot_ease_init_ratio(&e, 3, 3, 5, NULL), MOT_E_INVAL);
	assert_int_equal(mot_ease_init_ratio(&e, INT64_MAX, INT64_MAX, INT64_MAX, NULL),
			 MOT_E_INVAL);
	assert_int_equal(mot_ease_init_ratio(&e, 2, 3, 5, NULL), MOT_OK);
	/* outside [0, 1]: the nearest end, flagged */
	assert_int_equal(mot_ease_apply(&e, -MOT_Q32_ONE, &sat), 0);
	assert_true(sat & MOT_SAT_DOMAIN);
	sat = 0;
	assert_int_equal(mot_ease_apply(&e, MOT_Q32_MAX, &sat), MOT_Q32_ONE);
	assert_true(sat & MOT_SAT_DOMAIN);
	sat = 0;
	assert_int_equal(mot_ease_apply(&e, MOT_Q32_HALF, &sat),
			 mot_ease_apply(&e, MOT_Q32_HALF, NULL));
	assert_int_equal(sat, 0);
	assert_int_equal(mot_ease_apply62(&e, -5), 0);
	assert_int_equal(mot_ease_apply62(&e, INT64_MAX), MOT_Q62_ONE);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_ease_vs_ref),
		cmocka_unit_test(test_ease_q32),
		cmocka_unit_test(test_ease_ratio),
		cmocka_unit_test(test_ease_ends_identity),
		cmocka_unit_test(test_ease_joins_monotone),
		cmocka_unit_test(test_ease_plateau_speed),
		cmocka_unit_test(test_ease_span),
		cmocka_unit_test(test_ease_fused),
		cmocka_unit_test(test_ease_errors),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
