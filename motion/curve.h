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
 * keys, parameter s = (f - f(i)) / h; a hermite piece without ease is kept
 * in s' = (f - f(i)) / 2^e instead, 2^e the power of two above h, whose
 * Q2.62 value is a shift of the frame (its coefficients prepared for it,
 * exactly): no product to find the parameter. The approximating kinds (bspline,
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
 * every kind. A warped frame is a Q32.32 frame like any input: where it is
 * rounded (the strand warp; the key warp of the approximating kinds) the
 * result is the curve's value at that rounded frame.
 *
 * Accuracy, measured against a long double reference by tests/test_curve.c:
 * step, linear and hermite are within 1/2 LSB (of Q32.32) of the exact value;
 * the approximating kinds and every eased curve within 1/2 LSB plus 1/2 LSB
 * of frame times the slope dv/df at the (warped) frame. Results are the same
 * bits on every target (__int128 or not).
 *
 * Cost per evaluation, playing 10 keys at 1 kHz ticks with a cursor (x86_64,
 * AMD EPYC, -O2; random access adds 10-30 ns): step 4 ns, linear 7 ns,
 * hermite 8 ns, bspline 60-70 ns, beta 70-80 ns (about 3.5 Newton
 * iterations); bezier O(n) per iteration in power form (a few keys, not
 * too far apart: 145 ns for 10 keys over 100 units and 200 frames), else
 * O(n^2) by de Casteljau: 130 ns for 4 keys, 400 ns for 10, 2.3 us for 32. Key intervals or Beta shapes far from uniform (gap
 * ratios of 1e4 and more, beta1 < 0.01, beta2 > 100) flatten a piece's frame
 * near its ends and take up to about 20 iterations; the solve never exceeds
 * 64 (NEWTON_MAX_IT in curve_solve.c).
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

/* Most keys a Bezier curve may have: it is one curve of degree n-1,
 * evaluated in power form (O(n)) where that keeps its precision and by de
 * Casteljau's algorithm (O(n^2)) otherwise. */
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

/*
 * An explicit tangent on a key of a hermite curve: the slope arriving at the
 * key (in) and leaving it (out), value per frame. It is what an animator's
 * Bezier handle is when the handle sits a third of the interval away (the
 * Bezier control point v + h m / 3), and what glTF's CUBICSPLINE in- and
 * out-tangents are (per second there; divide by the frame rate). A side not
 * in `set` takes the Catmull-Rom tangent of FORMULAS section 6.
 */
struct mot_tangent {
	mot_q32 in, out; /* value per frame, |m| < MOT_LEN_LIMIT, |h m| < 2^31 */
	uint32_t set;    /* MOT_TANGENT_IN | MOT_TANGENT_OUT: the sides given */
};
#define MOT_TANGENT_IN  1u
#define MOT_TANGENT_OUT 2u

struct mot_curve_opts {
	mot_q32 beta1, beta2;    /* Beta-spline bias (>= 0) and tension (>= 0) */
	mot_q32 ease_in_frames;  /* strand-wide slow-in, frames (0 = none) */
	mot_q32 ease_out_frames; /* strand-wide slow-out, frames (0 = none) */
	bool integral;           /* prepare running integrals (rpm strands) */
	/* hermite only: one entry per key, or NULL (Catmull-Rom everywhere);
	 * read at init only */
	const struct mot_tangent *tangents;
	/* step and linear only, without ease or integral: keep the keys alone,
	 * no segment array (seg may be NULL, nseg 0). For sampled motion, a
	 * key every frame: 32 bytes a key where a prepared curve takes 32 +
	 * sizeof(struct mot_curve_seg). A linear value is then one exact
	 * product and division, round(v(i) + (f - f(i)) dv / h), within 1/2
	 * LSB like the prepared one but not always the same bits. */
	bool compact;
};

/*
 * Prepared data; entry j of the array holds two things.
 *
 * Piece j of the curve: for step/linear/hermite the key interval j; for
 * bspline/beta the cubic on extended control points j..j+3; for bezier only
 * entry 0 (the whole curve), and the c[] and fc[] of every entry hold its
 * power form (curve_bezier.c). A polynomial P is kept as int64 coefficients
 * of powers of a parameter u in Q2.62, scaled by 2^sh so that their
 * magnitudes add up to at most 2^61 (block floating point: ~60 significant
 * bits however small or large the segment):
 *     value(u) = vref + P(u) / 2^vsh        (Q32.32 value)
 *     frame(u) = fref + F(u) / 2^fsh        (Q32.32 frame; approximating kinds)
 *
 * Key interval j (j < nkeys - 1), for every kind: its slow-in/out and, for
 * the approximating kinds, the reciprocal of its width.
 */
struct mot_curve_seg {
	/* in the order evaluation reads them: an interpolating piece's first 88
	 * bytes */
	mot_q32 f0, f1;          /* frames covered by piece j: [f0, f1) */
	mot_q32 vref, fref;      /* reference value and frame of the polynomials */
	int64_t c[4];            /* value polynomial P */
	struct mot_recip inv_w;  /* 1 / (f1 - f0) */
	int16_t vsh, fsh;        /* scales of c[] and of fc[] or ic[] (may be negative) */
	uint8_t start;           /* Newton start rule (curve_solve.c) */
	int8_t ush;              /* hermite without ease: c[], ic[] in u' = (f - f0) 2^ush
				  * (Q2.62), a shift; -1: in u = (f - f0) / (f1 - f0) */
	uint8_t plain;           /* step, linear or hermite without any ease, vsh in
				  * [1, 62]: scene.c's inline path may take it */
	uint8_t ntol;            /* a Newton step below 2^-ntol is the solve's last
				  * (curve_approx.c: what the piece needs, 31 at most) */
	union {
		int64_t fc[4];   /* frame polynomial F (bspline, beta) */
		int64_t ic[4];   /* c[p] / (p + 1): the mean value (hermite integral) */
		struct mot_ease_fused ef; /* linear, hermite with ease (no integral):
					   * the plateau of ease in frames (ease.h) */
		struct mot_udiv_inv inv_hd; /* linear with integral: f1 - f0, for
					     * exact quotients (curve_integral.c) */
	};
	union {
		struct {
			struct mot_recip inv_h; /* 1 / width of key interval j
						 * (approximating kinds) */
			struct mot_ease ease;   /* slow-in/out of key interval j */
		};
		/* START_TAB (bspline, beta, on a curve without any key
		 * interval's ease, whose inv_h and ease it never reads: every
		 * ease is the identity): the Newton start, u on each half of the
		 * chord fraction t as a degree-7 polynomial in x = 4 t - 1 or
		 * 4 t - 3, its coefficients in Q1.30, x^0 first
		 * (curve_approx.c, tab_start()) */
		int32_t ut[16];
	};
	union {
		mot_acc area;    /* integral from frame 0 to key j, value x frames, Q64.64 */
		/* START_INV (bspline, beta, bezier: no integral): the Newton
		 * start, a Hermite cubic on each quarter of the chord fraction t,
		 * from u at t = 1/4, 1/2, 3/4 (Q1.15) and du/dt / 4 at t = 0 .. 1
		 * (Q2.14) (curve_approx.c); a Bezier curve's table spread over its
		 * key intervals' entries (curve_solve.c) */
		uint16_t us[8];
	};
};

struct mot_curve {
	uint32_t kind;          /* enum mot_interp */
	uint32_t nkeys;
	uint32_t nseg;          /* entries of seg[] in use */
	bool seg_ease;          /* some key interval has a non-zero ease fraction */
	bool power;             /* bezier evaluated in power form (curve_bezier.c) */
	bool span_ease;         /* strand-wide ease present */
	bool integral;
	bool plain;             /* step, linear or hermite with 2 keys or more, prepared */
	bool compact;           /* keys only (opts->compact) */
	bool solve;             /* bspline, beta or bezier with keys and no ease, not
				 * compact: mot_curve_eval() goes straight to the solve */
	const struct mot_key *keys;
	struct mot_curve_seg *seg;
	mot_q32 span_f0, span_f1;    /* first and last key frame */
	mot_q32 beta1, beta2;
	struct mot_ease_span span;   /* the strand-wide ease over span_f1 - span_f0 */
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
 * invalid kind or nkeys == 0): one per key interval for step, linear,
 * hermite and bezier, nkeys + 1 for bspline and beta, at least 1. A compact
 * curve (opts->compact) needs none. */
uint32_t mot_curve_seg_count(enum mot_interp kind, uint32_t nkeys);

/*
 * Validate and prepare. opts may be NULL (beta1 = 1, beta2 = 0, no ease, no
 * integral). Errors, in this order of precedence: MOT_E_INVAL (c or keys
 * NULL, kind), MOT_E_NOKEYS (nkeys == 0), MOT_E_CAPACITY (seg NULL or nseg
 * below mot_curve_seg_count(), a Bezier curve with more than
 * MOT_BEZIER_MAX_KEYS keys), then for the first offending key MOT_E_RANGE
 * (|frame| or |value| of 2^30 or more: MOT_LEN_LIMIT) or MOT_E_ORDER (frame
 * not above the previous one), then
 * MOT_E_INVAL (ease fractions outside [0, 1] or summing above 1 on an
 * interval, strand ease negative or longer than the span, beta1 or beta2
 * outside [0, MOT_BETA1_MAX] / [0, MOT_BETA2_MAX] for a Beta-spline,
 * integral requested for an approximating kind or with any ease, tangents
 * on a kind other than hermite or with set bits other than MOT_TANGENT_*,
 * compact on a kind other than step and linear or with ease or integral),
 * MOT_E_RANGE for a tangent of MOT_LEN_LIMIT or more or whose h m reaches
 * 2^31 units on its interval (its handle beyond the core's range). On error
 * the curve evaluates to 0 and sets MOT_SAT_DOMAIN. keys and seg must
 * outlive the curve. Init only (divides; O(nkeys)).
 */
int mot_curve_init(struct mot_curve *c, enum mot_interp kind, const struct mot_key *keys,
		   uint32_t nkeys, const struct mot_curve_opts *opts, struct mot_curve_seg *seg,
		   uint32_t nseg, uint32_t *sat);

/* Value at a frame (Q32.32 frames). cur may be NULL (random access, binary
 * search); the result is the same either way. Real-time safe: no allocation,
 * bounded time (see Cost above). MOT_SAT_OVERFLOW only where a Hermite
 * overshoot leaves Q32.32, which keys within MOT_LEN_LIMIT cannot do. */
mot_q32 mot_curve_eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 frame,
		       uint32_t *sat);

/*
 * Integral of the curve from frame 0 to `frame`, in value x frames, as a
 * Q64.64 number in *out (negative for frames before 0). Closed form: a step
 * or linear curve is exact up to one rounding of the partial segment (half a
 * unit of 2^-64); a hermite curve's partial segment is within about 2^-57 of
 * (frame - key) x its largest value (measured 7.5 x 2^-60 of the terms);
 * the held ends are exact, and nothing accumulates from tick to tick, so the
 * result after a day is as good as after a second. Only for curves prepared
 * with opts->integral (else MOT_E_INVAL and *out = 0). Real-time safe (two
 * 128/64 divisions for linear, none for the others).
 */
int mot_curve_integral(mot_acc *out, const struct mot_curve *c, struct mot_cursor *cur,
		       mot_q32 frame, uint32_t *sat);

/*
 * A bound on |mot_curve_eval(c, ..)| at any frame, in raw Q32.32 units
 * (UINT64_MAX when it would not fit; 0 for a curve that failed init): the
 * keys' values, and for every piece the convex hull of its polynomial's
 * Bernstein coefficients with the evaluation's roundings (curve.c's proof):
 * within a few units of the largest value for the interpolating kinds'
 * pieces and the splines', the keys' largest for a Bezier curve. The curve
 * stays inside it whatever its ease or overshoot. Init only.
 */
uint64_t mot_curve_bound(const struct mot_curve *c);

/* Diagnostics for tests and benchmarks: the Newton iterations that
 * mot_curve_eval() takes at this frame (0 where it solves nothing: the
 * interpolating kinds, the held ends). Real-time safe. */
int mot_curve_newton_iterations(const struct mot_curve *c, mot_q32 frame);

#endif /* MOT_CURVE_H */
