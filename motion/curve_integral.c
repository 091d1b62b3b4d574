/* SPDX-License-Identifier: MIT */
/*
 * curve_integral.c - running integrals of the interpolating kinds, for rpm
 * strands: the angle as the exact integral of a keyed speed (FORMULAS
 * section 8; the seed paper section 8.1, a propeller's revolutions per
 * minute as a function of time).
 *
 * Init prepares the integral from frame 0 to every key (mot_cv_prep_area);
 * mot_curve_integral() adds one partial piece in closed form, so nothing
 * accumulates from tick to tick: the result after a day is as good as after
 * a second.
 */
#include "curve_priv.h"

/*
 * Integral over [f0, f0 + e] of interpolating piece s, 0 <= e <= f1 - f0, in
 * value x frames, Q64.64 (FORMULAS section 8). With s = e / h:
 *   step:     e v0                                  exact
 *   linear:   e v0 + dv e^2 / (2h)                  exact but for one rounding:
 *             e^2 / h = q + r / h and dv r / h = q2 + r2 / h, two exact divisions
 *   hermite:  e (v0 + sum c_p s^p / (p + 1))        the mean value in the block
 *             scale of c (~2^-59 of sum |c_p|), times e in 128 bits; in s'
 *             = e / 2^e' with its own c_p where the piece is kept in s'
 *             (curve.h), the same sum
 */
static mot_acc seg_integral(const struct mot_curve *c, uint32_t i, int64_t e, int64_t s62)
{
	const struct mot_curve_seg *s = &c->seg[i];
	mot_acc a = mot_acc_mul(e, s->vref);

	if (s->ush >= 0) /* ic[] in s' (curve.h) */
		s62 = e << s->ush;

	if (c->kind == MOT_INTERP_LINEAR) {
		/* |dv| < 2^63 and 0 <= e <= h < 2^63 (curve.h limits), so every
		 * quotient below fits 63 bits */
		int64_t dv = c->keys[i + 1].value - s->vref;
		int64_t adv = dv < 0 ? -dv : dv;
		uint64_t r, r2, q, q2;
		mot_acc t, ee = mot_acc_mul(e, e), ar;

		/* by h = f1 - f0's prepared reciprocal (mot_cv_prep_area()):
		 * e^2 < h 2^63 and adv r < h 2^63, high words below h, the
		 * quotients exact (mot_acc_udiv()'s) */
		q = mot_udiv_by_inv(mot_acc_hi(ee), mot_acc_lo(ee), &s->inv_hd, &r);
		ar = mot_acc_mul(adv, (int64_t)r);
		q2 = mot_udiv_by_inv(mot_acc_hi(ar), mot_acc_lo(ar), &s->inv_hd, &r2);
		t = mot_acc_add(mot_acc_mul(adv, (int64_t)q), mot_acc_from((int64_t)q2, 0));
		/* half of t + r2/h, rounded to nearest, ties toward +infinity */
		if (dv >= 0)
			t = mot_cv_acc_sar(mot_acc_add(t, mot_acc_from(1, 0)), 1);
		else
			t = mot_acc_neg(mot_cv_acc_sar(mot_acc_add(t, mot_acc_from(r2 != 0, 0)), 1));
		return mot_acc_add(a, t);
	}
	if (c->kind == MOT_INTERP_HERMITE)
		a = mot_acc_add(a, mot_cv_acc_round_shift(mot_acc_mul(e, poly_eval(s->ic, s62)),
							  s->fsh));
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
			 piece_u(frame - c->seg[i].f0, &c->seg[i].inv_w));
	*out = mot_acc_add(c->seg[i].area, a);
	return MOT_OK;
}

/* Running integrals: area of piece j = integral from frame 0 to key j. Built
 * from the first key with the same function the run time uses, then shifted
 * so that the integral at frame 0 is 0 exactly. */
int mot_cv_prep_area(struct mot_curve *c)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, j;
	mot_acc a = mot_acc_zero(), zero;

	c->area_first = a;
	for (j = 0; j + 1 < n && c->kind == MOT_INTERP_LINEAR; j++) {
		int err = mot_udiv_inv_init(&c->seg[j].inv_hd, (uint64_t)(k[j + 1].frame - k[j].frame));

		if (err)
			return err;
	}
	for (j = 0; j + 1 < n; j++) {
		c->seg[j].area = a;
		a = mot_acc_add(a, seg_integral(c, j, k[j + 1].frame - k[j].frame, ONE62));
		if (mot_cv_acc_bitlen(a) > 124)
			return MOT_E_RANGE;
	}
	c->area_last = a;
	mot_curve_integral(&zero, c, NULL, 0, NULL);
	zero = mot_acc_neg(zero);
	c->area_first = mot_acc_add(c->area_first, zero);
	c->area_last = mot_acc_add(c->area_last, zero);
	for (j = 0; j + 1 < n; j++)
		c->seg[j].area = mot_acc_add(c->seg[j].area, zero);
	if (mot_cv_acc_bitlen(c->area_first) > 124 || mot_cv_acc_bitlen(c->area_last) > 124)
		return MOT_E_RANGE;
	return MOT_OK;
}
