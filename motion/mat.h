/* SPDX-License-Identifier: MIT */
/*
 * mat.h - affine transforms in row-vector form (FORMULAS.md section 1).
 *
 * A point is a row vector: P' = (x, y, z, 1) . M. Only affine matrices are
 * transforms of a rig, so the fourth column, always (0, 0, 0, 1), is not
 * stored: m[0..2] are the rows of the linear part (rotation, scale, shear)
 * and m[3] is the translation. Entries are Q32.32, lengths in scene units.
 *
 * Output-first signatures. Unless a comment says otherwise, the output may
 * alias any input (results are built in locals and stored last).
 *
 * Every function takes a sticky status word `sat` (fix.h; may be NULL) and
 * is safe in the real-time loop: bounded time, no allocation.
 */
#ifndef MOT_MAT_H
#define MOT_MAT_H

#include "fix.h"

struct mot_mat {
	mot_q32 m[4][3];
};

void mot_mat_identity(struct mot_mat *out);

/* T(t): identity with translation row t. */
void mot_mat_translate(struct mot_mat *out, const mot_q32 t[3]);

/* S(s): diag(sx, sy, sz). */
void mot_mat_scale(struct mot_mat *out, const mot_q32 s[3]);

/* H(h): unit lower-triangular shear, rows (1,0,0), (hxy,1,0), (hxz,hyz,1),
 * with h = {hxy, hxz, hyz} (FORMULAS section 2). */
void mot_mat_shear(struct mot_mat *out, const mot_q32 h[3]);

/* Rx, Ry, Rz by an angle in turns (counter-clockwise looking down the axis,
 * so (1,0,0) . Rz(1/4) = (0,1,0)). */
void mot_mat_rot_x(struct mot_mat *out, mot_q32 turns);
void mot_mat_rot_y(struct mot_mat *out, mot_q32 turns);
void mot_mat_rot_z(struct mot_mat *out, mot_q32 turns);

/* Rotation by `turns` about a unit axis (the matrix of the quaternion
 * (cos a/2, axis sin a/2), FORMULAS section 4). The axis must be unit
 * length; the scene loader normalises it. */
void mot_mat_rot_axis(struct mot_mat *out, const mot_q32 axis[3], mot_q32 turns,
		      uint32_t *sat);

/* Euler angles in turns: Rx(e[0]) . Ry(e[1]) . Rz(e[2]) (x first). */
void mot_mat_euler(struct mot_mat *out, const mot_q32 e[3], uint32_t *sat);

/* out = a . b (apply a, then b). Each entry is the exact sum of its three
 * products (plus b's translation in row 3) rounded once; a sum that does not
 * fit saturates with its true sign. 36 exact 64x64->128 products, about
 * 20 ns on the x86_64 build machine (make bench). */
void mot_mat_mul(struct mot_mat *out, const struct mot_mat *a, const struct mot_mat *b,
		 uint32_t *sat);

/* out = inverse of the affine matrix a: adjugate over the exact determinant,
 * each linear entry within 1 LSB of the true inverse of a (any scale). The
 * translation row is -t . inverse, rounded once. MOT_E_SINGULAR when the
 * determinant is zero or so near it that an entry of the inverse's linear
 * part would reach 2^30 in magnitude (fix.h's length limit); out is then left
 * untouched. About 110 ns (make bench): prepare, do not call per tick. */
int mot_mat_inverse(struct mot_mat *out, const struct mot_mat *a, uint32_t *sat);

/* Determinant of the linear part, exact (192 bits) and rounded once to
 * Q32.32, saturating. */
mot_q32 mot_mat_det(const struct mot_mat *a, uint32_t *sat);

/* out = (p, 1) . m: transform a point, each coordinate rounded once. */
void mot_mat_apply(mot_q32 out[3], const mot_q32 p[3], const struct mot_mat *m, uint32_t *sat);

/* out = (v, 0) . m: transform a direction (no translation). */
void mot_mat_apply_dir(mot_q32 out[3], const mot_q32 v[3], const struct mot_mat *m,
		       uint32_t *sat);

/*
 * The three editing operations on a node matrix (seed paper section 4), for
 * jog and teach modes. `delta` carries an incremental linear part (for
 * example R.S, in delta->m[0..2]) and an incremental translation (delta->m[3]).
 *
 * Local: the increment acts in the node's own frame, about its pivot p (in
 * the node's model coordinates), before the accumulated matrix:
 *     M' = T(-p) . D . T(p) . T(t) . M
 * so a pure rotation leaves the pivot where it was.
 *
 * World: the increment acts in world space, about a world pivot w, after the
 * accumulated matrix, translation first as in the paper:
 *     M' = M . T(t) . T(-w) . D . T(w)
 * A scale about a world pivot pulls the node toward it (the paper's
 * "implosion").
 *
 * Switching spaces re-expresses M so that the node does not move: a matrix
 * applied about the pivot (local space, T(-p).M.T(p) is what is drawn) and
 * one applied about the origin (world space, M is what is drawn):
 *     to local:  M' = T(p) . M . T(-p)
 *     to world:  M' = T(-p) . M . T(p)
 */
void mot_mat_edit_local(struct mot_mat *m, const struct mot_mat *delta, const mot_q32 pivot[3],
			uint32_t *sat);
void mot_mat_edit_world(struct mot_mat *m, const struct mot_mat *delta,
			const mot_q32 world_pivot[3], uint32_t *sat);
void mot_mat_to_local(struct mot_mat *m, const mot_q32 pivot[3], uint32_t *sat);
void mot_mat_to_world(struct mot_mat *m, const mot_q32 pivot[3], uint32_t *sat);

/* out = T(-p) . a . T(p): a linear part applied about pivot p, plus a's own
 * translation after it (FORMULAS section 3, L = T(-p).S.H.R.T(p).T(t)). */
void mot_mat_about_pivot(struct mot_mat *out, const struct mot_mat *a, const mot_q32 p[3],
			 uint32_t *sat);

#endif /* MOT_MAT_H */
