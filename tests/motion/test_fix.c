/* SPDX-License-Identifier: MIT */
/*
 * test_fix.c - the 128-bit intermediates and exact divisions of fix.h/fix.c,
 * against the compiler's __int128 (exact), on both code paths: this file is
 * built normally and the portable two-word path is exercised through
 * tests/fix_portable.c, compiled with MOT_NO_INT128.
 */
#include "fix_portable.h"
#include "testutil.h"

typedef __int128 i128;
typedef unsigned __int128 u128;

#define N 1000000

static i128 acc_to_i128(uint64_t hi, uint64_t lo)
{
	return (i128)(((u128)hi << 64) | lo);
}

static int64_t ref_round(i128 p, unsigned shift, int *ovf)
{
	i128 r = (i128)((u128)p + ((u128)1 << (shift - 1)));

	r >>= shift;
	*ovf = r > INT64_MAX || r < INT64_MIN;
	if (*ovf)
		return p < 0 ? INT64_MIN : INT64_MAX;
	return (int64_t)r;
}

static void test_mul_round(void **state)
{
	struct tu_rng rng;
	long bad = 0;
	int i;

	tu_seed(&rng, 1);
	for (i = 0; i < N; i++) {
		int64_t a = tu_i64(&rng), b = tu_i64(&rng);
		unsigned sh = 1 + (unsigned)(tu_u64(&rng) % 126);
		i128 p = (i128)a * b;
		mot_acc n = mot_acc_mul(a, b);
		uint64_t phi, plo;
		uint32_t s1 = 0, s2 = 0;
		int ovf;
		int64_t want = ref_round(p, sh, &ovf);

		fixp_mul(a, b, &phi, &plo);
		if (acc_to_i128(mot_acc_hi(n), mot_acc_lo(n)) != p || acc_to_i128(phi, plo) != p)
			bad++;
		if (mot_acc_round(n, sh, &s1) != want || fixp_round(a, b, sh, &s2) != want)
			bad++;
		if ((s1 != 0) != ovf || (s2 != 0) != ovf)
			bad++;
	}
	assert_int_equal(bad, 0);
}

/* The hot-path kernel: round(a0 b0 + a1 b1 + a2 b2 + c 2^shift) / 2^shift,
 * and an overflow word that is nonzero exactly when the result does not fit,
 * for any factors (wrap-around of the 128-bit sum included), on both paths. */
static void test_sum3_ov(void **state)
{
	static const unsigned shifts[2] = { 32, 62 };
	struct tu_rng rng;
	long bad = 0, ovs = 0;
	int i, k;

	tu_seed(&rng, 5);
	for (i = 0; i < N; i++) {
		int64_t a[3], b[3], c = tu_i64(&rng), got, got2;
		unsigned sh = shifts[i % 2];
		i128 q, r = (i128)1 << (sh - 1);
		uint64_t ov = 0, ov2 = 0;
		bool fits;

		/* the addend bound of fix.h at shift 62, |c| <= 2^62 */
		if (sh == 62)
			c /= 2;
		/* the exact floor, each product split as q 2^sh + r, 0 <= r < 2^sh */
		q = c;
		for (k = 0; k < 3; k++) {
			i128 p;

			a[k] = tu_i64(&rng);
			b[k] = tu_i64(&rng);
			p = (i128)a[k] * b[k];
			q += p >> sh;
			r += p & (((i128)1 << sh) - 1);
		}
		q += r >> sh;
		fits = q >= INT64_MIN && q <= INT64_MAX;
		got = mot_sum3_ov(a[0], b[0], a[1], b[1], a[2], b[2], c, sh, &ov);
		got2 = fixp_sum3_ov(a, b, c, sh, &ov2);
		ovs += !fits;
		if ((ov != 0) != !fits || (ov2 != 0) != !fits || got2 != got ||
		    (fits && got != (int64_t)q))
			bad++;
	}
	assert_int_equal(bad, 0);
	/* tu_i64 spreads magnitudes over every bit length: both outcomes occur */
	assert_true(ovs > N / 10 && ovs < N - N / 10);
}

static void test_udiv(void **state)
{
	struct tu_rng rng;
	long bad = 0;
	int i;

	tu_seed(&rng, 2);
	for (i = 0; i < N; i++) {
		uint64_t d = (uint64_t)tu_i64(&rng) | 1;
		u128 x = ((u128)(tu_u64(&rng) % d) << 64) | tu_u64(&rng);
		uint64_t rem, rem2;
		uint64_t q = mot_acc_udiv(mot_acc_make((uint64_t)(x >> 64), (uint64_t)x), d, &rem,
					  NULL);
		uint64_t q2 = fixp_udiv((uint64_t)(x >> 64), (uint64_t)x, d, &rem2);

		if (q != (uint64_t)(x / d) || rem != (uint64_t)(x % d) || q2 != q || rem2 != rem)
			bad++;
	}
	assert_int_equal(bad, 0);
	/* quotient overflow is reported, not wrapped */
	{
		uint32_t sat = 0;

		mot_acc_udiv(mot_acc_make(5, 0), 5, NULL, &sat);
		assert_true(sat & MOT_SAT_OVERFLOW);
	}
}

/* Division by a prepared reciprocal (mot_udiv_by_inv): exact, the same
 * quotient and remainder as __int128's, on both paths, for divisors of
 * every bit length and dividends up to (d - 1) 2^64 + 2^64 - 1; and the
 * edges: d = 1, 2^63, 2^64 - 1, the largest dividend for each. */
static void test_udiv_inv(void **state)
{
	static const uint64_t edge[] = { 1, 2, 3, 60, 60 * 30000ull, (uint64_t)1 << 63,
					 ((uint64_t)1 << 63) + 1, ~(uint64_t)0, ~(uint64_t)0 - 1 };
	struct tu_rng rng;
	long bad = 0, n = 0;
	unsigned i, k;

	(void)state;
	tu_seed(&rng, 7);
	for (i = 0; i < N + sizeof(edge) / sizeof(edge[0]) * 4; i++) {
		uint64_t d, hi, lo, rem, rem2;
		uint64_t q, q2;
		struct mot_udiv_inv in;
		u128 x;

		if (i < N) {
			d = tu_u64(&rng) >> (tu_u64(&rng) % 64);
			d = d ? d : 1;
			hi = tu_u64(&rng) % d;
			lo = tu_u64(&rng);
		} else {
			k = (i - N) / 4;
			d = edge[k];
			hi = (i - N) % 2 ? d - 1 : 0;
			lo = (i - N) % 4 >= 2 ? ~(uint64_t)0 : 0;
		}
		assert_int_equal(mot_udiv_inv_init(&in, d), MOT_OK);
		q = mot_udiv_by_inv(hi, lo, &in, &rem);
		q2 = fixp_udiv_by_inv(hi, lo, d, &rem2);
		x = ((u128)hi << 64) | lo;
		if (q != (uint64_t)(x / d) || rem != (uint64_t)(x % d) || q2 != q || rem2 != rem)
			bad++;
		n++;
	}
	assert_int_equal(bad, 0);
	assert_true(n > N);
	{
		struct mot_udiv_inv in;

		assert_int_equal(mot_udiv_inv_init(&in, 0), MOT_E_INVAL);
	}
}

static void test_muldiv_div(void **state)
{
	struct tu_rng rng;
	long bad = 0;
	int i;

	tu_seed(&rng, 3);
	for (i = 0; i < N; i++) {
		int64_t a = tu_i64(&rng), m = tu_i64(&rng), d = tu_i64(&rng);
		i128 n2, d2, fq;
		int64_t want;

		if (d == INT64_MIN)
			d = 7;
		if (d < 0)
			d = -d;
		if (d == 0)
			d = 1;
		/* round half up: floor((2am + d) / 2d) */
		n2 = 2 * (i128)a * m + d;
		d2 = 2 * (i128)d;
		fq = n2 / d2;
		if (n2 % d2 < 0)
			fq--;
		want = fq > INT64_MAX ? INT64_MAX : fq < INT64_MIN ? INT64_MIN : (int64_t)fq;
		if (mot_muldiv(a, m, d, NULL) != want || fixp_muldiv(a, m, d) != want)
			bad++;
	}
	assert_int_equal(bad, 0);
	assert_int_equal(mot_div(MOT_Q32_ONE, 3 * MOT_Q32_ONE, NULL), 1431655765);
	assert_int_equal(mot_div(-MOT_Q32_ONE, 3 * MOT_Q32_ONE, NULL), -1431655765);
	assert_int_equal(mot_div(MOT_Q32_INT(7), -MOT_Q32_INT(2), NULL), -MOT_Q32_INT(7) / 2);
	{
		uint32_t sat = 0;

		assert_int_equal(mot_div(1, 0, &sat), MOT_Q32_MAX);
		assert_true(sat & MOT_SAT_DOMAIN);
	}
}

static void test_recip(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int i;

	tu_seed(&rng, 4);
	for (i = 0; i < N; i++) {
		int64_t d = tu_i64(&rng), x = tu_i64(&rng) >> 1;
		struct mot_recip r;
		i128 exact;

		if (d <= 0)
			d = d == INT64_MIN ? 3 : 1 - d;
		assert_int_equal(mot_recip_init(&r, d), MOT_OK);
		exact = (i128)x * 4294967296 / d;
		if (exact > INT64_MAX / 2 || exact < INT64_MIN / 2)
			continue;
		tu_worst_add(&w, (double)((i128)mot_recip_ratio(x, &r, NULL) - exact), (double)d);
	}
	tu_bound("fix.recip_ratio", &w, 2.0, "LSB");
	assert_int_equal(mot_recip_init(&(struct mot_recip){ 0, 0 }, 0), MOT_E_INVAL);
}

static void test_floordiv(void **state)
{
	int64_t r;

	assert_int_equal(mot_floordiv(-7, 2, &r), -4);
	assert_int_equal(r, 1);
	assert_int_equal(mot_floordiv(7, 2, &r), 3);
	assert_int_equal(r, 1);
	assert_int_equal(mot_floordiv(-8, 2, &r), -4);
	assert_int_equal(r, 0);
}

static void test_sat(void **state)
{
	uint32_t sat = 0;

	assert_int_equal(mot_mul(MOT_Q32_MAX, MOT_Q32_INT(2), &sat), MOT_Q32_MAX);
	assert_true(sat & MOT_SAT_OVERFLOW);
	sat = 0;
	assert_int_equal(mot_mul(MOT_Q32_MAX, -MOT_Q32_INT(2), &sat), MOT_Q32_MIN);
	assert_true(sat & MOT_SAT_OVERFLOW);
	sat = 0;
	assert_int_equal(mot_add_sat(MOT_Q32_MAX, 1, &sat), MOT_Q32_MAX);
	assert_int_equal(mot_sub_sat(MOT_Q32_MIN, 1, &sat), MOT_Q32_MIN);
	assert_true(sat & MOT_SAT_OVERFLOW);
	sat = 0;
	/* ties round toward +inf: 0.5 LSB -> 1, -0.5 LSB -> 0 */
	assert_int_equal(mot_mul(1, MOT_Q32_HALF, &sat), 1);
	assert_int_equal(mot_mul(-1, MOT_Q32_HALF, &sat), 0);
	assert_int_equal(sat, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_mul_round), cmocka_unit_test(test_sum3_ov),
		cmocka_unit_test(test_udiv), cmocka_unit_test(test_udiv_inv),
		cmocka_unit_test(test_muldiv_div), cmocka_unit_test(test_recip),
		cmocka_unit_test(test_floordiv), cmocka_unit_test(test_sat),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
