/* SPDX-License-Identifier: MIT */
/*
 * quat.c - unit quaternions for rotation keys (see quat.h).
 *
 * Sums of products go through mot_sum_prod(): one rounding per component,
 * and a true saturation for absurd inputs. Angles inside are in turns like
 * everywhere in the core, including the vector part of log() and the
 * argument of exp() (a constant factor that cancels in squad).
 */
#include "quat.h"
#include "trig.h"

#define ONE MOT_Q32_ONE

/* Below this sin of the arc (about 0.056 degrees of quaternion arc) slerp
 * is replaced by normalised linear interpolation: its deviation from the
 * great arc, at most theta^3 / 60, is then under a tenth of an LSB. */
#define SLERP_NLERP_SIN ((mot_q32)1 << 22)

void mot_quat_identity(struct mot_quat *out)
{
	*out = (struct mot_quat){ ONE, 0, 0, 0 };
}

/* Loops over the four components unrolled, and the sines of the real-time
 * slerps inlined, where 128-bit integers are native (gcc -O2 keeps the
 * loops, their operands on the stack), as decomp.c's and scene.c's kernels;
 * kept loops and calls elsewhere, where code size is the point. */
#if MOT_HAVE_INT128
#define UNROLL4 _Pragma("GCC unroll 4")
#define HOT __attribute__((always_inline))
#else
#define UNROLL4
#define HOT
#endif

/* round(x / 2^shift), 1 <= shift <= 64, for a value known to fit:
 * mot_acc_round()'s bits without its test (the low 64 bits of the shifted
 * sum are the same whether the shift fills with the sign or with zeros) */
static inline int64_t round_fits(mot_acc x, unsigned shift)
{
#if MOT_HAVE_INT128
	x = mot_acc_add(x, mot_acc_make(0, (uint64_t)1 << (shift - 1)));
	return shift == 64 ? (int64_t)mot_acc_hi(x) :
			     (int64_t)mot_dw_shr(mot_acc_hi(x), mot_acc_lo(x), shift);
#else
	return mot_acc_round(x, shift, NULL);
#endif
}

/*
 * sin and cos of an angle held with 64 fractional bits of a turn (a Q64.64
 * mot_acc): mot_sincos64() of its phase, one rounding of each. Half angles
 * and t * theta then cost no rounding of the angle (the turn LSB is
 * 1.46e-9 rad, several quaternion LSB).
 */
static inline HOT struct mot_sc sincos_fine_in(mot_acc turns)
{
#if MOT_HAVE_INT128
	return mot_sincos64_in(mot_acc_lo(turns));
#else
	return mot_sincos64(mot_acc_lo(turns));
#endif
}

static void sincos_fine(mot_acc turns, mot_q32 *s, mot_q32 *c)
{
	struct mot_sc r = sincos_fine_in(turns);

	*s = r.s;
	*c = r.c;
}

/* sin and cos of turns / 2, exactly halved */
static void sincos_half(mot_q32 turns, mot_q32 *s, mot_q32 *c)
{
	sincos_fine(mot_acc_from(turns, 31), s, c);
}

static mot_q32 neg(mot_q32 a, uint32_t *sat)
{
	return mot_sub_sat(0, a, sat);
}

void mot_quat_from_axis_angle(struct mot_quat *out, const mot_q32 axis[3], mot_q32 turns,
			      uint32_t *sat)
{
	mot_q32 s, c;

	sincos_half(turns, &s, &c);
	*out = (struct mot_quat){ c, mot_mul(axis[0], s, sat), mot_mul(axis[1], s, sat),
				  mot_mul(axis[2], s, sat) };
}

void mot_quat_from_euler(struct mot_quat *out, const mot_q32 e[3], uint32_t *sat)
{
	/* qz * qy * qx with half angles a, b, c about x, y, z, multiplied out. */
	mot_q32 sa, ca, sb, cb, sc, cc;
	int64_t cacb, sasb, sacb, casb;

	sincos_half(e[0], &sa, &ca);
	sincos_half(e[1], &sb, &cb);
	sincos_half(e[2], &sc, &cc);
	cacb = mot_mul_q62(ca, cb);
	sasb = mot_mul_q62(sa, sb);
	sacb = mot_mul_q62(sa, cb);
	casb = mot_mul_q62(ca, sb);
	out->w = mot_sum2_q62(cacb, cc, sasb, sc);
	out->x = mot_sum2_q62(sacb, cc, -casb, sc);
	out->y = mot_sum2_q62(casb, cc, sacb, sc);
	out->z = mot_sum2_q62(cacb, sc, -sasb, cc);
}

/*
 * R(q) of FORMULAS section 4 as exact Q64.64 sums, when every component is
 * below 2^62 in magnitude (then nothing can wrap); false otherwise.
 */
static inline __attribute__((always_inline)) bool rot_exact(mot_acc e[3][3],
							     const struct mot_quat *q)
{
	const mot_q32 lim = (mot_q32)1 << 62;
	const mot_q32 w = q->w, x = q->x, y = q->y, z = q->z;
	mot_acc xx, yy, zz, xy, xz, yz, wx, wy, wz, one;

	if (w >= lim || w <= -lim || x >= lim || x <= -lim || y >= lim || y <= -lim ||
	    z >= lim || z <= -lim)
		return false;
	xx = mot_acc_mul(x, x), yy = mot_acc_mul(y, y), zz = mot_acc_mul(z, z);
	xy = mot_acc_mul(x, y), xz = mot_acc_mul(x, z), yz = mot_acc_mul(y, z);
	wx = mot_acc_mul(w, x), wy = mot_acc_mul(w, y), wz = mot_acc_mul(w, z);
	one = mot_acc_from(MOT_Q32_ONE, MOT_Q32_FRAC);
#define TWICE(v) mot_acc_add((v), (v))
	e[0][0] = mot_acc_sub(one, TWICE(mot_acc_add(yy, zz)));
	e[0][1] = TWICE(mot_acc_add(xy, wz));
	e[0][2] = TWICE(mot_acc_sub(xz, wy));
	e[1][0] = TWICE(mot_acc_sub(xy, wz));
	e[1][1] = mot_acc_sub(one, TWICE(mot_acc_add(xx, zz)));
	e[1][2] = TWICE(mot_acc_add(yz, wx));
	e[2][0] = TWICE(mot_acc_add(xz, wy));
	e[2][1] = TWICE(mot_acc_sub(yz, wx));
	e[2][2] = mot_acc_sub(one, TWICE(mot_acc_add(xx, yy)));
#undef TWICE
	return true;
}

void mot_quat_to_mat(struct mot_mat *out, const struct mot_quat *q, uint32_t *sat)
{
	/* FORMULAS section 4, each entry rounded once. Components beyond 2^62
	 * (not a rotation at all) take the wrap-aware sums, with pairs that
	 * spell out the factor 2. */
	const mot_q32 w = q->w, x = q->x, y = q->y, z = q->z;
	struct mot_mat r = { { { 0 } } };
	mot_acc e[3][3];
	int i;

	if (rot_exact(e, q)) {
		uint64_t ov = 0;
		int j;

		/* saturating only when an entry does not fit (fix.h's kernel) */
		for (i = 0; i < 3; i++)
			for (j = 0; j < 3; j++)
				r.m[i][j] = mot_acc_round_ov(e[i][j], MOT_Q32_FRAC, &ov);
		for (i = 0; ov && i < 9; i++)
			r.m[i / 3][i % 3] = mot_acc_round(e[i / 3][i % 3], MOT_Q32_FRAC, sat);
	} else {
		const mot_q32 nx = neg(x, sat), ny = neg(y, sat), nz = neg(z, sat);
		const mot_q32 nw = neg(w, sat);
		const mot_q32 pairs[9][10] = {
			{ ONE, ONE, y, ny, y, ny, z, nz, z, nz }, { x, y, x, y, w, z, w, z, 0, 0 },
			{ x, z, x, z, nw, y, nw, y, 0, 0 },       { x, y, x, y, nw, z, nw, z, 0, 0 },
			{ ONE, ONE, x, nx, x, nx, z, nz, z, nz }, { y, z, y, z, w, x, w, x, 0, 0 },
			{ x, z, x, z, w, y, w, y, 0, 0 },         { y, z, y, z, nw, x, nw, x, 0, 0 },
			{ ONE, ONE, x, nx, x, nx, y, ny, y, ny },
		};

		for (i = 0; i < 9; i++) {
			const mot_q32 *p = pairs[i];
			mot_q32 a[5] = { p[0], p[2], p[4], p[6], p[8] };
			mot_q32 b[5] = { p[1], p[3], p[5], p[7], p[9] };

			r.m[i / 3][i % 3] = mot_sum_prod(a, b, 5, sat);
		}
	}
	*out = r;
}

/* the saturating path of mot_quat_to_rot_q62() (quat.h) */
void mot_quat_to_rot_q62_sat(int64_t r[3][3], const struct mot_quat *q, uint32_t *sat)
{
	mot_acc e[3][3];
	int i;

	if (rot_exact(e, q)) /* it is: the caller checked */
		for (i = 0; i < 9; i++)
			r[i / 3][i % 3] = mot_acc_round(e[i / 3][i % 3], 2, sat);
}

#if !MOT_HAVE_INT128
int mot_quat_to_rot_q62(int64_t r[3][3], const struct mot_quat *q, uint32_t *sat)
{
	return mot_quat_rot_q62_in(r, q, sat);
}
#endif

/* Hamilton product terms: component k of a * b is sum a[i] * sign * b[j]. */
void mot_quat_mul(struct mot_quat *out, const struct mot_quat *a, const struct mot_quat *b,
		  uint32_t *sat)
{
	const mot_q32 l[4] = { a->w, a->x, a->y, a->z };
	const mot_q32 nbx = neg(b->x, sat), nby = neg(b->y, sat), nbz = neg(b->z, sat);
	const mot_q32 rw[4] = { b->w, nbx, nby, nbz };
	const mot_q32 rx[4] = { b->x, b->w, b->z, nby };
	const mot_q32 ry[4] = { b->y, nbz, b->w, b->x };
	const mot_q32 rz[4] = { b->z, b->y, nbx, b->w };

	*out = (struct mot_quat){ mot_sum_prod(l, rw, 4, sat), mot_sum_prod(l, rx, 4, sat),
				  mot_sum_prod(l, ry, 4, sat), mot_sum_prod(l, rz, 4, sat) };
}

mot_q32 mot_quat_dot(const struct mot_quat *a, const struct mot_quat *b, uint32_t *sat)
{
	const mot_q32 l[4] = { a->w, a->x, a->y, a->z }, r[4] = { b->w, b->x, b->y, b->z };

	return mot_sum_prod(l, r, 4, sat);
}

int mot_quat_normalize(struct mot_quat *out, const struct mot_quat *q, uint32_t *sat)
{
	/*
	 * Scale by a power of two so that the largest component is in [1, 2]
	 * (exact unless it was above 2), take the reciprocal square root of
	 * the sum of squares, then one Newton step on the result itself,
	 * u' = u (3 - |u|^2) / 2, with |u|^2 exact in 128 bits: it squares the
	 * error of rsqrt and of the rounded sum, leaving the rounding of u'.
	 */
	mot_q32 v[4] = { q->w, q->x, q->y, q->z };
	uint64_t big = 0;
	mot_acc s = mot_acc_zero(), e;
	mot_q32 r;
	int64_t e63;
	int sh, i;

	for (i = 0; i < 4; i++)
		big |= v[i] < 0 ? (uint64_t)0 - (uint64_t)v[i] : (uint64_t)v[i];
	if (big == 0)
		return MOT_E_INVAL;
	sh = 32 - (63 - (int)mot_clz64(big));
	for (i = 0; i < 4; i++) {
		if (sh >= 0)
			v[i] = (mot_q32)((uint64_t)v[i] << sh);
		else
			v[i] = mot_acc_round(mot_acc_from(v[i], 0), (unsigned)-sh, NULL);
		s = mot_acc_mac(s, v[i], v[i]);
	}
	r = mot_rsqrt(mot_acc_round(s, MOT_Q32_FRAC, NULL), sat);
	s = mot_acc_zero();
	for (i = 0; i < 4; i++) {
		v[i] = mot_mul(v[i], r, NULL);
		s = mot_acc_mac(s, v[i], v[i]);
	}
	e = mot_acc_sub(mot_acc_from(ONE, MOT_Q32_FRAC), s); /* 1 - |u|^2, Q64.64 */
	e63 = mot_acc_round(e, 1, NULL);
	for (i = 0; i < 4; i++)
		v[i] += mot_acc_round(mot_acc_mul(v[i], e63), 64, NULL);
	*out = (struct mot_quat){ v[0], v[1], v[2], v[3] };
	return MOT_OK;
}

void mot_quat_from_mat(struct mot_quat *out, const struct mot_mat *mat, uint32_t *sat)
{
	/*
	 * Shoemake, "Animating rotation with quaternion curves" (SIGGRAPH 85)
	 * and Graphics Gems IV "Euler angle conversion": with the trace positive
	 * w is large and 4w^2 = 1 + trace; otherwise the largest diagonal entry
	 * names the largest of x, y, z, e.g. 4x^2 = 1 + m00 - m11 - m22. The
	 * other components follow from sums and differences of symmetric
	 * off-diagonal pairs (m12 - m21 = 4wx, m01 + m10 = 4xy, ...), so 4q_i q
	 * is known without a square root, and one normalisation replaces both
	 * the square root and the division by 4q_i. The chosen entry, 4q_i^2,
	 * is at least 1, so the vector is never near zero.
	 */
	const mot_q32(*m)[3] = mat->m;
	mot_q32 d0 = m[0][0], d1 = m[1][1], d2 = m[2][2];
	mot_q32 tr = mot_add_sat(mot_add_sat(d0, d1, sat), d2, sat);
	mot_q32 wx = mot_sub_sat(m[1][2], m[2][1], sat), xy = mot_add_sat(m[0][1], m[1][0], sat);
	mot_q32 wy = mot_sub_sat(m[2][0], m[0][2], sat), xz = mot_add_sat(m[0][2], m[2][0], sat);
	mot_q32 wz = mot_sub_sat(m[0][1], m[1][0], sat), yz = mot_add_sat(m[1][2], m[2][1], sat);
	struct mot_quat q;

	if (tr > 0) {
		q = (struct mot_quat){ mot_add_sat(ONE, tr, sat), wx, wy, wz };
	} else if (d0 >= d1 && d0 >= d2) {
		mot_q32 k = mot_sub_sat(mot_sub_sat(mot_add_sat(ONE, d0, sat), d1, sat), d2, sat);

		q = (struct mot_quat){ wx, k, xy, xz };
	} else if (d1 >= d2) {
		mot_q32 k = mot_sub_sat(mot_sub_sat(mot_add_sat(ONE, d1, sat), d2, sat), d0, sat);

		q = (struct mot_quat){ wy, xy, k, yz };
	} else {
		mot_q32 k = mot_sub_sat(mot_sub_sat(mot_add_sat(ONE, d2, sat), d0, sat), d1, sat);

		q = (struct mot_quat){ wz, xz, yz, k };
	}
	if (q.w < 0)
		q = (struct mot_quat){ neg(q.w, sat), neg(q.x, sat), neg(q.y, sat), neg(q.z, sat) };
	mot_quat_normalize(out, &q, sat);
}

/* q within +-1 and |q|^2 within 1/8 of 1 (prepare's unit) */
static bool near_unit(const struct mot_quat *q)
{
	const mot_q32 v[4] = { q->w, q->x, q->y, q->z };
	mot_acc n = mot_acc_zero();
	mot_q32 n32;
	int i;

	for (i = 0; i < 4; i++) {
		if (mot_mag(v[i]) > (uint64_t)ONE)
			return false;
		n = mot_acc_mac(n, v[i], v[i]);
	}
	n32 = mot_acc_round(n, MOT_Q32_FRAC, NULL); /* below 4 */
	return n32 >= ONE - ONE / 8 && n32 <= ONE + ONE / 8;
}

/* ---- slerp -------------------------------------------------------------------- */

/*
 * Slerp (Shoemake 1985) as a rotation in the plane of a and b: with c the
 * unit vector of that plane orthogonal to a (Gram-Schmidt of b against a),
 *     slerp(t) = a cos(t theta) + c sin(t theta),
 * which equals the textbook a sin((1-t)theta)/sin(theta) + b sin(t theta)/
 * sin(theta) but divides by nothing at evaluation: the textbook form
 * multiplies the absolute error of the sines by 1/sin(theta), hundreds of
 * LSB for arcs of a few tenths of a degree. The arc angle comes from
 * atan2(|b - (a.b)a|, a.b), well conditioned at every angle, where
 * acos(a.b) loses half the digits near 0. Results are unit within the
 * rounding of the products (|a| = |c| = 1 and a.c = 0 within 1 LSB).
 */

static void quat_lerp(struct mot_quat *out, const struct mot_quat *a, const struct mot_quat *b,
		      mot_q32 t, uint32_t *sat)
{
	const mot_q32 u = ONE - t;
	const mot_q32 l[8] = { a->w, b->w, a->x, b->x, a->y, b->y, a->z, b->z };
	const mot_q32 r[2] = { u, t };
	struct mot_quat q;

	q.w = mot_sum_prod(l, r, 2, sat);
	q.x = mot_sum_prod(l + 2, r, 2, sat);
	q.y = mot_sum_prod(l + 4, r, 2, sat);
	q.z = mot_sum_prod(l + 6, r, 2, sat);
	if (mot_quat_normalize(out, &q, sat) != MOT_OK)
		*out = *a;
}

void mot_slerp_prepare(struct mot_slerp *s, const struct mot_quat *a, const struct mot_quat *b,
		       uint32_t *sat)
{
	struct mot_quat bb = *b, u;
	mot_q32 d, k, len;
	mot_acc n;
	int pass;

	d = mot_quat_dot(a, &bb, sat);
	if (d < 0) {
		bb = (struct mot_quat){ neg(bb.w, sat), neg(bb.x, sat), neg(bb.y, sat),
					neg(bb.z, sat) };
		d = neg(d, sat);
	}
	/* u = b - d a, then once more with k = a.u: the second pass removes
	 * what the rounding of d and of a's norm left along a. */
	u = bb;
	k = d;
	for (pass = 0; pass < 2; pass++) {
		const mot_q32 l[8] = { u.w, a->w, u.x, a->x, u.y, a->y, u.z, a->z };
		const mot_q32 r[2] = { ONE, neg(k, sat) };

		u.w = mot_sum_prod(l, r, 2, sat);
		u.x = mot_sum_prod(l + 2, r, 2, sat);
		u.y = mot_sum_prod(l + 4, r, 2, sat);
		u.z = mot_sum_prod(l + 6, r, 2, sat);
		if (pass == 0) {
			k = mot_quat_dot(a, &u, sat);
			d = mot_add_sat(d, k, sat);
		}
	}
	n = mot_acc_mul(u.w, u.w);
	n = mot_acc_mac(n, u.x, u.x);
	n = mot_acc_mac(n, u.y, u.y);
	n = mot_acc_mac(n, u.z, u.z);
	len = (mot_q32)mot_isqrt_acc(n, sat);
	s->a = *a;
	s->b = bb;
	s->theta = mot_atan2(len, d);
	s->nlerp = len < SLERP_NLERP_SIN;
	if (s->nlerp || mot_quat_normalize(&s->c, &u, sat) != MOT_OK)
		s->c = (struct mot_quat){ 0, 0, 0, 0 };
	/* |a_i cos + c_i sin| <= sqrt(a_i^2 + c_i^2) <= sqrt 2, nlerp's
	 * results are unit, the ends are a and b */
	s->small = (mot_mag(a->w) | mot_mag(a->x) | mot_mag(a->y) | mot_mag(a->z) | mot_mag(bb.w) | mot_mag(bb.x) |
		    mot_mag(bb.y) | mot_mag(bb.z) | mot_mag(s->c.w) | mot_mag(s->c.x) | mot_mag(s->c.y) |
		    mot_mag(s->c.z)) <= (uint64_t)ONE;
	s->plain = s->small && !s->nlerp;
	/* |a cos + c sin|^2 = |a|^2 cos^2 + |c|^2 sin^2 + 2 a.c sin cos is
	 * then within 1/4 of 1 (nlerp's results are unit). Only where
	 * 128-bit integers are native: scene.c (a track's unit, strand.c)
	 * uses it there alone. */
	s->unit = MOT_HAVE_INT128 && s->small && near_unit(a) && near_unit(&bb) &&
		  (s->nlerp ||
		   (near_unit(&s->c) && mot_mag(mot_quat_dot(a, &s->c, NULL)) <= (uint64_t)ONE / 8));
}

/* mot_slerp_eval()'s sums for arcs not within +-1: saturating */
static __attribute__((noinline)) void slerp_sum_sat(struct mot_quat *out,
						    const struct mot_slerp *s, mot_q32 cs,
						    mot_q32 sn, uint32_t *sat)
{
	const mot_q32 l[8] = { s->a.w, s->c.w, s->a.x, s->c.x, s->a.y, s->c.y, s->a.z, s->c.z };
	const mot_q32 r[2] = { cs, sn };

	*out = (struct mot_quat){ mot_sum_prod(l, r, 2, sat), mot_sum_prod(l + 2, r, 2, sat),
				  mot_sum_prod(l + 4, r, 2, sat), mot_sum_prod(l + 6, r, 2, sat) };
}

/* round(a cs + c sn), Q32.32, known to fit */
static inline int64_t slerp_sum2(mot_q32 a, mot_q32 cs, mot_q32 c, mot_q32 sn)
{
	return round_fits(mot_acc_mac(mot_acc_mul(a, cs), c, sn), MOT_Q32_FRAC);
}

/* slerp_mid_q()'s arcs not plain: nlerp, or saturating sums for keys far
 * from unit (out of the way, so that the caller's in-between stays in
 * registers) */
static __attribute__((noinline)) struct mot_quat slerp_mid_cold(const struct mot_slerp *s,
								mot_q32 t, uint32_t *sat)
{
	struct mot_quat q;
	struct mot_sc sc;

	if (s->nlerp) {
		quat_lerp(&q, &s->a, &s->b, t, sat);
		return q;
	}
	sc = sincos_fine_in(mot_acc_mul(t, s->theta));
	slerp_sum_sat(&q, s, sc.c, sc.s, sat);
	return q;
}

/* the same through a pointer (mot_slerp_eval()'s frame without the
 * returned quaternion's) */
static __attribute__((noinline)) void slerp_mid_cold_to(struct mot_quat *out,
							const struct mot_slerp *s, mot_q32 t,
							uint32_t *sat)
{
	*out = slerp_mid_cold(s, t, sat);
}

/* mot_slerp_eval() for t in (0, 1) of a plain arc */
static inline HOT struct mot_quat slerp_mid_plain(const struct mot_slerp *s, mot_q32 t)
{
	struct mot_sc sc;
	mot_q32 sn, cs;

	sc = sincos_fine_in(mot_acc_mul(t, s->theta));
	sn = sc.s;
	cs = sc.c;
	/* a, c within +-1: every sum below 2, mot_sum_prod()'s bits untested */
	return (struct mot_quat){ slerp_sum2(s->a.w, cs, s->c.w, sn),
				  slerp_sum2(s->a.x, cs, s->c.x, sn),
				  slerp_sum2(s->a.y, cs, s->c.y, sn),
				  slerp_sum2(s->a.z, cs, s->c.z, sn) };
}

/* mot_slerp_eval() for t in (0, 1) */
static inline HOT struct mot_quat slerp_mid_q(const struct mot_slerp *s, mot_q32 t,
					      uint32_t *sat)
{
	return s->plain ? slerp_mid_plain(s, t) : slerp_mid_cold(s, t, sat);
}

static inline HOT void slerp_mid(struct mot_quat *out, const struct mot_slerp *s, mot_q32 t,
				 uint32_t *sat)
{
	if (!s->plain) {
		slerp_mid_cold_to(out, s, t, sat);
		return;
	}
	*out = slerp_mid_plain(s, t);
}

static inline HOT void slerp_eval_in(struct mot_quat *out, const struct mot_slerp *s, mot_q32 t,
				     uint32_t *sat)
{
	if (t <= 0 || t >= ONE) {
		if ((t < 0 || t > ONE) && sat)
			*sat |= MOT_SAT_DOMAIN;
		*out = t <= 0 ? s->a : s->b;
		return;
	}
	slerp_mid(out, s, t, sat);
}

void mot_slerp_eval(struct mot_quat *out, const struct mot_slerp *s, mot_q32 t, uint32_t *sat)
{
	slerp_eval_in(out, s, t, sat);
}

/*
 * One slerp for components below 2 in magnitude (every unit quaternion):
 * the arc of mot_slerp_prepare(), the same d and u bit for bit, but no unit
 * c, and the angle from its cosine d and sine |u| without a division
 * (mot_atan2_unit_q62(), in Q62 turns where prepare rounds mot_atan2() to
 * Q32.32; mot_atan2() for keys far from unit). The in-between is
 *     a cos(t theta) + u k,  k = sin(t theta) / |u|,
 * which is a cos + c sin with c = u / |u|, with 1/|u| from the iteration
 * that finds |u| (mot_isqrt_acc_inv_near()) where normalising u took a
 * reciprocal square root, its Newton step and twelve products. k is kept
 * in Q2.62: its relative error (1/|u|'s, below 2^-58, and its rounding)
 * times |u k| <= 1 is far below an LSB, and the sine's absolute error is
 * not divided by |u|: u k carries it times |u| / |u|. Nearly equal keys
 * take nlerp, as prepare does. False, nothing written, when a component is
 * too large or k does not fit (k >= 2, only for quaternions far from
 * unit): the caller then prepares.
 *
 * Bounds: with |a_i|, |b_i| < 2 the dot products are below 2^68, |d| < 16,
 * u below 2^42 and |u|^2 below 2^86, the last sum below 2^106: no sum wraps
 * and every rounded value fits.
 */
static inline HOT bool slerp_once(struct mot_quat *out, const struct mot_quat *a,
				  const struct mot_quat *b, mot_q32 t, bool small, uint32_t *sat)
{
	const mot_q32 av[4] = { a->w, a->x, a->y, a->z };
	mot_q32 bv[4] = { b->w, b->x, b->y, b->z }, u[4], d, k, len, sn, cs;
	uint64_t big = 0, ov = 0; /* ov: t theta fits, never set */
	uint32_t local = 0;
	struct mot_sc sc;
	mot_acc n;
	int64_t k62, inv, theta; /* theta: Q62 turns */
	unsigned sh;
	int i;

	if (!small) { /* known below 2 (mot_squad_eval) or tested */
		UNROLL4
		for (i = 0; i < 4; i++)
			big |= mot_mag(av[i]) | mot_mag(bv[i]);
		if (big >= (uint64_t)1 << 33)
			return false;
	}
	n = mot_acc_zero();
	UNROLL4
	for (i = 0; i < 4; i++)
		n = mot_acc_mac(n, av[i], bv[i]);
	d = round_fits(n, MOT_Q32_FRAC);
	if (d < 0) {
		UNROLL4
		for (i = 0; i < 4; i++)
			bv[i] = -bv[i];
		d = -d;
	}
	if (t <= 0 || t >= ONE) {
		if ((t < 0 || t > ONE) && sat)
			*sat |= MOT_SAT_DOMAIN;
		*out = t <= 0 ? *a : (struct mot_quat){ bv[0], bv[1], bv[2], bv[3] };
		return true;
	}
	/* prepare's two passes of u = b - d a, the same roundings */
	n = mot_acc_zero();
	UNROLL4
	for (i = 0; i < 4; i++) {
		u[i] = bv[i] + round_fits(mot_acc_mul(av[i], -d), MOT_Q32_FRAC);
		n = mot_acc_mac(n, av[i], u[i]);
	}
	k = round_fits(n, MOT_Q32_FRAC);
	d += k;
	n = mot_acc_zero();
	UNROLL4
	for (i = 0; i < 4; i++) {
		u[i] += round_fits(mot_acc_mul(av[i], -k), MOT_Q32_FRAC);
		n = mot_acc_mac(n, u[i], u[i]);
	}
	len = (mot_q32)mot_isqrt_acc_inv_near(n, &inv, &sh); /* |u|, within 0.51 LSB */
	if (len < SLERP_NLERP_SIN) {
		const struct mot_quat bb = { bv[0], bv[1], bv[2], bv[3] };

		quat_lerp(out, a, &bb, t, sat);
		return true;
	}
	/* the arc in Q62 turns, and t times it in Q64.64 (below 1/4 turn) */
	theta = mot_atan2_unit_q62(len, d);
	sc = sincos_fine_in(mot_acc_from(mot_acc_floor_ov(mot_acc_mul(t, theta), 30, &ov), 0));
	sn = sc.s;
	cs = sc.c;
	/* sh - 62 in [22, 42]: |u| >= 2^-10 and below 2^10 */
	k62 = mot_acc_round(mot_acc_mul(sn, inv), sh - 62, &local);
	if (local)
		return false;
	cs *= (mot_q32)1 << 30; /* Q2.62, |cs| <= 1 */
	UNROLL4
	for (i = 0; i < 4; i++)
		bv[i] = round_fits(mot_acc_mac(mot_acc_mul(av[i], cs), u[i], k62), 62);
	*out = (struct mot_quat){ bv[0], bv[1], bv[2], bv[3] };
	return true;
}

/* slerp_near()'s nearly equal in-betweens: nlerp, as slerp_once() */
static __attribute__((noinline)) void slerp_near_lerp(struct mot_quat *out,
						      const struct mot_quat *a, const mot_q32 bv[4],
						      mot_q32 t, uint32_t *sat)
{
	const struct mot_quat bb = { bv[0], bv[1], bv[2], bv[3] };

	quat_lerp(out, a, &bb, t, sat);
}

/* |q|^2 (Q64.64) in [3/4 - 2^-20, 5/4 + 2^-20]: every in-between of a
 * unit arc (struct mot_slerp's unit: within 1/4 of 1 but for the
 * roundings of its products, a few 2^-32) */
static inline bool near_norm(mot_acc n)
{
	const uint64_t lo = ((uint64_t)3 << 62) - ((uint64_t)1 << 44);

	n = mot_acc_sub(n, mot_acc_make(0, lo));
	return mot_acc_hi(n) == 0 && mot_acc_lo(n) <= ((uint64_t)1 << 63) + ((uint64_t)1 << 45);
}

/* mot_isqrt_acc_inv_near() of 4 x62 (Q64.64) for x62 in [2^42, 2^63):
 * inline where 128-bit integers are native (mot_isqrt_inv_unit_in(), the
 * same bits) */
static inline HOT uint64_t isqrt_inv_unit(int64_t x62, int64_t *inv, unsigned *sh)
{
#if MOT_HAVE_INT128
	return mot_isqrt_inv_unit_in(x62, inv, sh);
#else
	return mot_isqrt_acc_inv_near(mot_acc_from(x62, 2), inv, sh);
#endif
}

/*
 * mot_squad_eval()'s slerp between its in-betweens a and b at t in
 * (0, 1/2], when both have |q|^2 within 1/4 of 1 (near_norm(), tested
 * unless unit says so; false otherwise, nothing written: the caller takes
 * slerp_once()) and components below 2 (both arcs small).
 * slerp_once()'s a cos(t theta) + u sin(t theta) / |u| with u = b - d a,
 * d = a.b / |a|^2 to first order, a.b (2 - |a|^2) (relative error
 * (|a|^2 - 1)^2, some 2^-60 for in-betweens unit within a few LSB), kept
 * in Q62; but u is never formed. Its square comes from the dot products,
 *     |u|^2 = |b|^2 - d (2 a.b - d |a|^2),
 * and the result is a (cos - d k) + b k, k = sin / |u|: u is exactly
 * b - d a for the d used (a.u = a.b - d |a|^2, some 2^-60, where u's
 * rounded components left an LSB), its components' roundings (k times
 * half an LSB each) are gone, and the shorter arc's sign goes on k and a.b
 * instead of b. And cos(t theta) / |a| multiplies a, to first order
 * cos (3 - |a|^2) / 2: a's norm error (a few LSB, the arc's slerp) no
 * longer passes to the result, whose own is then the roundings of the
 * sine, cosine and sums (tests/test_quat.c: 1.33 LSB where slerp_once()
 * gave 3.4).
 *
 * Bounds, with |a|^2, |b|^2 in [3/4, 5/4] (the 2^-20 more of near_norm()
 * changes none): |a.b| <= 5/4, 2 - |a|^2 in [3/4, 5/4], (3 - |a|^2) / 2 in
 * [7/8, 9/8], d <= 25/16, each in Q62 below 2^63. With p = a.b / |a|^2,
 * b = p a + w (w orthogonal to a), d = p + e, e = -p (|a|^2 - 1)^2 / |a|^2
 * (|e| <= |p| / 12): d |a|^2 = a.b + e |a|^2 and 2 a.b - d |a|^2 differ
 * from a.b by |e| |a|^2 <= 5/48, and d (2 a.b - d |a|^2) = |a|^2 (p^2 - e^2)
 * is in [0, |a|^2 p^2], at most (a.b)^2 / |a|^2 <= |b|^2: each below 2 in
 * Q62, and |u|^2 = |w|^2 + e^2 |a|^2 in [0, 5/4]. Its roundings (|b|^2,
 * a.b twice d, d |a|^2 and |a|^2 in it, the product: 4.6 units of 2^-62)
 * are below 2^-39.7 of |u|^2 >= 2^-20 (nlerp below): 2^-40.7 of |u| and
 * of 1/|u|, 2^-8.5 LSB of the result. The root's input below 2^63 (the
 * range of isqrt_inv_unit()). k = sin(t theta) / |u| with tan theta =
 * |u| / d, theta <= 1/4 turn: k = (sin(t theta) / sin theta) /
 * sqrt(|u|^2 + d^2) <= (1 / sqrt 2) / sqrt(|w|^2 + (p + e)^2), and
 * |w|^2 + p^2 |a|^2 = |b|^2 >= 3/4 gives |w|^2 >= 3/8 or p^2 >= 3/10,
 * (p + e)^2 >= (11/12)^2 3/10: k below 1.5, k62 fits untested. d k =
 * cos theta sin(t theta) / sin theta <= t <= 1/2, so cos / |a| - d k is in
 * [-1/2, 9/8]; the sums a (cos / |a| - d k) + b k are below 1.3 + 1.7.
 */
static inline HOT bool slerp_near(struct mot_quat *out, const struct mot_quat *a,
				  const struct mot_quat *b, mot_q32 t, bool unit, bool lerp,
				  uint32_t *sat)
{
	const mot_q32 av[4] = { a->w, a->x, a->y, a->z };
	mot_q32 bv[4] = { b->w, b->x, b->y, b->z }, len, cs, al;
	uint64_t ov = 0; /* ov: t theta fits, never set */
	mot_acc n = mot_acc_zero(), na = mot_acc_zero(), nb = mot_acc_zero();
	int64_t na62, ab62, d62, w62, u2, sg, k62, inv, theta;
	struct mot_sc sc;
	unsigned sh;
	int i;

	UNROLL4
	for (i = 0; i < 4; i++) {
		n = mot_acc_mac(n, av[i], bv[i]);
		na = mot_acc_mac(na, av[i], av[i]);
		nb = mot_acc_mac(nb, bv[i], bv[i]);
	}
	if (!unit && (!near_norm(na) || !near_norm(nb)))
		return false;
	na62 = round_fits(na, 2);
	ab62 = round_fits(n, 2);
	d62 = round_fits(mot_acc_mul(ab62, (int64_t)(((uint64_t)1 << 63) - (uint64_t)na62)), 62);
	/* the shorter arc: b, a.b and d negated when d < 0, by masks (the sign
	 * of d, about even in a scene, would mispredict); b by the sign of k */
	sg = d62 >> 63;
	d62 = (d62 ^ sg) - sg;
	ab62 = (ab62 ^ sg) - sg;
	/* |u|^2 = |b|^2 - d (2 a.b - d |a|^2), Q62 */
	w62 = ab62 + (ab62 - round_fits(mot_acc_mul(d62, na62), 62));
	u2 = round_fits(nb, 2) - round_fits(mot_acc_mul(d62, w62), 62);
	/* |u| below 2^-10 (len below SLERP_NLERP_SIN): nlerp */
	if (u2 < (int64_t)1 << 42) {
		if (!lerp)
			return false;
		UNROLL4
		for (i = 0; i < 4; i++)
			bv[i] = (bv[i] ^ sg) - sg;
		slerp_near_lerp(out, a, bv, t, sat);
		return true;
	}
	len = (mot_q32)isqrt_inv_unit(u2, &inv, &sh); /* |u|, within 0.52 LSB */
	/* d in Q32.32, rounded in 64 bits (d62 <= 25/16 2^62: no carry out) */
	theta = mot_atan2_unit_q62(len, (d62 + ((int64_t)1 << 29)) >> 30);
	sc = sincos_fine_in(mot_acc_from(mot_acc_floor_ov(mot_acc_mul(t, theta), 30, &ov), 0));
	/* cos / |a| to first order, Q2.62: floor((3 - |a|^2) / 2) as a signed
	 * difference (a factor known non-negative costs a widening unsigned
	 * multiply and its sign fix) */
	cs = round_fits(mot_acc_mul(sc.c, ((int64_t)3 << 61) - ((na62 + 1) >> 1)), 32);
	/* sin / |u| = sin inv 2^(62 - sh), sh in [84, 94]: inv floored to
	 * 2^(sh - 84), at least 2^51, so that one fixed shift rounds */
	k62 = round_fits(mot_acc_mul(sc.s, inv >> (sh - 84)), 22);
	/* a cs + (b - d a) k = a (cs - d k) + b k */
	al = cs - round_fits(mot_acc_mul(d62, k62), 62);
	k62 = (k62 ^ sg) - sg;
	UNROLL4
	for (i = 0; i < 4; i++)
		bv[i] = round_fits(mot_acc_mac(mot_acc_mul(av[i], al), bv[i], k62), 62);
	*out = (struct mot_quat){ bv[0], bv[1], bv[2], bv[3] };
	return true;
}

/* mot_slerp_prepare() and mot_slerp_eval(), out of slerp_once()'s way */
static __attribute__((noinline)) void slerp_long(struct mot_quat *out, const struct mot_quat *a,
						 const struct mot_quat *b, mot_q32 t,
						 uint32_t *sat)
{
	struct mot_slerp s;

	mot_slerp_prepare(&s, a, b, sat);
	mot_slerp_eval(out, &s, t, sat);
}

void mot_quat_slerp(struct mot_quat *out, const struct mot_quat *a, const struct mot_quat *b,
		    mot_q32 t, uint32_t *sat)
{
	if (!slerp_once(out, a, b, t, false, sat))
		slerp_long(out, a, b, t, sat);
}

/* mot_squad_eval() but for unit arcs away from nlerp: its in-betweens
 * again (the same bits), then slerp_near() after its test, else
 * slerp_once(). Out of the way, so that the usual in-betweens stay in
 * registers. */
static __attribute__((noinline)) void squad_cold(struct mot_quat *out,
						 const struct mot_slerp *arc,
						 const struct mot_slerp *inner, mot_q32 t, mot_q32 h,
						 uint32_t *sat)
{
	const bool small = arc->small && inner->small;
	struct mot_quat qa, qb;

	slerp_mid(&qa, arc, t, sat);
	slerp_mid(&qb, inner, t, sat);
	if (small && slerp_near(out, &qa, &qb, h, false, true, sat))
		return;
	if (!slerp_once(out, &qa, &qb, h, small, sat))
		slerp_long(out, &qa, &qb, h, sat);
}

void mot_squad_eval(struct mot_quat *out, const struct mot_slerp *arc,
		    const struct mot_slerp *inner, mot_q32 t, uint32_t *sat)
{
	mot_q32 h;

	/* squad(0) = q(i), squad(1) = q(i+1): the ends of arc */
	if (t <= 0 || t >= ONE) {
		if ((t < 0 || t > ONE) && sat)
			*sat |= MOT_SAT_DOMAIN;
		*out = t <= 0 ? arc->a : arc->b;
		return;
	}
	h = 2 * round_fits(mot_acc_mul(t, ONE - t), MOT_Q32_FRAC); /* 2 t (1 - t), (0, 1/2] */
	/* in-betweens of arcs within +-1 are below sqrt 2 (slerp_near()'s
	 * components below 2), those of unit arcs pass its test (only where
	 * 128-bit integers are native: the same bits) */
#if MOT_HAVE_INT128
	if (arc->unit && inner->unit) {
		const struct mot_quat qa = slerp_mid_q(arc, t, sat), qb = slerp_mid_q(inner, t, sat);

		if (slerp_near(out, &qa, &qb, h, true, false, sat))
			return;
	}
#endif
	squad_cold(out, arc, inner, t, h, sat);
}

/* ---- squad -------------------------------------------------------------------- */

/* log of a unit quaternion with w >= 0: (0, v/|v| phi), phi = atan2(|v|, w)
 * in turns, at most 1/4. */
static void quat_log(mot_q32 out[3], const struct mot_quat *q, uint32_t *sat)
{
	const mot_q32 v[3] = { q->x, q->y, q->z };
	mot_q32 len = mot_norm3(v, sat), phi;
	int i;

	if (len == 0) {
		out[0] = out[1] = out[2] = 0;
		return;
	}
	phi = mot_atan2(len, q->w);
	for (i = 0; i < 3; i++)
		out[i] = mot_muldiv(v[i], phi, len, sat);
}

/* exp of (0, l), |l| in turns: (cos |l|, l/|l| sin |l|). */
static void quat_exp(struct mot_quat *out, const mot_q32 l[3], uint32_t *sat)
{
	mot_q32 len = mot_norm3(l, sat), s, c;

	if (len == 0) {
		mot_quat_identity(out);
		return;
	}
	mot_sincos(len, &s, &c);
	*out = (struct mot_quat){ c, mot_muldiv(l[0], s, len, sat), mot_muldiv(l[1], s, len, sat),
				  mot_muldiv(l[2], s, len, sat) };
}

/* log(cur^-1 * other) on the shorter arc. */
static void rel_log(mot_q32 out[3], const struct mot_quat *cur, const struct mot_quat *other,
		    uint32_t *sat)
{
	struct mot_quat inv = { cur->w, neg(cur->x, sat), neg(cur->y, sat), neg(cur->z, sat) }, r;

	mot_quat_mul(&r, &inv, other, sat);
	if (r.w < 0)
		r = (struct mot_quat){ neg(r.w, sat), neg(r.x, sat), neg(r.y, sat), neg(r.z, sat) };
	quat_log(out, &r, sat);
}

void mot_squad_inner(struct mot_quat *out, const struct mot_quat *prev,
		     const struct mot_quat *cur, const struct mot_quat *next, uint32_t *sat)
{
	/*
	 * Shoemake's inner control point (quat.h): the average of the log
	 * tangents toward both neighbours, negated and quartered, so that the
	 * Bezier-like squad curve leaves q(i) with the same angular velocity
	 * on both sides (Shoemake, "Quaternion calculus and fast animation",
	 * SIGGRAPH 87 course notes).
	 */
	mot_q32 ln[3], lp[3], l[3];
	struct mot_quat e, s;
	int i;

	rel_log(ln, cur, next, sat);
	rel_log(lp, cur, prev, sat);
	for (i = 0; i < 3; i++)
		l[i] = mot_acc_round(mot_acc_from(-(ln[i] + lp[i]), 0), 2, NULL);
	quat_exp(&e, l, sat);
	mot_quat_mul(&s, cur, &e, sat);
	if (mot_quat_normalize(out, &s, sat) != MOT_OK)
		*out = *cur;
}

void mot_quat_squad(struct mot_quat *out, const struct mot_quat *q0, const struct mot_quat *q1,
		    const struct mot_quat *s0, const struct mot_quat *s1, mot_q32 t, uint32_t *sat)
{
	/* squad(t) = slerp(slerp(q0, q1, t), slerp(s0, s1, t), 2t(1-t)). When
	 * q1 is on the far side of q0 its inner point s1 goes with it. */
	struct mot_quat b = *q1, sb = *s1, p, r;

	if (mot_quat_dot(q0, q1, sat) < 0) {
		b = (struct mot_quat){ neg(b.w, sat), neg(b.x, sat), neg(b.y, sat), neg(b.z, sat) };
		sb = (struct mot_quat){ neg(sb.w, sat), neg(sb.x, sat), neg(sb.y, sat),
					neg(sb.z, sat) };
	}
	mot_quat_slerp(&p, q0, &b, t, sat);
	mot_quat_slerp(&r, s0, &sb, t, sat);
	mot_quat_slerp(out, &p, &r, mot_acc_round(mot_acc_mul(t, ONE - t), 31, NULL), sat);
}
