/* SPDX-License-Identifier: MIT */
/*
 * curve_solve.c - the value of an approximating curve (bspline, beta,
 * bezier) at a frame: its value coordinate at the parameter u where its
 * frame coordinate equals the frame (FORMULAS section 6), u found by a
 * safeguarded Newton iteration on a spline piece (curve_approx.c) or on the
 * one Bezier curve (curve_bezier.c). Real-time safe: a small stack frame
 * (bezier: 62 int64), at most NEWTON_MAX_IT iterations of one 64-bit
 * division each.
 *
 * Every evaluator the iteration calls is in this file or inline in
 * curve_priv.h, as when the curves were one file: the loop's code, and so
 * its cost, depends on what the compiler knows of them.
 */
#include "curve_priv.h"

#define NEWTON_MAX_IT 64
#define BISECT_TOL ((int64_t)1 << 12) /* 2^-50: a bracket this narrow is the answer */

/*
 * q = r * 2^62 / d in Q2.62 for d > 0, to a relative 2^-30, with |q| < 2^62;
 * false when it would not fit. One 64-bit division of |r| moved up to 62
 * bits by d cut to its top 31: a quotient of 31 or 32 bits, exact, so the
 * same on every target. A Newton step of the curve solve needs only a good
 * direction and size, the solve's own convergence makes up the rest. The
 * division is the hardware's where it has one for 64 bits (x86_64,
 * aarch64: a dozen cycles, where a reciprocal by products took two dozen
 * and four times the instructions) and libgcc's elsewhere.
 */
static bool ratio62(int64_t r, int64_t d, int64_t *q)
{
	uint64_t ar = r < 0 ? 0 - (uint64_t)r : (uint64_t)r, a, b, x;
	unsigned lr, ld;
	int e;

	if (ar == 0) {
		*q = 0;
		return true;
	}
	/* one count each: mot_clz64()'s two halves cost a branch each here */
	lr = 64 - (unsigned)__builtin_clzll(ar);
	ld = 64 - (unsigned)__builtin_clzll((uint64_t)d);
	a = lr <= 62 ? ar << (62 - lr) : ar >> (lr - 62); /* [2^61, 2^62) */
	b = ld >= 31 ? (uint64_t)d >> (ld - 31) : (uint64_t)d << (31 - ld); /* [2^30, 2^31) */
	x = a / b; /* (2^30, 2^32): |r| / d = x 2^(lr - ld - 31) */
	e = (int)lr - (int)ld + 31;
	if (e >= 0) {
		if (e > 31 || x >> (62 - e))
			return false; /* |q| >= 2^62 */
		x <<= e;
	} else {
		x = -e >= 64 ? 0 : x >> -e;
	}
	*q = r < 0 ? -(int64_t)x : (int64_t)x;
	return true;
}

/* cbrt(x) for x in Q2.62 [0, 1], to about 1%: the Newton start on a piece
 * whose frame grows as u^3 (the tripled end keys). */
static int64_t cbrt62(int64_t x)
{
	static const int64_t k_third[3] = {
		ONE62, 3660297618499336453, 2905180145061270980, /* 2^(-r/3) */
	};
	unsigned e, q, r;
	int64_t m, g;

	if (x <= 0)
		return 0;
	e = 63 - bitlen64((uint64_t)x); /* x = (1 + m) 2^-e, m in [0, 1) */
	q = e / 3;
	r = e % 3;
	m = (int64_t)((uint64_t)x << e) - ONE62;
	g = ONE62 + mul62(m, 1198674271695154057); /* cbrt(1 + m) ~ 1 + m (2^(1/3) - 1) */
	return mul62(g, k_third[r]) >> q;
}

/* ---- frame(u) and value(u) of a Bezier curve ------------------------------------ */

/* Horner's rule on the power form (curve_bezier.c), a[k - 1] multiplying
 * u^k: the frame and its derivative, or the value. */
static void power_frame(const int64_t *a, uint32_t m, int64_t u, int64_t *f, int64_t *df)
{
	int64_t r = a[m - 1], d = (int64_t)m * a[m - 1];
	uint32_t k;

	for (k = m - 1; k >= 1; k--) {
		r = mul62(r, u) + a[k - 1];
		d = mul62(d, u) + (int64_t)k * a[k - 1];
	}
	*f = mul62(r, u);
	*df = d;
}

static int64_t power_value(const int64_t *a, uint32_t m, int64_t u)
{
	int64_t r = a[m - 1];
	uint32_t k;

	for (k = m - 1; k >= 1; k--)
		r = mul62(r, u) + a[k - 1];
	return mul62(r, u);
}

/* De Casteljau's algorithm, for the curves the power form would not keep
 * precise: at u on the keys' frames (or values) relative to the first key,
 * scaled by 2^fsh (2^vsh), until `left` points remain in w[]. */
static void bezier_reduce(const struct mot_curve *c, bool value, int64_t u, uint32_t left,
			  int64_t w[MOT_BEZIER_MAX_KEYS])
{
	const struct mot_key *k = c->keys;
	uint32_t n = c->nkeys, i, r;
	int sh = value ? c->seg[0].vsh : c->seg[0].fsh;

	/* the offsets are below 2^(58 - sh) (bezier_shift): no overflow */
	for (i = 0; i < n; i++) {
		int64_t x = value ? k[i].value - k[0].value : k[i].frame - k[0].frame;

		w[i] = sh >= 0 ? x * ((int64_t)1 << sh) : round_shift(x, -sh, NULL);
	}
	for (r = n - 1; r >= left; r--)
		for (i = 0; i < r; i++)
			w[i] += mul62(w[i + 1] - w[i], u);
}

/* The frame and its derivative (from the last two points). */
static void bezier_frame(const struct mot_curve *c, int64_t u, int64_t *f, int64_t *df)
{
	int64_t w[MOT_BEZIER_MAX_KEYS];

	bezier_reduce(c, false, u, 2, w);
	*f = w[0] + mul62(w[1] - w[0], u);
	*df = (int64_t)(c->nkeys - 1) * (w[1] - w[0]);
}

static int64_t bezier_value(const struct mot_curve *c, int64_t u, uint32_t *sat)
{
	int64_t w[MOT_BEZIER_MAX_KEYS];

	bezier_reduce(c, true, u, 1, w);
	return value_of(c->keys[0].value, w[0], c->seg[0].vsh, sat);
}

/* ---- the solve ------------------------------------------------------------------ */

struct solve {
	const struct mot_curve *c;
	const struct mot_curve_seg *s;
	int64_t d;        /* target: frame - fref, scaled by 2^fsh */
	int it;           /* iterations taken (mot_curve_newton_iterations) */
	const int64_t *pw; /* bezier in power form: the coefficients, else NULL */
};

/*
 * Solve frame(u) = f on one piece: safeguarded Newton (rtsafe, Numerical
 * Recipes 9.4). The bracket [lo, hi] starts as [0, 1] and shrinks to the
 * evaluated points on either side of the root; a Newton step that leaves it,
 * or that does not halve the step before last, is replaced by bisection. An
 * end of [0, 1] that has not been evaluated may be stepped to, so a root
 * that rounding put just outside the piece ends there after one step instead
 * of after fifty bisections. frame'(u) is zero at the tripled end keys, which
 * is why the safeguard matters, and why those pieces start from a cube root.
 *
 * Determinism: the start is a function of f alone (the chord fraction, or its
 * cube root), the iteration is pure integer arithmetic and the stopping rule
 * is fixed: stop after a Newton step below 2^-ntol, the piece's (the error
 * is then about the square of it: curve_approx.c bounds it for what the
 * frame needs; 2^-31 where it cannot, and on a Bezier curve), or once the
 * bracket is narrower than 2^-50, or after NEWTON_MAX_IT iterations. Random
 * and sequential access therefore give the same u, bit for bit, on every
 * target.
 */
static int64_t solve_u(struct solve *sv, int64_t u)
{
	const struct mot_curve_seg *s = sv->s;
	bool bezier = sv->c->kind == MOT_INTERP_BEZIER;
	bool lo_known = false, hi_known = false;
	int64_t lo = 0, hi = ONE62, dx = ONE62, dxold = ONE62;

	for (sv->it = 1; sv->it <= NEWTON_MAX_IT; sv->it++) {
		int64_t f, df, du = 0, un = 0, tol;
		bool newton;

		if (sv->pw) {
			power_frame(sv->pw, sv->c->nkeys - 1, u, &f, &df);
		} else if (bezier) {
			bezier_frame(sv->c, u, &f, &df);
		} else {
			f = poly_eval(s->fc, u);
			df = poly_deriv(s->fc, u);
		}
		f -= sv->d;
		if (f == 0)
			return u;
		if (f < 0) {
			lo = u;
			lo_known = true;
		} else {
			hi = u;
			hi_known = true;
		}
		if (lo >= hi) /* the root lies beyond an end of the piece */
			return u;
		newton = df > 0 && ratio62(f, df, &du);
		if (newton) {
			/* rtsafe's progress test: |du| at most half the step before last */
			if (du > dxold / 2 || du < -(dxold / 2))
				newton = false;
			un = u - du;
			if (un <= lo) {
				newton = newton && !lo_known;
				un = lo;
			} else if (un >= hi) {
				newton = newton && !hi_known;
				un = hi;
			}
		}
		dxold = dx;
		if (newton) {
			dx = u - un;
			if (dx < 0)
				dx = -dx;
			tol = (int64_t)1 << (62 - s->ntol);
		} else {
			dx = (hi - lo) / 2;
			un = lo + dx;
			tol = BISECT_TOL;
		}
		if (dx <= tol)
			return un;
		u = un;
	}
	sv->it = NEWTON_MAX_IT;
	return u;
}

/* The piece of f (a Bezier curve has one), the start of the solve by the
 * piece's rule, the solve, and the value at its root. */
mot_q32 mot_cv_approx_eval(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 f,
			   int *iters, uint32_t *sat)
{
	const struct mot_curve_seg *s;
	struct solve sv;
	int64_t u, pw[2 * (MOT_BEZIER_MAX_KEYS - 1)];
	uint32_t m = c->nkeys - 1, j;

	sv.c = c;
	sv.pw = NULL;
	if (c->kind == MOT_INTERP_BEZIER) {
		s = &c->seg[0];
		if (c->power) {
			/* contiguous for the iterations */
			for (j = 0; j < 2 * m; j++)
				pw[j] = *power_slot(c, j);
			sv.pw = pw;
		}
	} else {
		s = &c->seg[locate_seg(c, cur, f)];
	}
	sv.s = s;
	sv.d = round_shift(f - s->fref, -s->fsh, NULL);
	u = frac62(f - s->f0, &s->inv_w);
	if (s->start == START_CUBE0)
		u = cbrt62(u);
	else if (s->start == START_CUBE1)
		u = ONE62 - cbrt62(ONE62 - u);
	u = solve_u(&sv, u);
	*iters = sv.it;
	if (sv.pw)
		return value_of(s->vref, power_value(pw + m, m, u), s->vsh, sat);
	if (c->kind == MOT_INTERP_BEZIER)
		return bezier_value(c, u, sat);
	return value_of(s->vref, poly_eval(s->c, u), s->vsh, sat);
}
