/* SPDX-License-Identifier: MIT */
/*
 * curve.c - scalar curves over keys (FORMULAS.md sections 5 to 8; see
 * curve.h): init and its checks, evaluation and its dispatch by kind, and
 * the time warps of ease. The kinds' own algorithms are in the files that
 * curve_priv.h lists.
 *
 * Real time. mot_curve_eval() and mot_curve_integral() touch only the curve,
 * its keys and segments, and a small stack frame (bezier: 62 int64);
 * they allocate nothing, take no lock and run in bounded time: a segment
 * lookup is O(1) for a cursor that moved to the same or next segment and
 * O(log n) otherwise (curve_locate.c); the Newton solve of the approximating
 * kinds stops after at most NEWTON_MAX_IT iterations (curve_solve.c).
 */
#include "curve_priv.h"

/* ---- evaluation -------------------------------------------------------------- */

/* The value of an interpolating curve's piece s at a frame inside it. */
static inline __attribute__((always_inline)) mot_q32
piece_at(const struct mot_curve *c, const struct mot_curve_seg *s, mot_q32 f, uint32_t *sat)
{
	int64_t u;

	if (c->kind == MOT_INTERP_STEP)
		return s->vref;
	if (s->ush >= 0) /* a hermite piece in s', without ease (curve.h) */
		return value_of(s->vref, poly_eval(s->c, (f - s->f0) << s->ush), s->vsh, sat);
	if (c->seg_ease && !mot_ease_is_identity(&s->ease))
		u = eased_u(s, f - s->f0);
	else
		u = piece_u(f - s->f0, &s->inv_w);
	if (c->kind == MOT_INTERP_LINEAR)
		return value_of(s->vref, mul62(s->c[1], u), s->vsh, sat);
	return value_of(s->vref, poly_eval(s->c, u), s->vsh, sat);
}

/* The same, one copy, called from every path but mot_curve_eval()'s
 * plainest (eval_plain(), which has it inline). */
static __attribute__((noinline)) mot_q32 piece_value(const struct mot_curve *c,
						     const struct mot_curve_seg *s, mot_q32 f,
						     uint32_t *sat)
{
	return piece_at(c, s, f, sat);
}

/* A compact curve (keys only) strictly inside its span: step holds key i,
 * linear is v(i) + (f - f(i)) dv / h with one exact product and division
 * (|f - f(i)| < 2^63, |dv| < 2^63, the quotient within dv). */
static mot_q32 compact_eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f,
			    uint32_t *sat)
{
	const struct mot_key *k = c->keys;
	uint32_t i = locate_key(c, cur, f);

	if (c->kind == MOT_INTERP_STEP)
		return k[i].value;
	return k[i].value + mot_muldiv(f - k[i].frame, k[i + 1].value - k[i].value,
				       k[i + 1].frame - k[i].frame, sat);
}

static inline __attribute__((always_inline)) mot_q32
eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 frame, int *iters, uint32_t *sat)
{
	const struct mot_key *k;
	const struct mot_curve_seg *s;
	uint32_t n;
	int64_t u;

	if (!c || c->nkeys == 0) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN;
		return 0;
	}
	k = c->keys;
	n = c->nkeys;
	if (frame <= c->span_f0)
		return k[0].value;
	if (frame >= c->span_f1)
		return k[n - 1].value;
	if (c->span_ease) {
		frame = span_warp(c, frame);
		if (frame <= c->span_f0)
			return k[0].value;
		if (frame >= c->span_f1)
			return k[n - 1].value;
	}
	if (c->compact)
		return compact_eval(c, cur, frame, sat);
	if (c->kind >= MOT_INTERP_BSPLINE) {
		if (c->seg_ease) {
			/* the key interval's warp, in frames, before the solve */
			uint32_t i = locate_key(c, cur, frame);

			s = &c->seg[i];
			if (!mot_ease_is_identity(&s->ease)) {
				int64_t h = k[i + 1].frame - k[i].frame;

				u = piece_u(frame - k[i].frame, &s->inv_h);
				u = mot_ease_apply62(&s->ease, u);
				frame = k[i].frame + mot_acc_round(mot_acc_mul(u, h), 62, NULL);
				if (frame <= c->span_f0)
					return k[0].value;
				if (frame >= c->span_f1)
					return k[n - 1].value;
			}
		}
		return mot_cv_approx_eval(c, cur, frame, iters, sat);
	}
	return piece_value(c, &c->seg[locate_seg(c, cur, frame)], frame, sat);
}

static __attribute__((noinline)) mot_q32 eval_any(const struct mot_curve *c,
						  struct mot_cursor *cur, mot_q32 frame,
						  uint32_t *sat)
{
	int iters;

	return eval(c, cur, frame, &iters, sat);
}

/* The piece of f that the cursor holds, or the next one (moving the
 * cursor), for an interpolating curve and span_f0 < f < span_f1; NULL for
 * any other: the way through eval() finds it. */
static inline __attribute__((always_inline)) const struct mot_curve_seg *
held_piece(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f)
{
	uint32_t j = cur->seg;

	if (j >= c->nseg || f < c->seg[j].f0)
		return NULL;
	if (f >= c->seg[j].f1) {
		/* f < span_f1, the last piece's f1: j + 1 exists */
		if (f >= c->seg[j + 1].f1)
			return NULL;
		cur->seg = ++j;
	}
	return &c->seg[j];
}

/* mot_curve_eval() for a curve with a strand-wide ease: out of the plain
 * path's way, so that it needs no saved register (the calls below would
 * make it save some). */
static __attribute__((noinline)) mot_q32 eval_warped(const struct mot_curve *c,
						     struct mot_cursor *cur, mot_q32 frame,
						     uint32_t *sat)
{
	const struct mot_curve_seg *s;
	mot_q32 f = span_warp(c, frame);

	if (f <= c->span_f0)
		return c->keys[0].value;
	if (f >= c->span_f1)
		return c->keys[c->nkeys - 1].value;
	s = held_piece(c, cur, f);
	/* the way back is with the frame as given: eval() warps it again */
	return s ? piece_value(c, s, f, sat) : eval_any(c, cur, frame, sat);
}

/* mot_curve_eval() for a plain curve (c->plain) strictly inside its span:
 * out of the way of the approximating curves' tail call, which then saves
 * no register (this path's calls make it save some); scene.c's free nodes
 * call it straight (curve_priv.h). */
mot_q32 mot_cv_eval_plain(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 frame,
			  uint32_t *sat)
{
	const struct mot_curve_seg *s;

	if (c->span_ease)
		return eval_warped(c, cur, frame, sat);
	s = held_piece(c, cur, frame);
	if (!s)
		return eval_any(c, cur, frame, sat);
	return piece_at(c, s, frame, sat);
}

/*
 * Playback's common case first, kept small: the held ends, or a piece of an
 * interpolating curve that the cursor holds, or the next one. It is
 * eval()'s own path for that case, step for step, so the bits are the
 * same; everything else goes the whole way.
 */
mot_q32 mot_curve_eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 frame,
		       uint32_t *sat)
{
	if (!c || !cur)
		return eval_any(c, cur, frame, sat);
	if (!c->plain) {
		/* an approximating curve without eases: eval()'s way to the solve,
		 * which it ends with, as a tail call (half a random scene's curves) */
		if (!c->solve)
			return eval_any(c, cur, frame, sat);
		if (frame <= c->span_f0)
			return c->keys[0].value;
		if (frame >= c->span_f1)
			return c->keys[c->nkeys - 1].value;
		return mot_cv_approx_eval(c, cur, frame, NULL, sat);
	}
	if (frame <= c->span_f0)
		return c->keys[0].value;
	if (frame >= c->span_f1)
		return c->keys[c->nkeys - 1].value;
	return mot_cv_eval_plain(c, cur, frame, sat);
}

int mot_curve_newton_iterations(const struct mot_curve *c, mot_q32 frame)
{
	int iters = 0;

	eval(c, NULL, frame, &iters, NULL);
	return iters;
}

/* ---- bounds ------------------------------------------------------------------------ */

static uint64_t add_sat(uint64_t a, uint64_t b)
{
	return a + b < a ? UINT64_MAX : a + b;
}

/* |ref + round(P(u) / 2^sh)| for u in [0, 1] and P with coefficients c[0..n)
 * evaluated with `rounds` roundings (Horner's rule, curve_priv.h: the
 * partial sums stay within sum |c| + rounds): the coarse bound, for the
 * scales that hull_bound() does not take. */
static uint64_t poly_bound(mot_q32 ref, const int64_t *c, uint32_t n, uint32_t rounds, int sh)
{
	uint64_t s = rounds;
	uint32_t p;

	for (p = 0; p < n; p++)
		s = add_sat(s, mot_mag(c[p]));
	if (sh > 0)
		s = sh >= 64 ? 1 : (s >> sh) + 1;
	else if (sh < 0)
		s = -sh >= 64 || s > UINT64_MAX >> -sh ? UINT64_MAX : s << -sh;
	return add_sat(add_sat(mot_mag(ref), s), 1);
}

static bool acc_lt(mot_acc x, mot_acc y) /* |x|, |y| < 2^126 */
{
	return mot_acc_is_neg(mot_acc_sub(x, y));
}

static mot_acc acc_abs(mot_acc x)
{
	return mot_acc_is_neg(x) ? mot_acc_neg(x) : x;
}

/*
 * The tight bound. A polynomial of degree m on u in [0, 1] is
 * sum_k b_k B_k(u) in the Bernstein basis, B_k(u) = C(m,k) u^k (1-u)^(m-k)
 * >= 0 with sum_k B_k(u) = 1: every P(u) is a convex combination of the
 * b_k, in [min b_k, max b_k] (the convex hull property). Evaluated with
 * roundings whose errors add up to at most e units (each Horner step's
 * error is multiplied by powers of u <= 1 after it), the result p is in
 * [min b_k - e, max b_k + e], and ref + round(p / 2^sh), an integer, is at
 * most M + 1/2 in magnitude for M = max |ref + x / 2^sh| over that
 * interval (a linear function of x: its largest magnitude at an end), so
 * at most floor(M) + 1. Here the b_k come scaled by K (K b_k exact for the
 * cubics, K = 3), lo and hi their extremes, and M = max |K ref 2^sh + lo -
 * K e|, |K ref 2^sh + hi + K e| over K 2^sh, floored by one division
 * (for sh <= 0, value_of()'s exact ref + p 2^-sh: the same with the hull
 * scaled by 2^-sh instead).
 * With ref + hull the keys' range rather than |ref| + sum |c_p|, a piece
 * from 0.7 to 1.4 is bounded by about 1.4, where the sum of its
 * coefficients' magnitudes gave up to 2.1 and more (its cubic's terms
 * cancel). 0 when the scale is not one it takes (the caller falls back to
 * poly_bound()): sh in [-32, 63] and K 2^sh < 2^64; |ref| < 2^63, |lo|,
 * |hi| < 2^90 and e <= 2^60 keep every sum within 128 bits.
 */
static uint64_t hull_bound(mot_q32 ref, mot_acc lo, mot_acc hi, uint64_t e, unsigned K, int sh)
{
	mot_acc r = mot_acc_mul(ref, (int64_t)K), ke = mot_acc_mul((int64_t)e, (int64_t)K), a, b;
	unsigned up = sh < 0 ? (unsigned)-sh : 0;
	uint64_t rem, q;

	if (sh < -32 || sh > 63 || (sh > 0 && (uint64_t)K > UINT64_MAX >> sh) ||
	    e > (uint64_t)1 << 60)
		return 0;
	if (sh > 0)
		r = acc_shl(r, (unsigned)sh);
	a = acc_shl(mot_acc_sub(lo, ke), up);
	b = acc_shl(mot_acc_add(hi, ke), up);
	a = acc_abs(mot_acc_add(r, a));
	b = acc_abs(mot_acc_add(r, b));
	q = mot_acc_udiv(acc_lt(a, b) ? b : a, (uint64_t)K << (sh > 0 ? sh : 0), &rem, NULL);
	return add_sat(q, 1);
}

/*
 * A cubic piece: |vref + round(P(u) / 2^vsh)| for u in [0, rho] (rho = 1,
 * or rho62 / 2^62 for a hermite piece in s', curve.h: its u' = (f - f0)
 * 2^ush is below (f1 - f0) 2^ush = rho62 <= 2^62), P's value computed with
 * errors of at most 2 units (poly_eval()'s three roundings 3/2; the
 * solve's spline_value() 2, its comment; a linear piece's one 1/2).
 * On [0, rho] P(u) = Q(t), t = u / rho in [0, 1], Q's coefficients
 * c_p rho^p, each here by mul62()s (p roundings of 1/2 and the products
 * by rho <= 1 after them: at most p / 2 units off, 3 in all at any t).
 * Q's Bernstein coefficients times 3: 3 q0, 3 q0 + q1, 3 q0 + 2 q1 + q2,
 * 3 (q0 + q1 + q2 + q3), exact in 128 bits. So e = 2 + 3, taken as 8.
 */
static uint64_t cubic_bound(mot_q32 vref, const int64_t c[4], int64_t rho62, int vsh)
{
	int64_t q[4];
	mot_acc b[4], lo, hi;
	uint64_t r;
	int p;

	q[0] = c[0];
	q[1] = rho62 == ONE62 ? c[1] : mul62(c[1], rho62);
	q[2] = rho62 == ONE62 ? c[2] : mul62(mul62(c[2], rho62), rho62);
	q[3] = rho62 == ONE62 ? c[3] : mul62(mul62(mul62(c[3], rho62), rho62), rho62);
	b[0] = mot_acc_mul(q[0], 3);
	b[1] = mot_acc_add(b[0], mot_acc_from(q[1], 0));
	b[2] = mot_acc_add(mot_acc_add(b[1], mot_acc_from(q[1], 0)), mot_acc_from(q[2], 0));
	b[3] = mot_acc_add(mot_acc_add(b[0], mot_acc_mul(q[1], 3)),
			   mot_acc_add(mot_acc_mul(q[2], 3), mot_acc_mul(q[3], 3)));
	lo = hi = b[0];
	for (p = 1; p < 4; p++) {
		lo = acc_lt(b[p], lo) ? b[p] : lo;
		hi = acc_lt(hi, b[p]) ? b[p] : hi;
	}
	r = hull_bound(vref, lo, hi, 8, 3, vsh);
	return r ? r : poly_bound(vref, c, 4, 4, vsh);
}

/*
 * A Bezier curve in power form (curve_solve.c, mot_cv_approx_eval()):
 * value = vref + round(4 p / 2^vsh), 4 p its Horner on A(u) = sum a_k u^k,
 * k = 1 .. m, with m floored products (4 mulhi(r, u), each in
 * (r u / 2^62 - 4, r u / 2^62], the partial sums' errors multiplied by
 * u^j <= 1 after): 4 p in [A(u) - 4 m, A(u)]. A's Bernstein coefficients
 * are b_k = sum_{i=1..k} C(k,i) / C(m,i) a_i (a_0 = 0); with the weights
 * floored to W = floor(C(k,i) 2^32 / C(m,i)) (<= 2^32, below the exact
 * weight by less than 2^-32) and the sum floored once, b~_k = floor(sum a_i
 * W / 2^32) is within (sum |a_i|) 2^-32 + 1 of b_k. So e = 4 m + (sum
 * |a_i| >> 32) + 2 with the hull of the b~_k.
 */
static uint64_t power_bound(const struct mot_curve *c, uint64_t fallback)
{
	uint32_t m = c->nkeys - 1, k, i;
	int64_t a[MOT_BEZIER_MAX_KEYS];
	uint64_t cm[MOT_BEZIER_MAX_KEYS], ck[MOT_BEZIER_MAX_KEYS], s = 0, r, rem;
	mot_acc lo = mot_acc_zero(), hi = mot_acc_zero(); /* b_0 = a_0 = 0 */

	for (i = 1; i <= m; i++) {
		a[i] = *power_slot(c, power_vslot(m) + i - 1);
		s = add_sat(s, mot_mag(a[i]));
	}
	/* row m of Pascal's triangle (C(31, 15) < 2^29), and row k built in
	 * place as k goes up */
	cm[0] = ck[0] = 1;
	for (i = 1; i <= m; i++)
		cm[i] = 0;
	for (k = 1; k <= m; k++)
		for (i = k; i >= 1; i--)
			cm[i] += cm[i - 1];
	for (k = 1; k <= m; k++) {
		mot_acc t = mot_acc_zero();

		ck[k] = 0;
		for (i = k; i >= 1; i--)
			ck[i] += ck[i - 1];
		for (i = 1; i <= k; i++) {
			uint64_t w = mot_acc_udiv(mot_acc_make(0, ck[i] << 32), cm[i], &rem, NULL);

			t = mot_acc_add(t, mot_acc_mul(a[i], (int64_t)w));
		}
		t = mot_cv_acc_sar(t, 32);
		lo = acc_lt(t, lo) ? t : lo;
		hi = acc_lt(hi, t) ? t : hi;
	}
	r = hull_bound(c->seg[0].vref, lo, hi, 4 * (uint64_t)m + (s >> 32) + 2, 1, c->seg[0].vsh);
	return r ? r : fallback;
}

/*
 * Every value mot_curve_eval() returns (and scene.c's paths, which give
 * its bits) is one of: a key's value (a single key, the held ends before
 * and after the span, also after the strand-wide or a key interval's warp
 * in frames, or a compact step); a compact linear value between two keys
 * rounded once; a piece's value at a parameter in [0, 1] (interpolating
 * kinds: s from piece_u() or eased_u(), both clamped to [0, 2^62], or s'
 * below the piece's rho; approximating kinds: the solve's root, in its
 * bracket [0, 1]); or a Bezier curve's value at a root in [0, 1], in power
 * form or by de Casteljau. Each piece's bound is its polynomial's convex
 * hull and the evaluation's roundings (above); de Casteljau's points are
 * convex combinations of the keys' offsets from the first key scaled by
 * 2^vsh (exact for vsh >= 0, else rounded: 1/2 unit), each level's product
 * rounded (1/2 unit, nkeys - 1 levels), so v0 + that hull is within the
 * keys' values and nkeys units of 2^-vsh. Saturated (UINT64_MAX) where it
 * does not fit.
 */
uint64_t mot_curve_bound(const struct mot_curve *c)
{
	uint64_t b = 0;
	uint32_t i;

	if (!c || c->nkeys == 0)
		return 0;
	for (i = 0; i < c->nkeys; i++) {
		uint64_t v = mot_mag(c->keys[i].value);

		b = v > b ? v : b;
	}
	if (c->nkeys == 1)
		return b;
	if (c->compact) /* between two keys, rounded once */
		return add_sat(b, 1);
	if (c->kind != MOT_INTERP_BEZIER) {
		for (i = 0; i < c->nseg; i++) {
			const struct mot_curve_seg *s = &c->seg[i];
			int64_t cf[4] = { 0, 0, 0, 0 }, rho62 = ONE62;
			uint64_t p;

			if (c->kind == MOT_INTERP_LINEAR) /* value_of(vref, c1 u): c[1] alone */
				cf[1] = s->c[1];
			else if (c->kind != MOT_INTERP_STEP) /* step: vref alone */
				cf[0] = s->c[0], cf[1] = s->c[1], cf[2] = s->c[2], cf[3] = s->c[3];
			if (c->kind == MOT_INTERP_HERMITE && s->ush >= 0)
				rho62 = (int64_t)((uint64_t)(s->f1 - s->f0) << s->ush);
			p = cubic_bound(s->vref, cf, rho62, s->vsh);
			b = p > b ? p : b;
		}
		return b;
	}
	if (c->power) {
		/* the coarse bound, as before, where the tight one cannot be had */
		uint32_t m = c->nkeys - 1;
		int64_t a[MOT_BEZIER_MAX_KEYS];
		uint64_t p;

		for (i = 0; i < m; i++)
			a[i] = *power_slot(c, power_vslot(m) + i);
		p = power_bound(c, add_sat(b, poly_bound(c->seg[0].vref, a, m, m, c->seg[0].vsh)));
		return p > b ? p : b;
	}
	/* de Casteljau (above) */
	return add_sat(b, poly_bound(0, NULL, 0, c->nkeys, c->seg[0].vsh));
}

/* ---- preparation ------------------------------------------------------------------- */

uint32_t mot_curve_seg_count(enum mot_interp kind, uint32_t nkeys)
{
	if (nkeys == 0)
		return 0;
	switch (kind) {
	case MOT_INTERP_STEP:
	case MOT_INTERP_LINEAR:
	case MOT_INTERP_HERMITE:
	case MOT_INTERP_BEZIER:
		/* one per key interval (bezier: the key intervals carry the ease) */
		return nkeys > 1 ? nkeys - 1 : 1;
	case MOT_INTERP_BSPLINE:
	case MOT_INTERP_BETA:
		/* n + 4 control points with the ends tripled: n + 1 cubics */
		return nkeys == 1 ? 1 : nkeys < UINT32_MAX ? nkeys + 1 : 0;
	}
	return 0;
}

/* The pieces of each kind (one key has none: every frame holds its value;
 * nor has a compact curve). */
static int prep_pieces(struct mot_curve *c, const struct mot_tangent *tangents)
{
	if (c->nkeys == 1 || c->compact)
		return MOT_OK;
	if (c->kind == MOT_INTERP_BEZIER)
		return mot_cv_prep_bezier(c);
	if (c->kind >= MOT_INTERP_BSPLINE)
		return mot_cv_prep_spline(c);
	return mot_cv_prep_interp(c, tangents);
}

/* Explicit tangents: hermite only, each below MOT_LEN_LIMIT, and h m below
 * 2^31 units on each interval it shapes, so that the cubic's numerators stay
 * within curve_interp.c's bounds. */
static int check_tangents(const struct mot_curve *c, const struct mot_tangent *t)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, i;

	if (c->kind != MOT_INTERP_HERMITE)
		return MOT_E_INVAL;
	for (i = 0; i < n; i++) {
		if (t[i].set & ~(MOT_TANGENT_IN | MOT_TANGENT_OUT))
			return MOT_E_INVAL;
		if (mot_abs(t[i].in) >= MOT_LEN_LIMIT || mot_abs(t[i].out) >= MOT_LEN_LIMIT)
			return MOT_E_RANGE;
		/* |h m| < 2^31 units: the product of the raw Q32.32 numbers below 2^95 */
		if (i > 0 && mot_cv_acc_bitlen(mot_acc_mul(k[i].frame - k[i - 1].frame,
							   t[i].in)) > 95)
			return MOT_E_RANGE;
		if (i + 1 < n && mot_cv_acc_bitlen(mot_acc_mul(k[i + 1].frame - k[i].frame,
							       t[i].out)) > 95)
			return MOT_E_RANGE;
	}
	return MOT_OK;
}

static bool in_unit(mot_q32 x)
{
	return x >= 0 && x <= MOT_Q32_ONE;
}

/* The checks of curve.h, in its order of precedence. */
static int check(const struct mot_curve *c, const struct mot_curve_opts *o, uint32_t nseg)
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, i;

	if (c->kind == MOT_INTERP_BEZIER && n > MOT_BEZIER_MAX_KEYS)
		return MOT_E_CAPACITY;
	if (!o->compact && (!c->seg || nseg < mot_curve_seg_count(c->kind, n)))
		return MOT_E_CAPACITY;
	for (i = 0; i < n; i++) {
		if (mot_abs(k[i].frame) >= MOT_LEN_LIMIT || mot_abs(k[i].value) >= MOT_LEN_LIMIT)
			return MOT_E_RANGE;
		if (i > 0 && k[i].frame <= k[i - 1].frame)
			return MOT_E_ORDER;
	}
	for (i = 0; i < n; i++) {
		if (!in_unit(k[i].ease_in) || !in_unit(k[i].ease_out))
			return MOT_E_INVAL;
		if (i + 1 < n && k[i].ease_out > MOT_Q32_ONE - k[i + 1].ease_in)
			return MOT_E_INVAL;
	}
	if (o->ease_in_frames < 0 || o->ease_out_frames < 0 ||
	    o->ease_in_frames > k[n - 1].frame - k[0].frame ||
	    o->ease_out_frames > k[n - 1].frame - k[0].frame - o->ease_in_frames)
		return MOT_E_INVAL;
	if (c->kind == MOT_INTERP_BETA &&
	    (o->beta1 < 0 || o->beta1 > MOT_BETA1_MAX || o->beta2 < 0 || o->beta2 > MOT_BETA2_MAX))
		return MOT_E_INVAL;
	if (o->compact && (c->kind > MOT_INTERP_LINEAR || o->integral || o->ease_in_frames ||
			   o->ease_out_frames))
		return MOT_E_INVAL;
	for (i = 0; o->compact && i < n; i++)
		if (k[i].ease_in || k[i].ease_out)
			return MOT_E_INVAL;
	return o->tangents ? check_tangents(c, o->tangents) : MOT_OK;
}

int mot_curve_init(struct mot_curve *c, enum mot_interp kind, const struct mot_key *keys,
		   uint32_t nkeys, const struct mot_curve_opts *opts, struct mot_curve_seg *seg,
		   uint32_t nseg, uint32_t *sat)
{
	static const struct mot_curve_opts defaults = { MOT_Q32_ONE, 0, 0, 0, false, NULL, false };
	uint32_t i;
	int err;

	if (!c)
		return MOT_E_INVAL;
	/* An unusable curve until the end: eval gives 0 and MOT_SAT_DOMAIN. */
	c->nkeys = 0;
	c->nseg = 0;
	c->kind = (uint32_t)kind;
	c->keys = keys;
	c->seg = seg;
	c->seg_ease = c->span_ease = c->integral = c->power = c->plain = c->compact = false;
	c->solve = false;
	if (!opts)
		opts = &defaults;
	if (mot_curve_seg_count(kind, 1) == 0 || (nkeys > 0 && !keys))
		return MOT_E_INVAL;
	if (nkeys == 0)
		return MOT_E_NOKEYS;
	c->nkeys = nkeys;
	err = check(c, opts, nseg);
	if (!err && opts->integral && kind >= MOT_INTERP_BSPLINE)
		err = MOT_E_INVAL;
	if (err)
		goto fail;
	c->compact = opts->compact;
	c->nseg = c->compact ? 0 : mot_curve_seg_count(kind, nkeys);
	c->beta1 = opts->beta1;
	c->beta2 = opts->beta2;
	c->span_f0 = keys[0].frame;
	c->span_f1 = keys[nkeys - 1].frame;
	c->span_ease = opts->ease_in_frames || opts->ease_out_frames;
	for (i = 0; i < c->nseg; i++) {
		struct mot_curve_seg *s = &c->seg[i];
		bool interval = i + 1 < nkeys;

		s->f0 = s->f1 = s->fref = keys[0].frame;
		s->vref = keys[0].value;
		s->c[0] = s->c[1] = s->c[2] = s->c[3] = 0;
		s->fc[0] = s->fc[1] = s->fc[2] = s->fc[3] = 0;
		s->vsh = s->fsh = 0;
		s->start = START_CHORD;
		s->ntol = NEWTON_TOL_BITS;
		s->ush = -1;
		s->plain = 0;
		s->inv_w.m = s->inv_h.m = 0;
		s->inv_w.shift = s->inv_h.shift = 32;
		s->area = mot_acc_zero();
		err = mot_ease_init(&s->ease, interval ? keys[i].ease_out : 0,
				    interval ? keys[i + 1].ease_in : 0, sat);
		if (!err && interval)
			err = mot_recip_init(&s->inv_h, keys[i + 1].frame - keys[i].frame);
		if (err)
			goto fail;
		c->seg_ease = c->seg_ease || !mot_ease_is_identity(&s->ease);
	}
	if (opts->integral && (c->seg_ease || c->span_ease)) {
		err = MOT_E_INVAL;
		goto fail;
	}
	if (c->span_ease) {
		int64_t span = c->span_f1 - c->span_f0;

		err = mot_ease_span_init(&c->span, opts->ease_out_frames, opts->ease_in_frames,
					 span, sat);
		if (err)
			goto fail;
	}
	err = prep_pieces(c, opts->tangents);
	if (err)
		goto fail;
	/* an eased linear or hermite piece: its plateau fused with frac62, in
	 * ic[]'s place (no integral with an ease) */
	for (i = 0; c->seg_ease && (kind == MOT_INTERP_LINEAR || kind == MOT_INTERP_HERMITE) &&
		    i + 1 < nkeys; i++) {
		struct mot_curve_seg *s = &c->seg[i];

		if (!mot_ease_is_identity(&s->ease))
			mot_ease_fused_init(&s->ef, &s->ease, &s->inv_w);
	}
	c->integral = opts->integral;
	if (c->integral) {
		err = mot_cv_prep_area(c);
		if (err)
			goto fail;
	}
	c->plain = kind <= MOT_INTERP_HERMITE && nkeys > 1 && !c->compact;
	c->solve = kind >= MOT_INTERP_BSPLINE && nkeys > 0 && !c->compact && !c->span_ease &&
		   !c->seg_ease;
	for (i = 0; c->plain && !c->span_ease && i + 1 < nkeys; i++) {
		struct mot_curve_seg *s = &c->seg[i];

		s->plain = mot_ease_is_identity(&s->ease) && s->vsh >= 1 && s->vsh <= 62 &&
			   (kind != MOT_INTERP_HERMITE || s->ush >= 0);
	}
	return MOT_OK;
fail:
	c->nkeys = 0;
	c->integral = c->plain = c->solve = false;
	return err;
}
