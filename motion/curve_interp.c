/* SPDX-License-Identifier: MIT */
/*
 * curve_interp.c - the pieces of the interpolating kinds, which pass through
 * every key (FORMULAS section 6; the seed paper sections 5.3.1 and 5.3.2).
 *
 * Piece j is key interval j, a cubic in s = (f - f(j)) / h relative to v(j):
 *   step:     0 (the piece holds v(j); evaluation reads vref alone)
 *   linear:   (v(j+1) - v(j)) s: continuous, with a corner at every key
 *   hermite:  Catmull-Rom for uneven key times, continuous in velocity but
 *             free to overshoot between keys (the paper's "exaggerated
 *             path"); the tangents and coefficients below.
 * Init only.
 */
#include "curve_priv.h"

/* dv h / d at scale 2^58, rounded once (|dv| < 2^63, 0 < h <= d): a
 * Catmull-Rom tangent term h m = h dv / d. The integer part is an exact
 * division, the fraction a second one. */
static mot_acc tangent58(int64_t dv, int64_t h, int64_t d)
{
	int64_t adv = dv < 0 ? -dv : dv, fr = 0;
	uint64_t r, q = mot_acc_udiv(mot_acc_mul(adv, h), (uint64_t)d, &r, NULL);
	mot_acc t = acc_shl(mot_acc_from((int64_t)q, 0), 58);

	mot_cv_acc_div_round(&fr, mot_acc_from(dv < 0 ? -(int64_t)r : (int64_t)r, 0), 58,
			     (uint64_t)d);
	return mot_acc_add(dv < 0 ? mot_acc_neg(t) : t, mot_acc_from(fr, 0));
}

static mot_acc acc_times(mot_acc x, unsigned k)
{
	mot_acc r = mot_acc_zero();

	while (k--)
		r = mot_acc_add(r, x);
	return r;
}

/* Hermite piece i: numerators of c[] in powers of s relative to v(i), at
 * scale 2^58 (FORMULAS section 6): the tangent terms h m(i), h m(i+1) with
 * the chord of each tangent (one-sided at the ends), or an explicit tangent
 * (key i's out, key i+1's in: h m exactly, h m 2^58 = h m 2^26 of the raw
 * numbers, below 2^121 as curve.c checks), then
 *   c1 = h m(i), c2 = 3 dv - 2 h m(i) - h m(i+1), c3 = -2 dv + h m(i) + h m(i+1).
 * Every term is below 2^121, every sum below 2^124. */
static void prep_hermite(const struct mot_curve *c, const struct mot_tangent *tan, uint32_t i,
			 mot_acc num[4], uint64_t *den)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, t;
	int64_t h = k[i + 1].frame - k[i].frame;
	mot_acc tm[2], d58 = acc_shl(mot_acc_from(k[i + 1].value - k[i].value, 0), 58);

	for (t = 0; t < 2; t++) {
		uint32_t j = i + t, a = j == 0 ? 0 : j - 1, b = j == n - 1 ? j : j + 1;
		uint32_t side = t ? MOT_TANGENT_IN : MOT_TANGENT_OUT;

		if (tan && (tan[j].set & side))
			tm[t] = acc_shl(mot_acc_mul(h, t ? tan[j].in : tan[j].out), 26);
		else
			tm[t] = tangent58(k[b].value - k[a].value, h, k[b].frame - k[a].frame);
	}
	num[0] = mot_acc_zero();
	num[1] = tm[0];
	num[2] = mot_acc_sub(acc_times(d58, 3), mot_acc_add(acc_times(tm[0], 2), tm[1]));
	num[3] = mot_acc_sub(mot_acc_add(tm[0], tm[1]), acc_times(d58, 2));
	*den = (uint64_t)1 << 58;
}

int mot_cv_prep_interp(struct mot_curve *c, const struct mot_tangent *tan)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, j, p;
	int err = MOT_OK;

	for (j = 0; j < n - 1 && !err; j++) {
		unsigned e;
		bool pow;
		struct mot_curve_seg *s = &c->seg[j];
		mot_acc num[4];
		uint64_t den = 1;

		s->f0 = s->fref = k[j].frame;
		s->f1 = k[j + 1].frame;
		s->vref = k[j].value;
		s->start = START_CHORD;
		err = mot_recip_init(&s->inv_w, s->f1 - s->f0);
		num[0] = num[1] = num[2] = num[3] = mot_acc_zero();
		if (c->kind == MOT_INTERP_LINEAR)
			num[1] = mot_acc_from(k[j + 1].value - k[j].value, 0);
		else if (c->kind == MOT_INTERP_HERMITE)
			prep_hermite(c, tan, j, num, &den);
		/* a hermite piece without ease in s' (curve.h): the polynomials
		 * of s at s = s' 2^e / h, each coefficient exact and rounded once */
		e = bitlen64((uint64_t)(s->f1 - s->f0));
		pow = c->kind == MOT_INTERP_HERMITE && mot_ease_is_identity(&s->ease) && e <= 62;
		s->ush = pow ? (int8_t)(62 - e) : -1;
		if (!err)
			err = pow ? mot_cv_poly_prep_pow(s->c, &s->vsh, num, den, e,
							 (uint64_t)(s->f1 - s->f0)) :
				    mot_cv_poly_prep(s->c, &s->vsh, num, den);
		if (!err && c->kind == MOT_INTERP_HERMITE) {
			/* the mean value, c[p] / (p + 1), in its own block scale
			 * (curve_integral.c): numerators 12 / (p + 1) times c's
			 * over 12 den (< 2^127) */
			mot_acc im[4];

			im[0] = mot_acc_zero();
			for (p = 1; p < 4; p++)
				im[p] = acc_times(num[p], 12 / (p + 1));
			err = pow ? mot_cv_poly_prep_pow(s->ic, &s->fsh, im, 12 * den, e,
							 (uint64_t)(s->f1 - s->f0)) :
				    mot_cv_poly_prep(s->ic, &s->fsh, im, 12 * den);
		}
	}
	return err;
}
