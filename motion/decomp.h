/* SPDX-License-Identifier: MIT */
/*
 * decomp.h - a matrix into scale, shear, rotation and translation, and back
 * (FORMULAS.md section 2; the seed paper's key-matrix pipeline).
 *
 * The linear part is S . H . R with H unit lower-triangular, found by
 * Gram-Schmidt on the rows. A reflection (det < 0) is carried by negating all
 * three scales so that R stays a proper rotation. A scale below 1e-9 of the
 * largest row norm is singular.
 */
#ifndef MOT_DECOMP_H
#define MOT_DECOMP_H

#include "fix.h"
#include "mat.h"
#include "quat.h"

struct mot_decomp {
	mot_q32 scale[3];     /* sx, sy, sz */
	mot_q32 shear[3];     /* hxy, hxz, hyz */
	struct mot_quat rot;  /* unit, w >= 0 */
	mot_q32 translate[3]; /* row 3 */
};

/* Decompose m. rot_mat, when not NULL, receives R as a matrix (exactly the
 * Gram-Schmidt rows, before the quaternion; translation row zero).
 * MOT_E_SINGULAR for a singular matrix (out and rot_mat untouched). Scales,
 * shears and R's entries are within 0.5 LSB of Gram-Schmidt in exact
 * arithmetic at any scale (the rows are normalised by a power of two and R is
 * carried in Q2.62 inside). Init-time and real-time safe; about 390 ns. */
int mot_mat_decompose(struct mot_decomp *out, struct mot_mat *rot_mat, const struct mot_mat *m,
		      uint32_t *sat);

/* Recompose: rows sx.R0, sy.(hxy.R0 + R1), sz.(hxz.R0 + hyz.R1 + R2), t,
 * with R = R(rot) taken in Q2.62 so that each entry is rounded once (R's own
 * rounding is not multiplied by the scale). About 55 ns. */
void mot_mat_compose(struct mot_mat *out, const struct mot_decomp *d, uint32_t *sat);

/* mot_mat_compose() with R(d->rot) in Q2.62 already made: r as
 * mot_quat_to_rot_q62(r, &d->rot) makes it when that returns MOT_OK and
 * saturates nothing (the same bits then), or NULL to make it here. */
void mot_mat_compose_r(struct mot_mat *out, const struct mot_decomp *d,
		       const struct mot_rot_q62 *r, uint32_t *sat);

/*
 * mot_mat_compose_r()'s sums: rows 0..2 of out = (S . H) . R for S . H's
 * lower triangle (sx; sy hxy, sy; sz hxz, sz hyz, sz) and R in Q2.62, each
 * entry one sum rounded once (fix.h's kernel, an entry that does not fit
 * ORed into *ov). Inline for the callers that know every entry fits (a
 * constant unused ov: no test left).
 */
static inline __attribute__((always_inline)) void
mot_compose_rows(struct mot_mat *out, mot_q32 sx, mot_q32 sy_hxy, mot_q32 sy, mot_q32 sz_hxz,
		 mot_q32 sz_hyz, mot_q32 sz, const int64_t r[3][3], uint64_t *ov)
{
	unsigned j;

#if MOT_HAVE_INT128
	_Pragma("GCC unroll 3")
#endif
	for (j = 0; j < 3; j++) {
		out->m[0][j] = mot_acc_floor_ov(mot_acc_mac(mot_acc_start(0, 62), sx, r[0][j]), 62,
						ov);
		out->m[1][j] = mot_sum2_ov(sy_hxy, r[0][j], sy, r[1][j], 0, 62, ov);
		out->m[2][j] = mot_sum3_ov(sz_hxz, r[0][j], sz_hyz, r[1][j], sz, r[2][j], 0, 62, ov);
	}
}

#endif /* MOT_DECOMP_H */
