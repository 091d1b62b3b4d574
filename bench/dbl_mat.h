/* SPDX-License-Identifier: MIT */
/*
 * dbl_mat.h - the double-precision twin of motion/mat.h, quat.h and
 * decomp.h, for the benchmarks: the same conventions (row vectors, affine
 * 4x3 matrices whose row 3 is the translation, quaternions (w, x, y, z),
 * S . H . R decomposition) and the same algorithms, so that timing one
 * against the other compares number formats and not methods. Not a
 * reference for accuracy (tests/ref_mat.h is): it computes the way a double
 * implementation of the core would, in double and libm.
 *
 * Outputs may alias inputs.
 */
#ifndef DBL_MAT_H
#define DBL_MAT_H

#include <stdbool.h>

struct dbl_mat {
	double m[4][3];
};

struct dbl_quat {
	double w, x, y, z;
};

/* Slerp prepared per pair of keys as in quat.h: a cos(t theta) + c sin(t
 * theta), c the unit direction of b orthogonal to a; theta in radians. */
struct dbl_slerp {
	struct dbl_quat a, b, c;
	double theta;
	bool nlerp; /* sin theta < 2^-10: normalised linear interpolation */
};

struct dbl_decomp {
	double scale[3], shear[3]; /* sx, sy, sz; hxy, hxz, hyz */
	struct dbl_quat rot;       /* unit, w >= 0 */
	double translate[3];
};

void dbl_mat_identity(struct dbl_mat *out);
/* out = a . b (apply a, then b) */
void dbl_mat_mul(struct dbl_mat *out, const struct dbl_mat *a, const struct dbl_mat *b);
/* out = (p, 1) . m */
void dbl_mat_apply(double out[3], const double p[3], const struct dbl_mat *m);
/* T(-p) . a . T(p), a's translation added after (mot_mat_about_pivot) */
void dbl_mat_about_pivot(struct dbl_mat *out, const struct dbl_mat *a, const double p[3]);

void dbl_quat_from_axis_angle(struct dbl_quat *out, const double axis[3], double rad);
void dbl_quat_to_mat(struct dbl_mat *out, const struct dbl_quat *q);
void dbl_quat_from_mat(struct dbl_quat *out, const struct dbl_mat *m);
double dbl_quat_dot(const struct dbl_quat *a, const struct dbl_quat *b);
void dbl_quat_normalize(struct dbl_quat *out, const struct dbl_quat *q);

void dbl_slerp_prepare(struct dbl_slerp *s, const struct dbl_quat *a, const struct dbl_quat *b);
void dbl_slerp_eval(struct dbl_quat *out, const struct dbl_slerp *s, double t);
/* Shoemake's inner control point of squad (mot_squad_inner). */
void dbl_squad_inner(struct dbl_quat *out, const struct dbl_quat *prev,
		     const struct dbl_quat *cur, const struct dbl_quat *next);

/* Gram-Schmidt on the rows; -1 when singular (a scale below 1e-9 of the
 * largest row norm), as mot_mat_decompose. */
int dbl_mat_decompose(struct dbl_decomp *out, const struct dbl_mat *m);
/* rows sx.R0, sy.(hxy.R0 + R1), sz.(hxz.R0 + hyz.R1 + R2), t */
void dbl_mat_compose(struct dbl_mat *out, const struct dbl_decomp *d);
/* the same with r = R(d->rot) already made (mot_mat_compose_r) */
void dbl_mat_compose_r(struct dbl_mat *out, const struct dbl_decomp *d, const struct dbl_mat *r);

#endif /* DBL_MAT_H */
