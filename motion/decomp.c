/* SPDX-License-Identifier: MIT */
/*
 * decomp.c - a matrix into scale, shear, rotation and translation, and back
 * (see decomp.h).
 */
#include "decomp.h"
#include "trig.h"

#define ONE MOT_Q32_ONE

/* v - k u for 3-vectors, rounded once per component. */
static void sub_scaled(mot_q32 v[3], mot_q32 k, const mot_q32 u[3], uint32_t *sat)
{
	const mot_q32 nk = mot_sub_sat(0, k, sat);
	int j;

	for (j = 0; j < 3; j++) {
		const mot_q32 a[2] = { v[j], u[j] }, b[2] = { ONE, nk };

		v[j] = mot_sum_prod(a, b, 2, sat);
	}
}

/* s / 2^k for a scale computed on rows multiplied by 2^k, saturating. */
static mot_q32 unscale(mot_q32 s, int k, uint32_t *sat)
{
	if (k > 0)
		return mot_acc_round(mot_acc_from(s, 0), (unsigned)k, sat);
	return mot_acc_round(mot_acc_from(s, (unsigned)(1 - k)), 1, sat); /* exact or saturated */
}

int mot_mat_decompose(struct mot_decomp *out, struct mot_mat *rot_mat, const struct mot_mat *m,
		      uint32_t *sat)
{
	/*
	 * Gram-Schmidt on the rows (FORMULAS section 2, the seed paper's
	 * normalize(), after Thomas, "Decomposing a matrix into simple
	 * transformations", Graphics Gems II). Two refinements keep the result
	 * as good as the input allows at every scale:
	 *  - the rows are first multiplied by one power of two that brings the
	 *    largest entry to [2^27, 2^28): exact, and every quantity below then
	 *    carries about 60 significant bits whether the matrix is in metres
	 *    or micrometres; shears are ratios and do not see it, scales are
	 *    divided back at the end;
	 *  - each projection is taken twice ("twice is enough", Parlett): the
	 *    second pass removes what the rounding of the first left along the
	 *    earlier rows, so R stays orthogonal even for strongly sheared or
	 *    nearly singular keys.
	 * The singular test compares the scales with the largest row norm
	 * exactly: s * 10^9 < max |r_i|.
	 */
	mot_q32 r[3][3], rn[3][3], nrm[3], nmax = 0, s[3], h[3], k;
	struct mot_recip rc[3];
	struct mot_mat rm;
	uint64_t big = 0;
	int sh, i, j, pass;
	mot_acc det;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++) {
			mot_q32 v = m->m[i][j];

			big |= v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
		}
	if (big == 0)
		return MOT_E_SINGULAR;
	sh = 59 - (63 - (int)mot_clz64(big));
	for (i = 0; i < 3; i++) {
		for (j = 0; j < 3; j++) {
			mot_q32 v = m->m[i][j];

			r[i][j] = sh >= 0 ? (mot_q32)((uint64_t)v << sh)
					  : mot_acc_round(mot_acc_from(v, 0), (unsigned)-sh, NULL);
		}
		nrm[i] = mot_norm3(r[i], sat);
		if (nrm[i] > nmax)
			nmax = nrm[i];
	}

	/* rn[i] = R_i: row i minus its projections on R_0 .. R_i-1, normalised.
	 * h = { hxy, hxz, hyz } collect the projections. */
	h[0] = h[1] = h[2] = 0;
	for (i = 0; i < 3; i++) {
		mot_q32 *u = rn[i];

		u[0] = r[i][0], u[1] = r[i][1], u[2] = r[i][2];
		for (pass = 0; pass < 2; pass++) {
			for (j = 0; j < i; j++) {
				mot_q32 *hk = &h[i + j - 1]; /* (1,0) hxy, (2,0) hxz, (2,1) hyz */

				k = mot_dot3(rn[j], u, sat);
				*hk = mot_add_sat(*hk, k, sat);
				sub_scaled(u, k, rn[j], sat);
			}
		}
		s[i] = mot_norm3(u, sat);
		/* s < 1e-9 max |r|, exactly; also catches s == 0 */
		if (mot_acc_is_neg(mot_acc_sub(mot_acc_mul(s[i], 1000000000), mot_acc_from(nmax, 0))))
			return MOT_E_SINGULAR;
		mot_recip_init(&rc[i], s[i]);
		for (j = 0; j < 3; j++)
			u[j] = mot_recip_ratio(u[j], &rc[i], sat);
	}
	h[0] = mot_recip_ratio(h[0], &rc[1], sat);
	h[1] = mot_recip_ratio(h[1], &rc[2], sat);
	h[2] = mot_recip_ratio(h[2], &rc[2], sat);

	/* det(R) = R2 . (R0 x R1), +-1 within rounding: only its sign is used */
	det = mot_acc_zero();
	for (j = 0; j < 3; j++) {
		int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
		mot_q32 cj = mot_acc_round(mot_acc_sub(mot_acc_mul(rn[0][j1], rn[1][j2]),
						       mot_acc_mul(rn[0][j2], rn[1][j1])),
					   MOT_Q32_FRAC, NULL);

		det = mot_acc_mac(det, cj, rn[2][j]);
	}
	for (i = 0; i < 3; i++) {
		s[i] = unscale(s[i], sh, sat);
		if (mot_acc_is_neg(det)) {
			s[i] = -s[i];
			for (j = 0; j < 3; j++)
				rn[i][j] = -rn[i][j];
		}
	}
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			rm.m[i][j] = rn[i][j];
	rm.m[3][0] = rm.m[3][1] = rm.m[3][2] = 0;

	mot_quat_from_mat(&out->rot, &rm, sat);
	for (i = 0; i < 3; i++) {
		out->scale[i] = s[i];
		out->shear[i] = h[i];
		out->translate[i] = m->m[3][i];
	}
	if (rot_mat)
		*rot_mat = rm;
	return MOT_OK;
}

void mot_mat_compose(struct mot_mat *out, const struct mot_decomp *d, uint32_t *sat)
{
	/* (S . H) . R with S . H lower-triangular, rows (sx, 0, 0),
	 * (sy hxy, sy, 0), (sz hxz, sz hyz, sz), and R carrying the
	 * translation: one product, each entry rounded once after the three
	 * scale-shear products. */
	const mot_q32 *s = d->scale, *h = d->shear;
	struct mot_mat sh = { { { s[0], 0, 0 },
				{ mot_mul(s[1], h[0], sat), s[1], 0 },
				{ mot_mul(s[2], h[1], sat), mot_mul(s[2], h[2], sat), s[2] },
				{ 0, 0, 0 } } };
	struct mot_mat r;

	mot_quat_to_mat(&r, &d->rot, sat);
	r.m[3][0] = d->translate[0];
	r.m[3][1] = d->translate[1];
	r.m[3][2] = d->translate[2];
	mot_mat_mul(out, &sh, &r, sat);
}
