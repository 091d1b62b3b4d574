/* SPDX-License-Identifier: MIT */
/*
 * curve.c - scalar curves over keys (FORMULAS.md sections 5 to 8; see curve.h).
 *
 * Numbers. Frames and values are Q32.32. Curve parameters (s of a key
 * interval, u of a spline piece) are Q2.62 in [0, 1]. Every cubic is kept in
 * power form with int64 coefficients in block floating point: one scale 2^sh
 * per polynomial, chosen at init so that the coefficients' magnitudes add up
 * to at most 2^61. Horner's rule then needs one 64x64 product and one
 * rounding per degree, never overflows, and keeps ~60 significant bits
 * whether a segment spans a thousandth of a frame or a million frames. The
 * divisions (tangent ratios, basis denominators, reciprocals of widths) are
 * all done here at init; evaluation multiplies.
 *
 * Real time. mot_curve_eval() and mot_curve_integral() touch only the curve,
 * its keys and segments, and a small stack frame (bezier: 62 int64);
 * they allocate nothing, take no lock and run in bounded time: a segment
 * lookup is O(1) for a cursor that moved to the same or next segment and
 * O(log n) otherwise; the Newton solve of the approximating kinds stops
 * after at most NEWTON_MAX_IT iterations.
 */
#include "curve.h"

#include "trig_table.h" /* the seed of 1/x (mot_trig_recip_q14) */

#define ONE62 MOT_Q62_ONE

/* Newton start rules (seg->start). */
enum {
	START_CHORD, /* u0 = (f - f0) / (f1 - f0) */
	START_CUBE0, /* frame(u) = frame(0) + w u^3: u0 ~ cbrt of the chord fraction */
	START_CUBE1, /* frame(u) = frame(1) - w (1 - u)^3: mirrored */
};

/* ---- 128-bit and scaling helpers ----------------------------------------- */

static unsigned bitlen64(uint64_t x)
{
	return 64 - mot_clz64(x);
}

/* x * 2^n for 0 <= n < 128 (bits above 127 are lost: callers check). */
static mot_acc acc_shl(mot_acc x, unsigned n)
{
	uint64_t hi = mot_acc_hi(x), lo = mot_acc_lo(x);

	if (n == 0)
		return x;
	if (n >= 64)
		return mot_acc_make(lo << (n - 64), 0);
	return mot_acc_make((hi << n) | (lo >> (64 - n)), lo << n);
}

/* floor(x / 2^n) for 0 <= n < 128 (arithmetic shift). */
static mot_acc acc_sar(mot_acc x, unsigned n)
{
	uint64_t hi = mot_acc_hi(x), lo = mot_acc_lo(x);
	uint64_t sx = (int64_t)hi < 0 ? ~(uint64_t)0 : 0;

	if (n == 0)
		return x;
	if (n >= 64) {
		/* (int64_t)hi >> k without shifting a negative value: via sx */
		unsigned k = n - 64;
		uint64_t l = k ? (hi >> k) | (sx << (64 - k)) : hi;

		return mot_acc_make(sx, l);
	}
	return mot_acc_make((hi >> n) | (sx << (64 - n)), (lo >> n) | (hi << (64 - n)));
}

/* Bit length of |x| (x != -2^127). */
static unsigned acc_bitlen(mot_acc x)
{
	if (mot_acc_is_neg(x))
		x = mot_acc_neg(x);
	if (mot_acc_hi(x))
		return 64 + bitlen64(mot_acc_hi(x));
	return bitlen64(mot_acc_lo(x));
}

/* round(x / 2^sh), 128 bits in and out, -127 < sh < 127; a left shift
 * (sh < 0) must not overflow (callers bound it). */
static mot_acc acc_round_shift(mot_acc x, int sh)
{
	if (sh <= 0)
		return acc_shl(x, (unsigned)-sh);
	return acc_sar(mot_acc_add(x, acc_shl(mot_acc_from(1, 0), (unsigned)sh - 1)),
		       (unsigned)sh);
}

/* round(x / 2^sh) for an int64 x and any sh, saturating. */
static int64_t round_shift(int64_t x, int sh, uint32_t *sat)
{
	if (sh > 0)
		return sh >= 127 ? 0 : mot_acc_round(mot_acc_from(x, 0), (unsigned)sh, sat);
	if (sh < 0) {
		int64_t lim = sh > -63 ? INT64_MAX >> -sh : 0;

		if (x > lim || x < -lim - 1) {
			if (sat)
				*sat |= MOT_SAT_OVERFLOW;
			return x < 0 ? INT64_MIN : INT64_MAX;
		}
		return x * ((int64_t)1 << -sh);
	}
	return x;
}

/* ref + round(p / 2^sh), saturating only when the sum does not fit: p / 2^sh
 * alone may exceed int64 by a little where ref brings it back (a piece from
 * -2^62 to 2^62). */
static mot_q32 value_of_wide(mot_q32 ref, int64_t p, int sh, uint32_t *sat)
{
	mot_acc a;
	uint64_t lo;

	if (sh > -64)
		a = acc_round_shift(mot_acc_from(p, 0), sh);
	else
		a = p ? acc_shl(mot_acc_from(p, 0), 64) : mot_acc_zero();
	a = mot_acc_add(a, mot_acc_from(ref, 0));
	lo = mot_acc_lo(a);
	if (mot_acc_hi(a) != ((int64_t)lo < 0 ? ~(uint64_t)0 : 0)) {
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		return mot_acc_is_neg(a) ? MOT_Q32_MIN : MOT_Q32_MAX;
	}
	return (mot_q32)lo;
}

/* The same in int64 when nothing overflows: scales are positive and the
 * polynomials stay below 2^62, so this is the path every valid curve takes. */
static inline mot_q32 value_of(mot_q32 ref, int64_t p, int sh, uint32_t *sat)
{
	int64_t q;
	mot_q32 r;

	if (sh > 0 && sh < 63 && !__builtin_add_overflow(p, (int64_t)1 << (sh - 1), &q) &&
	    !__builtin_add_overflow(ref, q >> sh, &r))
		return r;
	return value_of_wide(ref, p, sh, sat);
}

/*
 * round(num * 2^sh / den) for den > 0, as int64 in *out. False when the
 * shifted numerator or the quotient would not fit (the prepared scales keep
 * quotients below 2^59). For sh < 0 the numerator is floored first: an error
 * below one unit of the result.
 */
static bool acc_div_round(int64_t *out, mot_acc num, int sh, uint64_t den)
{
	bool neg = mot_acc_is_neg(num);
	uint64_t q, r;

	if (neg)
		num = mot_acc_neg(num);
	if (sh > 0) {
		if (acc_bitlen(num) + (unsigned)sh > 126)
			return false;
		num = acc_shl(num, (unsigned)sh);
	} else if (sh < 0) {
		num = -sh >= 127 ? mot_acc_zero() : acc_sar(num, (unsigned)-sh);
	}
	if (mot_acc_hi(num) >= den)
		return false;
	q = mot_acc_udiv(num, den, &r, NULL);
	/* ties toward +infinity, as everywhere in the core */
	if (neg ? r > den - r : r >= den - r)
		q++;
	if (q > (uint64_t)INT64_MAX)
		return false;
	*out = neg ? -(int64_t)q : (int64_t)q;
	return true;
}

/* a * u / 2^62, rounded, for |u| <= 2^62 (so the result fits without a
 * saturation test): one Horner or de Casteljau step with u in Q2.62. */
static inline int64_t mul62(int64_t a, int64_t u)
{
	uint64_t ov = 0; /* |a u| < 2^125: the result fits */

	return mot_acc_round_ov(mot_acc_mul(a, u), 62, &ov);
}

/*
 * Block floating point for one cubic: c[p] = round(num[p] / den * 2^sh) with
 * sh chosen so that sum |c[p]| <= 2^60 + 2. |num[p] / den| < 2^(L - ld + 1)
 * with L the largest bit length of num[] and ld that of den, so the scale
 * sh = 57 - L + ld bounds every |c[p]| by 2^58. The same ratio num/den gives
 * the same sh and coefficients whatever the common factor (which is what
 * makes the beta spline with beta1 = 1, beta2 = 0 the B-spline bit for bit).
 */
static int poly_prep(int64_t c[4], int16_t *sh, const mot_acc num[4], uint64_t den)
{
	unsigned l = 0, p;
	int s;

	for (p = 0; p < 4; p++) {
		unsigned lp = acc_bitlen(num[p]);

		l = lp > l ? lp : l;
	}
	if (l == 0) {
		c[0] = c[1] = c[2] = c[3] = 0;
		*sh = 0;
		return MOT_OK;
	}
	s = 57 - (int)l + (int)bitlen64(den);
	for (p = 0; p < 4; p++)
		if (!acc_div_round(&c[p], num[p], s, den))
			return MOT_E_RANGE;
	*sh = (int16_t)s;
	return MOT_OK;
}

/* P(u) = c0 + u (c1 + u (c2 + u c3)); |partial sums| <= sum |c| <= 2^61. */
static inline int64_t poly_eval(const int64_t c[4], int64_t u)
{
	int64_t r = c[3];

	r = mul62(r, u) + c[2];
	r = mul62(r, u) + c[1];
	return mul62(r, u) + c[0];
}

/* P'(u) = c1 + u (2 c2 + u 3 c3); |partial sums| <= 3 * 2^61 < 2^63. */
static inline int64_t poly_deriv(const int64_t c[4], int64_t u)
{
	int64_t r = 3 * c[3];

	r = mul62(r, u) + 2 * c[2];
	return mul62(r, u) + c[1];
}

/* round(x * 2^62 / d) for the prepared reciprocal of d: the parameter in
 * Q2.62 of an offset x in [0, d]. (Only d = 1 has a shift of 30.) */
static inline int64_t frac62(int64_t x, const struct mot_recip *r)
{
	unsigned sh = r->shift - 30; /* 1 .. 63 past the test below */
	uint64_t ov = 0;             /* below 2^64 / 2^63: never set */
	int64_t s;

	if (r->shift <= 30)
		return x <= 0 ? 0 : ONE62;
	if (x <= 0)
		return 0;
	if ((uint64_t)x >> sh)
		return ONE62; /* x / d >= m / 2^62 >= 1 */
	/* round(x m / 2^sh) with x moved up to 63 bits: the shift of the
	 * rounding is then a constant */
	s = mot_acc_round_ov(mot_acc_mul(x * ((int64_t)1 << (63 - sh)), r->m), 63, &ov);
	return s > ONE62 ? ONE62 : s;
}

/* ---- segment lookup -------------------------------------------------------- */

/* The start frame of key interval j (keys) or of piece j. */
static inline mot_q32 start_of(const struct mot_curve *c, bool keys, uint32_t j)
{
	return keys ? c->keys[j].frame : c->seg[j].f0;
}

/* The start of interval or piece j + 1 (j + 1 < n): a piece's own f1, so
 * that the cursor's test reads one segment entry, not two. */
static inline mot_q32 end_of(const struct mot_curve *c, bool keys, uint32_t j)
{
	return keys ? c->keys[j + 1].frame : c->seg[j].f1;
}

/*
 * The last index j in [0, n) whose start is at or before f, given a
 * non-decreasing array of starts with start(0) <= f: the key intervals (n =
 * nkeys - 1) or the pieces (n = nseg). The hint (the cursor's last answer)
 * is tried first, then its successor; otherwise a binary search. A stale or
 * foreign hint costs only the search. Empty pieces (equal starts) are never
 * the answer.
 */
static uint32_t locate(const struct mot_curve *c, bool keys, uint32_t n, uint32_t hint, mot_q32 f)
{
	uint32_t lo = 0, hi = n;

	if (hint < n && start_of(c, keys, hint) <= f) {
		if (hint + 1 == n || f < end_of(c, keys, hint))
			return hint;
		if (hint + 2 == n || f < end_of(c, keys, hint + 1))
			return hint + 1;
		lo = hint + 2;
	}
	while (hi - lo > 1) {
		uint32_t mid = lo + (hi - lo) / 2;

		if (start_of(c, keys, mid) <= f)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}

static uint32_t locate_seg(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f)
{
	uint32_t j = locate(c, false, c->nseg, cur ? cur->seg : 0, f);

	if (cur)
		cur->seg = j;
	return j;
}

static uint32_t locate_key(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f)
{
	uint32_t i = locate(c, true, c->nkeys - 1, cur ? cur->key : 0, f);

	if (cur)
		cur->key = i;
	return i;
}

/* ---- the Newton solve of the approximating kinds ---------------------------- */

#define NEWTON_MAX_IT 64
#define NEWTON_TOL ((int64_t)1 << 31) /* 2^-31: a Newton step this small is the last */
#define BISECT_TOL ((int64_t)1 << 12) /* 2^-50: a bracket this narrow is the answer */

/*
 * q = r * 2^62 / d in Q2.62 for d > 0, to a relative 2^-30, with |q| < 2^62;
 * false when it would not fit. The reciprocal of d comes from Newton-Raphson
 * on its top 31 bits: trig.c's table of 1/x (within 2^-8), then two steps,
 * 2^-16 and 2^-32 (Hacker's Delight / Goldschmidt), products only. A Newton
 * step of the curve solve needs only a good direction and size, the solve's
 * own convergence makes up the rest, and no target has to divide at run
 * time. Each step is a dependent product chain in a latency-bound loop:
 * the table saves the third step of a linear seed.
 */
static bool ratio62(int64_t r, int64_t d, int64_t *q)
{
	unsigned n = mot_clz64((uint64_t)d);
	uint64_t y = ((uint64_t)d << n) >> 33; /* d = y 2^(33 - n), y in [2^30, 2^31) */
	/* 2^62 / y in Q31: the Q14 seed of 1 / (y / 2^31) */
	int64_t z = (int64_t)mot_trig_recip_q14[(y >> 22) & 255] << 17;
	mot_acc p;
	int it;

	/* e = 2^62 (1 - y z), |e| <= 2^54: z e / 2^62 in two shifts (>> of a
	 * negative int64 is arithmetic in gcc and clang, as fix.h relies on) */
	for (it = 0; it < 2; it++) {
		int64_t e = ((int64_t)1 << 62) - (int64_t)y * z;

		z += (z * (e >> 31)) >> 31;
	}
	/* r / d = r z 2^-62 2^(n - 33), so r / d in Q2.62 is r z 2^(n - 33) */
	p = mot_acc_mul(r, z);
	if (n < 33) {
		uint32_t ovf = 0;

		*q = mot_acc_round(p, 33 - n, &ovf);
		if (ovf)
			return false;
	} else {
		if (acc_bitlen(p) + (n - 33) > 62)
			return false;
		*q = (int64_t)mot_acc_lo(acc_shl(p, n - 33));
	}
	return *q > -ONE62 && *q < ONE62;
}

/* cbrt(x) for x in Q2.62 [0, 1], to about 1%: the Newton start on a piece
 * whose frame grows as u^3 (the tripled end keys). */
static int64_t cbrt62(int64_t x)
{
	static const int64_t k_third[3] = {
		ONE62, 3660297618499336453, 2905180145061270980, /* 2^(-r/3) */
	};
	unsigned e, q, r;
	int64_t m, g;

	if (x <= 0)
		return 0;
	e = 63 - bitlen64((uint64_t)x); /* x = (1 + m) 2^-e, m in [0, 1) */
	q = e / 3;
	r = e % 3;
	m = (int64_t)((uint64_t)x << e) - ONE62;
	g = ONE62 + mul62(m, 1198674271695154057); /* cbrt(1 + m) ~ 1 + m (2^(1/3) - 1) */
	return mul62(g, k_third[r]) >> q;
}

struct solve {
	const struct mot_curve *c;
	const struct mot_curve_seg *s;
	int64_t d;        /* target: frame - fref, scaled by 2^fsh */
	int it;           /* iterations taken (mot_curve_newton_iterations) */
	const int64_t *pw; /* bezier in power form: the coefficients, else NULL */
};

/*
 * Bezier in power form. With x_i the offsets of the keys from the first,
 *     B(u) = sum x_i C(m, i) u^i (1 - u)^(m - i) = sum a_k u^k,
 *     a_k = C(m, k) Delta^k x_0,     m = n - 1, a_0 = 0,
 * (Delta^k: the k-th forward difference), so Horner's rule gives the frame
 * and its derivative for 2m - 1 products and the value for m, where de
 * Casteljau's algorithm takes m (m + 1) / 2 for each. The power form is
 * ill-conditioned: sum |a_k| can reach 3^m max |x_i| while the curve stays
 * within max |x_i|, and Horner's rounding is relative to sum |a_k|. So the
 * coefficients are kept as exact integers (raw Q32.32 units) scaled by 2^sh,
 * sum k |a_k| 2^sh < 2^61 for the frame (its derivative's partial sums too)
 * and sum |a_k| 2^sh < 2^61 for the value, and the form is used only when
 * sh >= 8: Horner's m roundings of half a unit stay below 1/16 LSB. Other
 * curves (many keys, or keys far apart: 12 keys over +-1000 units, 32 keys
 * of any size) keep de Casteljau. The coefficients live in the c[] and
 * fc[] of the curve's entries, which a Bezier curve does not otherwise use:
 * the frame's a_1 .. a_m in slots 0 .. m - 1, the value's in m .. 2m - 1
 * (the n - 1 entries hold 8 (n - 1) >= 2m slots).
 */
#define POWER_MIN_SHIFT 8

static inline int64_t *power_slot(const struct mot_curve *c, uint32_t j)
{
	struct mot_curve_seg *s = &c->seg[j / 8];

	return j % 8 < 4 ? &s->c[j % 4] : &s->fc[j % 4];
}

static void power_frame(const int64_t *a, uint32_t m, int64_t u, int64_t *f, int64_t *df)
{
	int64_t r = a[m - 1], d = (int64_t)m * a[m - 1];
	uint32_t k;

	for (k = m - 1; k >= 1; k--) {
		r = mul62(r, u) + a[k - 1];
		d = mul62(d, u) + (int64_t)k * a[k - 1];
	}
	*f = mul62(r, u);
	*df = d;
}

static int64_t power_value(const int64_t *a, uint32_t m, int64_t u)
{
	int64_t r = a[m - 1];
	uint32_t k;

	for (k = m - 1; k >= 1; k--)
		r = mul62(r, u) + a[k - 1];
	return mul62(r, u);
}

/* Bezier: de Casteljau at u on the keys' frames (or values) relative to the
 * first key, scaled by 2^fsh (2^vsh), until `left` points remain in w[]. */
static void bezier_reduce(const struct mot_curve *c, bool value, int64_t u, uint32_t left,
			  int64_t w[MOT_BEZIER_MAX_KEYS])
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, i, r;
	int sh = value ? c->seg[0].vsh : c->seg[0].fsh;

	/* the offsets are below 2^(58 - sh) (bezier_shift): no overflow */
	for (i = 0; i < n; i++) {
		int64_t x = value ? k[i].value - k[0].value : k[i].frame - k[0].frame;

		w[i] = sh >= 0 ? x * ((int64_t)1 << sh) : round_shift(x, -sh, NULL);
	}
	for (r = n - 1; r >= left; r--)
		for (i = 0; i < r; i++)
			w[i] += mul62(w[i + 1] - w[i], u);
}

/* The frame and its derivative (from the last two points). */
static void bezier_frame(const struct mot_curve *c, int64_t u, int64_t *f, int64_t *df)
{
	int64_t w[MOT_BEZIER_MAX_KEYS];

	bezier_reduce(c, false, u, 2, w);
	*f = w[0] + mul62(w[1] - w[0], u);
	*df = (int64_t)(c->nkeys - 1) * (w[1] - w[0]);
}

static int64_t bezier_value(const struct mot_curve *c, int64_t u, uint32_t *sat)
{
	int64_t w[MOT_BEZIER_MAX_KEYS];

	bezier_reduce(c, true, u, 1, w);
	return value_of(c->keys[0].value, w[0], c->seg[0].vsh, sat);
}

/*
 * Solve frame(u) = f on one piece: safeguarded Newton (rtsafe, Numerical
 * Recipes 9.4). The bracket [lo, hi] starts as [0, 1] and shrinks to the
 * evaluated points on either side of the root; a Newton step that leaves it,
 * or that does not halve the step before last, is replaced by bisection. An
 * end of [0, 1] that has not been evaluated may be stepped to, so a root
 * that rounding put just outside the piece ends there after one step instead
 * of after fifty bisections. frame'(u) is zero at the tripled end keys, which
 * is why the safeguard matters, and why those pieces start from a cube root.
 *
 * Determinism: the start is a function of f alone (the chord fraction, or its
 * cube root), the iteration is pure integer arithmetic and the stopping rule
 * is fixed: stop after a Newton step below 2^-31 (the error is then about
 * the square of it) or once the bracket is narrower than 2^-50, or after
 * NEWTON_MAX_IT iterations. Random and sequential access therefore give the
 * same u, bit for bit, on every target.
 */
static int64_t solve_u(struct solve *sv, int64_t u)
{
	const struct mot_curve_seg *s = sv->s;
	bool bezier = sv->c->kind == MOT_INTERP_BEZIER;
	bool lo_known = false, hi_known = false;
	int64_t lo = 0, hi = ONE62, dx = ONE62, dxold = ONE62;

	for (sv->it = 1; sv->it <= NEWTON_MAX_IT; sv->it++) {
		int64_t f, df, du = 0, un = 0, tol;
		bool newton;

		if (sv->pw) {
			power_frame(sv->pw, sv->c->nkeys - 1, u, &f, &df);
		} else if (bezier) {
			bezier_frame(sv->c, u, &f, &df);
		} else {
			f = poly_eval(s->fc, u);
			df = poly_deriv(s->fc, u);
		}
		f -= sv->d;
		if (f == 0)
			return u;
		if (f < 0) {
			lo = u;
			lo_known = true;
		} else {
			hi = u;
			hi_known = true;
		}
		if (lo >= hi) /* the root lies beyond an end of the piece */
			return u;
		newton = df > 0 && ratio62(f, df, &du);
		if (newton) {
			/* rtsafe's progress test: |du| at most half the step before last */
			if (du > dxold / 2 || du < -(dxold / 2))
				newton = false;
			un = u - du;
			if (un <= lo) {
				newton = newton && !lo_known;
				un = lo;
			} else if (un >= hi) {
				newton = newton && !hi_known;
				un = hi;
			}
		}
		dxold = dx;
		if (newton) {
			dx = u - un;
			if (dx < 0)
				dx = -dx;
			tol = NEWTON_TOL;
		} else {
			dx = (hi - lo) / 2;
			un = lo + dx;
			tol = BISECT_TOL;
		}
		if (dx <= tol)
			return un;
		u = un;
	}
	sv->it = NEWTON_MAX_IT;
	return u;
}

/* Value of an approximating curve at a (warped) frame strictly inside the
 * span; *iters: the Newton iterations it took. */
static mot_q32 approx_eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f,
			   int *iters, uint32_t *sat)
{
	const struct mot_curve_seg *s;
	struct solve sv;
	int64_t u, pw[2 * (MOT_BEZIER_MAX_KEYS - 1)];
	uint32_t m = c->nkeys - 1, j;

	sv.c = c;
	sv.pw = NULL;
	if (c->kind == MOT_INTERP_BEZIER) {
		s = &c->seg[0];
		if (c->power) {
			/* contiguous for the iterations */
			for (j = 0; j < 2 * m; j++)
				pw[j] = *power_slot(c, j);
			sv.pw = pw;
		}
	} else {
		s = &c->seg[locate_seg(c, cur, f)];
	}
	sv.s = s;
	sv.d = round_shift(f - s->fref, -s->fsh, NULL);
	u = frac62(f - s->f0, &s->inv_w);
	if (s->start == START_CUBE0)
		u = cbrt62(u);
	else if (s->start == START_CUBE1)
		u = ONE62 - cbrt62(ONE62 - u);
	u = solve_u(&sv, u);
	*iters = sv.it;
	if (sv.pw)
		return value_of(s->vref, power_value(pw + m, m, u), s->vsh, sat);
	if (c->kind == MOT_INTERP_BEZIER)
		return bezier_value(c, u, sat);
	return value_of(s->vref, poly_eval(s->c, u), s->vsh, sat);
}

/* ---- evaluation -------------------------------------------------------------- */

/* The strand-wide time warp: a frame strictly inside the span to its eased
 * frame, in [span_f0, span_f1]. */
static mot_q32 span_warp(const struct mot_curve *c, mot_q32 f)
{
	int64_t s = frac62(f - c->span_f0, &c->span_inv);

	s = mot_ease_apply62(&c->span, s);
	return c->span_f0 + mot_acc_round(mot_acc_mul(s, c->span_f1 - c->span_f0), 62, NULL);
}

static inline __attribute__((always_inline)) mot_q32
eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 frame, int *iters, uint32_t *sat)
{
	const struct mot_key *k;
	const struct mot_curve_seg *s;
	uint32_t n;
	int64_t u;

	if (!c || c->nkeys == 0) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN;
		return 0;
	}
	k = c->keys;
	n = c->nkeys;
	if (frame <= c->span_f0)
		return k[0].value;
	if (frame >= c->span_f1)
		return k[n - 1].value;
	if (c->span_ease) {
		frame = span_warp(c, frame);
		if (frame <= c->span_f0)
			return k[0].value;
		if (frame >= c->span_f1)
			return k[n - 1].value;
	}
	if (c->kind >= MOT_INTERP_BSPLINE) {
		if (c->seg_ease) {
			/* the key interval's warp, in frames, before the solve */
			uint32_t i = locate_key(c, cur, frame);

			s = &c->seg[i];
			if (!mot_ease_is_identity(&s->ease)) {
				int64_t h = k[i + 1].frame - k[i].frame;

				u = frac62(frame - k[i].frame, &s->inv_h);
				u = mot_ease_apply62(&s->ease, u);
				frame = k[i].frame + mot_acc_round(mot_acc_mul(u, h), 62, NULL);
				if (frame <= c->span_f0)
					return k[0].value;
				if (frame >= c->span_f1)
					return k[n - 1].value;
			}
		}
		return approx_eval(c, cur, frame, iters, sat);
	}
	s = &c->seg[locate_seg(c, cur, frame)];
	if (c->kind == MOT_INTERP_STEP)
		return s->vref;
	u = frac62(frame - s->f0, &s->inv_w);
	if (c->seg_ease && !mot_ease_is_identity(&s->ease))
		u = mot_ease_apply62(&s->ease, u);
	if (c->kind == MOT_INTERP_LINEAR)
		return value_of(s->vref, mul62(s->c[1], u), s->vsh, sat);
	return value_of(s->vref, poly_eval(s->c, u), s->vsh, sat);
}

mot_q32 mot_curve_eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 frame,
		       uint32_t *sat)
{
	int iters;

	return eval(c, cur, frame, &iters, sat);
}

int mot_curve_newton_iterations(const struct mot_curve *c, mot_q32 frame)
{
	int iters = 0;

	eval(c, NULL, frame, &iters, NULL);
	return iters;
}

/* ---- integral -------------------------------------------------------------------- */

/*
 * Integral over [f0, f0 + e] of interpolating piece s, 0 <= e <= f1 - f0, in
 * value x frames, Q64.64 (FORMULAS section 8). With s = e / h:
 *   step:     e v0                                  exact
 *   linear:   e v0 + dv e^2 / (2h)                  exact but for one rounding:
 *             e^2 / h = q + r / h and dv r / h = q2 + r2 / h, two exact divisions
 *   hermite:  e (v0 + sum c_p s^p / (p + 1))        the mean value in the block
 *             scale of c (~2^-59 of sum |c_p|), times e in 128 bits
 */
static mot_acc seg_integral(const struct mot_curve *c, uint32_t i, int64_t e, int64_t s62)
{
	const struct mot_curve_seg *s = &c->seg[i];
	mot_acc a = mot_acc_mul(e, s->vref);

	if (c->kind == MOT_INTERP_LINEAR) {
		/* |dv| < 2^63 and 0 <= e <= h < 2^63 (curve.h limits), so every
		 * quotient below fits 63 bits */
		int64_t h = s->f1 - s->f0, dv = c->keys[i + 1].value - s->vref;
		int64_t adv = dv < 0 ? -dv : dv;
		uint64_t r, r2, q, q2;
		mot_acc t;

		q = mot_acc_udiv(mot_acc_mul(e, e), (uint64_t)h, &r, NULL);
		q2 = mot_acc_udiv(mot_acc_mul(adv, (int64_t)r), (uint64_t)h, &r2, NULL);
		t = mot_acc_add(mot_acc_mul(adv, (int64_t)q), mot_acc_from((int64_t)q2, 0));
		/* half of t + r2/h, rounded to nearest, ties toward +infinity */
		if (dv >= 0)
			t = acc_sar(mot_acc_add(t, mot_acc_from(1, 0)), 1);
		else
			t = mot_acc_neg(acc_sar(mot_acc_add(t, mot_acc_from(r2 != 0, 0)), 1));
		return mot_acc_add(a, t);
	}
	if (c->kind == MOT_INTERP_HERMITE)
		a = mot_acc_add(a, acc_round_shift(mot_acc_mul(e, poly_eval(s->ic, s62)), s->fsh));
	return a;
}

int mot_curve_integral(mot_acc *out, const struct mot_curve *c, struct mot_cursor *cur,
		       mot_q32 frame, uint32_t *sat)
{
	const struct mot_key *k;
	uint32_t n, i;
	mot_acc a;

	if (!out)
		return MOT_E_INVAL;
	*out = mot_acc_zero();
	if (!c || !c->integral || c->nkeys == 0)
		return MOT_E_INVAL;
	k = c->keys;
	n = c->nkeys;
	/* Held ends: the integral grows linearly, exactly (two 128-bit products). */
	if (frame < k[0].frame) {
		a = mot_acc_sub(mot_acc_mul(k[0].value, frame),
				mot_acc_mul(k[0].value, k[0].frame));
		*out = mot_acc_add(c->area_first, a);
		return MOT_OK;
	}
	if (frame >= k[n - 1].frame) {
		a = mot_acc_sub(mot_acc_mul(k[n - 1].value, frame),
				mot_acc_mul(k[n - 1].value, k[n - 1].frame));
		*out = mot_acc_add(c->area_last, a);
		return MOT_OK;
	}
	i = locate_seg(c, cur, frame);
	a = seg_integral(c, i, frame - c->seg[i].f0,
			 frac62(frame - c->seg[i].f0, &c->seg[i].inv_w));
	*out = mot_acc_add(c->seg[i].area, a);
	return MOT_OK;
}

/* ---- preparation ------------------------------------------------------------------- */

uint32_t mot_curve_seg_count(enum mot_interp kind, uint32_t nkeys)
{
	if (nkeys == 0)
		return 0;
	switch (kind) {
	case MOT_INTERP_STEP:
	case MOT_INTERP_LINEAR:
	case MOT_INTERP_HERMITE:
	case MOT_INTERP_BEZIER:
		/* one per key interval (bezier: the key intervals carry the ease) */
		return nkeys > 1 ? nkeys - 1 : 1;
	case MOT_INTERP_BSPLINE:
	case MOT_INTERP_BETA:
		/* n + 4 control points with the ends tripled: n + 1 cubics */
		return nkeys == 1 ? 1 : nkeys < UINT32_MAX ? nkeys + 1 : 0;
	}
	return 0;
}

/* dv h / d at scale 2^58, rounded once (|dv| < 2^63, 0 < h <= d): a
 * Catmull-Rom tangent term h m = h dv / d. The integer part is an exact
 * division, the fraction a second one. */
static mot_acc tangent58(int64_t dv, int64_t h, int64_t d)
{
	int64_t adv = dv < 0 ? -dv : dv, fr = 0;
	uint64_t r, q = mot_acc_udiv(mot_acc_mul(adv, h), (uint64_t)d, &r, NULL);
	mot_acc t = acc_shl(mot_acc_from((int64_t)q, 0), 58);

	acc_div_round(&fr, mot_acc_from(dv < 0 ? -(int64_t)r : (int64_t)r, 0), 58, (uint64_t)d);
	return mot_acc_add(dv < 0 ? mot_acc_neg(t) : t, mot_acc_from(fr, 0));
}

static mot_acc acc_times(mot_acc x, unsigned k)
{
	mot_acc r = mot_acc_zero();

	while (k--)
		r = mot_acc_add(r, x);
	return r;
}

/* Hermite piece i: numerators of c[] in powers of s relative to v(i), at
 * scale 2^58 (FORMULAS section 6): the tangent terms h m(i), h m(i+1) with
 * the chord of each tangent (one-sided at the ends), then
 *   c1 = h m(i), c2 = 3 dv - 2 h m(i) - h m(i+1), c3 = -2 dv + h m(i) + h m(i+1).
 * Every term is below 2^121, every sum below 2^124. */
static void prep_hermite(const struct mot_curve *c, uint32_t i, mot_acc num[4], uint64_t *den)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, t;
	int64_t h = k[i + 1].frame - k[i].frame;
	mot_acc tm[2], d58 = acc_shl(mot_acc_from(k[i + 1].value - k[i].value, 0), 58);

	for (t = 0; t < 2; t++) {
		uint32_t j = i + t, a = j == 0 ? 0 : j - 1, b = j == n - 1 ? j : j + 1;

		tm[t] = tangent58(k[b].value - k[a].value, h, k[b].frame - k[a].frame);
	}
	num[0] = mot_acc_zero();
	num[1] = tm[0];
	num[2] = mot_acc_sub(acc_times(d58, 3), mot_acc_add(acc_times(tm[0], 2), tm[1]));
	num[3] = mot_acc_sub(mot_acc_add(tm[0], tm[1]), acc_times(d58, 2));
	*den = (uint64_t)1 << 58;
}

/* x * y for 0 <= x < 2^127, 0 <= y < 2^63, when the product fits 127 bits. */
static mot_acc acc_mul_u(mot_acc x, int64_t y)
{
	uint64_t lo = mot_acc_lo(x);
	mot_acc r = acc_shl(mot_acc_mul((int64_t)mot_acc_hi(x), y), 64);

	r = mot_acc_add(r, acc_shl(mot_acc_mul((int64_t)(lo >> 32), y), 32));
	return mot_acc_add(r, mot_acc_mul((int64_t)(lo & 0xffffffffu), y));
}

/*
 * The cubic basis of the uniform B-spline and of Barsky's Beta-spline
 * (FORMULAS section 6), as the power-form weights N[k][p] of control points
 * V(i-1+k) on u^p over a common denominator den. Expanding the section's
 * b(-1)..b(2) with T3 = 2 beta1^3, T2 = 2 beta1^2, T1 = 2 beta1:
 *   b(-1) = T3 (1 - 3u + 3u^2 - u^3)
 *   b(0)  = (2 T2 + 2 T1 + beta2) + 3 (T3 - T1) u - 3 (T3 + T2 + beta2) u^2
 *           + (T3 + T2 + T1 + 2 beta2) u^3
 *   b(1)  = 2 + 3 T1 u + 3 (T2 + beta2) u^2 - (T2 + T1 + 2 beta2 + 2) u^3
 *   b(2)  = 2 u^3,        den = delta = T3 + 2 T2 + 2 T1 + beta2 + 2.
 * For the Beta-spline everything is first formed exactly at scale 2^96 in
 * 128 bits (beta1 in Q32.32 has a cube in Q32.96), then rounded once to a
 * common scale that keeps the largest entry below 2^60: ~60 significant bits,
 * where rounding beta1^3 to Q32.32 would change a curve by tens of LSB.
 * Column u^0 must sum to den and the others to 0 for the curve to keep its
 * partition of unity and start and end exactly on the tripled keys, so b(1)'s
 * row is formed last as what the others leave; b(-1) stays T3 times
 * (1, -3, 3, -1), so the last piece is an exact cube. beta1 = 1, beta2 = 0
 * gives 2^k times the B-spline's integer matrix (den 6).
 */
static void basis(const struct mot_curve *c, int64_t nb[4][4], uint64_t *den)
{
	static const int8_t bsp[4][4] = {
		{ 1, -3, 3, -1 }, { 4, 0, -6, 3 }, { 1, 3, 3, -3 }, { 0, 0, 0, 1 },
	};
	mot_acc b1sq, t3, t2, t1, b2, two, d, r1[4];
	unsigned k, p, sh;

	if (c->kind == MOT_INTERP_BSPLINE) {
		for (k = 0; k < 4; k++)
			for (p = 0; p < 4; p++)
				nb[k][p] = bsp[k][p] * MOT_Q32_ONE;
		*den = 6 * (uint64_t)MOT_Q32_ONE;
		return;
	}
	/* beta1 <= 2^40 raw, beta2 <= 2^56 raw: every term below is < 2^124 */
	b1sq = mot_acc_mul(c->beta1, c->beta1);
	t3 = acc_shl(acc_mul_u(b1sq, c->beta1), 1);
	t2 = acc_shl(b1sq, 33);
	t1 = acc_shl(mot_acc_from(c->beta1, 0), 65);
	b2 = acc_shl(mot_acc_from(c->beta2, 0), 64);
	two = acc_shl(mot_acc_from(1, 0), 97);
	/* den = T3 + 2 T2 + 2 T1 + beta2 + 2 */
	d = mot_acc_add(mot_acc_add(t3, acc_shl(mot_acc_add(t2, t1), 1)), mot_acc_add(b2, two));
	/* b(0): 2 T2 + 2 T1 + beta2, 3 (T3 - T1), -3 (T3 + T2 + beta2), T3 + T2 + T1 + 2 beta2 */
	r1[0] = mot_acc_add(acc_shl(mot_acc_add(t2, t1), 1), b2);
	r1[1] = mot_acc_sub(t3, t1);
	r1[1] = mot_acc_add(acc_shl(r1[1], 1), r1[1]);
	r1[2] = mot_acc_neg(mot_acc_add(mot_acc_add(t3, t2), b2));
	r1[2] = mot_acc_add(acc_shl(r1[2], 1), r1[2]);
	r1[3] = mot_acc_add(mot_acc_add(mot_acc_add(t3, t2), t1), acc_shl(b2, 1));
	sh = acc_bitlen(d) > 60 ? acc_bitlen(d) - 60 : 0; /* den is the largest but for 3 x */
	sh += 2;
	nb[0][0] = (int64_t)mot_acc_lo(acc_round_shift(t3, (int)sh));
	nb[0][1] = -3 * nb[0][0];
	nb[0][2] = 3 * nb[0][0];
	nb[0][3] = -nb[0][0];
	for (p = 0; p < 4; p++) {
		nb[1][p] = (int64_t)mot_acc_lo(acc_round_shift(r1[p], (int)sh));
		nb[3][p] = p == 3 ? (int64_t)mot_acc_lo(acc_round_shift(two, (int)sh)) : 0;
	}
	*den = mot_acc_lo(acc_round_shift(d, (int)sh));
	for (p = 0; p < 4; p++)
		nb[2][p] = (p == 0 ? (int64_t)*den : 0) - nb[0][p] - nb[1][p] - nb[3][p];
}

/* Spline piece j on the extended control points E(j)..E(j+3), E(m) = key
 * clamp(m - 2, 0, n - 1): both polynomials relative to E(j+1), their frame
 * interval [f0, ...) and the Newton start rule. */
static int prep_spline(struct mot_curve *c, uint32_t j, int64_t nb[4][4], uint64_t den)
{
	const struct mot_key *k = c->keys;
	struct mot_curve_seg *s = &c->seg[j];
	int64_t n1 = (int64_t)c->nkeys - 1, df[4], dv[4], f0;
	mot_acc nf[4], nv[4];
	unsigned p, m;
	int err;

	for (m = 0; m < 4; m++) {
		int64_t e = (int64_t)j + m - 2;
		const struct mot_key *km = &k[e < 0 ? 0 : e > n1 ? n1 : e];

		if (m == 0) {
			/* the reference point E(j+1) */
			const struct mot_key *kr = &k[e + 1 < 0 ? 0 : e + 1 > n1 ? n1 : e + 1];

			s->fref = kr->frame;
			s->vref = kr->value;
		}

		df[m] = km->frame - s->fref;
		dv[m] = km->value - s->vref;
	}
	for (p = 0; p < 4; p++) {
		nf[p] = nv[p] = mot_acc_zero();
		for (m = 0; m < 4; m++) {
			nf[p] = mot_acc_mac(nf[p], nb[m][p], df[m]);
			nv[p] = mot_acc_mac(nv[p], nb[m][p], dv[m]);
		}
	}
	err = poly_prep(s->fc, &s->fsh, nf, den);
	if (!err)
		err = poly_prep(s->c, &s->vsh, nv, den);
	if (err || !acc_div_round(&f0, nf[0], 0, den))
		return MOT_E_RANGE;
	/* The piece starts at ceil(frame(0)): a frame f in [ceil(F(0)),
	 * ceil(F(1))) has its root inside [0, 1), even when the piece is a few
	 * LSB wide (rounding to nearest would put it up to half an LSB of frame
	 * outside, and the solve would clamp). */
	{
		mot_acc rest = mot_acc_sub(nf[0], mot_acc_mul(f0, (int64_t)den)); /* F(0) - f0 */

		if (!mot_acc_is_neg(rest) && acc_bitlen(rest) != 0)
			f0++;
	}
	s->f0 = s->fref + f0;
	s->start = START_CHORD;
	/* frame(u) - frame(0) = w u^3, or frame(1) - frame(u) = w (1 - u)^3, tested
	 * on the exact numerators: the first and last piece (and every piece of a
	 * beta spline with beta1 = 0, beta2 = 0). */
	{
		mot_acc n3 = mot_acc_add(mot_acc_add(nf[3], nf[3]), nf[3]);

		if (acc_bitlen(nf[1]) == 0 && acc_bitlen(nf[2]) == 0)
			s->start = START_CUBE0;
		else if (acc_bitlen(mot_acc_sub(nf[1], n3)) == 0 &&
			 acc_bitlen(mot_acc_add(nf[2], n3)) == 0)
			s->start = START_CUBE1;
	}
	return MOT_OK;
}

/* Bezier: scales that keep the key offsets from the first key within 2^58:
 * de Casteljau differences are then within 2^59, and the frame derivative
 * (n - 1) (w1 - w0) within 31 * 2^58 < 2^63. */
static int bezier_shift(int64_t maxdiff)
{
	return maxdiff == 0 ? 0 : 58 - (int)bitlen64((uint64_t)maxdiff);
}

/* The power form of a Bezier curve when it keeps its precision (see
 * power_frame): exact coefficients and their scales, or c->power false. */
static void prep_power(struct mot_curve *c)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, m = n - 1, i, j, side;
	int64_t a[2][MOT_BEZIER_MAX_KEYS - 1];
	unsigned len[2];

	c->power = false;
	for (side = 0; side < 2; side++) {
		mot_acc d[MOT_BEZIER_MAX_KEYS];
		uint64_t b = 1, sum = 0;

		for (i = 0; i < n; i++)
			d[i] = mot_acc_from(side ? k[i].value - k[0].value
						 : k[i].frame - k[0].frame, 0);
		for (j = 1; j <= m; j++) {
			/* d[0] = Delta^j x_0 (|.| < 2^(63 + j)), b = C(m, j) */
			for (i = 0; i + j < n; i++)
				d[i] = mot_acc_sub(d[i + 1], d[i]);
			b = b * (m - j + 1) / j;
			if (acc_bitlen(d[0]) + bitlen64(b) > 54)
				return; /* |a_j| may reach 2^54: out of the form's range */
			a[side][j - 1] = (int64_t)mot_acc_lo(d[0]) * (int64_t)b;
			/* below 32 * 31 * 2^54 */
			sum += (side ? 1 : j) * (uint64_t)mot_abs(a[side][j - 1]);
		}
		len[side] = bitlen64(sum);
		if (len[side] > 61 - POWER_MIN_SHIFT)
			return;
	}
	for (side = 0; side < 2; side++) {
		int sh = 61 - (int)len[side];

		for (j = 0; j < m; j++) {
			uint32_t slot = side * m + j;

			*power_slot(c, slot) = a[side][j] * ((int64_t)1 << sh);
		}
		if (side)
			c->seg[0].vsh = (int16_t)sh;
		else
			c->seg[0].fsh = (int16_t)sh;
	}
	c->power = true;
}

static int prep_bezier(struct mot_curve *c)
{
	const struct mot_key *k = c->keys;
	struct mot_curve_seg *s = &c->seg[0];
	int64_t dv = 0;
	uint32_t i;

	for (i = 1; i < c->nkeys; i++) {
		int64_t d = k[i].value - k[0].value;

		d = d < 0 ? -d : d;
		dv = d > dv ? d : dv;
	}
	s->fsh = (int16_t)bezier_shift(k[c->nkeys - 1].frame - k[0].frame);
	s->vsh = (int16_t)bezier_shift(dv);
	s->fref = s->f0 = k[0].frame;
	s->vref = k[0].value;
	s->f1 = k[c->nkeys - 1].frame;
	s->start = START_CHORD;
	prep_power(c);
	return mot_recip_init(&s->inv_w, s->f1 - s->f0);
}

static int prep_pieces(struct mot_curve *c)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, j, p;
	int err = MOT_OK;

	if (n == 1)
		return MOT_OK;
	if (c->kind == MOT_INTERP_BEZIER)
		return prep_bezier(c);
	if (c->kind >= MOT_INTERP_BSPLINE) {
		int64_t nb[4][4];
		uint64_t den;

		basis(c, nb, &den);
		for (j = 0; j < c->nseg && !err; j++)
			err = prep_spline(c, j, nb, den);
		for (j = 0; j < c->nseg && !err; j++) {
			struct mot_curve_seg *s = &c->seg[j];

			s->f1 = j + 1 < c->nseg ? c->seg[j + 1].f0 : k[n - 1].frame;
			if (s->f1 > s->f0)
				err = mot_recip_init(&s->inv_w, s->f1 - s->f0);
		}
		return err;
	}
	for (j = 0; j < n - 1 && !err; j++) {
		struct mot_curve_seg *s = &c->seg[j];
		mot_acc num[4];
		uint64_t den = 1;

		s->f0 = s->fref = k[j].frame;
		s->f1 = k[j + 1].frame;
		s->vref = k[j].value;
		s->start = START_CHORD;
		err = mot_recip_init(&s->inv_w, s->f1 - s->f0);
		num[0] = num[1] = num[2] = num[3] = mot_acc_zero();
		if (c->kind == MOT_INTERP_LINEAR)
			num[1] = mot_acc_from(k[j + 1].value - k[j].value, 0);
		else if (c->kind == MOT_INTERP_HERMITE)
			prep_hermite(c, j, num, &den);
		err = err ? err : poly_prep(s->c, &s->vsh, num, den);
		if (!err && c->kind == MOT_INTERP_HERMITE) {
			/* the mean value, c[p] / (p + 1), in its own block scale:
			 * numerators 12 / (p + 1) times c's over 12 den (< 2^127) */
			mot_acc im[4];

			im[0] = mot_acc_zero();
			for (p = 1; p < 4; p++)
				im[p] = acc_times(num[p], 12 / (p + 1));
			err = poly_prep(s->ic, &s->fsh, im, 12 * den);
		}
	}
	return err;
}

/* Running integrals: area of piece j = integral from frame 0 to key j. Built
 * from the first key with the same function the run time uses, then shifted
 * so that the integral at frame 0 is 0 exactly. */
static int prep_area(struct mot_curve *c)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, j;
	mot_acc a = mot_acc_zero(), zero;

	c->area_first = a;
	for (j = 0; j + 1 < n; j++) {
		c->seg[j].area = a;
		a = mot_acc_add(a, seg_integral(c, j, k[j + 1].frame - k[j].frame, ONE62));
		if (acc_bitlen(a) > 124)
			return MOT_E_RANGE;
	}
	c->area_last = a;
	mot_curve_integral(&zero, c, NULL, 0, NULL);
	zero = mot_acc_neg(zero);
	c->area_first = mot_acc_add(c->area_first, zero);
	c->area_last = mot_acc_add(c->area_last, zero);
	for (j = 0; j + 1 < n; j++)
		c->seg[j].area = mot_acc_add(c->seg[j].area, zero);
	if (acc_bitlen(c->area_first) > 124 || acc_bitlen(c->area_last) > 124)
		return MOT_E_RANGE;
	return MOT_OK;
}

static bool in_unit(mot_q32 x)
{
	return x >= 0 && x <= MOT_Q32_ONE;
}

/* The checks of curve.h, in its order of precedence. */
static int check(const struct mot_curve *c, const struct mot_curve_opts *o, uint32_t nseg)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, i;

	if (c->kind == MOT_INTERP_BEZIER && n > MOT_BEZIER_MAX_KEYS)
		return MOT_E_CAPACITY;
	if (!c->seg || nseg < mot_curve_seg_count(c->kind, n))
		return MOT_E_CAPACITY;
	for (i = 0; i < n; i++) {
		if (mot_abs(k[i].frame) >= MOT_LEN_LIMIT || mot_abs(k[i].value) >= MOT_LEN_LIMIT)
			return MOT_E_RANGE;
		if (i > 0 && k[i].frame <= k[i - 1].frame)
			return MOT_E_ORDER;
	}
	for (i = 0; i < n; i++) {
		if (!in_unit(k[i].ease_in) || !in_unit(k[i].ease_out))
			return MOT_E_INVAL;
		if (i + 1 < n && k[i].ease_out > MOT_Q32_ONE - k[i + 1].ease_in)
			return MOT_E_INVAL;
	}
	if (o->ease_in_frames < 0 || o->ease_out_frames < 0 ||
	    o->ease_in_frames > k[n - 1].frame - k[0].frame ||
	    o->ease_out_frames > k[n - 1].frame - k[0].frame - o->ease_in_frames)
		return MOT_E_INVAL;
	if (c->kind == MOT_INTERP_BETA &&
	    (o->beta1 < 0 || o->beta1 > MOT_BETA1_MAX || o->beta2 < 0 || o->beta2 > MOT_BETA2_MAX))
		return MOT_E_INVAL;
	return MOT_OK;
}

int mot_curve_init(struct mot_curve *c, enum mot_interp kind, const struct mot_key *keys,
		   uint32_t nkeys, const struct mot_curve_opts *opts, struct mot_curve_seg *seg,
		   uint32_t nseg, uint32_t *sat)
{
	static const struct mot_curve_opts defaults = { MOT_Q32_ONE, 0, 0, 0, false };
	uint32_t i;
	int err;

	if (!c)
		return MOT_E_INVAL;
	/* An unusable curve until the end: eval gives 0 and MOT_SAT_DOMAIN. */
	c->nkeys = 0;
	c->nseg = 0;
	c->kind = (uint32_t)kind;
	c->keys = keys;
	c->seg = seg;
	c->seg_ease = c->span_ease = c->integral = c->power = false;
	if (!opts)
		opts = &defaults;
	if (mot_curve_seg_count(kind, 1) == 0 || (nkeys > 0 && !keys))
		return MOT_E_INVAL;
	if (nkeys == 0)
		return MOT_E_NOKEYS;
	c->nkeys = nkeys;
	err = check(c, opts, nseg);
	if (!err && opts->integral && kind >= MOT_INTERP_BSPLINE)
		err = MOT_E_INVAL;
	if (err)
		goto fail;
	c->nseg = mot_curve_seg_count(kind, nkeys);
	c->beta1 = opts->beta1;
	c->beta2 = opts->beta2;
	c->span_f0 = keys[0].frame;
	c->span_f1 = keys[nkeys - 1].frame;
	c->span_ease = opts->ease_in_frames || opts->ease_out_frames;
	for (i = 0; i < c->nseg; i++) {
		struct mot_curve_seg *s = &c->seg[i];
		bool interval = i + 1 < nkeys;

		s->f0 = s->f1 = s->fref = keys[0].frame;
		s->vref = keys[0].value;
		s->c[0] = s->c[1] = s->c[2] = s->c[3] = 0;
		s->fc[0] = s->fc[1] = s->fc[2] = s->fc[3] = 0;
		s->vsh = s->fsh = 0;
		s->start = START_CHORD;
		s->inv_w.m = s->inv_h.m = 0;
		s->inv_w.shift = s->inv_h.shift = 32;
		s->area = mot_acc_zero();
		err = mot_ease_init(&s->ease, interval ? keys[i].ease_out : 0,
				    interval ? keys[i + 1].ease_in : 0, sat);
		if (!err && interval)
			err = mot_recip_init(&s->inv_h, keys[i + 1].frame - keys[i].frame);
		if (err)
			goto fail;
		c->seg_ease = c->seg_ease || !mot_ease_is_identity(&s->ease);
	}
	if (opts->integral && (c->seg_ease || c->span_ease)) {
		err = MOT_E_INVAL;
		goto fail;
	}
	if (c->span_ease) {
		int64_t span = c->span_f1 - c->span_f0;

		err = mot_ease_init_ratio(&c->span, opts->ease_out_frames, opts->ease_in_frames,
					  span, sat);
		if (!err)
			err = mot_recip_init(&c->span_inv, span);
		if (err)
			goto fail;
	}
	err = prep_pieces(c);
	if (err)
		goto fail;
	c->integral = opts->integral;
	if (c->integral) {
		err = prep_area(c);
		if (err)
			goto fail;
	}
	return MOT_OK;
fail:
	c->nkeys = 0;
	c->integral = false;
	return err;
}
