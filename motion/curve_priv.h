/* SPDX-License-Identifier: MIT */
/*
 * curve_priv.h - what the files of the curves share; not a public interface
 * (see curve.h). The files, one idea each:
 *
 *     curve.c           init and its checks, evaluation and its dispatch by
 *                       kind, the time warps of ease
 *     curve_poly.c      the numbers: 128-bit shifts and roundings, block
 *                       floating point of a cubic
 *     curve_locate.c    the piece or key interval of a frame, from a cursor
 *     curve_interp.c    the interpolating kinds' pieces: step, linear, Hermite
 *     curve_integral.c  running integrals of the interpolating kinds (rpm)
 *     curve_approx.c    the B-spline's and Beta-spline's pieces
 *     curve_solve.c     an approximating curve's value at a frame: the Newton
 *                       solve of frame(u) = f on a spline piece or a Bezier
 *                       curve (Horner on its power form, or de Casteljau)
 *     curve_bezier.c    Bezier curves' preparation: the power form where it
 *                       keeps the precision
 *
 * Numbers. Frames and values are Q32.32. Curve parameters (s of a key
 * interval, u of a spline piece) are Q2.62 in [0, 1]. Every cubic is kept in
 * power form with int64 coefficients in block floating point: one scale 2^sh
 * per polynomial, chosen at init so that the coefficients' magnitudes add up
 * to at most 2^61 (mot_cv_poly_prep). Horner's rule then needs one 64x64
 * product and one rounding per degree, never overflows, and keeps ~60
 * significant bits whether a segment spans a thousandth of a frame or a
 * million frames. The divisions (tangent ratios, basis denominators,
 * reciprocals of widths) are all done at init; evaluation multiplies.
 *
 * Speed. mot_curve_eval() was one file's static functions, inlined or
 * called with everything the compiler knew of them; split, it must lose
 * none of it (make bench-count). So what evaluation needs on every sample is
 * defined here, static inline; the Newton solve keeps in its file every
 * evaluator it calls in its loop; and the functions it calls in other files
 * are declared const (a function of its arguments' values) or pure (it also
 * reads memory, writes none). Without that a loop around such a call must
 * load the curve's fields again after it: 1% more instructions on Bezier
 * curves, where it reloaded the degree in every iteration.
 *
 * The rest lives in the files above, named mot_cv_* (the core exports only
 * mot_ names; these are not curve.h's).
 *
 * scene.c includes this header too, for a joint's plainest case inline
 * (its piece_fast()) and a free node's channels (channel_value(), which
 * calls mot_cv_eval_plain() and the solve straight): one piece's
 * arithmetic, below.
 */
#ifndef MOT_CURVE_PRIV_H
#define MOT_CURVE_PRIV_H

#include "curve.h"

#define ONE62 MOT_Q62_ONE

/* The Newton solve's last step is below 2^-NEWTON_TOL_BITS, or below what
 * a spline piece or a Bezier curve needs (seg->ntol, curve_approx.c,
 * curve_bezier.c), whichever is larger. */
#define NEWTON_TOL_BITS 31

/* Newton start rules (seg->start; curve_solve.c). */
enum {
	START_CHORD, /* u0 = (f - f0) / (f1 - f0) */
	START_CUBE0, /* frame(u) = frame(0) + w u^3: u0 ~ cbrt of the chord fraction */
	START_CUBE1, /* frame(u) = frame(1) - w (1 - u)^3: mirrored */
	START_INV,   /* u0 = the inverse's Hermite cubics in the chord fraction (seg->us[]) */
	START_TAB,   /* u0 = the inverse's degree-7 polynomials on the halves (seg->ut[]) */
};

/* ---- 128-bit and scaling helpers (curve_poly.c) ------------------------------ */

static inline unsigned bitlen64(uint64_t x)
{
	return 64 - mot_clz64(x);
}

/* x * 2^n for 0 <= n < 128 (bits above 127 are lost: callers check). */
static inline mot_acc acc_shl(mot_acc x, unsigned n)
{
	uint64_t hi = mot_acc_hi(x), lo = mot_acc_lo(x);

	if (n == 0)
		return x;
	if (n >= 64)
		return mot_acc_make(lo << (n - 64), 0);
	return mot_acc_make((hi << n) | (lo >> (64 - n)), lo << n);
}

/* floor(x / 2^n) for 0 <= n < 128 (arithmetic shift). */
mot_acc mot_cv_acc_sar(mot_acc x, unsigned n) __attribute__((const));

/* Bit length of |x| (x != -2^127). */
unsigned mot_cv_acc_bitlen(mot_acc x) __attribute__((const));

/* round(x / 2^sh), 128 bits in and out, -127 < sh < 127; a left shift
 * (sh < 0) must not overflow (callers bound it). */
mot_acc mot_cv_acc_round_shift(mot_acc x, int sh) __attribute__((const));

/*
 * round(num * 2^sh / den) for den > 0, as int64 in *out. False when the
 * shifted numerator or the quotient would not fit (the prepared scales keep
 * quotients below 2^59). For sh < 0 the numerator is floored first: an error
 * below one unit of the result.
 */
bool mot_cv_acc_div_round(int64_t *out, mot_acc num, int sh, uint64_t den);

/* Block floating point for one cubic: c[p] = round(num[p] / den * 2^sh),
 * sum |c[p]| <= 2^60 + 2; MOT_E_RANGE when a coefficient does not fit. */
int mot_cv_poly_prep(int64_t c[4], int16_t *sh, const mot_acc num[4], uint64_t den);

/* round(num 2^k / (den w^p)) for den, w > 0, p <= 3, any k, exact (numbers
 * of up to 384 bits), as int64 in *out; false when its magnitude does not
 * fit below 2^63. */
bool mot_cv_div_pow_round(int64_t *out, mot_acc num, int k, uint64_t den, uint64_t w,
			  unsigned p);

/* mot_cv_poly_prep() for the polynomial in u' = u w / 2^e (2^(e-1) <= w <
 * 2^e) instead of u: every |c[p]| below 2^58; MOT_E_RANGE when none fits. */
int mot_cv_poly_prep_pow(int64_t c[4], int16_t *sh, const mot_acc num[4], uint64_t den,
			 unsigned e, uint64_t w);

/* round(x / 2^sh) for an int64 x and any sh, saturating. */
static inline int64_t round_shift(int64_t x, int sh, uint32_t *sat)
{
	if (sh > 0)
		return sh >= 127 ? 0 : mot_acc_round(mot_acc_from(x, 0), (unsigned)sh, sat);
	if (sh < 0) {
		/* x 2^k fits iff shifting it back gives x: fewer instructions than
		 * a bound (on the solve's every sample, a frame's offset to its
		 * piece's scale) */
		unsigned k = (unsigned)-sh;
		int64_t y = k < 64 ? (int64_t)((uint64_t)x << k) : 0;

		if ((k < 64 && y >> k == x) || x == 0)
			return y;
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		return x < 0 ? INT64_MIN : INT64_MAX;
	}
	return x;
}

/* ref + round(p / 2^sh), saturating only when the sum does not fit: p / 2^sh
 * alone may exceed int64 by a little where ref brings it back (a piece from
 * -2^62 to 2^62). */
static inline mot_q32 value_of_wide(mot_q32 ref, int64_t p, int sh, uint32_t *sat)
{
	mot_acc a;
	uint64_t lo;

	if (sh > -64)
		a = mot_cv_acc_round_shift(mot_acc_from(p, 0), sh);
	else
		a = p ? acc_shl(mot_acc_from(p, 0), 64) : mot_acc_zero();
	a = mot_acc_add(a, mot_acc_from(ref, 0));
	lo = mot_acc_lo(a);
	if (mot_acc_hi(a) != ((int64_t)lo < 0 ? ~(uint64_t)0 : 0)) {
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		return mot_acc_is_neg(a) ? MOT_Q32_MIN : MOT_Q32_MAX;
	}
	return (mot_q32)lo;
}

/* The same in int64 when nothing overflows: scales are positive and the
 * polynomials stay below 2^62, so this is the path every valid curve takes. */
static inline mot_q32 value_of(mot_q32 ref, int64_t p, int sh, uint32_t *sat)
{
	int64_t q;
	mot_q32 r;

	if (sh > 0 && sh < 63 && !__builtin_add_overflow(p, (int64_t)1 << (sh - 1), &q) &&
	    !__builtin_add_overflow(ref, q >> sh, &r))
		return r;
	return value_of_wide(ref, p, sh, sat);
}

/* a * u / 2^62, rounded, for |u| <= 2^62 (so the result fits without a
 * saturation test): one Horner or de Casteljau step with u in Q2.62. */
static inline int64_t mul62(int64_t a, int64_t u)
{
	uint64_t ov = 0; /* |a u| < 2^125: the result fits */

	return mot_acc_round_ov(mot_acc_mul(a, u), 62, &ov);
}

/* P(u) = c0 + u (c1 + u (c2 + u c3)); |partial sums| <= sum |c| <= 2^61. */
static inline int64_t poly_eval(const int64_t c[4], int64_t u)
{
	int64_t r = c[3];

	r = mul62(r, u) + c[2];
	r = mul62(r, u) + c[1];
	return mul62(r, u) + c[0];
}

/* P'(u) = c1 + u (2 c2 + u 3 c3); |partial sums| <= 3 * 2^61 < 2^63. */
static inline int64_t poly_deriv(const int64_t c[4], int64_t u)
{
	int64_t r = 3 * c[3];

	r = mul62(r, u) + 2 * c[2];
	return mul62(r, u) + c[1];
}

/* round(x * 2^62 / d) for the prepared reciprocal of d: the parameter in
 * Q2.62 of an offset x in [0, d]. (Only d = 1 has a shift of 30.) */
static inline int64_t frac62(int64_t x, const struct mot_recip *r)
{
	unsigned sh = r->shift - 30; /* 1 .. 63 past the test below */
	uint64_t ov = 0;             /* below 2^64 / 2^63: never set */
	int64_t s;

	if (r->shift <= 30)
		return x <= 0 ? 0 : ONE62;
	if (x <= 0)
		return 0;
	if ((uint64_t)x >> sh)
		return ONE62; /* x / d >= m / 2^62 >= 1 */
	/* round(x m / 2^sh) with x moved up to 63 bits: the shift of the
	 * rounding is then a constant */
	s = mot_acc_round_ov(mot_acc_mul(x * ((int64_t)1 << (63 - sh)), r->m), 63, &ov);
	return s > ONE62 ? ONE62 : s;
}

/*
 * frac62()'s u for an offset x in [0, d) of a piece of width d, as the
 * caller knows it to be (scene.c's memo span, curve.c's held piece, the
 * solve's piece): x < d < 2^(shift - 30) (mot_recip_init()), so neither of
 * frac62()'s ends past 0 is taken and x = 0 gives 0 by the product itself
 * (also for d = 1, shift 30). The same bits without the branches, whose
 * constants would make the callers' products full 128-bit ones (a merge of
 * 128-bit values where a 64-bit u was).
 */
static inline __attribute__((always_inline)) int64_t piece_u(int64_t x, const struct mot_recip *r)
{
	uint64_t ov = 0; /* below 2^126: never set */
	int64_t s = mot_acc_round_ov(
		mot_acc_mul((int64_t)((uint64_t)x << (93 - r->shift)), r->m), 63, &ov);

	return s > ONE62 ? ONE62 : s;
}

/* The eased parameter, Q2.62, of an eased linear or hermite piece at an
 * offset x in [0, f1 - f0): on the profile's plateau fused with the
 * fraction of the width (struct mot_ease_fused), else frac62 and the
 * profile. */
static inline __attribute__((always_inline)) int64_t eased_u(const struct mot_curve_seg *s,
							     int64_t x)
{
	const struct mot_ease_fused *e = &s->ef;
	int64_t xs = x << (93 - s->inv_w.shift), u; /* frac62's; x = 0 for a width of 1 */

	if (xs >= e->xa && xs <= e->xd) {
		/* x' M < 2^126, a V < 2^124 */
		u = mot_ease_round(mot_acc_sub(mot_acc_mul(xs, e->m),
					       mot_acc_mul(s->ease.a, s->ease.v)),
				   62);
		return u < 0 ? 0 : u > ONE62 ? ONE62 : u;
	}
	return mot_ease_apply62(&s->ease, piece_u(x, &s->inv_w));
}

/* round(x / 2^sh): mot_cv_acc_round_shift()'s bits, inline for the usual
 * 0 < sh < 127 where 128-bit integers are the compiler's. */
static inline __attribute__((always_inline)) mot_acc acc_round_shift_in(mot_acc x, int sh)
{
#if MOT_HAVE_INT128
	if (sh > 0 && sh < 127)
		return (mot_acc)((mot_uacc)x + ((mot_uacc)1 << (sh - 1))) >> sh;
#endif
	return mot_cv_acc_round_shift(x, sh);
}

/*
 * Integral over [f0, f0 + e] of interpolating piece s of kind `kind`, 0 <= e
 * <= f1 - f0, in value x frames, Q64.64 (FORMULAS section 8), for u its
 * parameter at e (s' = e 2^ush where the piece is kept in s', curve.h) and
 * dv its key interval's change of value (linear). With s = e / h:
 *   step:     e v0                                  exact
 *   linear:   e v0 + dv e^2 / (2h)                  exact but for one rounding:
 *             e^2 / h = q + r / h and dv r / h = q2 + r2 / h, two exact divisions
 *   hermite:  e (v0 + sum c_p s^p / (p + 1))        the mean value in the block
 *             scale of c (~2^-59 of sum |c_p|), times e in 128 bits
 * curve_integral.c's pieces, and scene.c's spin joints inline (the kind a
 * constant there).
 */
static inline __attribute__((always_inline)) mot_acc
cv_seg_integral(uint32_t kind, const struct mot_curve_seg *s, int64_t dv, int64_t e, int64_t u)
{
	mot_acc a = mot_acc_mul(e, s->vref);

	if (kind == MOT_INTERP_LINEAR) {
		/* |dv| < 2^63 and 0 <= e <= h < 2^63 (curve.h limits), so every
		 * quotient below fits 63 bits */
		int64_t adv = dv < 0 ? -dv : dv;
		uint64_t r, r2, q, q2, hi, lo;
		mot_acc t, ee = mot_acc_mul(e, e), ar;

		/* by h = f1 - f0's prepared reciprocal (mot_cv_prep_area()):
		 * e^2 < h 2^63 and adv r < h 2^63, high words below h, the
		 * quotients exact (mot_acc_udiv()'s) */
		q = mot_udiv_by_inv(mot_acc_hi(ee), mot_acc_lo(ee), &s->inv_hd, &r);
		ar = mot_acc_mul(adv, (int64_t)r);
		q2 = mot_udiv_by_inv(mot_acc_hi(ar), mot_acc_lo(ar), &s->inv_hd, &r2);
		/* half of t = adv q + q2 + r2/h (below 2^126), rounded to
		 * nearest, ties toward +infinity: floor((t + 1) / 2) for dv >= 0,
		 * -floor((t + (r2 != 0)) / 2) else */
		t = mot_acc_add(mot_acc_mul(adv, (int64_t)q),
				mot_acc_make(0, q2 + (dv >= 0 || r2 != 0)));
		hi = mot_acc_hi(t);
		lo = mot_acc_lo(t);
		t = mot_acc_make(hi >> 1, (lo >> 1) | (hi << 63));
		return mot_acc_add(a, dv >= 0 ? t : mot_acc_neg(t));
	}
	if (kind == MOT_INTERP_HERMITE)
		a = mot_acc_add(a, acc_round_shift_in(mot_acc_mul(e, poly_eval(s->ic, u)), s->fsh));
	return a;
}

/* The strand-wide time warp: a frame strictly inside the span to its eased
 * frame, in [span_f0, span_f1] (curve.c, and scene.c's piece memo): the
 * profile's polynomials in the frame (ease.h). */
static inline mot_q32 span_warp(const struct mot_curve *c, mot_q32 f)
{
	return c->span_f0 + mot_ease_span_apply_in(&c->span, f - c->span_f0);
}

/* ---- segment lookup (curve_locate.c) ------------------------------------------ */

/* The last index j in [0, n) whose start is at or before f: of the key
 * intervals (keys, n = nkeys - 1) or of the pieces (n = nseg), trying the
 * hint first. */
uint32_t mot_cv_locate(const struct mot_curve *c, bool keys, uint32_t n, uint32_t hint,
		       mot_q32 f) __attribute__((pure));

/* The piece of frame f (span_f0 <= f), through the cursor when there is one:
 * the cursor's piece tested here, mot_cv_locate()'s first test without the
 * call (a piece's f1 is the next one's f0, the last's span_f1). */
static inline uint32_t locate_seg(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f)
{
	uint32_t j = cur ? cur->seg : c->nseg;

	if (j >= c->nseg || f < c->seg[j].f0 || f >= c->seg[j].f1) {
		j = mot_cv_locate(c, false, c->nseg, cur ? cur->seg : 0, f);
		if (cur)
			cur->seg = j;
	}
	return j;
}

/* The key interval of frame f (span_f0 <= f), likewise. */
static inline uint32_t locate_key(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f)
{
	uint32_t i = mot_cv_locate(c, true, c->nkeys - 1, cur ? cur->key : 0, f);

	if (cur)
		cur->key = i;
	return i;
}

/* mot_curve_eval() for a plain curve (c->plain) strictly inside its span
 * (curve.c). */
mot_q32 mot_cv_eval_plain(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 frame,
			  uint32_t *sat);

/* ---- Bezier in power form (curve_bezier.c) --------------------------------------- */

/* Slot j of the power form's coefficients: the frame's a_1 .. a_m in slots
 * 0 .. m - 1, the value's from slot power_vslot(m), kept in the c[] and fc[]
 * of the curve's entries, 8 an entry. */
static inline int64_t *power_slot(const struct mot_curve *c, uint32_t j)
{
	struct mot_curve_seg *s = &c->seg[j / 8];

	return j % 8 < 4 ? &s->c[j % 4] : &s->fc[j % 4];
}

/* The value's first slot: 8 for 2 <= m <= 8 (the m entries hold 8 m slots),
 * so that the frame's are entry 0's and the value's entry 1's, each at
 * places the solve's unrolled Horner knows (curve_solve.c); else m, after
 * the frame's. */
static inline uint32_t power_vslot(uint32_t m)
{
	return m >= 2 && m <= 8 ? 8 : m;
}

/* ---- preparation, by kind (init only) --------------------------------------------- */

/* The pieces of a step, linear or hermite curve of two keys or more, with
 * a hermite curve's explicit tangents (one per key, or NULL)
 * (curve_interp.c). */
int mot_cv_prep_interp(struct mot_curve *c, const struct mot_tangent *tan);

/* The pieces of a bspline or beta curve of two keys or more (curve_approx.c). */
int mot_cv_prep_spline(struct mot_curve *c);

/* Entry 0 of a Bezier curve of two keys or more: scales, frame range, and
 * its power form where that keeps the precision (curve_bezier.c). */
int mot_cv_prep_bezier(struct mot_curve *c);
void mot_cv_bezier_start(struct mot_curve *c); /* curve_solve.c */

/* START_TAB's fit (curve_approx.c): the chord fraction t in [0, 1] (Q2.62)
 * of node i of half h, the eight Chebyshev nodes of each half; and the
 * degree-7 polynomials of each half through u at them (y[8 h + i], Q2.60),
 * their coefficients in Q1.30 in ut[] as tab62() (curve_solve.c) reads them,
 * false (ut[] untouched) where tab62()'s sums would not fit. */
int64_t mot_cv_tab_node(unsigned h, unsigned i) __attribute__((const));
bool mot_cv_tab_fit(const int64_t y[16], int32_t ut[16]);

/* The running integrals of a prepared interpolating curve (curve_integral.c). */
int mot_cv_prep_area(struct mot_curve *c);

/* ---- evaluation of the approximating kinds (curve_solve.c) ------------------------- */

/* Value of an approximating curve at a (warped) frame strictly inside the
 * span; *iters (iters may be NULL): the Newton iterations it took. */
mot_q32 mot_cv_approx_eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f,
			   int *iters, uint32_t *sat);

#endif /* MOT_CURVE_PRIV_H */
