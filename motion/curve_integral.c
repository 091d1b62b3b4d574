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

/* Integral over [f0, f0 + e] of piece i, 0 <= e <= f1 - f0, at parameter
 * s62 = e / (f1 - f0) (cv_seg_integral()). */
static mot_acc seg_integral(const struct mot_curve *c, uint32_t i, int64_t e, int64_t s62)
{
	const struct mot_curve_seg *s = &c->seg[i];

	if (s->ush >= 0) /* ic[] in s' (curve.h) */
		s62 = e << s->ush;
	if (c->kind == MOT_INTERP_LINEAR)
		return cv_seg_integral(MOT_INTERP_LINEAR, s, c->keys[i + 1].value - s->vref, e, s62);
	return cv_seg_integral(c->kind, s, 0, e, s62);
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
