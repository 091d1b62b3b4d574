/* SPDX-License-Identifier: MIT */
/*
 * quat.h - unit quaternions for rotation keys (FORMULAS.md section 4).
 *
 * q = (w, x, y, z), components Q32.32. Its row-vector rotation matrix is
 * FORMULAS section 4's, so Rz(a) is (cos a/2, 0, 0, sin a/2). Because points
 * are row vectors, applying q1 then q2 is the matrix product
 * R(q1) . R(q2), which equals R(q2 * q1) with * the Hamilton product.
 *
 * All functions are safe in the real-time loop; outputs may alias inputs.
 */
#ifndef MOT_QUAT_H
#define MOT_QUAT_H

#include "fix.h"
#include "mat.h"

struct mot_quat {
	mot_q32 w, x, y, z;
};

void mot_quat_identity(struct mot_quat *out);

/* Rotation by `turns` about a unit axis. */
void mot_quat_from_axis_angle(struct mot_quat *out, const mot_q32 axis[3], mot_q32 turns,
			      uint32_t *sat);

/* Euler angles in turns, R = Rx(e0) . Ry(e1) . Rz(e2). */
void mot_quat_from_euler(struct mot_quat *out, const mot_q32 e[3], uint32_t *sat);

/* Linear part of out = R(q), translation zero. q should be unit; the
 * matrix is built from q as given (no renormalisation). */
void mot_quat_to_mat(struct mot_mat *out, const struct mot_quat *q, uint32_t *sat);

/* The linear part of R(q) in Q2.62 (entries value * 2^62, range +-2), so
 * that a product with it rounds once at Q32.32 (mot_mat_compose). For a
 * unit q; components of 2^30 or more give MOT_E_RANGE (r untouched), entries
 * beyond +-2 saturate. */
int mot_quat_to_rot_q62(int64_t r[3][3], const struct mot_quat *q, uint32_t *sat);

/* Such a matrix kept (a rotation track's held end keys, strand.h). */
struct mot_rot_q62 {
	int64_t r[3][3];
};

/* Quaternion of the proper rotation in m's linear part (Shoemake, on the
 * trace, largest-diagonal branch otherwise); result normalised, w >= 0. */
void mot_quat_from_mat(struct mot_quat *out, const struct mot_mat *m, uint32_t *sat);

/* Hamilton product a * b. */
void mot_quat_mul(struct mot_quat *out, const struct mot_quat *a, const struct mot_quat *b,
		  uint32_t *sat);

mot_q32 mot_quat_dot(const struct mot_quat *a, const struct mot_quat *b, uint32_t *sat);

/* q / |q|. MOT_E_INVAL for a zero quaternion (out untouched). */
int mot_quat_normalize(struct mot_quat *out, const struct mot_quat *q, uint32_t *sat);

/*
 * Slerp between two keys, prepared once per segment: the shorter arc is
 * chosen (b negated when a.b < 0), and the arc angle and the unit direction
 * c in the plane of a and b orthogonal to a are computed here, so that an
 * in-between is a cos(t theta) + c sin(t theta): one sincos and eight
 * products, no division. Nearly equal keys (sin theta < 2^-10) fall back to
 * normalised linear interpolation. t = 0 and t = 1 give a and b exactly.
 */
struct mot_slerp {
	struct mot_quat a, b; /* b on a's side of the sphere */
	struct mot_quat c;    /* unit, orthogonal to a, in the plane of a and b */
	mot_q32 theta;        /* arc angle between a and b, turns, [0, 1/4] */
	bool nlerp;           /* theta too small: normalised linear interpolation */
};

void mot_slerp_prepare(struct mot_slerp *s, const struct mot_quat *a, const struct mot_quat *b,
		       uint32_t *sat);
/* t in [0, 1] (Q32.32); outside, the nearer end and MOT_SAT_DOMAIN. For
 * unit keys the result is unit within 4 LSB (9.3e-10) and within 4e-9 rad of
 * the exact slerp (tests/test_quat.c). About 22 ns. */
void mot_slerp_eval(struct mot_quat *out, const struct mot_slerp *s, mot_q32 t, uint32_t *sat);
/* One slerp, for one-off use: prepare's arc and eval's bounds (the same
 * ends, nlerp below the same angle), with c = u / |u| folded into the
 * sine's factor instead of normalising u; about 60% fewer instructions
 * than prepare + eval. Components of 2 or more take prepare + eval. */
void mot_quat_slerp(struct mot_quat *out, const struct mot_quat *a, const struct mot_quat *b,
		    mot_q32 t, uint32_t *sat);

/*
 * Squad (Shoemake): for keys q(i-1), q(i), q(i+1) the inner control point
 *     s(i) = q(i) * exp(-(log(q(i)^-1 q(i+1)) + log(q(i)^-1 q(i-1))) / 4)
 * and between q(i) and q(i+1):
 *     squad(t) = slerp(slerp(q(i), q(i+1), t), slerp(s(i), s(i+1), t), 2t(1-t))
 * which has a continuous angular velocity through the keys. At the ends the
 * missing neighbour is the key itself. Inner points are computed once
 * (about 370 ns each); mot_quat_squad() takes its three slerps one-shot
 * (mot_quat_slerp).
 */
/* squad(t) of a segment whose two arcs are prepared (q(i) to q(i+1) and
 * s(i) to s(i+1)): their slerps at t, then the one-shot slerp between
 * them at 2t(1-t), in one call. */
void mot_squad_eval(struct mot_quat *out, const struct mot_slerp *arc,
		    const struct mot_slerp *inner, mot_q32 t, uint32_t *sat);
void mot_squad_inner(struct mot_quat *out, const struct mot_quat *prev,
		     const struct mot_quat *cur, const struct mot_quat *next, uint32_t *sat);
void mot_quat_squad(struct mot_quat *out, const struct mot_quat *q0, const struct mot_quat *q1,
		    const struct mot_quat *s0, const struct mot_quat *s1, mot_q32 t, uint32_t *sat);

#endif /* MOT_QUAT_H */
