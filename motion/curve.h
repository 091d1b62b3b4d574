/* SPDX-License-Identifier: MIT */
/*
 * curve.h - scalar curves over keys at uneven frame times (FORMULAS.md
 * sections 6 and 7).
 *
 * A curve is the caller's key array plus a prepared segment array, both
 * owned by the caller and sized with mot_curve_seg_count(). mot_curve_init()
 * validates the keys and precomputes everything that does not depend on the
 * sample frame (tangents, cubic coefficients, reciprocals of segment widths,
 * ease profiles, running integrals), so an evaluation is a segment lookup
 * and a few products.
 *
 * Interpolating kinds (step, linear, hermite) have one segment per pair of
 * keys, parameter s = (f - f(i)) / h. The approximating kinds (bspline,
 * beta, bezier) are curves on the 2-D control points (frame, value): the
 * value at frame f is taken where the curve's frame coordinate equals f,
 * found by a safeguarded Newton iteration whose starting point depends only
 * on f, so sequential and random access give identical bits.
 *
 * Before the first key a curve holds the first value, after the last key the
 * last value.
 *
 * Ease: a key's ease_out / ease_in fractions remap the parameter of the key
 * interval they belong to; the strand-wide ease (opts) remaps the frame over
 * the span from the first to the last key. Both are applied as time warps
 * before evaluation: strand warp first, then the key interval's warp, for
 * every kind.
 */
#ifndef MOT_CURVE_H
#define MOT_CURVE_H

#include "ease.h"
#include "fix.h"

enum mot_interp {
	MOT_INTERP_STEP,
	MOT_INTERP_LINEAR,
	MOT_INTERP_HERMITE,
	MOT_INTERP_BSPLINE,
	MOT_INTERP_BETA,
	MOT_INTERP_BEZIER,
};

/* Most keys a Bezier curve may have: it is one curve of degree n-1 and is
 * evaluated by de Casteljau's algorithm, O(n^2) per evaluation. */
#define MOT_BEZIER_MAX_KEYS 32

struct mot_key {
	mot_q32 frame;    /* strictly increasing along the array, |frame| <= 2^30 */
	mot_q32 value;    /* |value| <= 2^30 (MOT_LEN_LIMIT) */
	mot_q32 ease_in;  /* fraction of the interval arriving here, [0, 1] */
	mot_q32 ease_out; /* fraction of the interval leaving here, [0, 1] */
};

/* Beta-spline shape limits: beta1 in [0, MOT_BETA1_MAX], beta2 in
 * [0, MOT_BETA2_MAX]; the curve is already within a few LSB of its limit
 * shape there, and the basis fits 64 bits. */
#define MOT_BETA1_MAX MOT_Q32_INT(256)
#define MOT_BETA2_MAX MOT_Q32_INT(1 << 24)

struct mot_curve_opts {
	mot_q32 beta1, beta2;    /* Beta-spline bias (>= 0) and tension (>= 0) */
	mot_q32 ease_in_frames;  /* strand-wide slow-in, frames (0 = none) */
	mot_q32 ease_out_frames; /* strand-wide slow-out, frames (0 = none) */
	bool integral;           /* prepare running integrals (rpm strands) */
};

/*
 * Prepared data; entry j of the array holds two things.
 *
 * Piece j of the curve: for step/linear/hermite the key interval j; for
 * bspline/beta the cubic on extended control points j..j+3; for bezier only
 * entry 0 (the whole curve). A polynomial P is kept as int64 coefficients of
 * powers of a parameter u in Q2.62, scaled by 2^sh so that their magnitudes
 * add up to at most 2^61 (block floating point: ~60 significant bits however
 * small or large the segment):
 *     value(u) = vref + P(u) / 2^vsh        (Q32.32 value)
 *     frame(u) = fref + F(u) / 2^fsh        (Q32.32 frame; approximating kinds)
 *
 * Key interval j (j < nkeys - 1), for every kind: its slow-in/out and, for
 * the approximating kinds, the reciprocal of its width.
 */
struct mot_curve_seg {
	mot_q32 f0, f1;          /* frames covered by piece j: [f0, f1) */
	mot_q32 vref, fref;      /* reference value and frame of the polynomials */
	int64_t c[4];            /* value polynomial P */
	union {
		int64_t fc[4];   /* frame polynomial F (bspline, beta) */
		int64_t ic[4];   /* c[p] / (p + 1): the mean value (hermite integral) */
	};
	struct mot_recip inv_w;  /* 1 / (f1 - f0) */
	int16_t vsh, fsh;        /* scales of c[] and of fc[] or ic[] (may be negative) */
	uint8_t start;           /* Newton start rule (curve.c) */
	struct mot_recip inv_h;  /* 1 / width of key interval j (approximating kinds) */
	struct mot_ease ease;    /* slow-in/out of key interval j */
	mot_acc area;            /* integral from frame 0 to key j, value x frames, Q64.64 */
};

struct mot_curve {
	uint32_t kind;          /* enum mot_interp */
	uint32_t nkeys;
	uint32_t nseg;          /* entries of seg[] in use */
	bool seg_ease;          /* some key interval has a non-zero ease fraction */
	bool span_ease;         /* strand-wide ease present */
	bool integral;
	const struct mot_key *keys;
	struct mot_curve_seg *seg;
	mot_q32 beta1, beta2;
	mot_q32 span_f0, span_f1;    /* first and last key frame */
	struct mot_recip span_inv;   /* 1 / (span_f1 - span_f0) */
	struct mot_ease span;
	mot_acc area_first;          /* integral from frame 0 to the first key */
	mot_acc area_last;           /* integral from frame 0 to the last key */
};

/* Cursor for sequential playback: remembers the segment of the last sample so
 * that the next lookup is O(1) when time moves forward by a tick. Zero it to
 * start; one per curve per evaluating thread. */
struct mot_cursor {
	uint32_t seg;
	uint32_t key;
};

/* Segments that mot_curve_init() needs for nkeys keys of this kind (0 for an
 * invalid kind or nkeys == 0). */
uint32_t mot_curve_seg_count(enum mot_interp kind, uint32_t nkeys);

/*
 * Validate and prepare. Errors: MOT_E_NOKEYS (nkeys == 0), MOT_E_ORDER (frames
 * not strictly increasing), MOT_E_INVAL (kind, ease fractions outside [0, 1]
 * or summing above 1 on an interval, strand ease longer than the span,
 * beta1 <= 0 or beta2 < 0, integral requested for an approximating kind or
 * with ease), MOT_E_CAPACITY (nseg too small, or a Bezier curve with more than
 * MOT_BEZIER_MAX_KEYS keys), MOT_E_RANGE (a value or frame outside the
 * representable range of the prepared coefficients). keys and seg must
 * outlive the curve. Init only.
 */
int mot_curve_init(struct mot_curve *c, enum mot_interp kind, const struct mot_key *keys,
		   uint32_t nkeys, const struct mot_curve_opts *opts, struct mot_curve_seg *seg,
		   uint32_t nseg, uint32_t *sat);

/* Value at a frame (Q32.32 frames). cur may be NULL (random access, binary
 * search); the result is the same either way. Real-time safe. */
mot_q32 mot_curve_eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 frame,
		       uint32_t *sat);

/*
 * Integral of the curve from frame 0 to `frame`, in value x frames, as a
 * Q64.64 number in *out (negative for frames before 0). Closed form: a step
 * or linear curve is exact up to one rounding of the partial segment, a
 * hermite curve to 2^-60 relative; nothing accumulates from tick to tick, so
 * the result after a day is as good as after a second. Only for curves
 * prepared with opts->integral. Real-time safe.
 */
int mot_curve_integral(mot_acc *out, const struct mot_curve *c, struct mot_cursor *cur,
		       mot_q32 frame, uint32_t *sat);

/* Diagnostics for tests and benchmarks: the Newton iterations that
 * mot_curve_eval() takes at this frame (0 where it solves nothing: the
 * interpolating kinds, the held ends). Real-time safe. */
int mot_curve_newton_iterations(const struct mot_curve *c, mot_q32 frame);

#endif /* MOT_CURVE_H */
