/* SPDX-License-Identifier: MIT */
/*
 * curve_bezier.c - Bezier curves: one curve of degree n - 1 on all n keys as
 * control points (frame, value), through the first and last key only, the
 * paper's damped path (FORMULAS section 6; the seed paper section 5.3.4).
 * Here its preparation: the scales of its key offsets and, where it keeps
 * the precision, its power form. Like the splines it is evaluated where its
 * frame coordinate equals the frame, by Horner's rule on the power form or by
 * de Casteljau's algorithm (curve_solve.c). Init only.
 */
#include "curve_priv.h"

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
 * sum k |a_k| 2^sh < 2^63 for the frame (its derivative's partial sums too)
 * and sum |a_k| 2^sh < 2^63 for the value, and the form is used only when
 * sh >= 10. Horner's step (curve_solve.c, power_frame()) takes the high
 * word of the 128-bit product r u, u in Q2.62, times 4: the product to a
 * multiple of 4 units, floored, one product and one lea; each a_k but the
 * top one holds 2 units more, so that the floor's loss of [0, 4) becomes
 * (-2, 2]: half a unit of 2^(sh - 2), the rounding of the 2^61 scale
 * before, and m of them (the value's last a floor: a unit) stay within
 * 1/16 LSB (2^(sh - 2) >= 2^8, m <= 31).
 * Other curves (many keys, or keys far apart: 12 keys over +-1000 units,
 * 32 keys of any size) keep de Casteljau. The coefficients live in the c[]
 * and fc[] of the curve's entries, which a Bezier curve does not otherwise
 * use: the frame's a_1 .. a_m in slots 0 .. m - 1, the value's from slot
 * power_vslot(m) (the n - 1 entries hold 8 (n - 1) slots, enough for both).
 */
#define POWER_MIN_SHIFT 10

/* Bezier: scales that keep the key offsets from the first key within 2^58:
 * de Casteljau differences are then within 2^59, and the frame derivative
 * (n - 1) (w1 - w0) within 31 * 2^58 < 2^63. */
static int bezier_shift(int64_t maxdiff)
{
	return maxdiff == 0 ? 0 : 58 - (int)bitlen64((uint64_t)maxdiff);
}

/* The power form of a Bezier curve when it keeps its precision (see
 * above): exact coefficients and their scales, or c->power false. */
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
			if (mot_cv_acc_bitlen(d[0]) + bitlen64(b) > 54)
				return; /* |a_j| may reach 2^54: out of the form's range */
			a[side][j - 1] = (int64_t)mot_acc_lo(d[0]) * (int64_t)b;
			/* below 32 * 31 * 2^54 */
			sum += (side ? 1 : j) * (uint64_t)mot_abs(a[side][j - 1]);
		}
		len[side] = bitlen64(sum);
		if (len[side] > 63 - POWER_MIN_SHIFT)
			return;
	}
	for (side = 0; side < 2; side++) {
		/* (62 at most: a constant value has sum |a_k| = 0) */
		int sh = len[side] ? 63 - (int)len[side] : 62;

		/* |a_j| 2^sh <= 2^63 - 2^sh: the 2 units fit */
		for (j = 0; j < m; j++) {
			uint32_t slot = side ? power_vslot(m) + j : j;

			*power_slot(c, slot) = a[side][j] * ((int64_t)1 << sh) + (j + 1 < m ? 2 : 0);
		}
		if (side)
			c->seg[0].vsh = (int16_t)sh;
		else
			c->seg[0].fsh = (int16_t)sh;
	}
	c->power = true;
}

/*
 * The Newton tolerance of a Bezier curve (seg[0].ntol): what its frame
 * needs, the frame at the solve's u within 2^-4 of a raw unit of f (as
 * newton_bits() in curve_approx.c), bounded without the minimum of F'.
 * A Newton step du = (1 + e) F(u) / F'(u) from u (F(u) less the target,
 * e the step's own error) ends at u' = u - du with, by Taylor's theorem,
 *     F(u') = -e F'(u) du + F''(x) du^2 / 2,   x between u and u',
 * so |F(u')| <= 2^-29 Dmax |du| + M2 du^2 / 2 for |e| <= 2^-29, with Dmax
 * and M2 bounds of |F'| and |F''| on [0, 1]. In raw units of frame (the
 * scale 2^fsh cancels), x_i the keys' frames less the first's:
 *     F'(u)  = m sum (x_(i+1) - x_i) B_(i,m-1)(u),
 *     F''(u) = m (m - 1) sum (x_(i+2) - 2 x_(i+1) + x_i) B_(i,m-2)(u),
 * the Bernstein polynomials B non-negative with sum 1: F' <= m max dx,
 * |F''| <= m (m - 1) max |d2x|, and F' >= m min dx > 0 (the keys' frames
 * increase). Each term at most 2^-5 after a last step below 2^-k, from bit
 * lengths (x < 2^bitlen(x), bitlen(a b) <= bitlen(a) + bitlen(b)):
 *     2 k >= bitlen(m (m - 1)) + bitlen(max |d2x|) + 4,
 *     k >= bitlen(m) + bitlen(max dx) - 24.
 * e is ratio62()'s 2^-29.4 (curve_solve.c) and F'(u)'s own rounding,
 * below m^3 units of F (Horner's or de Casteljau's roundings; the power
 * form's units are 2^(fsh - 2), its steps' floors to 4 of 2^fsh), relative
 * to F' >= m min dx 2^fsh at most 2^-32 where bitlen(min dx) + fsh >= 48
 * (50 in power form: the same curves as its 2^61 scale took): else
 * NEWTON_TOL_BITS. At least 16, at most NEWTON_TOL_BITS. |dx| < 2^63 and
 * |d2x| < 2^63 (|frame| < 2^62 raw): no overflow. Most of the random
 * scene's Bezier curves need 20 .. 26 bits.
 */
static uint8_t bezier_ntol(const struct mot_curve *c)
{
	const struct mot_key *k = c->keys;
	uint32_t m = c->nkeys - 1, i;
	uint64_t dmin = UINT64_MAX, dmax = 0, d2 = 0;
	int b, br;

	for (i = 0; i < m; i++) {
		uint64_t dx = (uint64_t)(k[i + 1].frame - k[i].frame);

		dmin = dx < dmin ? dx : dmin;
		dmax = dx > dmax ? dx : dmax;
		if (i + 1 < m) {
			int64_t e = (k[i + 2].frame - k[i + 1].frame) - (int64_t)dx;
			uint64_t ae = e < 0 ? 0 - (uint64_t)e : (uint64_t)e;

			d2 = ae > d2 ? ae : d2;
		}
	}
	if ((int)bitlen64(dmin) + c->seg[0].fsh < 48 + 2 * c->power)
		return NEWTON_TOL_BITS;
	b = d2 ? ((int)bitlen64((uint64_t)m * (m - 1)) + (int)bitlen64(d2) + 4 + 1) / 2 : 0;
	br = (int)bitlen64(m) + (int)bitlen64(dmax) - 24;
	b = b > br ? b : br;
	b = b < 16 ? 16 : b;
	return (uint8_t)(b < NEWTON_TOL_BITS ? b : NEWTON_TOL_BITS);
}

int mot_cv_prep_bezier(struct mot_curve *c)
{
	const struct mot_key *k = c->keys;
	struct mot_curve_seg *s = &c->seg[0];
	int64_t dv = 0;
	uint32_t i;
	int err;

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
	s->ntol = c->nkeys > 1 ? bezier_ntol(c) : NEWTON_TOL_BITS;
	err = mot_recip_init(&s->inv_w, s->f1 - s->f0);
	if (!err)
		mot_cv_bezier_start(c);
	return err;
}
