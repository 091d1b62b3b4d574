/* SPDX-License-Identifier: MIT */
/*
 * shim_trig.c - TEST-ONLY stand-in for motion/trig.c while that file is being
 * written on its own branch: trig.h implemented with libm doubles, rounded to
 * Q32.32. Delete it when the real motion/trig.c is merged.
 */
#include <math.h>

#include "trig.h"

static mot_q32 shim_round(double x)
{
	if (x >= 9.2e18 / 4294967296.0)
		return MOT_Q32_MAX;
	if (x <= -9.2e18 / 4294967296.0)
		return MOT_Q32_MIN;
	return (mot_q32)llround(x * 4294967296.0);
}

void mot_sincos(mot_q32 turns, mot_q32 *s, mot_q32 *c)
{
	uint32_t ph = (uint32_t)turns; /* phase within the turn */
	uint32_t quad = ph >> 30;
	double a = (double)(ph & 0x3fffffffu) / 4294967296.0 * 2.0 * M_PI;
	mot_q32 sa = shim_round(sin(a)), ca = shim_round(cos(a));

	switch (quad) {
	case 0:
		*s = sa, *c = ca;
		break;
	case 1:
		*s = ca, *c = -sa;
		break;
	case 2:
		*s = -sa, *c = -ca;
		break;
	default:
		*s = -ca, *c = sa;
		break;
	}
}

mot_q32 mot_sin(mot_q32 turns)
{
	mot_q32 s, c;

	mot_sincos(turns, &s, &c);
	return s;
}

mot_q32 mot_cos(mot_q32 turns)
{
	mot_q32 s, c;

	mot_sincos(turns, &s, &c);
	return c;
}

mot_q32 mot_atan2(mot_q32 y, mot_q32 x)
{
	mot_q32 r;

	if (x == 0 && y == 0)
		return 0;
	r = shim_round(atan2((double)y, (double)x) / (2.0 * M_PI));
	return r == -MOT_Q32_HALF ? MOT_Q32_HALF : r;
}

mot_q32 mot_acos(mot_q32 x, uint32_t *sat)
{
	if (x > MOT_Q32_ONE || x < -MOT_Q32_ONE) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN;
		x = x > 0 ? MOT_Q32_ONE : -MOT_Q32_ONE;
	}
	return shim_round(acos((double)x / 4294967296.0) / (2.0 * M_PI));
}

uint64_t mot_isqrt_acc(mot_acc x, uint32_t *sat)
{
	unsigned __int128 v = ((unsigned __int128)mot_acc_hi(x) << 64) | mot_acc_lo(x);
	unsigned __int128 r, lo = 0, hi = (unsigned __int128)1 << 64;

	if ((int64_t)mot_acc_hi(x) < 0) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN;
		return 0;
	}
	/* floor sqrt by bisection, then round to nearest: r + 1/2 <= sqrt(v)
	 * iff r^2 + r < v (integers, v not a quarter-square). */
	while (hi - lo > 1) {
		unsigned __int128 mid = (lo + hi) / 2;

		if (mid * mid <= v)
			lo = mid;
		else
			hi = mid;
	}
	r = lo;
	if (r * r + r < v)
		r++;
	return (uint64_t)r;
}

mot_q32 mot_sqrt(mot_q32 x, uint32_t *sat)
{
	if (x < 0) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN;
		return 0;
	}
	return (mot_q32)mot_isqrt_acc(mot_acc_from(x, 32), sat);
}

mot_q32 mot_rsqrt(mot_q32 x, uint32_t *sat)
{
	if (x <= 0) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN;
		return MOT_Q32_MAX;
	}
	return shim_round(1.0 / sqrt((double)x / 4294967296.0));
}

mot_q32 mot_norm3(const mot_q32 v[3], uint32_t *sat)
{
	mot_acc s = mot_acc_mul(v[0], v[0]);

	s = mot_acc_mac(s, v[1], v[1]);
	s = mot_acc_mac(s, v[2], v[2]);
	return (mot_q32)mot_isqrt_acc(s, sat);
}
