/* SPDX-License-Identifier: MIT */
/*
 * curve_approx.c - the pieces of the approximating splines: the uniform
 * cubic B-spline and Barsky's Beta-spline (FORMULAS section 6; the seed
 * paper sections 5.3.3 and 5.3.5).
 *
 * Both are curves on the 2-D control points (frame, value) of the keys, the
 * first and last key tripled so that the curve starts and ends on them: n + 4
 * control points, n + 1 cubic pieces, each inside the convex hull of its four
 * points. Piece j is kept as two cubics in u, frame(u) and value(u); the
 * value at a frame is found by solving frame(u) = f (curve_solve.c). Init
 * only.
 */
#include "curve_priv.h"

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
	/* den is the largest but for 3 x */
	sh = mot_cv_acc_bitlen(d) > 60 ? mot_cv_acc_bitlen(d) - 60 : 0;
	sh += 2;
	nb[0][0] = (int64_t)mot_acc_lo(mot_cv_acc_round_shift(t3, (int)sh));
	nb[0][1] = -3 * nb[0][0];
	nb[0][2] = 3 * nb[0][0];
	nb[0][3] = -nb[0][0];
	for (p = 0; p < 4; p++) {
		nb[1][p] = (int64_t)mot_acc_lo(mot_cv_acc_round_shift(r1[p], (int)sh));
		nb[3][p] = p == 3 ? (int64_t)mot_acc_lo(mot_cv_acc_round_shift(two, (int)sh)) : 0;
	}
	*den = mot_acc_lo(mot_cv_acc_round_shift(d, (int)sh));
	for (p = 0; p < 4; p++)
		nb[2][p] = (p == 0 ? (int64_t)*den : 0) - nb[0][p] - nb[1][p] - nb[3][p];
}

/*
 * The Newton tolerance of a piece (seg->ntol), from the frame's residual
 * after the last step: what the frame needs is F within 2^-4 of a raw unit,
 * 2^(fsh - 4), of the target d. A step h = u - u' from u, h = (1 + e)
 * (F(u) - d) / (F'(u) + r) with e ratio62()'s error (curve_solve.c,
 * |e| <= 2^-29.4) and r poly_frame()'s (|r| < 3 units: a's rounding three
 * times, and the floor), leaves by Taylor's expansion of the cubic (exact)
 *     F(u') - d = h (r - e F'(u)) / (1 + e) + (fc2 + fc3 (2 u + u')) h^2,
 * with 2 u + u' in [0, 3] (u, u' in [0, 1]): |F(u') - d| <= (2^-29 Dmax +
 * 4) |h| + M h^2, M = max(|fc2|, |fc2 + 3 fc3|), Dmax = |fc1| + 2 |fc2| +
 * 3 |fc3| (and F(u)'s own rounding, a unit or two, which no tolerance
 * removes). Each term at most 2^(fsh - 5) for |h| <= 2^-k:
 *     2 k >= bitlen(M) - fsh + 5,   k >= max(bitlen(Dmax) - 29, 2) + 1 - fsh + 5.
 * At least 16, at most NEWTON_TOL_BITS (|fc| summing to 2^61 at most: M and
 * Dmax below 2^63). No bound of 1 / F' is needed (the bound on u's error,
 * times max F', that this replaced asked 1 to 3 bits more of a typical
 * piece, and NEWTON_TOL_BITS of the cube-root end pieces, whose F' is 0 at
 * an end): the random scene's spline solves take 1.29 iterations where they
 * took 1.38, the end pieces' 1.00 where they took 2.00 (with cbrt62()
 * within 2^-24.5 of their root, where they need about 2^-22).
 */
static uint8_t newton_bits(const int64_t fc[4], int fsh)
{
	uint64_t a1 = (uint64_t)mot_abs(fc[1]), a2 = (uint64_t)mot_abs(fc[2]);
	uint64_t a3 = (uint64_t)mot_abs(fc[3]), m2 = (uint64_t)mot_abs(fc[2] + 3 * fc[3]);
	int lq = (int)bitlen64(a2 > m2 ? a2 : m2), ld = (int)bitlen64(a1 + 2 * a2 + 3 * a3) - 29;
	int k = (lq - fsh + 5 + 1) / 2, kr = (ld > 2 ? ld : 2) + 1 - fsh + 5; /* 2^ld + 4 */

	k = k > kr ? k : kr;
	k = k < 16 ? 16 : k;
	return (uint8_t)(k < NEWTON_TOL_BITS ? k : NEWTON_TOL_BITS);
}

/* Spline piece j on the extended control points E(j)..E(j+3), E(m) = key
 * clamp(m - 2, 0, n - 1): both polynomials relative to E(j+1), their frame
 * interval [f0, ...) and the Newton start rule. */
static int prep_piece(struct mot_curve *c, uint32_t j, int64_t nb[4][4], uint64_t den)
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
	err = mot_cv_poly_prep(s->fc, &s->fsh, nf, den);
	if (!err)
		err = mot_cv_poly_prep(s->c, &s->vsh, nv, den);
	if (err || !mot_cv_acc_div_round(&f0, nf[0], 0, den))
		return MOT_E_RANGE;
	/* The piece starts at ceil(frame(0)): a frame f in [ceil(F(0)),
	 * ceil(F(1))) has its root inside [0, 1), even when the piece is a few
	 * LSB wide (rounding to nearest would put it up to half an LSB of frame
	 * outside, and the solve would clamp). */
	{
		mot_acc rest = mot_acc_sub(nf[0], mot_acc_mul(f0, (int64_t)den)); /* F(0) - f0 */

		if (!mot_acc_is_neg(rest) && mot_cv_acc_bitlen(rest) != 0)
			f0++;
	}
	s->f0 = s->fref + f0;
	s->start = START_CHORD;
	/* frame(u) - frame(0) = w u^3, or frame(1) - frame(u) = w (1 - u)^3, tested
	 * on the exact numerators: the first and last piece (and every piece of a
	 * beta spline with beta1 = 0, beta2 = 0). */
	{
		mot_acc n3 = mot_acc_add(mot_acc_add(nf[3], nf[3]), nf[3]);

		if (mot_cv_acc_bitlen(nf[1]) == 0 && mot_cv_acc_bitlen(nf[2]) == 0)
			s->start = START_CUBE0;
		else if (mot_cv_acc_bitlen(mot_acc_sub(nf[1], n3)) == 0 &&
			 mot_cv_acc_bitlen(mot_acc_add(nf[2], n3)) == 0)
			s->start = START_CUBE1;
	}
	s->ntol = newton_bits(s->fc, s->fsh);
	return MOT_OK;
}

/* The u in [0, 1] where F reaches target, by bisection: the largest
 * u < 1 (to 2^-62) with F(u) < target, F increasing. */
static int64_t inv_frame(const int64_t fc[4], int64_t target)
{
	int64_t lo = 0, hi = ONE62;
	unsigned i;

	for (i = 0; i < 62; i++) {
		int64_t mid = lo + (hi - lo) / 2;

		if (poly_eval(fc, mid) < target)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}

/*
 * The Newton start of a chord-started piece (START_INV): u(t) with frame(u(t))
 * = frame(0) + t (frame(1) - frame(0)) is the inverse of F, and on each
 * quarter of [0, 1] in t its cubic Hermite from the exact u at the quarters'
 * ends (bisection) and the slopes there, (W / 4) / F'(u), W = F(1) - F(0),
 * is within about 2^-16 of it on a typical piece of uneven keys, where the
 * chord fraction alone is within 2^-6: most solves then end at their second
 * step, where they took three or four. The piece keeps the chord where a
 * slope exceeds 3 times its quarter's rise (each cubic monotone: Fritsch and
 * Carlson) or F' is not positive. A function of the piece alone, as every
 * start is. The three u in Q1.15 and the five slopes in Q2.14 take the 16
 * bytes of the key interval's area, which these kinds do not have: the
 * pieces' stride is unchanged. On a curve without eases a better start
 * replaces it where it can (tab_start() below).
 */
static void inv_start(struct mot_curve_seg *s)
{
	/* |fc| summing to 2^61 at most: F, F' and 3 W fit 63 bits */
	const int64_t *fc = s->fc;
	int64_t w = fc[1] + fc[2] + fc[3], uk[5];
	uint64_t m[5];
	unsigned k;

	if (s->start != START_CHORD || w <= 0)
		return;
	uk[0] = 0;
	uk[4] = ONE62;
	for (k = 1; k < 4; k++)
		uk[k] = inv_frame(fc, fc[0] + (int64_t)k * (w / 4));
	for (k = 0; k < 5; k++) {
		int64_t d = poly_deriv(fc, uk[k]);
		uint64_t r, q;
		uint32_t sat = 0;

		if (d <= 0)
			return;
		/* du/ds = (W / 4) / F' in Q2.62, saturated where it exceeds 64 bits */
		q = mot_acc_udiv(mot_acc_from(w / 4, 62), (uint64_t)d, &r, &sat);
		if (sat || q > (uint64_t)3 << 62 ||
		    (k > 0 && q > 3 * (uint64_t)(uk[k] - uk[k - 1])) ||
		    (k < 4 && q > 3 * (uint64_t)(uk[k + 1] - uk[k])))
			return;
		m[k] = q;
	}
	for (k = 0; k < 3; k++)
		s->us[k] = (uint16_t)((uk[k + 1] + ((int64_t)1 << 46)) >> 47);
	for (k = 0; k < 5; k++)
		s->us[3 + k] = (uint16_t)((m[k] + ((uint64_t)1 << 47)) >> 48);
	s->start = START_INV;
}

/*
 * The Newton start of a START_INV piece on a curve without eases
 * (START_TAB): the same inverse u(t) on each half of [0, 1] in t, as the
 * degree-7 polynomial through u at the half's eight Chebyshev nodes
 * (bisection), in x = 4 t - 1 or 4 t - 3 in [-1, 1]: within the piece's
 * 2^-ntol (2^-20 .. 2^-21 mostly) of the root for most solves, whose first
 * Newton step is then their last. The random scene's 133,492 solves on such
 * pieces take 1.29 iterations, 71% of them one (1.38 and 62% with the
 * tolerances of 2^-22 .. 2^-24 that newton_bits() gave before it bounded
 * the residual), where the Hermite quarters (within 2^-16 at best in
 * Q1.15) took 2.09 and 2% one; unquantised they would take 2.04, on eight
 * parts 1.77, on sixteen (twice this table's numbers) 1.38. The 16 coefficients in Q1.30 (rounded: 2^-31 each) take
 * the 64 bytes of inv_h and ease, which only an eased key interval reads
 * (curve.c's eval(), under seg_ease): the pieces' stride is unchanged, and
 * an eased curve keeps START_INV. Kept where the coefficients' magnitudes
 * sum below 2 (less a margin for the evaluation's truncations), so that
 * every partial sum of tab62()'s Horner (curve_solve.c) fits Q1.62; else
 * the piece stays START_INV. The coefficients are V^-1 y for the
 * Vandermonde matrix V of the nodes: V^-1 in Q5.58 (|V^-1| < 31), each row
 * even or odd in the node (x(7 - i) = -x(i)), so four columns kept; y in
 * Q2.60.
 */
_Static_assert(sizeof(((struct mot_curve_seg *)0)->ut) <=
		       sizeof(struct mot_recip) + sizeof(struct mot_ease),
	       "START_TAB's table within inv_h and ease: the stride unchanged");

static const int64_t tab_node[4] = { /* cos((2i + 1) pi / 16), Q2.62 */
	4523073764714963030, 3834476785802888710, 2562115475870945497, 899695310372275547,
};

int64_t mot_cv_tab_node(unsigned h, unsigned i)
{
	/* t = (2 h + 1 + x) / 4, x the node: x(7 - i) = -x(i) */
	int64_t x = i < 4 ? tab_node[i] : -tab_node[7 - i];

	return ((int64_t)(2 * h + 1) << 60) + x / 4;
}

bool mot_cv_tab_fit(const int64_t y[16], int32_t ut[16])
{
	static const int64_t vinv[8][4] = { /* V^-1, Q5.58, columns 0 .. 3 */
		{ -7166573308883288, 24073672518002241, -53920905240486667, 181128994107223585 },
		{ -7306974780389132, 28953159756898729, -97055065292859510, 928436594062567137 },
		{ 221880219004929289, -735535851415222588, 1550774465498521476,
		  -1037118833088228178 },
		{ 226227109478751180, -884621446811918585, 2791320292791506324,
		  -5316095756930929466 },
		{ -915992568849766137, 2787862435053499929, -3603101049136798817,
		  1731231182933065025 },
		{ -933937924183745833, 3352933641595413863, -6485410547561986357,
		  8873998284701907479 },
		{ 882407917260943721, -2130321161396766249, 2130321161396766249,
		  -882407917260943721 },
		{ 899695310372275547, -2562115475870945497, 3834476785802888710,
		  -4523073764714963030 },
	};
	int64_t a[16];
	unsigned h, i, k;
	uint64_t sum;

	for (h = 0; h < 2; h++) {
		const int64_t *yh = y + 8 * h;

		for (k = 0; k < 8; k++) {
			mot_acc r = mot_acc_zero();

			for (i = 0; i < 4; i++)
				r = mot_acc_mac(r, vinv[k][i],
						k % 2 ? yh[i] - yh[7 - i] : yh[i] + yh[7 - i]);
			/* Q.118 to Q1.30, within int64 */
			a[8 * h + k] = (int64_t)mot_acc_lo(mot_cv_acc_round_shift(r, 88));
		}
		for (sum = 0, k = 0; k < 8; k++)
			sum += (uint64_t)(a[8 * h + k] < 0 ? -a[8 * h + k] : a[8 * h + k]);
		if (sum > ((uint64_t)1 << 31) - 256)
			return false;
	}
	for (k = 0; k < 16; k++)
		ut[k] = (int32_t)a[k];
	return true;
}

static void tab_start(struct mot_curve_seg *s)
{
	const int64_t *fc = s->fc;
	int64_t w = fc[1] + fc[2] + fc[3], y[16];
	unsigned k;

	for (k = 0; k < 16; k++) /* Q2.60 */
		y[k] = (inv_frame(fc, fc[0] + mul62(w, mot_cv_tab_node(k / 8, k % 8))) + 2) >> 2;
	if (mot_cv_tab_fit(y, s->ut))
		s->start = START_TAB;
}

int mot_cv_prep_spline(struct mot_curve *c)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, j;
	int64_t nb[4][4];
	uint64_t den;
	int err = MOT_OK;

	basis(c, nb, &den);
	for (j = 0; j < c->nseg && !err; j++)
		err = prep_piece(c, j, nb, den);
	/* the first piece starts at the first key: its F(0) is the tripled
	 * key's frame, a weighted mean of three equal numbers, exact. Held so,
	 * every frame the solve sees is at or past some piece's f0
	 * (curve_solve.c's start_u() relies on it) */
	if (!err && c->seg[0].f0 > k[0].frame)
		c->seg[0].f0 = k[0].frame;
	for (j = 0; j < c->nseg && !err; j++) {
		struct mot_curve_seg *s = &c->seg[j];

		s->f1 = j + 1 < c->nseg ? c->seg[j + 1].f0 : k[n - 1].frame;
		if (s->f1 > s->f0) {
			err = mot_recip_init(&s->inv_w, s->f1 - s->f0);
			inv_start(s);
			if (s->start == START_INV && !c->seg_ease)
				tab_start(s);
		}
	}
	return err;
}
