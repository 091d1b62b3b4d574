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

/* The block scale 57 - L + bitlen(den) of the numerators (below); false,
 * with c[] and *sh zero, when they are all zero. */
static bool block_scale(int *s, int64_t c[4], int16_t *sh, const mot_acc num[4], uint64_t den)
{
	unsigned l = 0, p;

	for (p = 0; p < 4; p++) {
		unsigned lp = mot_cv_acc_bitlen(num[p]);

		l = lp > l ? lp : l;
	}
	if (l == 0) {
		c[0] = c[1] = c[2] = c[3] = 0;
		*sh = 0;
		return false;
	}
	*s = 57 - (int)l + (int)bitlen64(den);
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
	unsigned p;
	int s;

	if (!block_scale(&s, c, sh, num, den))
		return MOT_OK;
	for (p = 0; p < 4; p++)
		if (!mot_cv_acc_div_round(&c[p], num[p], s, den))
			return MOT_E_RANGE;
	*sh = (int16_t)s;
	return MOT_OK;
}

/* ---- exact rationals of many words (init only) ------------------------------------ */

#define MW 6 /* 384 bits: numerators below 2^124 times 2^(3 * 62 + 64) */

/* x <<= n, false when a set bit would leave the top word */
static bool mw_shl(uint64_t x[MW], unsigned n)
{
	unsigned w = n / 64, b = n % 64, top = 0, i;

	for (i = MW; i-- > 0 && !top;)
		top = x[i] ? 64 * i + bitlen64(x[i]) : 0;
	if (top + n > 64 * MW)
		return false;
	for (i = MW; i-- > 0;) {
		uint64_t hi = i >= w ? x[i - w] : 0, lo = i >= w + 1 ? x[i - w - 1] : 0;

		x[i] = b ? (hi << b) | (lo >> (64 - b)) : hi;
	}
	return true;
}

/* x = floor(x / d), d > 0; the remainder is returned */
static uint64_t mw_div(uint64_t x[MW], uint64_t d)
{
	uint64_t r = 0;
	unsigned i;

	for (i = MW; i-- > 0;)
		x[i] = mot_acc_udiv(mot_acc_make(r, x[i]), d, &r, NULL);
	return r;
}

/* x = floor(x / 2^n), n < 64; whether the bits shifted out were all zero */
static bool mw_shr(uint64_t x[MW], unsigned n)
{
	bool exact = n == 0 || (x[0] & (((uint64_t)1 << n) - 1)) == 0;
	unsigned i;

	for (i = 0; n && i < MW; i++)
		x[i] = (x[i] >> n) | (i + 1 < MW ? x[i + 1] << (64 - n) : 0);
	return exact;
}

bool mot_cv_div_pow_round(int64_t *out, mot_acc num, int k, uint64_t den, uint64_t w,
			  unsigned p)
{
	uint64_t x[MW] = { 0 }, q;
	bool neg = mot_acc_is_neg(num), exact = true;
	unsigned i;
	int r = k < 0 ? -k : 0;

	if (neg)
		num = mot_acc_neg(num);
	x[0] = mot_acc_lo(num);
	x[1] = mot_acc_hi(num);
	/* 2 |num| 2^k: floor(2 X / D) and whether it is exact decide the rounding */
	if (!mw_shl(x, (unsigned)(k > 0 ? k : 0) + 1))
		return false;
	exact = mw_div(x, den) == 0;
	for (i = 0; i < p; i++)
		exact = mw_div(x, w) == 0 && exact;
	for (; r > 0; r -= 63)
		exact = mw_shr(x, (unsigned)(r > 63 ? 63 : r)) && exact;
	for (i = 1; i < MW; i++)
		if (x[i])
			return false;
	q = x[0];
	/* ties toward +infinity: half up for a positive value, down for a
	 * negative one (as mot_cv_acc_div_round) */
	q = neg ? (q >> 1) + ((q & 1) && !exact) : (q >> 1) + (q & 1);
	if (q > (uint64_t)INT64_MAX)
		return false;
	*out = neg ? -(int64_t)q : (int64_t)q;
	return true;
}

/*
 * The polynomial of mot_cv_poly_prep() in u' = u w / 2^e (u' = (f - f0) /
 * 2^e for a piece f1 - f0 = w, 2^(e - 1) <= w < 2^e): c[p] = round(num[p] /
 * den (2^e / w)^p 2^sh), each exact and rounded once, with the largest sh
 * of poly_prep's, give or take four, that keeps every |c[p]| below 2^58.
 */
int mot_cv_poly_prep_pow(int64_t c[4], int16_t *sh, const mot_acc num[4], uint64_t den,
			 unsigned e, uint64_t w)
{
	unsigned p;
	int s0, s;

	if (!block_scale(&s0, c, sh, num, den))
		return MOT_OK;
	for (s = s0 + 1; s >= s0 - 4; s--) {
		bool fits = true;

		for (p = 0; p < 4 && fits; p++)
			fits = mot_cv_div_pow_round(&c[p], num[p], (int)(e * p) + s, den, w, p) &&
			       c[p] < ((int64_t)1 << 58) && c[p] > -((int64_t)1 << 58);
		if (fits) {
			*sh = (int16_t)s;
			return MOT_OK;
		}
	}
	return MOT_E_RANGE;
}
