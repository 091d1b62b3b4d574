/* SPDX-License-Identifier: MIT */
/*
 * mat.c - affine transforms in row-vector form (see mat.h).
 *
 * Every entry of a product is one sum of exact 128-bit products rounded once.
 * A 128-bit sum of three products can wrap only when the entry is far outside
 * Q32.32, so the unrolled loops collect overflow in a local word and, only
 * then, redo the result with mot_sum_prod(), which gets the saturation sign
 * right. Results are built in locals and stored last: outputs may alias
 * inputs.
 */
#include "mat.h"
#include "quat.h"
#include "trig.h"

#define ONE MOT_Q32_ONE

void mot_mat_identity(struct mot_mat *out)
{
	*out = (struct mot_mat){ { { ONE, 0, 0 }, { 0, ONE, 0 }, { 0, 0, ONE }, { 0, 0, 0 } } };
}

void mot_mat_translate(struct mot_mat *out, const mot_q32 t[3])
{
	struct mot_mat r = { { { ONE, 0, 0 }, { 0, ONE, 0 }, { 0, 0, ONE }, { t[0], t[1], t[2] } } };

	*out = r;
}

void mot_mat_scale(struct mot_mat *out, const mot_q32 s[3])
{
	struct mot_mat r = { { { s[0], 0, 0 }, { 0, s[1], 0 }, { 0, 0, s[2] }, { 0, 0, 0 } } };

	*out = r;
}

void mot_mat_shear(struct mot_mat *out, const mot_q32 h[3])
{
	struct mot_mat r = { { { ONE, 0, 0 }, { h[0], ONE, 0 }, { h[1], h[2], ONE }, { 0, 0, 0 } } };

	*out = r;
}

void mot_mat_rot_x(struct mot_mat *out, mot_q32 turns)
{
	mot_q32 s, c;

	mot_sincos(turns, &s, &c);
	*out = (struct mot_mat){ { { ONE, 0, 0 }, { 0, c, s }, { 0, -s, c }, { 0, 0, 0 } } };
}

void mot_mat_rot_y(struct mot_mat *out, mot_q32 turns)
{
	mot_q32 s, c;

	mot_sincos(turns, &s, &c);
	*out = (struct mot_mat){ { { c, 0, -s }, { 0, ONE, 0 }, { s, 0, c }, { 0, 0, 0 } } };
}

void mot_mat_rot_z(struct mot_mat *out, mot_q32 turns)
{
	mot_q32 s, c;

	mot_sincos(turns, &s, &c);
	*out = (struct mot_mat){ { { c, s, 0 }, { -s, c, 0 }, { 0, 0, ONE }, { 0, 0, 0 } } };
}

void mot_mat_rot_axis(struct mot_mat *out, const mot_q32 axis[3], mot_q32 turns, uint32_t *sat)
{
	struct mot_quat q;

	mot_quat_from_axis_angle(&q, axis, turns, sat);
	mot_quat_to_mat(out, &q, sat);
}

void mot_mat_euler(struct mot_mat *out, const mot_q32 e[3], uint32_t *sat)
{
	/* Rx(a).Ry(b).Rz(c) multiplied out; three-factor terms keep 62 bits
	 * between the two products, so each entry is rounded once. */
	mot_q32 sa, ca, sb, cb, sc, cc;
	int64_t sasb, casb;

	mot_sincos(e[0], &sa, &ca);
	mot_sincos(e[1], &sb, &cb);
	mot_sincos(e[2], &sc, &cc);
	sasb = mot_mul_q62(sa, sb);
	casb = mot_mul_q62(ca, sb);
	*out = (struct mot_mat){ {
		{ mot_mul(cb, cc, NULL), mot_mul(cb, sc, NULL), -sb },
		{ mot_sum2_q62(sasb, cc, -mot_mul_q62(ca, sc), ONE),
		  mot_sum2_q62(sasb, sc, mot_mul_q62(ca, cc), ONE), mot_mul(sa, cb, NULL) },
		{ mot_sum2_q62(casb, cc, mot_mul_q62(sa, sc), ONE),
		  mot_sum2_q62(casb, sc, -mot_mul_q62(sa, cc), ONE), mot_mul(ca, cb, NULL) },
		{ 0, 0, 0 },
	} };
}

/* Redo out = a . b entry by entry with the wrap-aware sum (see the top). */
static void mat_mul_wide(mot_q32 r[4][3], const struct mot_mat *a, const struct mot_mat *b,
			 uint32_t *sat)
{
	int i, j;

	for (i = 0; i < 4; i++) {
		for (j = 0; j < 3; j++) {
			mot_q32 x[4] = { a->m[i][0], a->m[i][1], a->m[i][2], b->m[3][j] };
			mot_q32 y[4] = { b->m[0][j], b->m[1][j], b->m[2][j], ONE };

			r[i][j] = mot_sum_prod(x, y, i == 3 ? 4 : 3, sat);
		}
	}
}

/* One row of a product: round(x . B + c) for the three columns, with
 * overflow left in *ov (fix.h's kernel). */
static inline void row_mul(mot_q32 r[3], const mot_q32 x[3], const mot_q32 (*b)[3],
			   const mot_q32 c[3], uint64_t *ov)
{
	r[0] = mot_sum3_ov(x[0], b[0][0], x[1], b[1][0], x[2], b[2][0], c[0], 32, ov);
	r[1] = mot_sum3_ov(x[0], b[0][1], x[1], b[1][1], x[2], b[2][1], c[1], 32, ov);
	r[2] = mot_sum3_ov(x[0], b[0][2], x[1], b[1][2], x[2], b[2][2], c[2], 32, ov);
}

static const mot_q32 zero3[3] = { 0, 0, 0 };

void mot_mat_mul(struct mot_mat *out, const struct mot_mat *a, const struct mot_mat *b,
		 uint32_t *sat)
{
	const mot_q32(*y)[3] = b->m;
	mot_q32 r[4][3];
	uint64_t ov = 0;

	row_mul(r[0], a->m[0], y, zero3, &ov);
	row_mul(r[1], a->m[1], y, zero3, &ov);
	row_mul(r[2], a->m[2], y, zero3, &ov);
	row_mul(r[3], a->m[3], y, y[3], &ov);
	if (ov)
		mat_mul_wide(r, a, b, sat);
	*out = (struct mot_mat){ { { r[0][0], r[0][1], r[0][2] },
				   { r[1][0], r[1][1], r[1][2] },
				   { r[2][0], r[2][1], r[2][2] },
				   { r[3][0], r[3][1], r[3][2] } } };
}

/* out = (p, w) . m for w = 0 (direction) or 1 (point). */
static void apply(mot_q32 out[3], const mot_q32 p[3], const struct mot_mat *m, bool point,
		  uint32_t *sat)
{
	mot_q32 r[3];
	uint64_t ov = 0;
	int j;

	row_mul(r, p, m->m, point ? m->m[3] : zero3, &ov);
	for (j = 0; ov && j < 3; j++) {
		mot_q32 x[4] = { p[0], p[1], p[2], m->m[3][j] };
		mot_q32 y[4] = { m->m[0][j], m->m[1][j], m->m[2][j], ONE };

		r[j] = mot_sum_prod(x, y, point ? 4 : 3, sat);
	}
	out[0] = r[0];
	out[1] = r[1];
	out[2] = r[2];
}

void mot_mat_apply(mot_q32 out[3], const mot_q32 p[3], const struct mot_mat *m, uint32_t *sat)
{
	apply(out, p, m, true, sat);
}

void mot_mat_apply_dir(mot_q32 out[3], const mot_q32 v[3], const struct mot_mat *m,
		       uint32_t *sat)
{
	apply(out, v, m, false, sat);
}

/* ---- determinant and inverse ------------------------------------------------ */

/*
 * The determinant of three rows of Q32.32 is a sum of triple products, a
 * Q96.96 number of up to 190 bits: it is kept exact in three words, so the
 * inverse below divides by the true determinant however ill-conditioned the
 * matrix, and mot_mat_det() rounds once.
 */
struct w192 {
	uint64_t w[3]; /* two's complement, w[0] least significant */
};

/* s += x * 2^shift, shift 0, 32 or 64. */
static void w192_add(struct w192 *s, mot_acc x, unsigned shift)
{
	uint64_t lo = mot_acc_lo(x), hi = mot_acc_hi(x);
	uint64_t ext = (int64_t)hi < 0 ? ~(uint64_t)0 : 0;
	uint64_t v0, v1, v2, c;

	if (shift == 0) {
		v0 = lo, v1 = hi, v2 = ext;
	} else if (shift == 32) {
		v0 = lo << 32, v1 = (hi << 32) | (lo >> 32), v2 = (ext << 32) | (hi >> 32);
	} else {
		v0 = 0, v1 = lo, v2 = hi;
	}
	s->w[0] += v0;
	c = s->w[0] < v0;
	s->w[1] += c;
	v2 += s->w[1] < c;
	s->w[1] += v1;
	v2 += s->w[1] < v1;
	s->w[2] += v2;
}

/* s += a * c for a 64-bit a and a 128-bit c: three partial products. */
static void w192_mac(struct w192 *s, int64_t a, mot_acc c)
{
	uint64_t lo = mot_acc_lo(c);

	w192_add(s, mot_acc_mul(a, (int64_t)mot_acc_hi(c)), 64);
	w192_add(s, mot_acc_mul(a, (int64_t)(lo >> 32)), 32);
	w192_add(s, mot_acc_mul(a, (int64_t)(lo & 0xffffffffu)), 0);
}

static bool w192_is_neg(const struct w192 *s)
{
	return (int64_t)s->w[2] < 0;
}

static void w192_neg(struct w192 *s)
{
	s->w[0] = ~s->w[0] + 1;
	s->w[1] = ~s->w[1] + (s->w[0] == 0);
	s->w[2] = ~s->w[2] + (s->w[0] == 0 && s->w[1] == 0);
}

/* Bits k .. k+63 of s (sign-extended past bit 191), 0 <= k. */
static uint64_t w192_bits(const struct w192 *s, unsigned k)
{
	uint64_t ext = w192_is_neg(s) ? ~(uint64_t)0 : 0;
	unsigned i = k / 64, b = k % 64;
	uint64_t lo = i < 3 ? s->w[i] : ext, hi = i + 1 < 3 ? s->w[i + 1] : ext;

	return b ? (lo >> b) | (hi << (64 - b)) : lo;
}

/* Position of the highest set bit of a non-negative s, -1 for zero. */
static int w192_top(const struct w192 *s)
{
	int i;

	for (i = 2; i >= 0; i--)
		if (s->w[i])
			return 64 * i + 63 - (int)mot_clz64(s->w[i]);
	return -1;
}

/* round(s / 2^shift) (ties toward +inf), saturating, 1 <= shift < 128. */
static int64_t w192_round(struct w192 s, unsigned shift, uint32_t *sat)
{
	struct w192 half = { { 0, 0, 0 } };
	uint64_t lo, ext;

	half.w[(shift - 1) / 64] = (uint64_t)1 << ((shift - 1) % 64);
	w192_add(&s, mot_acc_make(half.w[1], half.w[0]), 0);
	lo = w192_bits(&s, shift);
	ext = (int64_t)lo < 0 ? ~(uint64_t)0 : 0;
	if (w192_bits(&s, shift + 64) != ext) {
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		return w192_is_neg(&s) ? MOT_Q32_MIN : MOT_Q32_MAX;
	}
	return (int64_t)lo;
}

/*
 * The linear part of a as integers n, halved (e = 1) when an entry reaches
 * 2^62 so that cofactors stay below 2^125 and the determinant below 2^189;
 * its cofactors c (c[i][j] multiplies n[i][j] in the expansion) and its
 * determinant, exact. Returns e.
 */
static unsigned cofactors(mot_acc c[3][3], struct w192 *det, const struct mot_mat *a)
{
	const int64_t big = (int64_t)1 << 62;
	mot_q32 n[3][3];
	unsigned e = 0;
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			if (a->m[i][j] >= big || a->m[i][j] <= -big)
				e = 1;
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			n[i][j] = a->m[i][j] >> e;
	for (i = 0; i < 3; i++) {
		int i1 = (i + 1) % 3, i2 = (i + 2) % 3;

		for (j = 0; j < 3; j++) {
			int j1 = (j + 1) % 3, j2 = (j + 2) % 3;

			c[i][j] = mot_acc_sub(mot_acc_mul(n[i1][j1], n[i2][j2]),
					      mot_acc_mul(n[i1][j2], n[i2][j1]));
		}
	}
	*det = (struct w192){ { 0, 0, 0 } };
	for (j = 0; j < 3; j++)
		w192_mac(det, n[0][j], c[0][j]);
	return e;
}

mot_q32 mot_mat_det(const struct mot_mat *a, uint32_t *sat)
{
	mot_acc c[3][3];
	struct w192 det;
	unsigned e = cofactors(c, &det, a);

	/* det(n) is Q96.96 and det(a) = det(n) 2^(3e): Q32.32 after 64 - 3e bits */
	return w192_round(det, 64 - 3 * e, sat);
}

/* |x| of a 128-bit value below 2^127 in magnitude, and its top bit. */
static int acc_top(mot_acc x)
{
	uint64_t hi, lo;

	if (mot_acc_is_neg(x))
		x = mot_acc_neg(x);
	hi = mot_acc_hi(x);
	lo = mot_acc_lo(x);
	if (hi)
		return 127 - (int)mot_clz64(hi);
	return lo ? 63 - (int)mot_clz64(lo) : -1;
}

/* round(x / 2^sh) for sh >= 1, x itself for sh == 0, x * 2^-sh for sh < 0
 * (the caller makes sure it fits). */
static int64_t acc_scale(mot_acc x, int sh)
{
	if (sh > 0)
		return mot_acc_round(x, (unsigned)sh, NULL);
	return (int64_t)(mot_acc_lo(x) << -sh);
}

int mot_mat_inverse(struct mot_mat *out, const struct mot_mat *a, uint32_t *sat)
{
	/*
	 * Adjugate over determinant, with every quantity normalised like a
	 * floating-point number so that no relative precision is lost whatever
	 * the scale of the matrix: cofactors to 62 bits (c' = c / 2^sc), the
	 * exact determinant to 63 bits (d' = det / 2^ds), one prepared
	 * reciprocal of d', then for each entry one product rounded once:
	 *     inv[i][j] = c'[j][i] / d' * 2^(64 - e + sc - ds)   (raw Q32.32)
	 * "Near zero" is made precise as: an entry of the inverse's linear part
	 * would reach 2^30 (the length limit of fix.h), which also keeps the
	 * translation row's sums exact in 128 bits.
	 */
	const mot_q32 lim = (mot_q32)1 << 62;
	mot_acc c[3][3];
	struct w192 det;
	unsigned e = cofactors(c, &det, a);
	bool neg = w192_is_neg(&det);
	struct mot_recip rc;
	mot_q32 inv[3][3], t[3];
	int ctop = -1, top, sc, ds, sh, i, j;
	int64_t d;
	uint32_t ov = 0;

	if (neg)
		w192_neg(&det);
	top = w192_top(&det);
	if (top < 0)
		return MOT_E_SINGULAR;
	ds = top - 62;
	if (ds <= 0) {
		d = (int64_t)(det.w[0] << -ds);
	} else {
		d = (int64_t)(w192_bits(&det, (unsigned)ds) & ~((uint64_t)1 << 63));
		if ((w192_bits(&det, (unsigned)ds - 1) & 1) && ++d == INT64_MIN) {
			d = (int64_t)1 << 62;
			ds++;
		}
	}
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			if (acc_top(c[i][j]) > ctop)
				ctop = acc_top(c[i][j]);
	sc = ctop - 61;
	mot_recip_init(&rc, d);
	sh = (int)rc.shift + ds + (int)e - sc - 32;
	if (sh < 1)
		return MOT_E_SINGULAR;
	if (sh > 126)
		sh = 126;
	for (i = 0; i < 3; i++) {
		for (j = 0; j < 3; j++) {
			mot_acc p = mot_acc_mul(acc_scale(c[j][i], sc), rc.m);

			inv[i][j] = mot_acc_round(neg ? mot_acc_neg(p) : p, (unsigned)sh, &ov);
			if (inv[i][j] >= lim || inv[i][j] <= -lim)
				ov = 1;
		}
	}
	if (ov)
		return MOT_E_SINGULAR;
	/* translation: -t . inv, three products below 2^125 each */
	for (j = 0; j < 3; j++) {
		mot_acc s = mot_acc_mul(a->m[3][0], inv[0][j]);

		s = mot_acc_mac(s, a->m[3][1], inv[1][j]);
		s = mot_acc_mac(s, a->m[3][2], inv[2][j]);
		t[j] = mot_acc_round(mot_acc_neg(s), MOT_Q32_FRAC, sat);
	}
	*out = (struct mot_mat){ { { inv[0][0], inv[0][1], inv[0][2] },
				   { inv[1][0], inv[1][1], inv[1][2] },
				   { inv[2][0], inv[2][1], inv[2][2] },
				   { t[0], t[1], t[2] } } };
	return MOT_OK;
}

/* ---- editing operations ------------------------------------------------------- */

/* out_j = round((d . L)_j + c_j + u_j), sums exact (d, c, u in Q32.32). */
static void pivot_row(mot_q32 out[3], const mot_q32 d[3], const struct mot_mat *l,
		      const mot_q32 c[3], const mot_q32 u[3], uint32_t *sat)
{
	mot_q32 r[3];
	int j;

	for (j = 0; j < 3; j++) {
		mot_q32 x[5] = { d[0], d[1], d[2], c[j], u[j] };
		mot_q32 y[5] = { l->m[0][j], l->m[1][j], l->m[2][j], ONE, ONE };

		r[j] = mot_sum_prod(x, y, 5, sat);
	}
	out[0] = r[0];
	out[1] = r[1];
	out[2] = r[2];
}

static void vec_neg(mot_q32 out[3], const mot_q32 v[3], uint32_t *sat)
{
	out[0] = mot_sub_sat(0, v[0], sat);
	out[1] = mot_sub_sat(0, v[1], sat);
	out[2] = mot_sub_sat(0, v[2], sat);
}

void mot_mat_about_pivot(struct mot_mat *out, const struct mot_mat *a, const mot_q32 p[3],
			 uint32_t *sat)
{
	/* T(-p) . a . T(p): linear part a's, translation -p.A + t + p, each
	 * entry three products and two addends below 2^96 (fix.h's kernel);
	 * the saturating sums when that overflows, or when -p does not exist */
	mot_q32 np[3], t[3];
	struct mot_mat r = *a;
	uint64_t ov = p[0] == MOT_Q32_MIN || p[1] == MOT_Q32_MIN || p[2] == MOT_Q32_MIN;
	int j;

	for (j = 0; j < 3; j++) {
		mot_acc x = mot_acc_add(mot_acc_start(a->m[3][j], MOT_Q32_FRAC),
					mot_acc_from(p[j], MOT_Q32_FRAC));

		x = mot_acc_sub(x, mot_acc_mul(p[0], a->m[0][j]));
		x = mot_acc_sub(x, mot_acc_mul(p[1], a->m[1][j]));
		x = mot_acc_sub(x, mot_acc_mul(p[2], a->m[2][j]));
		t[j] = mot_acc_floor_ov(x, MOT_Q32_FRAC, &ov);
	}
	if (ov) {
		vec_neg(np, p, sat);
		pivot_row(t, np, a, a->m[3], p, sat);
	}
	r.m[3][0] = t[0];
	r.m[3][1] = t[1];
	r.m[3][2] = t[2];
	*out = r;
}

void mot_mat_to_world(struct mot_mat *m, const mot_q32 pivot[3], uint32_t *sat)
{
	mot_mat_about_pivot(m, m, pivot, sat);
}

void mot_mat_to_local(struct mot_mat *m, const mot_q32 pivot[3], uint32_t *sat)
{
	/* T(p) . M . T(-p): translation p.M + t - p */
	mot_q32 np[3];

	vec_neg(np, pivot, sat);
	pivot_row(m->m[3], pivot, m, m->m[3], np, sat);
}

void mot_mat_edit_local(struct mot_mat *m, const struct mot_mat *delta, const mot_q32 pivot[3],
			uint32_t *sat)
{
	/* T(-p) . D . T(p) . T(t) = T(-p) . [D; t] . T(p): translations commute */
	struct mot_mat x;

	mot_mat_about_pivot(&x, delta, pivot, sat);
	mot_mat_mul(m, &x, m, sat);
}

void mot_mat_edit_world(struct mot_mat *m, const struct mot_mat *delta,
			const mot_q32 world_pivot[3], uint32_t *sat)
{
	/* T(t) . T(-w) . D . T(w): linear part D, translation (t - w).D + w */
	static const mot_q32 zero[3] = { 0, 0, 0 };
	struct mot_mat y = *delta;
	mot_q32 d[3];
	int k;

	for (k = 0; k < 3; k++)
		d[k] = mot_sub_sat(delta->m[3][k], world_pivot[k], sat);
	pivot_row(y.m[3], d, delta, world_pivot, zero, sat);
	mot_mat_mul(m, m, &y, sat);
}
