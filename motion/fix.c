/* SPDX-License-Identifier: MIT */
/* fix.c - exact integer divisions for the Q32.32 core (see fix.h). */
#include "fix.h"

uint64_t mot_acc_udiv(mot_acc x, uint64_t d, uint64_t *rem, uint32_t *sat)
{
	/* Knuth's algorithm D on 32-bit digits (Hacker's Delight, divlu): two
	 * quotient digits, each estimated with a 64/32 division and corrected
	 * at most twice. It needs no 128-bit divide from the compiler runtime,
	 * which a freestanding core cannot call, and it is exact everywhere. */
	const uint64_t b = (uint64_t)1 << 32;
	uint64_t u1 = mot_acc_hi(x), u0 = mot_acc_lo(x);
	uint64_t vn1, vn0, un32, un21, un10, un1, un0, q1, q0, rhat;
	unsigned s;

	if (d == 0 || u1 >= d) {
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		if (rem)
			*rem = 0;
		return UINT64_MAX;
	}
	s = mot_clz64(d);
	d <<= s;
	vn1 = d >> 32;
	vn0 = d & 0xffffffffu;
	un32 = s ? (u1 << s) | (u0 >> (64 - s)) : u1;
	un10 = u0 << s;
	un1 = un10 >> 32;
	un0 = un10 & 0xffffffffu;

	q1 = un32 / vn1;
	rhat = un32 - q1 * vn1;
	while (q1 >= b || q1 * vn0 > b * rhat + un1) {
		q1--;
		rhat += vn1;
		if (rhat >= b)
			break;
	}
	un21 = un32 * b + un1 - q1 * d;

	q0 = un21 / vn1;
	rhat = un21 - q0 * vn1;
	while (q0 >= b || q0 * vn0 > b * rhat + un0) {
		q0--;
		rhat += vn1;
		if (rhat >= b)
			break;
	}
	if (rem)
		*rem = (un21 * b + un0 - q0 * d) >> s;
	return q1 * b + q0;
}

int mot_recip_init(struct mot_recip *r, int64_t d)
{
	unsigned n;
	uint64_t dn;

	if (d <= 0)
		return MOT_E_INVAL;
	n = mot_clz64((uint64_t)d);
	dn = (uint64_t)d << n; /* in [2^63, 2^64) */
	/* m = floor(2^126 / dn) is in (2^62, 2^63]; dn = 2^63 gives 2^63. */
	if (dn == (uint64_t)1 << 63) {
		r->m = (int64_t)1 << 62;
		r->shift = 94 - n - 1;
		return MOT_OK;
	}
	r->m = (int64_t)mot_acc_udiv(mot_acc_make((uint64_t)1 << 62, 0), dn, NULL, NULL);
	r->shift = 94 - n;
	return MOT_OK;
}

int mot_udiv_inv_init(struct mot_udiv_inv *in, uint64_t d)
{
	uint64_t r;

	if (d == 0)
		return MOT_E_INVAL;
	in->s = mot_clz64(d);
	in->dn = d << in->s;
	/* floor((2^128 - 1) / dn) - 2^64 = floor(((2^64 - 1 - dn) 2^64 + 2^64 - 1) / dn):
	 * its high word below dn, the quotient below 2^64 */
	in->v = mot_acc_udiv(mot_acc_make(~in->dn, ~(uint64_t)0), in->dn, &r, NULL);
	return MOT_OK;
}

int64_t mot_floordiv(int64_t n, int64_t d, int64_t *rem)
{
	int64_t q = n / d, r = n % d;

	if (r < 0) {
		q -= 1;
		r += d;
	}
	if (rem)
		*rem = r;
	return q;
}

int64_t mot_muldiv(int64_t a, int64_t m, int64_t d, uint32_t *sat)
{
	mot_acc p = mot_acc_mul(a, m);
	bool neg = mot_acc_is_neg(p);
	uint64_t q, r, ud;
	uint32_t local = 0;

	if (d <= 0) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN | MOT_SAT_OVERFLOW;
		return neg ? INT64_MIN : INT64_MAX;
	}
	ud = (uint64_t)d;
	if (neg)
		p = mot_acc_neg(p);
	q = mot_acc_udiv(p, ud, &r, &local);
	if (local)
		goto overflow;
	if (!neg) {
		/* round(p/d) = q + (r >= d - r) */
		if (r >= ud - r)
			q++;
		if (q > (uint64_t)INT64_MAX)
			goto overflow;
		return (int64_t)q;
	}
	/* -p/d = -(q + r/d); floor(-p/d + 1/2) = -q - (r > d/2 strictly) */
	if (r > ud - r)
		q++;
	if (q > (uint64_t)INT64_MAX + 1)
		goto overflow;
	return (int64_t)(0 - q);
overflow:
	if (sat)
		*sat |= MOT_SAT_OVERFLOW;
	return neg ? INT64_MIN : INT64_MAX;
}

mot_q32 mot_div(mot_q32 a, mot_q32 b, uint32_t *sat)
{
	if (b == 0) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN | MOT_SAT_OVERFLOW;
		return a < 0 ? MOT_Q32_MIN : MOT_Q32_MAX;
	}
	if (b < 0) {
		/* a*2^32/b = (-a)*2^32/(-b); -MIN is not representable, but
		 * MIN/2^32 * ... is handled by using the multiplier's sign. */
		if (b == MOT_Q32_MIN)
			return mot_muldiv(a, -(MOT_Q32_ONE / 2), -(b / 2), sat);
		return mot_muldiv(a, -MOT_Q32_ONE, -b, sat);
	}
	return mot_muldiv(a, MOT_Q32_ONE, b, sat);
}

mot_q32 mot_sum_prod_wide(const mot_q32 *a, const mot_q32 *b, unsigned n, uint32_t *sat)
{
	/* The true sum is acc + wraps * 2^128: each addition that carries out of
	 * the signed range is counted. Every term is below 2^126 in magnitude, so
	 * a nonzero count means the sum is far beyond what a Q32.32 can hold. */
	mot_acc acc = mot_acc_zero();
	long wraps = 0;
	unsigned i;

	for (i = 0; i < n; i++) {
		mot_acc p = mot_acc_mul(a[i], b[i]);
		mot_acc s = mot_acc_add(acc, p);
		bool np = mot_acc_is_neg(p);

		if (np == mot_acc_is_neg(acc) && np != mot_acc_is_neg(s))
			wraps += np ? -1 : 1;
		acc = s;
	}
	if (wraps != 0) {
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		return wraps > 0 ? MOT_Q32_MAX : MOT_Q32_MIN;
	}
	return mot_acc_round(acc, MOT_Q32_FRAC, sat);
}
