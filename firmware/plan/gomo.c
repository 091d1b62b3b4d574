/* SPDX-License-Identifier: MIT */
/* gomo.c - go-motion's exposure in ticks (see gomo.h). */
#include "gomo.h"

#include <errno.h>
#include <math.h>

/*
 * The tick of the Q32.32 frame time q, q * tick_hz * den / (num * 2^32),
 * rounded up (ceil) or down: exact in 128 bits (|q| < 2^63, tick_hz * den
 * < 2^44, num * 2^32 < 2^57), as mot_timing's own ticks are.
 */
static int64_t STRAND_RT tick_of(const struct mot_timing *t, mot_q32 q, bool up)
{
	mot_acc p = mot_acc_mul(q, (int64_t)t->ticks_den);
	uint64_t d = (uint64_t)t->num << 32, r;
	int64_t k;

	if (mot_acc_is_neg(p)) {
		k = -(int64_t)mot_acc_udiv(mot_acc_neg(p), d, &r, NULL);
		return k - (!up && r != 0);
	}
	k = (int64_t)mot_acc_udiv(p, d, &r, NULL);
	return k + (up && r != 0);
}

int STRAND_RT gomo_window(const struct mot_timing *t, int64_t f, mot_q32 s, int64_t *first,
			  int64_t *last)
{
	mot_q32 mid, half;

	if (s <= 0 || s > GOMO_SHUTTER_MAX)
		return -EINVAL;
	/* f < 2^31 (the command line's frames, a scene's span): f * 2^32 and
	 * the half shutter either side of it stay inside Q32.32 */
	mid = (mot_q32)f * MOT_Q32_ONE;
	half = s / 2;
	*first = tick_of(t, mid - half, true);
	*last = tick_of(t, mid + (s - half), false);
	return *last > *first ? 0 : -EINVAL;
}

int gomo_shutter_check(const struct mot_timing *t, mot_q32 s)
{
	uint64_t r;

	if (s <= 0 || s > GOMO_SHUTTER_MAX)
		return -EINVAL;
	/* s * tick_hz * den / num tick periods, at least 2: an interval that
	 * long holds two ticks wherever it lies */
	return mot_acc_udiv(mot_acc_mul(s, (int64_t)t->ticks_den), (uint64_t)t->num << 32, &r,
			    NULL) >= 2 ? 0 : -EINVAL;
}

bool gomo_shutter_of_angle(double angle, mot_q32 *s)
{
	double q;

	if (!(angle > 0) || !(angle <= 360))
		return false;
	q = nearbyint(angle / 360.0 * 4294967296.0);
	if (q < 1)
		return false;
	*s = (mot_q32)q;
	return true;
}
