/* SPDX-License-Identifier: MIT */
/*
 * ref_mat.h - double-precision reference for the matrix, quaternion and
 * decomposition code of motion/: full 4x4 row-vector matrices (P' = P . M),
 * quaternions (w, x, y, z), Gram-Schmidt decomposition, slerp and squad,
 * written straight from FORMULAS.md sections 1-4. Angles in radians. Test
 * code only: never linked into the core.
 */
#ifndef REF_MAT_H
#define REF_MAT_H

#include "motion/decomp.h"
#include "motion/mat.h"
#include "motion/quat.h"
#include "testutil.h"

struct ref_mat {
	double m[4][4];
};

struct ref_quat {
	double w, x, y, z;
};

struct ref_decomp {
	double scale[3], shear[3]; /* sx, sy, sz; hxy, hxz, hyz */
	double rot[3][3];          /* R, rows */
	double translate[3];
};

/* conversions with the fixed-point types (exact for |x| < 2^21) */
void ref_from_mat(struct ref_mat *out, const struct mot_mat *m);
void ref_to_mat(struct mot_mat *out, const struct ref_mat *m);
void ref_from_quat(struct ref_quat *out, const struct mot_quat *q);
void ref_to_quat(struct mot_quat *out, const struct ref_quat *q);

void ref_identity(struct ref_mat *out);
void ref_translate(struct ref_mat *out, double x, double y, double z);
void ref_scale(struct ref_mat *out, double x, double y, double z);
void ref_shear(struct ref_mat *out, double hxy, double hxz, double hyz);
void ref_rot_x(struct ref_mat *out, double rad);
void ref_rot_y(struct ref_mat *out, double rad);
void ref_rot_z(struct ref_mat *out, double rad);
void ref_euler(struct ref_mat *out, double rx, double ry, double rz); /* Rx.Ry.Rz */
void ref_mul(struct ref_mat *out, const struct ref_mat *a, const struct ref_mat *b);
/* general 4x4 inverse (Gauss-Jordan, partial pivoting); -1 when singular */
int ref_inverse(struct ref_mat *out, const struct ref_mat *a);
/* in long double: 64-bit mantissa on x86-64 */
long double ref_det3(const struct ref_mat *a);
void ref_apply(double out[3], const double p[3], const struct ref_mat *m);
void ref_apply_dir(double out[3], const double v[3], const struct ref_mat *m);
/* largest |a - b| over the linear part (rows 0-2, columns 0-2) */
double ref_lin_diff(const struct ref_mat *a, const struct ref_mat *b);
/* worst displacement, in length units, between transforming any point of the
 * cube |x|,|y|,|z| <= reach by a and by b */
double ref_point_diff(const struct ref_mat *a, const struct ref_mat *b, double reach);

void ref_quat_axis_angle(struct ref_quat *out, const double axis[3], double rad);
void ref_quat_to_mat(struct ref_mat *out, const struct ref_quat *q);
/* Shoemake from a rotation matrix; normalised, w >= 0 */
void ref_quat_from_mat(struct ref_quat *out, const struct ref_mat *m);
void ref_quat_mul(struct ref_quat *out, const struct ref_quat *a, const struct ref_quat *b);
double ref_quat_dot(const struct ref_quat *a, const struct ref_quat *b);
double ref_quat_norm(const struct ref_quat *q);
void ref_quat_normalize(struct ref_quat *out, const struct ref_quat *q);
/* angle of the rotation taking a to b, radians in [0, pi] (q and -q equal) */
double ref_quat_angle(const struct ref_quat *a, const struct ref_quat *b);
/* shortest-arc slerp by the textbook sine formula */
void ref_slerp(struct ref_quat *out, const struct ref_quat *a, const struct ref_quat *b, double t);
/* log and exp with the vector part in radians of quaternion arc */
void ref_quat_log(double out[3], const struct ref_quat *q);
void ref_quat_exp(struct ref_quat *out, const double v[3]);
void ref_squad_inner(struct ref_quat *out, const struct ref_quat *prev,
		     const struct ref_quat *cur, const struct ref_quat *next);
void ref_squad(struct ref_quat *out, const struct ref_quat *q0, const struct ref_quat *q1,
	       const struct ref_quat *s0, const struct ref_quat *s1, double t);

/* FORMULAS section 2; -1 when singular (a scale below 1e-9 of the largest
 * row norm) */
int ref_decompose(struct ref_decomp *out, const struct ref_mat *m);
void ref_compose(struct ref_mat *out, const struct ref_decomp *d);

/* random inputs: a uniformly distributed unit quaternion (w >= 0 not
 * enforced); a random unit vector; S.H.R.T with |scales| log-uniform in
 * [smin, smax] (each negated with probability 1/2 when reflect), shears
 * uniform in [-hmax, hmax], a random rotation and translations uniform in
 * [-tmax, tmax] */
void ref_rand_quat(struct ref_quat *q, struct tu_rng *r);
void ref_rand_axis(double axis[3], struct tu_rng *r);
void ref_rand_affine(struct ref_mat *m, struct tu_rng *r, double smin, double smax, double hmax,
		     double tmax, bool reflect);
/* quantise to Q32.32 and back, so that the reference sees the same input */
void ref_quantize(struct ref_mat *m);

#endif
