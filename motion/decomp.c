/* SPDX-License-Identifier: MIT */
/*
 * decomp.c - a matrix into scale, shear, rotation and translation, and back
 * (see decomp.h).
 */
#include "decomp.h"
#include "trig.h"

/* R . v for a unit row R in Q2.62 and v in Q32.32 (below 2^60), rounded
 * once to Q32.32. */
static mot_q32 dot62(const int64_t r[3], const mot_q32 v[3])
{
	mot_acc acc = mot_acc_mul(r[0], v[0]);

	acc = mot_acc_mac(acc, r[1], v[1]);
	acc = mot_acc_mac(acc, r[2], v[2]);
	return mot_acc_round(acc, 62, NULL);
}

/* v - k R for R in Q2.62, rounded once per component. */
static void sub_scaled(mot_q32 v[3], mot_q32 k, const int64_t r[3])
{
	int j;

	for (j = 0; j < 3; j++)
		v[j] = mot_acc_round(mot_acc_sub(mot_acc_from(v[j], 62), mot_acc_mul(k, r[j])), 62,
				     NULL);
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
	mot_q32 r[3][3], nrm[3], nmax = 0, s[3], h[3], k;
	int64_t rn[3][3];
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

	/* R_i (rn, Q2.62: thirty more bits than the output, because a
	 * projection multiplies R's rounding by the row's length): row i minus
	 * its projections on R_0 .. R_i-1, normalised. h = { hxy, hxz, hyz }
	 * collect the projections. The prescaled rows and every vector here
	 * stay below 2^60 raw. */
	h[0] = h[1] = h[2] = 0;
	for (i = 0; i < 3; i++) {
		mot_q32 u[3] = { r[i][0], r[i][1], r[i][2] };

		for (pass = 0; pass < 2; pass++) {
			for (j = 0; j < i; j++) {
				mot_q32 *hk = &h[i + j - 1]; /* (1,0) hxy, (2,0) hxz, (2,1) hyz */

				k = dot62(rn[j], u);
				*hk += k;
				sub_scaled(u, k, rn[j]);
			}
		}
		s[i] = mot_norm3(u, sat);
		/* s < 1e-9 max |r|, exactly; also catches s == 0 */
		if (mot_acc_is_neg(mot_acc_sub(mot_acc_mul(s[i], 1000000000), mot_acc_from(nmax, 0))))
			return MOT_E_SINGULAR;
		mot_recip_init(&rc[i], s[i]);
		for (j = 0; j < 3; j++) /* u / s, Q2.62 */
			rn[i][j] = mot_acc_round(mot_acc_mul(u[j], rc[i].m), rc[i].shift - 30, NULL);
	}
	h[0] = mot_recip_ratio(h[0], &rc[1], sat);
	h[1] = mot_recip_ratio(h[1], &rc[2], sat);
	h[2] = mot_recip_ratio(h[2], &rc[2], sat);
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			rm.m[i][j] = mot_acc_round(mot_acc_from(rn[i][j], 0), 30, NULL);

	/* det(R) = R2 . (R0 x R1), +-1 within rounding: only its sign is used */
	det = mot_acc_zero();
	for (j = 0; j < 3; j++) {
		int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
		mot_q32 cj = mot_acc_round(mot_acc_sub(mot_acc_mul(rm.m[0][j1], rm.m[1][j2]),
						       mot_acc_mul(rm.m[0][j2], rm.m[1][j1])),
					   MOT_Q32_FRAC, NULL);

		det = mot_acc_mac(det, cj, rm.m[2][j]);
	}
	for (i = 0; i < 3; i++) {
		s[i] = unscale(s[i], sh, sat);
		if (mot_acc_is_neg(det)) {
			s[i] = -s[i];
			for (j = 0; j < 3; j++)
				rm.m[i][j] = -rm.m[i][j];
		}
	}
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

/* |v| as an unsigned number (exact for every v) */
void mot_mat_compose(struct mot_mat *out, const struct mot_decomp *d, uint32_t *sat)
{
	mot_mat_compose_r(out, d, NULL, sat);
}

void mot_mat_compose_r(struct mot_mat *out, const struct mot_decomp *d,
		       const struct mot_rot_q62 *rp, uint32_t *sat)
{
	/*
	 * (S . H) . R with S . H lower-triangular, rows (sx, 0, 0),
	 * (sy hxy, sy, 0), (sz hxz, sz hyz, sz), and R taken in Q2.62: each
	 * entry is rounded once, so R's own rounding is not multiplied by the
	 * scale (at a scale of 100 and 100 m that would be 3 um). Entries of
	 * S . H beyond 2^30 take the plain Q32.32 product instead.
	 */
	const mot_q32 lim = (mot_q32)1 << 62, *s = d->scale, *h = d->shear;
	const mot_q32 sh[3][3] = { { s[0], 0, 0 },
				   { mot_mul(s[1], h[0], sat), s[1], 0 },
				   { mot_mul(s[2], h[1], sat), mot_mul(s[2], h[2], sat), s[2] } };
	struct mot_rot_q62 own;
	const int64_t(*r)[3];
	struct mot_mat m;
	uint64_t ov = 0, big;
	int i, j;

	/* every |sh| below 2^62: the OR of their magnitudes is */
	big = mot_mag(sh[0][0]) | mot_mag(sh[1][0]) | mot_mag(sh[1][1]) | mot_mag(sh[2][0]) | mot_mag(sh[2][1]) |
	      mot_mag(sh[2][2]);
	if (big >= (uint64_t)lim || (!rp && mot_quat_to_rot_q62(own.r, &d->rot, sat) != MOT_OK)) {
		struct mot_mat a = { { { sh[0][0], 0, 0 }, { sh[1][0], sh[1][1], 0 },
				       { sh[2][0], sh[2][1], sh[2][2] }, { 0, 0, 0 } } };

		mot_quat_to_mat(&m, &d->rot, sat);
		m.m[3][0] = d->translate[0];
		m.m[3][1] = d->translate[1];
		m.m[3][2] = d->translate[2];
		mot_mat_mul(out, &a, &m, sat);
		return;
	}
	r = (rp ? rp : &own)->r;
	/* S . H is lower-triangular: row i has i + 1 products (fix.h's kernel,
	 * the saturating rounding only when an entry does not fit); the columns
	 * unrolled where 128-bit integers are native, as scene.c's kernels */
	mot_compose_rows(&m, sh[0][0], sh[1][0], sh[1][1], sh[2][0], sh[2][1], sh[2][2], r, &ov);
	for (i = 0; ov && i < 3; i++)
		for (j = 0; j < 3; j++) {
			mot_acc acc = mot_acc_mul(sh[i][0], r[0][j]);

			acc = mot_acc_mac(acc, sh[i][1], r[1][j]);
			acc = mot_acc_mac(acc, sh[i][2], r[2][j]);
			m.m[i][j] = mot_acc_round(acc, 62, sat);
		}
	m.m[3][0] = d->translate[0];
	m.m[3][1] = d->translate[1];
	m.m[3][2] = d->translate[2];
	*out = m;
}
