/* SPDX-License-Identifier: MIT */
/*
 * test_trig.c - trig.h against libm in double (long double where a result
 * has more than 53 significant bits) and the square roots exactly against
 * __int128 arithmetic. Errors are in LSB of Q32.32 (2^-32 of the result's
 * unit: turns for angles). The portable two-word path (tests/trig_portable.c,
 * built with MOT_NO_INT128) must give the same bits as the native one.
 */
#include "motion/trig.h"
#include "testutil.h"
#include "trig_portable.h"

typedef __int128 i128;
typedef unsigned __int128 u128;

#define N 200000
#define LSB (1.0 / TU_Q32)

/* Angle difference a - b in turns, wrapped into [-1/2, 1/2). */
static double turn_diff(double a, double b)
{
	double d = a - b;

	return d - floor(d + 0.5);
}

/* ---- sin and cos ------------------------------------------------------------ */

/* Reference from the phase alone: the low 32 bits are exact in a double, so
 * libm sees the true angle however many turns `t` holds. */
static void ref_sincos(mot_q32 t, double *s, double *c)
{
	double rad = (double)(uint32_t)(uint64_t)t * LSB * 2.0 * M_PI;

	*s = sin(rad);
	*c = cos(rad);
}

static mot_q32 sincos_input(struct tu_rng *rng, int kind)
{
	switch (kind) {
	case 0: /* any number of turns, up to +-2^31 */
		return (mot_q32)tu_u64(rng);
	case 1: /* random magnitudes, tiny angles included */
		return tu_i64(rng);
	case 2: /* next to a quarter turn */
		return (mot_q32)(tu_u64(rng) % 64 - 32) * (MOT_Q32_ONE / 4) +
		       (mot_q32)(tu_u64(rng) % (1 << 23)) - (1 << 22);
	default: /* next to the middle between two table points (largest offset) */
		return (mot_q32)(tu_u64(rng) % 4096) * (1 << 22) + (1 << 21) +
		       (mot_q32)(tu_u64(rng) % 64) - 32;
	}
}

static void test_sincos_accuracy(void **state)
{
	struct tu_rng rng;
	struct tu_worst ws = { 0, 0 }, wc = { 0, 0 };
	long bad = 0;
	int i;

	tu_seed(&rng, 11);
	for (i = 0; i < 4 * N; i++) {
		mot_q32 t = sincos_input(&rng, i % 4), s, c;
		double rs, rc;

		mot_sincos(t, &s, &c);
		ref_sincos(t, &rs, &rc);
		tu_worst_add(&ws, (double)s - rs * TU_Q32, q2d(t));
		tu_worst_add(&wc, (double)c - rc * TU_Q32, q2d(t));
		if (s > MOT_Q32_ONE || s < -MOT_Q32_ONE || c > MOT_Q32_ONE || c < -MOT_Q32_ONE)
			bad++;
		if (mot_sin(t) != s || mot_cos(t) != c)
			bad++;
	}
	assert_int_equal(bad, 0);
	tu_bound("trig.sin", &ws, 0.55, "LSB");
	tu_bound("trig.cos", &wc, 0.55, "LSB");
}

/* mot_sincos64: a phase of 64 bits against long double, the same bits as
 * mot_sincos() where the low 32 are zero, and as the portable path */
static void test_sincos64(void **state)
{
	struct tu_rng rng;
	struct tu_worst ws = { 0, 0 }, wc = { 0, 0 };
	long bad = 0;
	int i;

	tu_seed(&rng, 13);
	for (i = 0; i < 4 * N; i++) {
		uint64_t ph = tu_u64(&rng);
		long double rad;
		struct mot_sc r;
		int64_t s2, c2;
		mot_q32 s1, c1;

		if (i % 4 == 1) /* next to a table point */
			ph = (ph & ~(((uint64_t)1 << 54) - 1)) + (ph >> 62) - 2 +
			     ((ph >> 60 & 1) << 53);
		r = mot_sincos64(ph);
		rad = (long double)ph / 18446744073709551616.0L * 2.0L * M_PI;
		tu_worst_add(&ws, (double)(((long double)r.s / TU_Q32 - sinl(rad)) * TU_Q32),
			     (double)(ph >> 32) * LSB);
		tu_worst_add(&wc, (double)(((long double)r.c / TU_Q32 - cosl(rad)) * TU_Q32),
			     (double)(ph >> 32) * LSB);
		mot_sincos((mot_q32)(ph >> 32), &s1, &c1);
		r = mot_sincos64(ph & ~(uint64_t)0xffffffff);
		bad += r.s != s1 || r.c != c1;
		trigp_sincos64(ph, &s2, &c2);
		r = mot_sincos64(ph);
		bad += r.s != s2 || r.c != c2;
	}
	assert_int_equal(bad, 0);
	tu_bound("trig.sin of a 64-bit phase", &ws, 0.55, "LSB");
	tu_bound("trig.cos of a 64-bit phase", &wc, 0.55, "LSB");
}

static void test_sincos_exact(void **state)
{
	static const mot_q32 sin_q[4] = { 0, MOT_Q32_ONE, 0, -MOT_Q32_ONE };
	static const int64_t turns[] = { 0, 1, -1, 7, -1000, 1 << 20, -(1 << 30), (1ll << 31) - 2 };
	struct tu_rng rng;
	size_t n;
	int k;

	/* quarter turns, on any turn */
	for (n = 0; n < sizeof(turns) / sizeof(turns[0]); n++) {
		for (k = 0; k < 8; k++) {
			mot_q32 t = MOT_Q32_INT(turns[n]) + k * (MOT_Q32_ONE / 4), s, c;

			mot_sincos(t, &s, &c);
			assert_int_equal(s, sin_q[k % 4]);
			assert_int_equal(c, sin_q[(k + 1) % 4]);
		}
	}
	/* whole turns change nothing, and 1/8 turn has sin == cos */
	tu_seed(&rng, 12);
	for (k = 0; k < N; k++) {
		mot_q32 t = (mot_q32)(uint32_t)tu_u64(&rng);
		mot_q32 u = t + MOT_Q32_INT((int64_t)(tu_u64(&rng) % (1u << 31)) - (1 << 30));
		mot_q32 s1, c1, s2, c2;

		mot_sincos(t, &s1, &c1);
		mot_sincos(u, &s2, &c2);
		if (s1 != s2 || c1 != c2)
			fail_msg("sincos(%lld) != sincos(%lld)", (long long)t, (long long)u);
	}
	assert_int_equal(mot_sin(MOT_Q32_ONE / 8), mot_cos(MOT_Q32_ONE / 8));
	assert_int_equal(mot_sin(MOT_Q32_MIN), 0); /* -2^31 turns */
	assert_int_equal(mot_cos(MOT_Q32_MIN), MOT_Q32_ONE);
}

/* ---- atan2 -------------------------------------------------------------------- */

static void atan2_pair(struct tu_rng *rng, int kind, mot_q32 *y, mot_q32 *x)
{
	unsigned bits = 1 + (unsigned)(tu_u64(rng) % 62);
	int64_t m = ((int64_t)1 << bits) - 1;

	switch (kind) {
	case 0: /* independent random magnitudes, all quadrants */
		*y = tu_i64(rng);
		*x = tu_i64(rng);
		break;
	case 1: /* same scale, any direction */
		*y = (int64_t)(tu_u64(rng) & (uint64_t)m) - m / 2;
		*x = (int64_t)(tu_u64(rng) & (uint64_t)m) - m / 2;
		break;
	case 2: /* next to a diagonal */
		*x = (int64_t)(tu_u64(rng) & (uint64_t)m) * ((tu_u64(rng) & 1) ? 1 : -1);
		*y = (*x + (int64_t)(tu_u64(rng) % 2001) - 1000) * ((tu_u64(rng) & 1) ? 1 : -1);
		break;
	default: /* next to an axis */
		*x = (int64_t)(tu_u64(rng) | 1) >> (tu_u64(rng) % 8);
		*y = tu_i64(rng) >> (tu_u64(rng) % 40);
		if (tu_u64(rng) & 1) {
			mot_q32 t = *x;

			*x = *y;
			*y = t;
		}
	}
}

static void test_atan2_accuracy(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	long bad = 0;
	int i;

	tu_seed(&rng, 21);
	for (i = 0; i < 4 * N; i++) {
		mot_q32 y, x, a;
		double ref;

		atan2_pair(&rng, i % 4, &y, &x);
		a = mot_atan2(y, x);
		ref = (x == 0 && y == 0) ? 0 : atan2((double)y, (double)x) / (2.0 * M_PI);
		tu_worst_add(&w, turn_diff(q2d(a), ref) * TU_Q32, ref);
		if (a <= -MOT_Q32_HALF || a > MOT_Q32_HALF)
			bad++;
		/* mirror symmetry, exact by construction */
		if (y != MOT_Q32_MIN && a != MOT_Q32_HALF && mot_atan2(-y, x) != -a)
			bad++;
	}
	assert_int_equal(bad, 0);
	tu_bound("trig.atan2", &w, 0.55, "LSB");
}

/* mot_atan2_unit_q62: vectors of the first quadrant whose squared length
 * is 1 within 2^-16 (the length within 0, 8 LSB, 2^-18, 2^-17 - 2 LSB of
 * 1), and others (mot_atan2's bits); errors against long double in LSB of
 * Q32.32 turns */
static void test_atan2_unit(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	long bad = 0;
	int i;

	tu_seed(&rng, 22);
	for (i = 0; i < 4 * N; i++) {
		long double ang = (long double)(tu_u64(&rng) >> 11) / 9007199254740992.0L * M_PI / 2;
		long double len = 1.0L;
		mot_q32 y, x;
		int64_t a;

		if (i % 4 == 1)
			len += (long double)((int64_t)(tu_u64(&rng) % 17) - 8) / TU_Q32;
		else if (i % 4 == 2)
			len += (tu_u64(&rng) & 1 ? 1.0L : -1.0L) / 262144.0L;
		else if (i % 4 == 3)
			len += (tu_u64(&rng) & 1 ? 1.0L : -1.0L) * (1.0L / 131072.0L - 2.0L / TU_Q32);
		y = (mot_q32)llroundl(sinl(ang) * len * TU_Q32);
		x = (mot_q32)llroundl(cosl(ang) * len * TU_Q32);
		a = mot_atan2_unit_q62(y, x);
		tu_worst_add(&w,
			     (double)(((long double)a / 4611686018427387904.0L -
				       atan2l((long double)y, (long double)x) / (2.0L * M_PI)) *
				      TU_Q32),
			     (double)ang);
		bad += a != trigp_atan2_unit_q62(y, x);
	}
	/* a vector too long or short, or outside the quadrant: mot_atan2() */
	for (i = 0; i < N; i++) {
		mot_q32 y = tu_i64(&rng) >> (tu_u64(&rng) % 40), x = tu_i64(&rng) >> (tu_u64(&rng) % 40);
		int64_t a = mot_atan2_unit_q62(y, x);

		if (!(y >= 0 && x >= 0 && a >> 30 != mot_atan2(y, x)))
			bad += a != (int64_t)((uint64_t)mot_atan2(y, x) << 30);
		bad += a != trigp_atan2_unit_q62(y, x);
	}
	assert_int_equal(mot_atan2_unit_q62(0, MOT_Q32_ONE), 0);
	assert_int_equal(mot_atan2_unit_q62(MOT_Q32_ONE, 0), (int64_t)1 << 60);
	assert_int_equal(bad, 0);
	tu_bound("trig.atan2_unit_q62 (|x^2 + y^2 - 1| < 2^-16)", &w, 0.05, "LSB");
}

static void test_atan2_exact(void **state)
{
	static const int64_t mags[] = { 1, 2, 3, 12345, MOT_Q32_ONE, (int64_t)1 << 53,
					((int64_t)1 << 53) + 1, MOT_Q32_MAX - 1, MOT_Q32_MAX };
	const mot_q32 q = MOT_Q32_ONE / 4, e = MOT_Q32_ONE / 8;
	struct tu_rng rng;
	size_t n;
	int i;

	assert_int_equal(mot_atan2(0, 0), 0);
	for (n = 0; n < sizeof(mags) / sizeof(mags[0]); n++) {
		int64_t v = mags[n];

		assert_int_equal(mot_atan2(0, v), 0);
		assert_int_equal(mot_atan2(v, 0), q);
		assert_int_equal(mot_atan2(0, -v), 2 * q);
		assert_int_equal(mot_atan2(-v, 0), -q);
		assert_int_equal(mot_atan2(v, v), e);
		assert_int_equal(mot_atan2(v, -v), 3 * e);
		assert_int_equal(mot_atan2(-v, -v), -3 * e);
		assert_int_equal(mot_atan2(-v, v), -e);
	}
	assert_int_equal(mot_atan2(MOT_Q32_MIN, MOT_Q32_MIN), -3 * e);
	assert_int_equal(mot_atan2(MOT_Q32_MIN, 0), -q);
	assert_int_equal(mot_atan2(0, MOT_Q32_MIN), 2 * q);
	/* -1/2 turn is reported as +1/2 */
	assert_int_equal(mot_atan2(-1, MOT_Q32_MIN), 2 * q);
	/* the ratio matters, not the scale */
	tu_seed(&rng, 22);
	for (i = 0; i < N; i++) {
		mot_q32 y = tu_i64(&rng) >> 24, x = tu_i64(&rng) >> 24;
		unsigned k = (unsigned)(tu_u64(&rng) % 24);

		if (mot_atan2(y, x) != mot_atan2(y * ((int64_t)1 << k), x * ((int64_t)1 << k)))
			fail_msg("atan2(%lld, %lld) changes with scale 2^%u", (long long)y,
				 (long long)x, k);
	}
}

/* ---- acos ------------------------------------------------------------------------ */

static void test_acos(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	uint32_t sat = 0;
	int i;

	tu_seed(&rng, 31);
	for (i = 0; i < 2 * N; i++) {
		mot_q32 x;
		mot_q32 a;

		if (i % 2)
			x = (mot_q32)(tu_u64(&rng) % (2 * (uint64_t)MOT_Q32_ONE + 1)) - MOT_Q32_ONE;
		else /* next to +-1, where acos is steep */
			x = (MOT_Q32_ONE - (tu_i64(&rng) & ((1ll << (tu_u64(&rng) % 33)) - 1))) *
			    ((tu_u64(&rng) & 1) ? 1 : -1);
		a = mot_acos(x, &sat);
		tu_worst_add(&w, (q2d(a) - acos(q2d(x)) / (2.0 * M_PI)) * TU_Q32, q2d(x));
		if (a < 0 || a > MOT_Q32_HALF)
			fail_msg("acos(%lld) = %lld out of [0, 1/2]", (long long)x, (long long)a);
	}
	assert_int_equal(sat, 0);
	tu_bound("trig.acos", &w, 0.55, "LSB");

	assert_int_equal(mot_acos(MOT_Q32_ONE, &sat), 0);
	assert_int_equal(mot_acos(-MOT_Q32_ONE, &sat), MOT_Q32_HALF);
	assert_int_equal(mot_acos(0, &sat), MOT_Q32_ONE / 4);
	assert_int_equal(sat, 0);
	assert_int_equal(mot_acos(MOT_Q32_ONE + 1, &sat), 0);
	assert_int_equal(sat, MOT_SAT_DOMAIN);
	sat = 0;
	assert_int_equal(mot_acos(MOT_Q32_MIN, &sat), MOT_Q32_HALF);
	assert_int_equal(sat, MOT_SAT_DOMAIN);
	assert_int_equal(mot_acos(MOT_Q32_MAX, NULL), 0);
}

/* ---- square roots ---------------------------------------------------------------- */

/* r == round(sqrt(n)) exactly: -r < n - r^2 <= r (r = 0 only for n = 0). */
static bool is_round_sqrt(u128 n, uint64_t r)
{
	i128 d = (i128)(n - (u128)r * r);

	if (r == 0)
		return n == 0;
	return d > -(i128)r && d <= (i128)r;
}

/* |r - sqrt(n)| = |r^2 - n| / (r + sqrt(n)), with the numerator exact. */
static double sqrt_err(u128 n, uint64_t r)
{
	i128 d = (i128)((u128)r * r - n);

	if (n == 0)
		return (double)r;
	return (double)d / ((double)r + sqrtl((long double)n));
}

/* floor(sqrt(n)) bit by bit, independent of trig.c. */
static uint64_t ref_isqrt_floor(u128 n)
{
	uint64_t r = 0;
	int b;

	for (b = 63; b >= 0; b--) {
		uint64_t t = r | ((uint64_t)1 << b);

		if ((u128)t * t <= n)
			r = t;
	}
	return r;
}

static uint64_t ref_isqrt_round(u128 n)
{
	uint64_t f = ref_isqrt_floor(n);

	return f + (n - (u128)f * f > f);
}

static void test_sqrt(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	uint32_t sat = 0;
	long bad = 0;
	int64_t k;
	int i;

	tu_seed(&rng, 41);
	for (i = 0; i < 2 * N; i++) {
		mot_q32 x = (i % 2) ? tu_i64(&rng) & MOT_Q32_MAX : (mot_q32)(tu_u64(&rng) >> 1);
		mot_q32 r = mot_sqrt(x, &sat);
		u128 n = (u128)x << 32;

		tu_worst_add(&w, sqrt_err(n, (uint64_t)r), q2d(x));
		if (!is_round_sqrt(n, (uint64_t)r))
			bad++;
	}
	assert_int_equal(bad, 0);
	assert_int_equal(sat, 0);
	tu_bound("trig.sqrt", &w, 0.5, "LSB");

	assert_int_equal(mot_sqrt(0, &sat), 0);
	assert_int_equal(mot_sqrt(1, &sat), 1 << 16);
	assert_int_equal(mot_sqrt(MOT_Q32_ONE, &sat), MOT_Q32_ONE);
	assert_int_equal(mot_sqrt(MOT_Q32_INT(4), &sat), MOT_Q32_INT(2));
	/* sqrt(2^31 - 2^-32) 2^32 = 199032864766430.39... */
	assert_int_equal(mot_sqrt(MOT_Q32_MAX, &sat), ref_isqrt_round((u128)MOT_Q32_MAX << 32));
	assert_int_equal(mot_sqrt(MOT_Q32_MAX, &sat), 199032864766430ll);
	assert_int_equal(sat, 0);
	/* perfect squares, as raw values and as integers */
	for (k = 1; k < 3037000499ll; k += k / 7 + 1) {
		assert_int_equal(mot_sqrt(k * k, &sat), k << 16);
		if (k <= 46340)
			assert_int_equal(mot_sqrt(MOT_Q32_INT(k * k), &sat), MOT_Q32_INT(k));
	}
	assert_int_equal(sat, 0);
	assert_int_equal(mot_sqrt(-1, &sat), 0);
	assert_int_equal(sat, MOT_SAT_DOMAIN);
}

static void test_isqrt_acc(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wi = { 0, 0 }, wn = { 0, 0 };
	uint32_t sat = 0;
	int i;

	tu_seed(&rng, 42);
	for (i = 0; i < 2 * N; i++) {
		u128 n;
		uint64_t r, want;

		if (i % 2) { /* random bit length 1..127 */
			n = ((u128)tu_u64(&rng) << 64 | tu_u64(&rng)) >> (1 + tu_u64(&rng) % 127);
		} else { /* next to k^2 and to the rounding boundary k^2 + k */
			uint64_t kk = tu_u64(&rng) >> (tu_u64(&rng) % 64);

			if (kk > 13043817825332782212ull) /* floor(sqrt(2^127)) */
				kk >>= 1;
			n = (u128)kk * kk + ((tu_u64(&rng) & 1) ? kk : 0) + (tu_u64(&rng) % 5) - 2;
			if (n >> 127) /* also 0 - 2 wrapped */
				n = (u128)kk * kk;
		}
		r = mot_isqrt_acc(mot_acc_make((uint64_t)(n >> 64), (uint64_t)n), &sat);
		want = ref_isqrt_round(n);
		if (n) { /* the root with its reciprocal: the same root */
			int64_t inv;
			unsigned sh;

			assert_true(mot_isqrt_acc_inv(mot_acc_make((uint64_t)(n >> 64), (uint64_t)n),
						      &inv, &sh) == r);
			assert_true(sh >= 62 && sh <= 125);
			{ /* without the last correction: the same inv, the root
			   * within 1/2 + 2^-8 below 2^102 (long double: 64 bits) */
				int64_t inv2;
				unsigned sh2;
				uint64_t r2 = mot_isqrt_acc_inv_near(
					mot_acc_make((uint64_t)(n >> 64), (uint64_t)n), &inv2, &sh2);

				assert_true(inv2 == inv && sh2 == sh);
				if (!(n >> 102))
					tu_worst_add(&wn,
						     fabsl((long double)r2 - sqrtl((long double)n)),
						     (double)n);
				else
					assert_true(r2 + 4 >= r && r2 <= r + 4);
			}
			tu_worst_add(&wi,
				     fabsl(ldexpl((long double)inv, -(int)sh) * sqrtl((long double)n) - 1),
				     (double)n);
		}
		tu_worst_add(&w, (double)r - (double)want, (double)n);
		if (r != want)
			fail_msg("isqrt(0x%016llx%016llx) = %llu, want %llu",
				 (unsigned long long)(n >> 64), (unsigned long long)n,
				 (unsigned long long)r, (unsigned long long)want);
	}
	assert_int_equal(sat, 0);
	tu_bound("trig.isqrt_acc", &w, 0, "units (exact)");
	tu_bound("trig.isqrt_acc_inv 1/sqrt relative", &wi, 0x1p-58, "(1)");
	tu_bound("trig.isqrt_acc_inv_near root (below 2^102)", &wn, 0.5 + 0x1p-8, "units");

	assert_int_equal(mot_isqrt_acc(mot_acc_zero(), &sat), 0);
	assert_int_equal(mot_isqrt_acc(mot_acc_from(2, 0), &sat), 1);
	assert_int_equal(mot_isqrt_acc(mot_acc_from(3, 0), &sat), 2);
	assert_int_equal(mot_isqrt_acc(mot_acc_make(INT64_MAX, UINT64_MAX), &sat),
			 13043817825332782212ull);
	assert_int_equal(mot_isqrt_acc(mot_acc_make((uint64_t)1 << 62, 0), &sat),
			 (uint64_t)1 << 63);
	assert_int_equal(sat, 0);
	assert_int_equal(mot_isqrt_acc(mot_acc_from(-1, 0), &sat), 0);
	assert_int_equal(sat, MOT_SAT_DOMAIN);
}

#if MOT_HAVE_INT128
/* mot_isqrt_inv_unit_in() on its range, x62 in [2^42, 2^63) (the root of
 * 4 x62), log-uniform */
static void test_isqrt_inv_unit(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wi = { 0, 0 };
	int i;

	(void)state;
	tu_seed(&rng, 47);
	for (i = 0; i < 4 * N; i++) {
		unsigned bits = 43 + (unsigned)(tu_u64(&rng) % 21); /* 43..63 */
		uint64_t x62 = (tu_u64(&rng) >> (64 - bits)) | (uint64_t)1 << (bits - 1);
		long double n;
		int64_t inv;
		unsigned sh;
		uint64_t r;

		if (i < 4)
			x62 = i < 2 ? (uint64_t)1 << 42 : ((uint64_t)1 << 63) - 1;
		if (i & 1 && i < 4)
			x62 = i < 2 ? ((uint64_t)1 << 42) + 1 : (uint64_t)1 << 62;
		n = 4.0L * (long double)x62;
		r = mot_isqrt_inv_unit_in((int64_t)x62, &inv, &sh);
		assert_true(sh >= 84 && sh <= 94);
		tu_worst_add(&w, fabsl((long double)r - sqrtl(n)), (double)n);
		tu_worst_add(&wi, fabsl(ldexpl((long double)inv, -(int)sh) * sqrtl(n) - 1), (double)n);
	}
	tu_bound("trig.isqrt_inv_unit root", &w, 0.5 + 0x1p-8, "units");
	tu_bound("trig.isqrt_inv_unit 1/sqrt relative", &wi, 0x1p-58, "(1)");
}
#endif

static void test_rsqrt(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	uint32_t sat = 0;
	int i;

	tu_seed(&rng, 43);
	for (i = 0; i < 2 * N; i++) {
		mot_q32 x = (i % 2) ? tu_i64(&rng) & MOT_Q32_MAX : (mot_q32)(tu_u64(&rng) >> 1);
		mot_q32 r;
		long double ref;

		if (x == 0)
			x = 1;
		r = mot_rsqrt(x, &sat);
		/* 2^32 / sqrt(x 2^-32) = 2^48 / sqrt(x), up to 2^48: long double */
		ref = 281474976710656.0L / sqrtl((long double)x);
		tu_worst_add(&w, (double)((long double)r - ref), q2d(x));
	}
	assert_int_equal(sat, 0);
	tu_bound("trig.rsqrt", &w, 0.51, "LSB");

	assert_int_equal(mot_rsqrt(MOT_Q32_ONE, &sat), MOT_Q32_ONE);
	assert_int_equal(mot_rsqrt(MOT_Q32_INT(4), &sat), MOT_Q32_HALF);
	assert_int_equal(mot_rsqrt(MOT_Q32_ONE / 4, &sat), MOT_Q32_INT(2));
	assert_int_equal(mot_rsqrt(1, &sat), (int64_t)1 << 48);
	assert_int_equal(sat, 0);
	assert_int_equal(mot_rsqrt(0, &sat), MOT_Q32_MAX);
	assert_int_equal(sat, MOT_SAT_DOMAIN);
	sat = 0;
	assert_int_equal(mot_rsqrt(-MOT_Q32_ONE, &sat), MOT_Q32_MAX);
	assert_int_equal(sat, MOT_SAT_DOMAIN);
}

static void test_norm3(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	long bad = 0;
	int i, k;

	tu_seed(&rng, 44);
	for (i = 0; i < 2 * N; i++) {
		unsigned shift = (unsigned)(tu_u64(&rng) % 64);
		mot_q32 v[3];
		uint32_t sat = 0;
		u128 n = 0;
		mot_q32 r;
		uint64_t want;

		for (k = 0; k < 3; k++) {
			v[k] = (i % 2) ? (int64_t)tu_u64(&rng) >> shift : tu_i64(&rng);
			n += (u128)((i128)v[k] * v[k]);
		}
		r = mot_norm3(v, &sat);
		want = ref_isqrt_round(n);
		if (want > (uint64_t)MOT_Q32_MAX) {
			if (r != MOT_Q32_MAX || sat != MOT_SAT_OVERFLOW)
				bad++;
			continue;
		}
		tu_worst_add(&w, sqrt_err(n, (uint64_t)r), q2d(r));
		if ((uint64_t)r != want || sat != 0)
			bad++;
	}
	assert_int_equal(bad, 0);
	tu_bound("trig.norm3", &w, 0.5, "LSB");

	{
		const mot_q32 v345[3] = { MOT_Q32_INT(3), MOT_Q32_INT(-4), 0 };
		const mot_q32 vmax[3] = { 0, MOT_Q32_MAX, 0 };
		const mot_q32 vmin[3] = { 0, 0, MOT_Q32_MIN };
		const mot_q32 vbig[3] = { MOT_Q32_MIN, MOT_Q32_MIN, MOT_Q32_MIN };
		const mot_q32 vzero[3] = { 0, 0, 0 };
		uint32_t sat = 0;

		assert_int_equal(mot_norm3(v345, &sat), MOT_Q32_INT(5));
		assert_int_equal(mot_norm3(vmax, &sat), MOT_Q32_MAX);
		assert_int_equal(mot_norm3(vzero, &sat), 0);
		assert_int_equal(sat, 0);
		assert_int_equal(mot_norm3(vmin, &sat), MOT_Q32_MAX);
		assert_int_equal(sat, MOT_SAT_OVERFLOW);
		sat = 0;
		assert_int_equal(mot_norm3(vbig, &sat), MOT_Q32_MAX);
		assert_int_equal(sat, MOT_SAT_OVERFLOW);
	}
}

/* ---- the portable path ---------------------------------------------------------------- */

static void test_portable_same_bits(void **state)
{
	struct tu_rng rng;
	long bad = 0;
	int i;

	tu_seed(&rng, 51);
	for (i = 0; i < N; i++) {
		int64_t a = tu_i64(&rng), b = tu_i64(&rng);
		int64_t v[3] = { tu_i64(&rng), tu_i64(&rng), tu_i64(&rng) };
		int64_t s1, c1, s2, c2;
		uint64_t hi = tu_u64(&rng) >> (1 + tu_u64(&rng) % 63), lo = tu_u64(&rng);
		uint32_t sat1 = 0, sat2 = 0;

		mot_sincos(a, &s1, &c1);
		trigp_sincos(a, &s2, &c2);
		bad += s1 != s2 || c1 != c2;
		bad += mot_atan2(a, b) != trigp_atan2(a, b);
		bad += mot_acos(a >> 30, &sat1) != trigp_acos(a >> 30, &sat2);
		bad += mot_sqrt(a, &sat1) != trigp_sqrt(a, &sat2);
		bad += mot_rsqrt(a, &sat1) != trigp_rsqrt(a, &sat2);
		bad += mot_isqrt_acc(mot_acc_make(hi, lo), &sat1) != trigp_isqrt(hi, lo, &sat2);
		bad += mot_norm3(v, &sat1) != trigp_norm3(v, &sat2);
		bad += sat1 != sat2;
	}
	/* every point of sin/cos's table, the unfolded one of 64-bit targets
	 * against the folded quarter wave, at both ends of its offsets */
	for (i = 0; i < 3 * 1024; i++) {
		int64_t a = ((int64_t)(i / 3) << 22) + (i % 3 - 1) * (((int64_t)1 << 21) - 1) +
			    ((int64_t)tu_i64(&rng) & ~(int64_t)0xffffffff);
		int64_t s1, c1, s2, c2;

		mot_sincos(a, &s1, &c1);
		trigp_sincos(a, &s2, &c2);
		bad += s1 != s2 || c1 != c2;
	}
	assert_int_equal(bad, 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sincos_accuracy), cmocka_unit_test(test_sincos_exact),
		cmocka_unit_test(test_sincos64),
		cmocka_unit_test(test_atan2_accuracy),  cmocka_unit_test(test_atan2_exact),
		cmocka_unit_test(test_atan2_unit),
		cmocka_unit_test(test_acos),            cmocka_unit_test(test_sqrt),
		cmocka_unit_test(test_isqrt_acc),       cmocka_unit_test(test_rsqrt),
#if MOT_HAVE_INT128
		cmocka_unit_test(test_isqrt_inv_unit),
#endif
		cmocka_unit_test(test_norm3),           cmocka_unit_test(test_portable_same_bits),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
