/* SPDX-License-Identifier: MIT */
/*
 * affine.h - rotations and affine matrices in double precision, for the
 * scene loader and the tests' reference (FORMULAS sections 1, 2 and 4).
 *
 * Row-vector convention throughout: P' = P . M, translation in row 3.
 * Quaternions are (w, x, y, z). Not used by the real-time path: the core has
 * its own fixed-point versions (motion/decomp.h, motion/quat.h).
 */
#ifndef STRAND_AFFINE_H
#define STRAND_AFFINE_H

/* The row-vector rotation matrix of a unit quaternion (FORMULAS section 4). */
void affine_quat_mat(double m[3][3], const double q[4]);

/* The unit quaternion (w >= 0) of a proper rotation matrix: Shoemake's method
 * on the trace, or on the largest diagonal entry when the trace is small. */
void affine_mat_quat(double q[4], const double m[3][3]);

/* Euler angles in degrees, R = Rx(e0) . Ry(e1) . Rz(e2), as a quaternion. */
void affine_euler_quat(double q[4], const double deg[3]);

struct affine_decomp {
	double scale[3];     /* sx, sy, sz (all negated for a reflection) */
	double shear[3];     /* hxy, hxz, hyz */
	double rot[3][3];    /* R, a proper rotation */
	double q[4];         /* R as a unit quaternion */
	double translate[3]; /* row 3 */
};

enum affine_err {
	AFFINE_OK = 0,
	AFFINE_E_NOT_AFFINE = -1, /* the last column is not (0, 0, 0, 1) */
	AFFINE_E_SINGULAR = -2,   /* a scale below 1e-9 of the largest row norm */
};

/* Decompose a 4x4 matrix into S . H . R and a translation (FORMULAS section 2).
 * On AFFINE_E_SINGULAR, *axis says which scale (0, 1, 2) vanished. */
int affine_decompose(struct affine_decomp *out, const double m[4][4], int *axis);

/* Recompose the upper 3x3 and translation of a decomposition into m. */
void affine_compose(double m[4][4], const struct affine_decomp *d);

#endif /* STRAND_AFFINE_H */
