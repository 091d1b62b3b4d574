/* SPDX-License-Identifier: MIT */
/*
 * ease.c - the trapezoidal slow-in/slow-out profile (see ease.h).
 *
 * FORMULAS.md section 7 defines s' piecewise. Everything with a division is
 * done here, at init: the peak speed v = 2 / (2 - a - b) and the two
 * parabola factors v/(2a), v/(2b), kept as normalised mantissas so that a
 * tiny a (a large factor) loses no relative precision. Applying the profile
 * is then a comparison and two or three products:
 *     s < a:        t = s * v/(2a)       (t < v/2, no overflow)   s' = t * s
 *     middle:       s' = v (2s - a) / 2  (one 128-bit sum, one rounding)
 *     s > 1 - b:    r = 1 - s, t = r * v/(2b), s' = 1 - t * r
 * Multiplying s into the factor before squaring keeps each rounding at half
 * a unit of 2^-62 however large v/(2a) is. The pieces meet at s = a and
 * s = 1 - b to within those roundings.
 */
#include "ease.h"

/* round(num * 2^shift / den) with the mantissa in [2^62, 2^63), for
 * 0 < num < 2^63, 0 < den < 2^63. */
static void ease_mantissa(int64_t num, int64_t den, int64_t *m, uint32_t *shift)
{
	unsigned ln = 64 - mot_clz64((uint64_t)num), ld = 64 - mot_clz64((uint64_t)den);
	/* num / den is in (2^(ln - 1 - ld), 2^(ln + 1 - ld)), so with
	 * s = 62 - ln + ld the quotient is in (2^61, 2^63); one retry. */
	unsigned s = 62 + ld - ln;
	uint64_t q, r;

	for (;;) {
		mot_acc x = mot_acc_from(num, 0);

		/* num * 2^s < 2^(ln + s) = 2^(62 + ld) <= 2^125: fits. */
		if (s >= 64)
			x = mot_acc_make(mot_acc_lo(x) << (s - 64), 0);
		else if (s > 0)
			x = mot_acc_make(mot_acc_lo(x) >> (64 - s), mot_acc_lo(x) << s);
		q = mot_acc_udiv(x, (uint64_t)den, &r, NULL);
		if (q >= (uint64_t)1 << 62)
			break;
		s++;
	}
	if (r >= (uint64_t)den - r)
		q++;
	if (q >= (uint64_t)1 << 63) {
		q >>= 1;
		s--;
	}
	/* A factor of 2^62 or more (shift 0) comes only from a fraction of one
	 * unit, 2^-62, whose parabola holds no s > 0 and is never applied; keep
	 * the shift at 1 so that the rounding in the apply stays defined. */
	if (s == 0)
		s = 1;
	*m = (int64_t)q;
	*shift = s;
}

int mot_ease_init_ratio(struct mot_ease *e, int64_t a_num, int64_t b_num, int64_t den,
			uint32_t *sat)
{
	int64_t a, b;

	e->a = e->b = e->ka = e->kb = 0;
	e->v = (int64_t)1 << 61;
	e->ka_shift = e->kb_shift = 0;
	if (den <= 0 || a_num < 0 || b_num < 0 || a_num > den || b_num > den - a_num)
		return MOT_E_INVAL;
	a = mot_muldiv(a_num, MOT_Q62_ONE, den, sat);
	b = mot_muldiv(b_num, MOT_Q62_ONE, den, sat);
	if (b > MOT_Q62_ONE - a) /* both rounded up */
		b = MOT_Q62_ONE - a;
	e->a = a;
	e->b = b;
	/* v = 2 / (2 - a - b) = 2^124 / (2^63 - A - B) in Q3.61; the divisor is
	 * in [2^62, 2^63], the quotient in [2^61, 2^62]. */
	{
		uint64_t d = ((uint64_t)1 << 63) - (uint64_t)a - (uint64_t)b, r;
		uint64_t q = mot_acc_udiv(mot_acc_make((uint64_t)1 << 60, 0), d, &r, NULL);

		if (r >= d - r)
			q++;
		e->v = (int64_t)q;
	}
	/* v/(2a) = (V / 2^61) / (2 A / 2^62) = V / A */
	if (a > 0)
		ease_mantissa(e->v, a, &e->ka, &e->ka_shift);
	if (b > 0)
		ease_mantissa(e->v, b, &e->kb, &e->kb_shift);
	return MOT_OK;
}

/* The mantissa of v/(2L) 2^62 = V / L for a length L > 0 (ease_mantissa),
 * its shift at most 63 (mot_ease_round's): only for L above 2^60 units
 * (2^28 frames) is it rounded to fewer bits, as many as v/(2L) 2^62 has. */
static void span_factor(int64_t v, int64_t l, int64_t *m, uint32_t *shift)
{
	ease_mantissa(v, l, m, shift);
	if (*shift > 63) {
		unsigned d = *shift - 63;

		*m = (int64_t)(((uint64_t)*m + ((uint64_t)1 << (d - 1))) >> d);
		*shift = 63;
	}
}

int mot_ease_span_init(struct mot_ease_span *e, int64_t a, int64_t b, int64_t w, uint32_t *sat)
{
	e->a = e->ka = e->kb = 0;
	e->w = e->d = w > 0 ? w : 1;
	e->v = (int64_t)1 << 61;
	e->ka_shift = e->kb_shift = 1;
	e->av = mot_acc_zero();
	if (w <= 0 || a < 0 || b < 0 || a > w || b > w - a)
		return MOT_E_INVAL;
	e->a = a;
	e->d = w - b;
	/* V = v 2^61 = 2^62 W / (2W - A - B); the divisor is in [W, 2W] (below
	 * 2^64), the quotient in [2^61, 2^62]. */
	{
		uint64_t d = 2 * (uint64_t)w - (uint64_t)a - (uint64_t)b, r;
		uint64_t q = mot_acc_udiv(mot_acc_make((uint64_t)w >> 2, (uint64_t)w << 62), d, &r,
					  sat);

		if (r >= d - r)
			q++;
		e->v = (int64_t)q;
	}
	if (a > 0)
		span_factor(e->v, a, &e->ka, &e->ka_shift);
	if (b > 0)
		span_factor(e->v, b, &e->kb, &e->kb_shift);
	e->av = mot_acc_mul(a, e->v);
	return MOT_OK;
}

/* floor(x 2^63 / m) for 0 <= x <= 2^62 < m: below 2^63 */
static int64_t over_m(int64_t x, int64_t m, bool ceil)
{
	uint64_t r, q = mot_acc_udiv(mot_acc_make((uint64_t)x >> 1, (uint64_t)x << 63), (uint64_t)m,
				     &r, NULL);

	return (int64_t)(q + (ceil && r != 0));
}

void mot_ease_fused_init(struct mot_ease_fused *f, const struct mot_ease *e,
			 const struct mot_recip *r)
{
	f->xa = INT64_MAX;
	f->xd = f->m = 0;
	if (r->shift <= 30)
		return; /* a width of one unit: frac62's own case, 0 or 1 */
	/* m < 2^63 and V <= 2^62: M below 2^63 */
	f->m = mot_acc_round(mot_acc_mul(r->m, e->v), 62, NULL);
	/* s < a: x' m < a 2^63; s > 1 - b: x' m > (1 - b) 2^63 */
	f->xa = over_m(e->a, r->m, true);
	f->xd = over_m(MOT_Q62_ONE - e->b, r->m, false);
}

int mot_ease_init(struct mot_ease *e, mot_q32 a, mot_q32 b, uint32_t *sat)
{
	return mot_ease_init_ratio(e, a, b, MOT_Q32_ONE, sat);
}

int64_t mot_ease_apply62(const struct mot_ease *e, int64_t s)
{
	return mot_ease_apply62_in(e, s);
}

mot_q32 mot_ease_apply(const struct mot_ease *e, mot_q32 s, uint32_t *sat)
{
	int64_t s62;

	if (s < 0 || s > MOT_Q32_ONE) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN;
		s = s < 0 ? 0 : MOT_Q32_ONE;
	}
	s62 = mot_ease_apply62(e, s * ((int64_t)1 << 30));
	return (s62 + ((int64_t)1 << 29)) >> 30;
}
