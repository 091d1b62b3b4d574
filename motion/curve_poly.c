/* SPDX-License-Identifier: MIT */
/*
 * curve_poly.c - the curves' numbers (curve_priv.h): the 128-bit shifts,
 * roundings and divisions that prepare the cubics, and the block floating
 * point of one cubic. The helpers every sample needs are inline in
 * curve_priv.h; these run at init, or on the rare path of a value that
 * does not fit int64 before its reference is added.
 */
#include "curve_priv.h"

mot_acc mot_cv_acc_sar(mot_acc x, unsigned n)
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

unsigned mot_cv_acc_bitlen(mot_acc x)
{
	if (mot_acc_is_neg(x))
		x = mot_acc_neg(x);
	if (mot_acc_hi(x))
		return 64 + bitlen64(mot_acc_hi(x));
	return bitlen64(mot_acc_lo(x));
}

mot_acc mot_cv_acc_round_shift(mot_acc x, int sh)
{
	if (sh <= 0)
		return acc_shl(x, (unsigned)-sh);
	return mot_cv_acc_sar(mot_acc_add(x, acc_shl(mot_acc_from(1, 0), (unsigned)sh - 1)),
			      (unsigned)sh);
}

bool mot_cv_acc_div_round(int64_t *out, mot_acc num, int sh, uint64_t den)
{
	bool neg = mot_acc_is_neg(num);
	uint64_t q, r;

	if (neg)
		num = mot_acc_neg(num);
	if (sh > 0) {
		if (mot_cv_acc_bitlen(num) + (unsigned)sh > 126)
			return false;
		num = acc_shl(num, (unsigned)sh);
	} else if (sh < 0) {
		num = -sh >= 127 ? mot_acc_zero() : mot_cv_acc_sar(num, (unsigned)-sh);
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

/*
 * Block floating point for one cubic: c[p] = round(num[p] / den * 2^sh) with
 * sh chosen so that sum |c[p]| <= 2^60 + 2. |num[p] / den| < 2^(L - ld + 1)
 * with L the largest bit length of num[] and ld that of den, so the scale
 * sh = 57 - L + ld bounds every |c[p]| by 2^58. The same ratio num/den gives
 * the same sh and coefficients whatever the common factor (which is what
 * makes the beta spline with beta1 = 1, beta2 = 0 the B-spline bit for bit).
 */
int mot_cv_poly_prep(int64_t c[4], int16_t *sh, const mot_acc num[4], uint64_t den)
{
	unsigned l = 0, p;
	int s;

	for (p = 0; p < 4; p++) {
		unsigned lp = mot_cv_acc_bitlen(num[p]);

		l = lp > l ? lp : l;
	}
	if (l == 0) {
		c[0] = c[1] = c[2] = c[3] = 0;
		*sh = 0;
		return MOT_OK;
	}
	s = 57 - (int)l + (int)bitlen64(den);
	for (p = 0; p < 4; p++)
		if (!mot_cv_acc_div_round(&c[p], num[p], s, den))
			return MOT_E_RANGE;
	*sh = (int16_t)s;
	return MOT_OK;
}
