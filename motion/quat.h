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

/* mot_quat_to_rot_q62() where an entry may not fit: saturating (quat.c). */
void mot_quat_to_rot_q62_sat(int64_t r[3][3], const struct mot_quat *q, uint32_t *sat);

/* floor(x / 2), for a value known to fit int64 (the low word shifted, and
 * the high word's low bit): round(y / 2) for y = x - 1 */
static inline int64_t mot_quat_half_floor(mot_acc x)
{
	return (int64_t)mot_dw_shr(mot_acc_hi(x), mot_acc_lo(x), 1);
}

/* The entries round((a b + c d) / 2) and round((a b - c d) / 2), Q2.62,
 * known to fit: floor((a b + 1 +- c d) / 2), the rounding's 1 added once
 * for both */
static inline __attribute__((always_inline)) void mot_quat_rot_pair(int64_t *plus,
								    int64_t *minus, mot_q32 a,
								    mot_q32 b, mot_q32 c, mot_q32 d)
{
	mot_acc p = mot_acc_add(mot_acc_mul(a, b), mot_acc_from(1, 0)), q = mot_acc_mul(c, d);

	*plus = mot_quat_half_floor(mot_acc_add(p, q));
	*minus = mot_quat_half_floor(mot_acc_sub(p, q));
}

/*
 * Each entry from its two products as soon as they are made, so that few
 * 128-bit values live at once: e = 2 (p + q) rounded from Q64.64 to Q2.62
 * is round((p + q) / 2), and 1 - 2 (p + q) is round((2^63 - p - q) / 2),
 * the same bits as quat.c's exact sums rounded by 4. With |q|^2 < 3/2
 * (every rotation) each entry fits: |xy + wz| <= |q|^2 / 2 < 3/4 and
 * 1 - 2 (x^2 + y^2) > -2, so no entry is tested. For a q known to be such
 * (components below 2^62 and |q|^2 < 3/2: a rotation track whose arcs are
 * near unit, struct mot_slerp's unit) this is mot_quat_to_rot_q62()
 * without its tests, the same bits.
 */
static inline __attribute__((always_inline)) void mot_quat_rot_q62_unit(int64_t r[3][3],
									 const struct mot_quat *q)
{
	const mot_q32 w = q->w, x = q->x, y = q->y, z = q->z;
	const mot_acc h = mot_acc_make(0, ((uint64_t)1 << 63) + 1); /* 2^63 and the rounding's 1 */
	mot_acc a = mot_acc_mul(x, x), b = mot_acc_mul(y, y), c = mot_acc_mul(z, z);

	mot_quat_rot_pair(&r[0][1], &r[1][0], x, y, w, z);
	mot_quat_rot_pair(&r[2][0], &r[0][2], x, z, w, y);
	mot_quat_rot_pair(&r[1][2], &r[2][1], y, z, w, x);
	r[2][2] = mot_quat_half_floor(mot_acc_sub(mot_acc_sub(h, a), b));
	c = mot_acc_sub(h, c);
	r[1][1] = mot_quat_half_floor(mot_acc_sub(c, a));
	r[0][0] = mot_quat_half_floor(mot_acc_sub(c, b));
}

/* The same after the tests: other quaternions take
 * mot_quat_to_rot_q62_sat(), whose bits are the same where an entry fits. */
static inline __attribute__((always_inline)) int mot_quat_rot_q62_in(int64_t r[3][3],
								      const struct mot_quat *q,
								      uint32_t *sat)
{
	const mot_q32 lim = (mot_q32)1 << 62;
	const mot_q32 w = q->w, x = q->x, y = q->y, z = q->z;
	mot_acc n;

	if (w >= lim || w <= -lim || x >= lim || x <= -lim || y >= lim || y <= -lim ||
	    z >= lim || z <= -lim)
		return MOT_E_RANGE;
	n = mot_acc_mac(mot_acc_mac(mot_acc_mac(mot_acc_mul(x, x), y, y), z, z), w,
			w); /* below 2^126 */
	if (!mot_acc_is_neg(mot_acc_sub(n, mot_acc_from(3, 63)))) {
		mot_quat_to_rot_q62_sat(r, q, sat);
		return MOT_OK;
	}
	mot_quat_rot_q62_unit(r, q);
	return MOT_OK;
}

/* The linear part of R(q) in Q2.62 (entries value * 2^62, range +-2), so
 * that a product with it rounds once at Q32.32 (mot_mat_compose). For a
 * unit q; components of 2^30 or more give MOT_E_RANGE (r untouched), entries
 * beyond +-2 saturate. Inline where 128-bit integers are native (a free
 * node's rotation makes one every tick), a call elsewhere (code size). */
#if MOT_HAVE_INT128
static inline int mot_quat_to_rot_q62(int64_t r[3][3], const struct mot_quat *q, uint32_t *sat)
{
	return mot_quat_rot_q62_in(r, q, sat);
}
#else
int mot_quat_to_rot_q62(int64_t r[3][3], const struct mot_quat *q, uint32_t *sat);
#endif

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
	bool small;           /* a, b, c within +-1: every in-between below sqrt 2 */
	bool plain;           /* small and not nlerp: eval's one test */
	bool unit;            /* small, |q|^2 within 1/8 of 1 for a and b, and for c
			       * with |a.c| <= 1/8 unless nlerp, so that every
			       * in-between has |q|^2 within 1/4 of 1 (only where
			       * 128-bit integers are native; false elsewhere) */
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
 * them at 2t(1-t), in one call; for near-unit in-betweens the arc from
 * their dot products alone and a cosine scaled by 1/|qa| (quat.c's
 * slerp_near()): unit within 1.33 LSB, 2.6e-9 rad of the double squad
 * (tests/test_quat.c). */
void mot_squad_eval(struct mot_quat *out, const struct mot_slerp *arc,
		    const struct mot_slerp *inner, mot_q32 t, uint32_t *sat);
void mot_squad_inner(struct mot_quat *out, const struct mot_quat *prev,
		     const struct mot_quat *cur, const struct mot_quat *next, uint32_t *sat);
void mot_quat_squad(struct mot_quat *out, const struct mot_quat *q0, const struct mot_quat *q1,
		    const struct mot_quat *s0, const struct mot_quat *s1, mot_q32 t, uint32_t *sat);

#endif /* MOT_QUAT_H */
