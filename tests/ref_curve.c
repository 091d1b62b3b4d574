/* SPDX-License-Identifier: MIT */
/* ref_curve.c - see ref_curve.h. Plain floating point, no fixed-point code. */
#include "ref_curve.h"

#include <math.h>

ref_t ref_ease(ref_t a, ref_t b, ref_t s)
{
	ref_t v;

	if (s <= 0)
		return 0;
	if (s >= 1)
		return 1;
	v = 1 / (1 - a / 2 - b / 2);
	if (s < a)
		return v * s * s / (2 * a);
	if (s > 1 - b)
		return 1 - v * (1 - s) * (1 - s) / (2 * b);
	return v * (s - a / 2);
}

static ref_t kf(const struct mot_key *k, int64_t i)
{
	return ref_q(k[i].frame);
}

static ref_t kv(const struct mot_key *k, int64_t i)
{
	return ref_q(k[i].value);
}

/* Catmull-Rom tangent at key i, per frame (FORMULAS section 6). */
static ref_t tangent(const struct mot_key *k, uint32_t n, uint32_t i)
{
	if (i == 0)
		return (kv(k, 1) - kv(k, 0)) / (kf(k, 1) - kf(k, 0));
	if (i == n - 1)
		return (kv(k, i) - kv(k, i - 1)) / (kf(k, i) - kf(k, i - 1));
	return (kv(k, i + 1) - kv(k, i - 1)) / (kf(k, i + 1) - kf(k, i - 1));
}

/* The interpolating kinds at parameter s of key interval i. */
static ref_t interp(enum mot_interp kind, const struct mot_key *k, uint32_t n, uint32_t i, ref_t s)
{
	ref_t h = kf(k, i + 1) - kf(k, i), v0 = kv(k, i), v1 = kv(k, i + 1);
	ref_t s2 = s * s, s3 = s2 * s;

	if (kind == MOT_INTERP_STEP)
		return v0;
	if (kind == MOT_INTERP_LINEAR)
		return v0 + s * (v1 - v0);
	return (2 * s3 - 3 * s2 + 1) * v0 + (s3 - 2 * s2 + s) * h * tangent(k, n, i) +
	       (-2 * s3 + 3 * s2) * v1 + (s3 - s2) * h * tangent(k, n, i + 1);
}

/* Weights of V(i-1), V(i), V(i+1), V(i+2) at u. B-spline: the textbook
 * uniform cubic; beta: FORMULAS section 6 verbatim. */
static void weights(enum mot_interp kind, ref_t b1, ref_t b2, ref_t u, ref_t w[4])
{
	ref_t d;

	if (kind == MOT_INTERP_BSPLINE) {
		w[0] = (1 - u) * (1 - u) * (1 - u) / 6;
		w[1] = (3 * u * u * u - 6 * u * u + 4) / 6;
		w[2] = (-3 * u * u * u + 3 * u * u + 3 * u + 1) / 6;
		w[3] = u * u * u / 6;
		return;
	}
	d = 2 * b1 * b1 * b1 + 4 * b1 * b1 + 4 * b1 + b2 + 2;
	w[0] = 2 * b1 * b1 * b1 * (1 - u) * (1 - u) * (1 - u) / d;
	w[1] = (2 * b1 * b1 * b1 * u * (u * u - 3 * u + 3) +
		2 * b1 * b1 * (u * u * u - 3 * u * u + 2) + 2 * b1 * (u * u * u - 3 * u + 2) +
		b2 * (2 * u * u * u - 3 * u * u + 1)) /
	       d;
	w[2] = (2 * b1 * b1 * u * u * (3 - u) + 2 * b1 * u * (3 - u * u) +
		b2 * u * u * (3 - 2 * u) + 2 * (1 - u * u * u)) /
	       d;
	w[3] = 2 * u * u * u / d;
}

/* Point (frame, value) of spline piece j at u: control points E(m) = key
 * clamp(m - 2, 0, n - 1), the ends tripled. */
static void spline_point(enum mot_interp kind, const struct mot_key *k, uint32_t n,
			 const struct mot_curve_opts *o, uint32_t j, ref_t u, ref_t *f, ref_t *v)
{
	ref_t w[4];
	int m;

	weights(kind, ref_q(o->beta1), ref_q(o->beta2), u, w);
	*f = *v = 0;
	for (m = 0; m < 4; m++) {
		int64_t e = (int64_t)j + m - 2;

		e = e < 0 ? 0 : e > (int64_t)n - 1 ? (int64_t)n - 1 : e;
		*f += w[m] * kf(k, e);
		*v += w[m] * kv(k, e);
	}
}

static void bezier_point(const struct mot_key *k, uint32_t n, ref_t u, ref_t *f, ref_t *v)
{
	ref_t wf[MOT_BEZIER_MAX_KEYS], wv[MOT_BEZIER_MAX_KEYS];
	uint32_t i, r;

	for (i = 0; i < n; i++) {
		wf[i] = kf(k, i);
		wv[i] = kv(k, i);
	}
	for (r = n - 1; r > 0; r--)
		for (i = 0; i < r; i++) {
			wf[i] = (1 - u) * wf[i] + u * wf[i + 1];
			wv[i] = (1 - u) * wv[i] + u * wv[i + 1];
		}
	*f = wf[0];
	*v = wv[0];
}

static void point(enum mot_interp kind, const struct mot_key *k, uint32_t n,
		  const struct mot_curve_opts *o, uint32_t j, ref_t u, ref_t *f, ref_t *v)
{
	if (kind == MOT_INTERP_BEZIER)
		bezier_point(k, n, u, f, v);
	else
		spline_point(kind, k, n, o, j, u, f, v);
}

/* The approximating kinds: the piece whose frame range holds f, then u by
 * bisection until the interval stops shrinking. */
static ref_t approx(enum mot_interp kind, const struct mot_key *k, uint32_t n,
		    const struct mot_curve_opts *o, ref_t f)
{
	uint32_t j = 0, pieces = kind == MOT_INTERP_BEZIER ? 1 : n + 1;
	ref_t lo = 0, hi = 1, pf, pv;

	for (j = 0; j + 1 < pieces; j++) {
		point(kind, k, n, o, j, 1, &pf, &pv);
		if (f < pf)
			break;
	}
	for (;;) {
		ref_t mid = (lo + hi) / 2;

		if (mid <= lo || mid >= hi)
			break;
		point(kind, k, n, o, j, mid, &pf, &pv);
		if (pf < f)
			lo = mid;
		else
			hi = mid;
	}
	point(kind, k, n, o, j, (lo + hi) / 2, &pf, &pv);
	return pv;
}

/* The strand warp of f, inside the span (FORMULAS section 7). */
static ref_t strand_warp(const struct mot_key *k, uint32_t n, const struct mot_curve_opts *o,
			 ref_t f)
{
	ref_t f0 = kf(k, 0), span = kf(k, n - 1) - f0;

	if (!o->ease_in_frames && !o->ease_out_frames)
		return f;
	return f0 + span * ref_ease(ref_q(o->ease_out_frames) / span,
				    ref_q(o->ease_in_frames) / span, (f - f0) / span);
}

/* The key interval holding f (f inside the span). */
static uint32_t interval(const struct mot_key *k, uint32_t n, ref_t f)
{
	uint32_t i;

	for (i = 0; i + 2 < n && f >= kf(k, i + 1); i++)
		;
	return i;
}

ref_t ref_curve_warp(const struct mot_key *k, uint32_t n, const struct mot_curve_opts *o,
		     ref_t f, bool keys_too)
{
	uint32_t i;
	ref_t h;

	if (n == 1 || f <= kf(k, 0) || f >= kf(k, n - 1))
		return f;
	f = strand_warp(k, n, o, f);
	if (!keys_too || f >= kf(k, n - 1))
		return f;
	i = interval(k, n, f);
	h = kf(k, i + 1) - kf(k, i);
	return kf(k, i) + h * ref_ease(ref_q(k[i].ease_out), ref_q(k[i + 1].ease_in),
				       (f - kf(k, i)) / h);
}

ref_t ref_curve_eval(enum mot_interp kind, const struct mot_key *k, uint32_t n,
		     const struct mot_curve_opts *o, ref_t f)
{
	uint32_t i;
	ref_t s;

	if (n == 1 || f <= kf(k, 0))
		return kv(k, 0);
	if (f >= kf(k, n - 1))
		return kv(k, n - 1);
	f = strand_warp(k, n, o, f);
	if (f >= kf(k, n - 1))
		return kv(k, n - 1);
	i = interval(k, n, f);
	s = (f - kf(k, i)) / (kf(k, i + 1) - kf(k, i));
	s = ref_ease(ref_q(k[i].ease_out), ref_q(k[i + 1].ease_in), s);
	if (kind <= MOT_INTERP_HERMITE)
		return interp(kind, k, n, i, s);
	f = kf(k, i) + s * (kf(k, i + 1) - kf(k, i));
	return approx(kind, k, n, o, f);
}

ref_t ref_curve_slope(enum mot_interp kind, const struct mot_key *k, uint32_t n,
		      const struct mot_curve_opts *o, ref_t f, ref_t df)
{
	ref_t v = ref_curve_eval(kind, k, n, o, f);
	ref_t a = fabsl(ref_curve_eval(kind, k, n, o, f + df) - v) / df;
	ref_t b = fabsl(v - ref_curve_eval(kind, k, n, o, f - df)) / df;

	return a > b ? a : b;
}

/* Integral over [f(i), f(i) + e] of key interval i, closed form. */
static ref_t interval_integral(enum mot_interp kind, const struct mot_key *k, uint32_t n,
			       uint32_t i, ref_t e)
{
	ref_t h = kf(k, i + 1) - kf(k, i), v0 = kv(k, i), v1 = kv(k, i + 1), s = e / h;
	ref_t m0, m1;

	if (kind == MOT_INTERP_STEP)
		return v0 * e;
	if (kind == MOT_INTERP_LINEAR)
		return v0 * e + (v1 - v0) * e * e / (2 * h);
	/* integral of the Hermite basis from 0 to s, times h */
	m0 = h * tangent(k, n, i);
	m1 = h * tangent(k, n, i + 1);
	return h *
	       (v0 * (s * s * s * s / 2 - s * s * s + s) +
		m0 * (s * s * s * s / 4 - 2 * s * s * s / 3 + s * s / 2) +
		v1 * (-s * s * s * s / 2 + s * s * s) + m1 * (s * s * s * s / 4 - s * s * s / 3));
}

/* Integral from the first key to f. */
static ref_t from_first(enum mot_interp kind, const struct mot_key *k, uint32_t n, ref_t f)
{
	ref_t a = 0;
	uint32_t i;

	if (f <= kf(k, 0))
		return kv(k, 0) * (f - kf(k, 0));
	for (i = 0; i + 1 < n; i++) {
		if (f < kf(k, i + 1))
			return a + interval_integral(kind, k, n, i, f - kf(k, i));
		a += interval_integral(kind, k, n, i, kf(k, i + 1) - kf(k, i));
	}
	return a + kv(k, n - 1) * (f - kf(k, n - 1));
}

ref_t ref_curve_integral(enum mot_interp kind, const struct mot_key *k, uint32_t n, ref_t f)
{
	return from_first(kind, k, n, f) - from_first(kind, k, n, 0);
}
