/* SPDX-License-Identifier: MIT */
/*
 * ease.h - slow-in and slow-out (FORMULAS.md section 7).
 *
 * A trapezoidal velocity profile remaps a parameter s in [0, 1]: it
 * accelerates uniformly over the first fraction a, runs at the peak speed
 * v = 1 / (1 - a/2 - b/2), and decelerates over the last fraction b:
 *     s' = v s^2 / (2a)               s < a
 *     s' = v (s - a/2)                a <= s <= 1 - b
 *     s' = 1 - v (1 - s)^2 / (2b)     s > 1 - b
 * s' is continuous with a continuous first derivative, s'(0) = 0, s'(1) = 1.
 *
 * Naming: a key's `ease_out` is the fraction spent leaving it (the a of the
 * segment that starts there), its `ease_in` the fraction spent arriving (the
 * b of the segment that ends there); a strand's `ease: {in, out}` is the same
 * over its whole span, in frames: `out` leaving the first key, `in` arriving
 * at the last.
 *
 * Precision. The profile is prepared and applied in Q2.62 (s, a, b, s'): a
 * strand-wide ease over millions of frames loses nothing before its warped
 * frame is rounded to Q32.32. Applied to s in Q2.62 the result is within 2
 * units of 2^-62 of the exact s' (measured 1.75; 2.25 including the rounding
 * of fractions given as frames over a span), monotone, and exact at 0 and 1;
 * the Q32.32 entry point rounds once more (tests/test_ease.c).
 */
#ifndef MOT_EASE_H
#define MOT_EASE_H

#include "fix.h"

/* 1 in Q2.62, the format of curve and ease parameters in [0, 1]. */
#define MOT_Q62_ONE ((int64_t)1 << 62)

struct mot_ease {
	int64_t a, b;    /* accelerating, decelerating fraction, Q2.62, a + b <= 1 */
	int64_t v;       /* peak speed 1 / (1 - a/2 - b/2), Q3.61, in [1, 2] */
	int64_t ka, kb;  /* v/(2a) = ka / 2^ka_shift, v/(2b) = kb / 2^kb_shift; 0 when
			  * a (b) is 0. Mantissas in [2^62, 2^63). */
	uint32_t ka_shift, kb_shift;
};

/* Prepare from Q32.32 fractions. a, b in [0, 1] with a + b <= 1, else
 * MOT_E_INVAL (and *e is the identity). a = b = 0 is the identity. Init only
 * (divides). */
int mot_ease_init(struct mot_ease *e, mot_q32 a, mot_q32 b, uint32_t *sat);

/* Prepare from the exact fractions a = a_num / den, b = b_num / den (den > 0,
 * a_num, b_num >= 0, a_num + b_num <= den, else MOT_E_INVAL): a strand's ease
 * in frames over its span in frames, without rounding the fractions to
 * Q32.32 first. Init only. */
int mot_ease_init_ratio(struct mot_ease *e, int64_t a_num, int64_t b_num, int64_t den,
			uint32_t *sat);

static inline bool mot_ease_is_identity(const struct mot_ease *e)
{
	return e->a == 0 && e->b == 0;
}

/* s' for s in Q2.62, both in [0, MOT_Q62_ONE] (s outside is taken as the
 * nearest end, silently: the curve code clamps by construction). Monotone,
 * exact at 0 and 1. Real-time safe: at most three products, no division. */
int64_t mot_ease_apply62(const struct mot_ease *e, int64_t s);

/* round(x / 2^sh) for 1 <= sh <= 63 (every shift of a prepared profile)
 * when the result fits int64: mot_acc_round()'s bits without its tests. */
static inline int64_t mot_ease_round(mot_acc x, unsigned sh)
{
	uint64_t lo = mot_acc_lo(x), hi = mot_acc_hi(x), r = lo + ((uint64_t)1 << (sh - 1));

	hi += r < lo;
	return (int64_t)((r >> sh) | (hi << (64 - sh)));
}

/* The same, inline: for the curves' playback path (curve_priv.h, scene.c).
 * Every rounding fits: s, r and 2s - a in [0, 1], v in [1, 2], t below
 * v/2. */
static inline __attribute__((always_inline)) int64_t mot_ease_apply62_in(const struct mot_ease *e,
									 int64_t s)
{
	int64_t t, r;

	if (s <= 0)
		return 0;
	if (s >= MOT_Q62_ONE)
		return MOT_Q62_ONE;
	if (s < e->a) {
		t = mot_ease_round(mot_acc_mul(s, e->ka), e->ka_shift);
		return mot_ease_round(mot_acc_mul(t, s), 62);
	}
	r = MOT_Q62_ONE - s;
	if (r < e->b) {
		t = mot_ease_round(mot_acc_mul(r, e->kb), e->kb_shift);
		return MOT_Q62_ONE - mot_ease_round(mot_acc_mul(t, r), 62);
	}
	{
		/* v (2s - a) / 2 = (2 s V - a V) / 2^62 with V = v 2^61 */
		mot_acc sv = mot_acc_mul(s, e->v);

		t = mot_ease_round(mot_acc_sub(mot_acc_add(sv, sv), mot_acc_mul(e->a, e->v)), 62);
	}
	return t < 0 ? 0 : t > MOT_Q62_ONE ? MOT_Q62_ONE : t;
}

/*
 * The same profile over a span of W units (a strand's ease: W, A and B in
 * Q32.32 frames, raw), applied to an offset x into the span in those units
 * directly: three polynomials in x, where s = x / W would cost a product
 * and the warped offset s' W another:
 *     g = v x^2 / (2A)                  x < A
 *     g = v (2x - A) / 2                A <= x <= W - B
 *     g = W - v (W - x)^2 / (2B)        x > W - B
 * with A, B the accelerating and decelerating lengths and v = 2W / (2W - A
 * - B), g continuous with a continuous first derivative, the pieces
 * meeting at A and W - B to within their roundings.
 *
 * Precision. v/(2A) and v/(2B) as normalised mantissas (relative error
 * 2^-63), x multiplied into them first as in the profile above: the
 * parabolas' g within 0.5 + x 2^-62 units of the exact, the plateau's
 * within 0.5 + |2x - A| 2^-63 (the rounding of v). For a span below 2^52
 * units (2^20 frames) that is half a unit and a thousandth; at the most a
 * Q32.32 span allows, 2^63, 2.5 units, where s' W was within 0.5 + 2.25 W
 * 2^-62 = 5.
 */
struct mot_ease_span {
	int64_t a, d, w;   /* A, W - B, W */
	int64_t v;         /* peak speed, Q3.61, in [1, 2] */
	int64_t ka, kb;    /* v/(2A) 2^62 = ka / 2^ka_shift (0 when A = 0), likewise
			    * for B; mantissas in [2^60, 2^63), shifts in [1, 63] */
	uint32_t ka_shift, kb_shift;
	mot_acc av;        /* A V (V = v 2^61): the plateau's offset */
};

/* Prepare for lengths A, B >= 0 over a span W > 0 with A + B <= W, else
 * MOT_E_INVAL (and *e is the identity over W, or over 1 when W <= 0).
 * Init only (divides). */
int mot_ease_span_init(struct mot_ease_span *e, int64_t a, int64_t b, int64_t w, uint32_t *sat);

/* g for an offset x strictly inside the span, 0 < x < W; g in [0, W].
 * Real-time safe: at most two products, no division. */
static inline __attribute__((always_inline)) int64_t
mot_ease_span_apply_in(const struct mot_ease_span *e, int64_t x)
{
	int64_t t, r;

	if (x < e->a) {
		/* t = x v/(2A) 2^62 <= v/2 2^62, g = t x / 2^62 */
		t = mot_ease_round(mot_acc_mul(x, e->ka), e->ka_shift);
		return mot_ease_round(mot_acc_mul(t, x), 62);
	}
	if (x > e->d) {
		r = e->w - x;
		t = mot_ease_round(mot_acc_mul(r, e->kb), e->kb_shift);
		return e->w - mot_ease_round(mot_acc_mul(t, r), 62);
	}
	{
		/* (2 x V - A V) / 2^62: |2 x V| < 2^126 */
		mot_acc xv = mot_acc_mul(x, e->v);

		t = mot_ease_round(mot_acc_sub(mot_acc_add(xv, xv), e->av), 62);
	}
	return t < 0 ? 0 : t > e->w ? e->w : t;
}

/*
 * A key interval's plateau fused with the fraction of the interval's width
 * (an eased linear or hermite piece; curve_priv.h's eased_u()). frac62
 * forms x' = (f - f0) 2^(63 - sh) and s = x' m / 2^63 for the width's
 * reciprocal m / 2^(sh + 30); on the plateau s' = v (2s - a) / 2 is then
 * (x' M - a V) / 2^62 with M = m V / 2^62: two products and one
 * rounding where frac62 and the profile took three and two. Within 3 units
 * of 2^-62 of the exact s' where the two steps are within 3.5 (the
 * roundings of m, V and M, each below 2^-62 relative; tests/test_ease.c);
 * off the plateau (x' below xa or above xd), frac62 and the profile as
 * they are.
 */
struct mot_ease_fused {
	int64_t xa, xd;  /* the plateau: xa <= x' <= xd (none for a width of 1) */
	int64_t m;       /* M = m V / 2^62, rounded */
};

/* Prepare from a prepared profile and the width's reciprocal. Init only. */
void mot_ease_fused_init(struct mot_ease_fused *f, const struct mot_ease *e,
			 const struct mot_recip *r);

/* s' for s in Q32.32. s outside [0, 1] is taken as the nearest end and sets
 * MOT_SAT_DOMAIN. Real-time safe. */
mot_q32 mot_ease_apply(const struct mot_ease *e, mot_q32 s, uint32_t *sat);

#endif /* MOT_EASE_H */
