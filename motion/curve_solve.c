/* SPDX-License-Identifier: MIT */
/*
 * curve_solve.c - the value of an approximating curve (bspline, beta,
 * bezier) at a frame: its value coordinate at the parameter u where its
 * frame coordinate equals the frame (FORMULAS section 6), u found by a
 * safeguarded Newton iteration on a spline piece (curve_approx.c) or on the
 * one Bezier curve (curve_bezier.c). Real-time safe: a small stack frame
 * (bezier: 62 int64), at most NEWTON_MAX_IT iterations of one 64-bit
 * division each.
 *
 * Every evaluator the iteration calls is in this file or inline in
 * curve_priv.h, as when the curves were one file: the loop's code, and so
 * its cost, depends on what the compiler knows of them.
 */
#include "curve_priv.h"

#define NEWTON_MAX_IT 64
#define BISECT_TOL ((int64_t)1 << 12) /* 2^-50: a bracket this narrow is the answer */

/*
 * |q| for q = r * 2^62 / d in Q2.62, d > 0, to a relative 2^-30 (within
 * the 2^-29.4 the tolerances allow for), with |q| < 2^62; false when it
 * would not fit. |r| moved up to 64 bits over d's top 32 bits b: one
 * 64-bit division, exact, so the same on every target (the hardware's on
 * x86_64 and aarch64, a dozen cycles; libgcc's elsewhere), its quotient in
 * (2^31, 2^33) moved up by 31 bits (a shift where the reciprocal's product
 * took a multiplication, on the iteration's path). Two truncations of at
 * most 2^-31 each (b and the quotient), within the 2^-29 of a step that
 * the tolerances allow for (curve_approx.c, newton_bits()); a Newton step
 * of the curve solve needs only a good direction and size, the solve's own
 * convergence makes up the rest. The quotient p is in [2^62, 2^64), so q
 * is it shifted right, never left: fewer tests than a quotient of |r|
 * moved up to 62 bits, which q had to be shifted either way from. The
 * sign is the caller's (r's), applied without a branch (solve_u()).
 */
static inline bool ratio62(int64_t r, int64_t d, int64_t *aq)
{
	uint64_t ar = r < 0 ? 0 - (uint64_t)r : (uint64_t)r, p, b;
	int cr, ld, sh;

	if (ar == 0) {
		*aq = 0;
		return true;
	}
	cr = __builtin_clzll(ar);
	ld = __builtin_clzll((uint64_t)d) ^ 63; /* d's top bit, bsr on x86_64 */
	/* b = d's top 32 bits, (d << clz(d)) >> 32, in one shift where d has
	 * them (the division waits for b: a shift less on the iteration's
	 * path) */
	b = __builtin_expect(ld >= 31, 1) ? (uint64_t)d >> (ld - 31) : (uint64_t)d << (31 - ld);
	/* |r| = A 2^-cr with A = |r| << cr in [2^63, 2^64), d ~ b 2^(ld - 31)
	 * with b in [2^31, 2^32): |r| / d 2^62 ~ (A / b) 2^31 2^(62 - ld - cr) */
	p = ((ar << cr) / b) << 31;
	sh = cr + ld - 62;
	if (sh <= 0 || (sh == 1 && p >> 63))
		return false; /* |q| >= 2^62 */
	*aq = (int64_t)(p >> sh); /* sh <= 63: cr <= 63, ld <= 62 (d > 0) */
	return true;
}

/*
 * floor(a * u / 2^62) for |u| <= 2^62: mul62() without its rounding (two
 * instructions of five on x86_64), for the numbers that need no more than
 * a unit of error a product (the rounding's is half): a derivative, whose
 * top 32 bits are all that ratio62() reads, and the value's u^2. The
 * frame's Horner and the value's products by its coefficients keep mul62():
 * the root and the answer are theirs.
 */
static inline int64_t mul62f(int64_t a, int64_t u)
{
	uint64_t ov = 0; /* |a u| < 2^125: the result fits */

	return mot_acc_floor_ov(mot_acc_mul(a, u), 62, &ov);
}

/*
 * A spline piece's frame F(u) = c0 + u (c1 + u (c2 + u c3)), poly_eval()'s
 * products and so its bits (inv_start()'s bisection placed the start's
 * table on this F), and its derivative in one product more: with a = c3 u
 * and t1 = c2 + a, F'(u) = c1 + u (2 c2 + 3 c3 u) = c1 + u (2 t1 + a). The
 * derivative is the iteration's critical path (ratio62()'s division waits
 * for it; F is needed only after), so it leaves F's chain at t1: one
 * product after a, where t2 + u (t1 + a) with t2 = c1 + u t1 waited for
 * two (|2 t1 + a| <= 2 |c2| + 3 |c3| + 2 <= 3 2^61, |F'| < 2^63). c0 in
 * place of c[0]: the solve's F(u) - d with c0 = c[0] - d, the same sum.
 */
static inline int64_t poly_frame(const int64_t c[4], int64_t c0, int64_t u, int64_t *df)
{
	int64_t a = mul62(c[3], u), t1 = a + c[2];

	*df = c[1] + mul62f(2 * t1 + a, u);
	return mul62(mul62(t1, u) + c[1], u) + c0;
}

/*
 * A spline piece's value at the solve's root u: vref + round(V(u) / 2^vsh),
 * value_of()'s bits, with V(u) = (c0 + c1 u) + u^2 (c2 + c3 u) (Estrin's
 * scheme): u^2 and the two halves' products are independent, so the chain
 * from u is two products where poly_eval()'s Horner is three; the value's
 * is the last link of every solve. One product more (u^2, floored: a unit
 * of 2^-62 in it moves the result by at most |c2 + c3 u| 2^-62 <= 1/2);
 * error at most 2 units where Horner's is 3/2, far below the value's
 * 2^-vsh. |c2 + c3 u|, |c0 + c1 u| and u^2 are within mul62()'s range, and
 * so is their sum V (sum |c| <= 2^61). value_of()'s half unit joins
 * c0 + c1 u, which is ready a product before the sum: a sum less on the
 * chain, and no overflow (|V| + 2^61 < 2^63).
 */
static inline mot_q32 spline_value(const struct mot_curve_seg *s, int64_t u, uint32_t *sat)
{
	const int64_t *c = s->c;
	int64_t u2 = mul62f(u, u), hi = mul62(c[3], u) + c[2], lo = mul62(c[1], u) + c[0];
	int sh = s->vsh;
	mot_q32 r;

	if (sh > 0 && sh < 63) {
		int64_t q = mul62(hi, u2) + (lo + ((int64_t)1 << (sh - 1)));

		if (!__builtin_add_overflow(s->vref, q >> sh, &r))
			return r;
	}
	return value_of_wide(s->vref, mul62(hi, u2) + lo, sh, sat);
}

/*
 * a[0] + a[1] x + .. + a[7] x^7 for x in [-1, 1] in Q1.31, the coefficients
 * in Q1.30, as E(y) + x O(y), y = x^2, the even and the odd coefficients
 * each by Estrin's scheme, (c0 + c1 y) + y^2 (c2 + c3 y): y, then y^2 and
 * the four halves side by side, then each chain's product by y^2: three
 * products deep where Horner's rule in y was four (a start's latency is
 * the solve's), one product more. The partial sums in Q1.31, a 64-bit
 * product each (no 128-bit one) floored back to Q1.31 and a coefficient
 * added at twice its Q1.30 (one lea: no shift of the coefficient up or of
 * the partial sum down), off by 2^-31 each, below 2^-27 in all with y's,
 * y^2's and the coefficients' roundings; the last products x O and
 * E 2^31 in Q1.62. The coefficients' magnitudes sum below 2 - 2^-22
 * (mot_cv_tab_fit()): every partial sum is below 2^32 in Q1.31, the
 * products below 2^63, and E + x O below 2 in Q1.62.
 */
static inline __attribute__((always_inline)) int64_t poly7_62(const int32_t a[8], int64_t x)
{
	int64_t y = (x * x) >> 31, y2 = (y * y) >> 31, e, o, eh, oh;

	eh = ((2 * (int64_t)a[6] * y) >> 31) + 2 * (int64_t)a[4];
	oh = ((2 * (int64_t)a[7] * y) >> 31) + 2 * (int64_t)a[5];
	e = ((2 * (int64_t)a[2] * y) >> 31) + 2 * (int64_t)a[0];
	o = ((2 * (int64_t)a[3] * y) >> 31) + 2 * (int64_t)a[1];
	e += (eh * y2) >> 31;
	o += (oh * y2) >> 31;
	return o * x + e * ((int64_t)1 << 31);
}

/*
 * The START_TAB start of a spline piece at the chord fraction t in [0, 1]
 * (t31 = floor(t 2^31), start_u()): half h's polynomial (curve_approx.c, tab_start()) at x = 4 t - 2 h - 1 in
 * Q1.31 (t to 2^-31, x to 2^-29: u to about 2^-31 where du/dt is near 1),
 * poly7_62()'s: below 2^-27 off, where a piece's tolerance is 2^-16 ..
 * 2^-31 and most solves' 2^-20 .. 2^-21. Clamped to [0, 1].
 */
static inline __attribute__((always_inline)) int64_t tab62(const int32_t ut[16], int64_t t31)
{
	int64_t x = t31, r;
	const int32_t *a = ut;

	if (x >= (int64_t)1 << 30) {
		a += 8;
		x -= (int64_t)1 << 30;
	}
	r = poly7_62(a, 4 * x - ((int64_t)1 << 31));
	return r <= 0 ? 0 : r >= ONE62 ? ONE62 : r;
}

/* cbrt(x) for x in Q2.62 [0, 1], to about 2^-24.5 relative: the Newton
 * start on a piece whose frame grows as u^3 (the tripled end keys).
 * cbrt(1 + m) for m in [0, 1) is its degree-7 polynomial in x = 2 m - 1
 * through the eight Chebyshev nodes (within 2^-24.7 with the coefficients
 * in Q1.30, summing to 1.29), evaluated as tab62()'s (poly7_62()), within
 * the 2^-22 or so that those pieces' tolerance asks of a first step
 * (curve_approx.c, newton_bits()), so most of their solves take one
 * iteration where the quartic's 2^-16.2 took two. */
static int64_t cbrt62(int64_t x)
{
	static const int64_t k_third[3] = {
		ONE62, 3660297618499336453, 2905180145061270980, /* 2^(-r/3) */
	};
	static const int32_t k_poly[8] = {
		1229127586, 136569721, -15175292, 2810327, -620137, 151412, -46253, 12582,
	};
	unsigned e, q, r;
	int64_t m, y;

	if (x <= 0)
		return 0;
	e = 63 - bitlen64((uint64_t)x); /* x = (1 + m) 2^-e, m in [0, 1) */
	q = e / 3;
	r = e % 3;
	m = (int64_t)((uint64_t)x << e) - ONE62;
	/* x = 2 m - 1 in Q1.31 */
	y = mul62(poly7_62(k_poly, (m >> 30) - ((int64_t)1 << 31)), k_third[r]) >> q;
	/* at most 1: the polynomial at x near 1 is above it (cbrt(1) as
	 * 1 + 38 2^-30), and a start outside [0, 1] (START_CUBE0 near its
	 * piece's end, START_CUBE1 at its start, 1 - cbrt) could end the solve
	 * outside it: a root below 0 masked to about 2 (solve_u()'s u &
	 * INT64_MAX), the value's products then overflowing (a B-spline's
	 * value at its last piece's first frame far outside its keys' hull) */
	return y > ONE62 ? ONE62 : y;
}

/* The cubic Hermite from u0, u1 (Q6.58) with slopes m0, m1 (Q6.58, in units
 * of the part) at s in [0, 1] (Q2.62): u0 + s (m0 + s ((3 du - 2 m0 - m1) +
 * s (m0 + m1 - 2 du))), du = u1 - u0, clamped to [0, 1] in Q2.62. The
 * products are of 32-bit halves, a 64-bit product each (no 128-bit one):
 * off by 2^-26 at most, where the table keeps u to 2^-16 and a start
 * needs no more. The slopes are at most 3 (inv_start(),
 * mot_cv_bezier_start(): 3 2^58 here) and |du| at most 2^58: the partial
 * sums stay below 2^62.6, their tops below 2^31.6, the products below
 * 2^62.6. */
static inline __attribute__((always_inline)) int64_t
herm62(int64_t u0, int64_t u1, int64_t m0, int64_t m1, int64_t s)
{
	int64_t du = u1 - u0, r, t = s >> 31;

	r = ((m0 + m1 - 2 * du) >> 31) * t + 3 * du - 2 * m0 - m1;
	r = (r >> 31) * t + m0;
	r = (r >> 31) * t + u0;
	return r <= 0 ? 0 : r >= (int64_t)1 << 58 ? ONE62 : r * 16;
}

/* The START_INV start of a spline piece at the chord fraction t in [0, 1]:
 * quarter k's cubic at s = 4 t - k, from Q1.15 and Q2.14. */
static int64_t inv62(const uint16_t us[8], int64_t t)
{
	int64_t k = t >> 60, s;

	k = k > 3 ? 3 : k;
	s = (t - (k << 60)) * 4;
	return herm62(k > 0 ? (int64_t)us[k - 1] << 43 : 0,
		      k < 3 ? (int64_t)us[k] << 43 : (int64_t)1 << 58, (int64_t)us[3 + k] << 44,
		      (int64_t)us[4 + k] << 44, s);
}

/* ---- frame(u) and value(u) of a Bezier curve ------------------------------------ */

/*
 * floor(r u / 2^64) for |u| <= 2^62: the high word of the 128-bit product,
 * one instruction on x86_64 and aarch64 (no rounding's add and shift): the
 * power form's Horner step 4 mulhi(r, u) + a is r u / 2^62 + a to a
 * multiple of 4 units, floored (curve_bezier.c: its coefficients carry the
 * 2 units that centre it). |r u| < 2^125: 4 mulhi(r, u) is within 4 units
 * of r u / 2^62, below 2^63 where |r| is.
 */
static inline int64_t mulhi(int64_t r, int64_t u)
{
	return (int64_t)mot_acc_hi(mot_acc_mul(r, u));
}

/*
 * Horner's rule on the power form (curve_bezier.c), a[k - 1] multiplying
 * u^k: the frame less the solve's target, 4 mulhi(r_1, u) + c0 with
 * c0 = 2 - d (the 2 units centring the last floor too), and its derivative
 * (the value's: mot_cv_approx_eval()). Each step's error is within 2 units
 * of 2^fsh (half a unit of 2^(fsh - 2)), m of them in all. The
 * derivative's coefficients k a_k without the 2 units (the low two bits
 * masked): its partial sums stay within sum k |a_k| 2^fsh + 4 m < 2^63
 * for every m; an error of 4 units a step (floors) where only its top 32
 * bits are read (ratio62()). With c0 = 2 the frame itself (init).
 */
static int64_t power_frame(const int64_t *a, uint32_t m, int64_t u, int64_t c0, int64_t *df)
{
	int64_t r = a[m - 1], d = (int64_t)m * a[m - 1];
	uint32_t k;

	for (k = m - 1; k >= 1; k--) {
		r = 4 * mulhi(r, u) + a[k - 1];
		d = 4 * mulhi(d, u) + (int64_t)k * (a[k - 1] & ~(int64_t)3);
	}
	*df = d;
	return 4 * mulhi(r, u) + c0;
}

/*
 * The same for 1 <= m <= 8, unrolled: the coefficients a_1 .. a_m are in
 * the c[] and fc[] of one entry (power_slot, power_vslot), each step's
 * place and factor k a constant, entered at the degree's step (without the
 * loop's index arithmetic and multiplications by k: a fifth of a Bezier
 * solve). The frame's products and sums are power_frame()'s, so its bits;
 * the derivative's take k a_k with the 2 units (no mask on its chain: at
 * most 2 k more a step, 72 in all, its partial sums below 2^63 with
 * m <= 8 and 2^fsh >= 2^10). With df NULL (a constant: inlined) the
 * value's Horner without the derivative, its result mulhi(r_1, u): the
 * value's polynomial in units of 2^(vsh - 2), floored. k a_k is formed only
 * with df: the value's coefficients reach past 2^61, where 3 a_3
 * overflows, and an overflow unused is still undefined (the fuzzer's
 * every_key.yaml found it).
 */
#define POWER_A(j) ((j) < 4 ? s->c[(j)] : s->fc[(j) - 4])
#define POWER_STEP(k)                                                       \
	do {                                                                \
		r = 4 * mulhi(r, u) + POWER_A((k) - 1);                     \
		if (df)                                                     \
			d = 4 * mulhi(d, u) + (int64_t)(k) * POWER_A((k) - 1); \
	} while (0)
#define POWER_TOP(k)                                                        \
	case k:                                                             \
		r = POWER_A((k) - 1);                                       \
		if (df)                                                     \
			d = (int64_t)(k) * r;                               \
		goto step##k

static inline __attribute__((always_inline)) int64_t
power_horner8(const struct mot_curve_seg *s, uint32_t m, int64_t u, int64_t c0, int64_t *df)
{
	int64_t r, d = 0;

	/* m % 8, 8 as 0: every case of the table taken, so no range check
	 * (the callers' test is m <= 8, m >= 1) */
	switch (m % 8) {
	case 0:
		r = POWER_A(7);
		if (df)
			d = 8 * r;
		goto step8;
	POWER_TOP(7);
	POWER_TOP(6);
	POWER_TOP(5);
	POWER_TOP(4);
	POWER_TOP(3);
	POWER_TOP(2);
	default:
		r = POWER_A(0);
		if (df)
			d = r;
		goto step1;
	}
step8:
	POWER_STEP(7);
step7:
	POWER_STEP(6);
step6:
	POWER_STEP(5);
step5:
	POWER_STEP(4);
step4:
	POWER_STEP(3);
step3:
	POWER_STEP(2);
step2:
	POWER_STEP(1);
step1:
	if (!df)
		return mulhi(r, u);
	*df = d;
	return 4 * mulhi(r, u) + c0;
}

#undef POWER_TOP
#undef POWER_STEP
#undef POWER_A

/* De Casteljau's algorithm, for the curves the power form would not keep
 * precise: at u on the keys' frames (or values) relative to the first key,
 * scaled by 2^fsh (2^vsh), until `left` points remain in w[]. */
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
 * The Bezier curve's Newton start (START_INV on seg[0]): curve_approx.c's
 * inv_start() over the whole curve, the chord fraction t cut into
 * nt = 4 (nkeys - 1) equal parts, each a Hermite cubic of the inverse from u
 * at its ends (bisection to 2^-20: the table keeps 2^-15) and the slopes
 * there. Entry p's area holds u at knots 4p + 1 .. 4p + 4 (Q1.15; the last
 * knot's u is 1, and its slot holds that knot's slope) and the slopes at
 * knots 4p .. 4p + 3 (Q2.14, in units of the part). A solve takes about two
 * steps where the chord took four, each step a pass over every key.
 */
static void bez_frame_at(const struct mot_curve *c, const int64_t *pw, int64_t u, int64_t *f,
			 int64_t *df)
{
	if (pw)
		*f = power_frame(pw, c->nkeys - 1, u, 2, df);
	else
		bezier_frame(c, u, f, df);
}

/* The u in [lo, 1] where the frame reaches target, by `steps` bisections:
 * the last u evaluated below it (F increasing). */
static int64_t bez_bisect(const struct mot_curve *c, const int64_t *pw, int64_t lo,
			  int64_t target, unsigned steps)
{
	int64_t hi = ONE62, f, df;

	while (steps--) {
		int64_t mid = lo + (hi - lo) / 2;

		bez_frame_at(c, pw, mid, &f, &df);
		if (f < target)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}

static uint16_t *bez_u(struct mot_curve *c, uint32_t i) /* knot i in 1 .. nt - 1 */
{
	return &c->seg[(i - 1) / 4].us[(i - 1) % 4];
}

static uint16_t *bez_m(struct mot_curve *c, uint32_t i, uint32_t nt) /* knot i in 0 .. nt */
{
	return i == nt ? &c->seg[(nt - 1) / 4].us[3] : &c->seg[i / 4].us[4 + i % 4];
}

/*
 * The Bezier curve's START_TAB (on a curve in power form without eases,
 * after START_INV succeeded): spline pieces' tab_start() (curve_approx.c)
 * on each of the m = nkeys - 1 equal parts of the chord fraction t, part j
 * in entry j's ut[] (the inv_h and ease that only an eased key interval
 * reads: sizeof(struct mot_curve_seg) unchanged), each a degree-7
 * polynomial of the inverse on either half of its part, from u at the
 * Chebyshev nodes (bisection to 2^-48, F(u) < t W). Kept only where every
 * part's fit is (mot_cv_tab_fit()). Init only: m 16 bisections of 48
 * steps of Horner's rule of degree m (de Casteljau curves, up to 32 keys
 * and m^2 / 2 products an evaluation, keep the Hermite quarters).
 */
static void bez_tab_start(struct mot_curve *c, const int64_t *pw, int64_t w)
{
	const struct mot_key *kk = c->keys;
	uint32_t m = c->nkeys - 1, j, k;
	int64_t y[16];

	for (j = 0; j < m; j++) {
		for (k = 0; k < 16; k++) {
			/* the node's t in the whole curve, (j + t') / m, times W:
			 * below 2^62 2^5 W, exact in 128 bits */
			mot_acc a = mot_acc_add(mot_acc_mul(w, mot_cv_tab_node(k / 8, k % 8)),
						acc_shl(mot_acc_mul(w, (int64_t)j), 62));
			int64_t target = 0;

			if (!mot_cv_acc_div_round(&target, a, -62, m))
				break;
			y[k] = (bez_bisect(c, pw, 0, target, 48) + 2) >> 2; /* Q2.60 */
		}
		if (k < 16 || !mot_cv_tab_fit(y, c->seg[j].ut))
			break;
	}
	if (j == m) {
		c->seg[0].start = START_TAB;
		return;
	}
	/* a part that does not fit (not seen on the random scenes): the
	 * entries before it get back their inv_h and ease as curve.c's init
	 * made them (every ease the identity; a table on the stack instead
	 * would be 2 KB), and the curve keeps START_INV */
	while (j--) {
		mot_ease_init(&c->seg[j].ease, kk[j].ease_out, kk[j + 1].ease_in, NULL);
		mot_recip_init(&c->seg[j].inv_h, kk[j + 1].frame - kk[j].frame);
	}
}

void mot_cv_bezier_start(struct mot_curve *c)
{
	uint32_t m = c->nkeys - 1, nt = 4 * m, i, j;
	int64_t pw[MOT_BEZIER_MAX_KEYS - 1] = { 0 }, *pp = NULL, w, f, df, prev = 0, step;
	uint64_t q[4 * (MOT_BEZIER_MAX_KEYS - 1) + 1], r;
	int64_t uk[4 * (MOT_BEZIER_MAX_KEYS - 1) + 1];

	if (c->nkeys < 2 || c->seg[0].start != START_CHORD)
		return;
	if (c->power) {
		for (j = 0; j < m; j++)
			pw[j] = *power_slot(c, j);
		pp = pw;
	}
	bez_frame_at(c, pp, ONE62, &w, &df);
	if (w <= 0)
		return;
	step = w / (int64_t)nt;
	uk[0] = 0;
	uk[nt] = ONE62;
	for (i = 1; i < nt; i++) {
		uk[i] = prev = bez_bisect(c, pp, prev, step * (int64_t)i, 40);
	}
	for (i = 0; i <= nt; i++) {
		uint32_t sat = 0;

		bez_frame_at(c, pp, uk[i], &f, &df);
		if (df <= 0)
			return;
		/* du/ds = (W / nt) / F' in Q2.62, s the part's own parameter */
		q[i] = mot_acc_udiv(mot_acc_from(step, 62), (uint64_t)df, &r, &sat);
		if (sat || q[i] > (uint64_t)3 << 62 ||
		    (i > 0 && q[i] > 3 * (uint64_t)(uk[i] - uk[i - 1])) ||
		    (i < nt && q[i] > 3 * (uint64_t)(uk[i + 1] - uk[i])))
			return;
	}
	for (i = 1; i < nt; i++)
		*bez_u(c, i) = (uint16_t)((uk[i] + ((int64_t)1 << 46)) >> 47);
	for (i = 0; i <= nt; i++)
		*bez_m(c, i, nt) = (uint16_t)((q[i] + ((uint64_t)1 << 47)) >> 48);
	c->seg[0].start = START_INV;
	if (pp && !c->seg_ease)
		bez_tab_start(c, pp, w);
}

/* The start at the chord fraction t in [0, 1] from that table (t32 =
 * floor(t 2^32), bez_start_u()): part j = floor(nt t), its cubic at s = nt t - j. Knot j + 1's
 * u and knot j's slope are in part j's entry e (j / 4), at r = j % 4 and
 * 4 + r; knot j's u one place before (the entry before's last for r = 0)
 * and knot j + 1's slope one after (the next entry's first for r = 3, or
 * e's us[3] after the last knot). */
static int64_t bez_inv62(const struct mot_curve *c, uint64_t t32)
{
	const struct mot_curve_seg *sg = c->seg;
	uint32_t nt = 4 * (c->nkeys - 1);
	uint64_t x = t32 * nt;
	uint32_t j = (uint32_t)(x >> 32), r;
	int64_t s = (int64_t)((x & 0xffffffffu) << 30), u0, u1, m1;
	const uint16_t *e;

	if (j >= nt) {
		j = nt - 1;
		s = ONE62;
	}
	e = sg[j / 4].us;
	r = j % 4;
	u0 = r ? (int64_t)e[r - 1] << 43 : j ? (int64_t)sg[j / 4 - 1].us[3] << 43 : 0;
	if (r < 3) {
		u1 = (int64_t)e[r] << 43;
		m1 = (int64_t)e[5 + r] << 44;
	} else if (j + 1 < nt) {
		u1 = (int64_t)e[3] << 43;
		m1 = (int64_t)sg[j / 4 + 1].us[4] << 44;
	} else {
		u1 = (int64_t)1 << 58;
		m1 = (int64_t)e[3] << 44;
	}
	return herm62(u0, u1, (int64_t)e[4 + r] << 44, m1, s);
}

/* The START_TAB start of a Bezier curve at the chord fraction t in [0, 1]
 * (t32 = floor(t 2^32), bez_start_u()): half k = floor(2 m t) of the m
 * parts (t = 1 in the last),
 * entry k / 2's polynomial of half k % 2 (tab62()'s) at x = 2 (2 m t - k)
 * - 1 in Q1.31 (to 2^-31), one index where the part and then its half
 * were two (the half a branch). Clamped to [0, 1]. */
static inline __attribute__((always_inline)) int64_t bez_tab62(const struct mot_curve *c,
							       uint64_t t32)
{
	uint32_t n2 = 2 * (c->nkeys - 1);
	uint64_t x = t32 * n2; /* t32 <= 2^32, n2 <= 62 */
	uint32_t k = (uint32_t)(x >> 32);
	int64_t xs = (int64_t)(x & 0xffffffffu) - ((int64_t)1 << 31), r;

	if (k >= n2) {
		k = n2 - 1;
		xs = (int64_t)1 << 31;
	}
	r = poly7_62(c->seg[k / 2].ut + 8 * (k % 2), xs);
	return r <= 0 ? 0 : r >= ONE62 ? ONE62 : r;
}

/*
 * A power form's value, vref + round(p / 2^(vsh - 2)) for p its Horner's
 * mulhi(r_1, u): value_of()'s bits without its tests, none of which can
 * fail here. vsh - 2 is in [8, 61] (POWER_MIN_SHIFT; 60 for a constant
 * value, sum |a_k| = 0), |p| <= (sum |a_k| 2^vsh + 8 m) / 4 < 2^61, so
 * p + 2^(vsh - 3) fits; and the rounded quotient is the value's offset
 * from the first key within a unit, in the keys' hull (|value| < 2^62 raw,
 * MOT_LEN_LIMIT): vref + it fits.
 */
static inline __attribute__((always_inline)) mot_q32 power_value_of(const struct mot_curve_seg *s,
								     int64_t p)
{
	int sh = s->vsh - 2;

	return s->vref + ((p + ((int64_t)1 << (sh - 1))) >> sh);
}

/* ---- the solve ------------------------------------------------------------------ */

/* How a solve evaluates the frame: a spline piece's cubic, a Bezier curve
 * in power form, or by de Casteljau. */
enum form { FORM_SPLINE, FORM_POWER, FORM_CASTELJAU };

/*
 * Solve frame(u) = d on one piece: safeguarded Newton (rtsafe, Numerical
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
 * is fixed: stop after a Newton step below 2^-ntol, the piece's (the error
 * is then about the square of it: curve_approx.c and curve_bezier.c bound
 * it for what the frame needs; 2^-31 where they cannot), or once the
 * bracket is narrower than 2^-50, or after NEWTON_MAX_IT iterations. Random
 * and sequential access therefore give the same u, bit for bit, on every
 * target.
 *
 * Inlined once per form with the form a constant, so that an iteration
 * tests nothing of the curve's kind (the solve is a third of a random
 * scene's instructions, one or two iterations each).
 */
static inline __attribute__((always_inline)) int64_t
solve_u(const enum form form, const struct mot_curve *c, const struct mot_curve_seg *s,
	const int64_t *pw, int64_t d, int64_t u, int *iters)
{
	const int64_t tol = (int64_t)1 << (62 - s->ntol);
	/* a piece's F(u) - d as F's Horner with c0 - d, F(0) - d: at most the
	 * piece's frame range, as F(u) - d is */
	const int64_t c0 = form == FORM_SPLINE ? s->fc[0] - d : form == FORM_POWER ? 2 - d : 0;
	bool lo_known = false, hi_known = false;
	int64_t lo = 0, hi = ONE62, dx = ONE62, dxold = ONE62;
	int it;

	for (it = 1; it <= NEWTON_MAX_IT; it++) {
		int64_t f, df, adu = 0, step = 0, un = 0;
		bool newton;

		if (form == FORM_POWER) {
			if (pw)
				f = power_frame(pw, c->nkeys - 1, u, c0, &df);
			else
				f = power_horner8(s, c->nkeys - 1, u, c0, &df);
		} else if (form == FORM_CASTELJAU) {
			bezier_frame(c, u, &f, &df);
			f -= d;
		} else {
			f = poly_frame(s->fc, c0, u, &df);
		}
		/* (the power form's f is 2 modulo 4: never 0) */
		if (form != FORM_POWER && f == 0)
			break;
		if (f < 0) {
			lo = u;
			lo_known = true;
		} else {
			hi = u;
			hi_known = true;
		}
		if (lo >= hi) /* the root lies beyond an end of the piece */
			break;
		/* (the power form's f is never 0: ratio62() need not test it) */
		if (form == FORM_POWER && f == 0)
			__builtin_unreachable();
		newton = df > 0 && ratio62(f, df, &adu);
		if (newton) {
			/* un = u - du, du = adu with f's sign: a conditional
			 * negation where a branch on that sign could not be
			 * predicted (the start misses the root on either side,
			 * the step after it on the side of the piece's curvature)
			 * and, mispredicted, restarted the step's last link. The
			 * step's size is adu, or, clamped, the distance to the end
			 * (u is in [lo, hi]) */
			const int64_t sg = f >> 63;

			step = adu;
			un = (u + sg) - (adu ^ sg); /* adu ^ sg = -adu - 1 for f < 0 */
			/* rtsafe's progress test: |du| at most half the step before last */
			if (adu > dxold / 2)
				newton = false;
			if (un <= lo) {
				newton = newton && !lo_known;
				un = lo;
				step = u - lo;
			} else if (un >= hi) {
				newton = newton && !hi_known;
				un = hi;
				step = hi - u;
			}
		}
		dxold = dx;
		if (newton) {
			dx = step;
			if (dx <= tol) {
				u = un;
				break;
			}
		} else {
			dx = (hi - lo) / 2;
			un = lo + dx;
			if (dx <= BISECT_TOL) {
				u = un;
				break;
			}
		}
		u = un;
	}
	*iters = it > NEWTON_MAX_IT ? NEWTON_MAX_IT : it;
	/* u is in [0, 1] already: the mask tells the compiler so (one
	 * instruction where a test and a conditional move took three, on the
	 * way to the value), and the value's products (inlined after this)
	 * multiply u's int64, one product each, where they multiplied u
	 * sign-extended at the loop's exits to 128 bits (three products and
	 * their sum) */
	return u & INT64_MAX;
}

/* The frame f at piece s's scale, (f - fref) 2^fsh: round_shift()'s bits,
 * its common case (0 <= fsh < 64, a shift that fits) first with one test
 * of the scale where it took three. */
static inline __attribute__((always_inline)) int64_t frame_offset(const struct mot_curve_seg *s,
								  mot_q32 f)
{
	int64_t x = f - s->fref, y;

	if ((unsigned)s->fsh < 64) {
		y = (int64_t)((uint64_t)x << s->fsh);
		if (y >> s->fsh == x)
			return y;
	}
	return round_shift(x, -s->fsh, NULL);
}

/* The Newton start of piece s at the frame offset x = f - f0, by its rule:
 * f is inside the piece, f0 <= f < f1 (the cursor's test or the lookup; a
 * spline's last piece and the Bezier curve end at span_f1, past every f
 * here; a spline's first piece starts at span_f0, mot_cv_prep_spline()),
 * so the chord fraction is piece_u()'s, frac62()'s bits without its ends. */
static inline __attribute__((always_inline)) int64_t
start_u(const struct mot_curve *c, const struct mot_curve_seg *s, int64_t x)
{
	int64_t u;

	/* START_TAB reads t to 31 bits: floor(t 2^31), piece_u()'s product's
	 * high word shifted (x' m / 2^64 = t 2^61; bez_start_u()), without
	 * its rounding and clamp */
	if (s->start == START_TAB)
		return tab62(s->ut, mulhi((int64_t)((uint64_t)x << (93 - s->inv_w.shift)),
					  s->inv_w.m) >> 30);
	u = piece_u(x, &s->inv_w);
	if (s->start == START_INV)
		return inv62(s->us, u);
	if (s->start == START_CUBE0)
		return cbrt62(u);
	if (s->start == START_CUBE1)
		return ONE62 - cbrt62(ONE62 - u);
	return u;
}

/* The Bezier curve's Newton start at the frame offset x = f - f0 (inside
 * the curve, as start_u()'s), by its rule. Its tables read the chord
 * fraction t to 32 bits: t32 = floor(t 2^32) from piece_u()'s product,
 * floored, x' m / 2^64 = t 2^61 (x' < 2^63 and 0 < m < 2^63, m rounded
 * down: t32 <= 2^32), one product's high word and a shift where piece_u()'s
 * rounding, its clamp and the tables' shift took seven instructions more
 * on the solve's path. */
static inline __attribute__((always_inline)) int64_t
bez_start_u(const struct mot_curve *c, const struct mot_curve_seg *s, int64_t x)
{
	uint64_t t32 = (uint64_t)mulhi((int64_t)((uint64_t)x << (93 - s->inv_w.shift)),
				       s->inv_w.m) >> 29;

	if (s->start == START_TAB)
		return bez_tab62(c, t32);
	if (s->start == START_INV)
		return bez_inv62(c, t32);
	return piece_u(x, &s->inv_w);
}

/* The piece of f (a Bezier curve has one), the start of the solve by the
 * piece's rule, the solve, and the value at its root. */
mot_q32 mot_cv_approx_eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f,
			   int *iters, uint32_t *sat)
{
	const struct mot_curve_seg *s;
	int64_t u, d, r, pw[MOT_BEZIER_MAX_KEYS - 1];
	uint32_t m, j;
	int it; /* the solve's iterations, a register: *iters written only
		 * where asked for (mot_curve_eval() does not) */

	if (c->kind != MOT_INTERP_BEZIER) {
		s = &c->seg[locate_seg(c, cur, f)];
		d = frame_offset(s, f);
		u = solve_u(FORM_SPLINE, c, s, NULL, d, start_u(c, s, f - s->f0), &it);
		if (iters)
			*iters = it;
		return spline_value(s, u, sat);
	}
	s = &c->seg[0];
	u = bez_start_u(c, s, f - s->f0);
	if (!c->power) {
		d = frame_offset(s, f);
		u = solve_u(FORM_CASTELJAU, c, s, NULL, d, u, &it);
		if (iters)
			*iters = it;
		return bezier_value(c, u, sat);
	}
	/* the frame's coefficients are power_slot(c, 0 .. m - 1): entry 0's for
	 * m <= 8, read in place (pw NULL, a constant: that solve's loop tests
	 * nothing of it), and the value's entry 1's (power_vslot); else
	 * copied. The value's Horner is power_frame()'s without the
	 * derivative, its last product floored to units of 2^(vsh - 2)
	 * (vsh >= 10). */
	m = c->nkeys - 1;
	/* frame_offset()'s d without its tests: f - fref is in [0, f1 - f0)
	 * (f inside the span), and (f1 - f0) 2^fsh = F(1) < 2^63 with fsh in
	 * [10, 62] (curve_bezier.c) */
	d = (int64_t)((uint64_t)(f - s->fref) << s->fsh);
	if (m <= 8) {
		u = solve_u(FORM_POWER, c, s, NULL, d, u, &it);
		if (iters)
			*iters = it;
		r = m > 1 ? power_horner8(&c->seg[1], m, u, 0, NULL) : mulhi(s->c[1], u);
		return power_value_of(s, r);
	}
	for (j = 0; j < m; j++)
		pw[j] = *power_slot(c, j);
	u = solve_u(FORM_POWER, c, s, pw, d, u, &it);
	if (iters)
		*iters = it;
	r = *power_slot(c, 2 * m - 1);
	for (j = m - 1; j >= 1; j--)
		r = 4 * mulhi(r, u) + *power_slot(c, m + j - 1);
	return power_value_of(s, mulhi(r, u));
}
