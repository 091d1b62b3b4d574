/* SPDX-License-Identifier: MIT */
/*
 * dbl_curve.c - scalar curves in double, doing what motion/curve*.c do
 * (see dbl_curve.h). Where the core needs integer machinery that double
 * does not (block floating point scales, 128-bit sums, the Newton
 * reciprocal), the twin does the plain double operation instead; the
 * algorithm, the preparation and the amount of work per evaluation are the
 * core's. Comments say where the core's reasons live rather than repeat
 * them.
 */
#include "dbl_curve.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Newton start rules and limits: curve_solve.c's */
enum { START_CHORD, START_CUBE0, START_CUBE1, START_INV, START_TAB };
#define NEWTON_MAX_IT 64
#define NEWTON_TOL (1.0 / 2147483648.0)     /* 2^-31 */
#define BISECT_TOL (1.0 / 1125899906842624.0) /* 2^-50 */

bool dbl_quantize(double v, double *out)
{
	mot_q32 x;

	if (!sd_to_q32(v, &x))
		return false;
	*out = (double)x / 4294967296.0;
	return true;
}

/* ---- ease (ease.c) ------------------------------------------------------------ */

void dbl_ease_init(struct dbl_ease *e, double a, double b)
{
	e->a = a;
	e->b = b;
	e->v = 1 / (1 - a / 2 - b / 2);
	e->ka = a > 0 ? e->v / (2 * a) : 0;
	e->kb = b > 0 ? e->v / (2 * b) : 0;
}

/* ---- evaluation helpers --------------------------------------------------------- */

static inline double poly_eval(const double c[4], double u)
{
	return ((c[3] * u + c[2]) * u + c[1]) * u + c[0];
}

static inline double poly_deriv(const double c[4], double u)
{
	return (3 * c[3] * u + 2 * c[2]) * u + c[1];
}

/* x / d for the prepared 1 / d, clamped to [0, 1] (frac62) */
static inline double frac(double x, double inv)
{
	double s = x * inv;

	return s < 0 ? 0 : s > 1 ? 1 : s;
}

static inline double start_of(const struct dbl_curve *c, bool keys, uint32_t j)
{
	return keys ? c->frame[j] : c->seg[j].f0;
}

static inline double end_of(const struct dbl_curve *c, bool keys, uint32_t j)
{
	return keys ? c->frame[j + 1] : c->seg[j].f1;
}

/* curve_locate.c's mot_cv_locate(): the hint, its successor, else a binary search */
static uint32_t locate(const struct dbl_curve *c, bool keys, uint32_t n, uint32_t hint, double f)
{
	uint32_t lo = 0, hi = n;

	if (hint < n && start_of(c, keys, hint) <= f) {
		if (hint + 1 == n || f < end_of(c, keys, hint))
			return hint;
		if (hint + 2 == n || f < end_of(c, keys, hint + 1))
			return hint + 1;
		lo = hint + 2;
	}
	while (hi - lo > 1) {
		uint32_t mid = lo + (hi - lo) / 2;

		if (start_of(c, keys, mid) <= f)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}

static uint32_t locate_seg(const struct dbl_curve *c, struct dbl_cursor *cur, double f)
{
	uint32_t j = locate(c, false, c->nseg, cur ? cur->seg : 0, f);

	if (cur)
		cur->seg = j;
	return j;
}

static uint32_t locate_key(const struct dbl_curve *c, struct dbl_cursor *cur, double f)
{
	uint32_t i = locate(c, true, c->nkeys - 1, cur ? cur->key : 0, f);

	if (cur)
		cur->key = i;
	return i;
}

/* ---- the approximating kinds ------------------------------------------------------ */

/* de Casteljau on the keys relative to the first, until `left` points remain */
static void bezier_reduce(const struct dbl_curve *c, const double *k, double u, uint32_t left,
			  double w[MOT_BEZIER_MAX_KEYS])
{
	uint32_t n = c->nkeys, i, r;

	for (i = 0; i < n; i++)
		w[i] = k[i] - k[0];
	for (r = n - 1; r >= left; r--)
		for (i = 0; i < r; i++)
			w[i] += (w[i + 1] - w[i]) * u;
}

/* curve_solve.c's power form evaluation: a[k - 1] multiplies u^k */
static void power_frame(const double *a, uint32_t m, double u, double *f, double *df)
{
	double r = a[m - 1], d = m * a[m - 1];
	uint32_t k;

	for (k = m - 1; k >= 1; k--) {
		r = r * u + a[k - 1];
		d = d * u + k * a[k - 1];
	}
	*f = r * u;
	*df = d;
}

static double power_value(const double *a, uint32_t m, double u)
{
	double r = a[m - 1];
	uint32_t k;

	for (k = m - 1; k >= 1; k--)
		r = r * u + a[k - 1];
	return r * u;
}

/* frame(u) - fref and its derivative on piece s (inline in the solve, as the
 * core's evaluators are, bezier_start() calling it too) */
static inline __attribute__((always_inline)) void frame_at(const struct dbl_curve *c,
							   const struct dbl_seg *s, double u,
							   double *f, double *df)
{
	double w[MOT_BEZIER_MAX_KEYS];

	if (c->pw) {
		power_frame(c->pw, c->nkeys - 1, u, f, df);
		return;
	}
	if (c->kind != MOT_INTERP_BEZIER) {
		*f = poly_eval(s->fc, u);
		*df = poly_deriv(s->fc, u);
		return;
	}
	bezier_reduce(c, c->frame, u, 2, w);
	*f = w[0] + (w[1] - w[0]) * u;
	*df = (double)(c->nkeys - 1) * (w[1] - w[0]);
}

/* START_TAB (curve_approx.c's tab_start(), curve_solve.c's tab62()): u at
 * the chord fraction t of a part as half h's degree-7 polynomial in
 * x = 4 t - 2 h - 1, even and odd powers side by side, each by Estrin's
 * scheme in y = x^2, as the core's (poly7_62()) */
static inline double tab_eval(const float ut[16], double t)
{
	unsigned h = t >= 0.5; /* an index, not a branch: the half is unpredictable */
	const float *a = ut + 8 * h;
	double x = 4 * t - 1 - 2 * h, y, y2, e, o, u;

	y = x * x;
	y2 = y * y;
	e = (a[2] * y + a[0]) + y2 * (a[6] * y + a[4]);
	o = (a[3] * y + a[1]) + y2 * (a[7] * y + a[5]);
	u = o * x + e;
	return u < 0 ? 0 : u > 1 ? 1 : u;
}

/* the Chebyshev node i of 8 on [-1, 1] */
static double tab_node(unsigned i)
{
	return cos((2 * i + 1) * 3.14159265358979323846 / 16);
}

/* The polynomial through (x_i, y_i), x_i the nodes, in powers of x (Newton's
 * divided differences, then expanded); false where its coefficients'
 * magnitudes reach 2, where the core keeps its older start. */
static bool tab_fit(const double y[8], float a[8])
{
	double d[8], p[8] = { 0 }, sum = 0;
	int i, j;

	for (i = 0; i < 8; i++)
		d[i] = y[i];
	for (j = 1; j < 8; j++)
		for (i = 7; i >= j; i--)
			d[i] = (d[i] - d[i - 1]) / (tab_node(i) - tab_node(i - j));
	/* p = d0 + (x - x0)(d1 + (x - x1)(d2 + ...)) */
	p[0] = d[7];
	for (j = 6; j >= 0; j--) {
		for (i = 7; i >= 1; i--)
			p[i] = p[i - 1] - tab_node(j) * p[i];
		p[0] = d[j] - tab_node(j) * p[0];
	}
	for (i = 0; i < 8; i++) {
		a[i] = (float)p[i];
		sum += fabs(p[i]);
	}
	return sum < 2;
}

/* u in [0, 1] with frame offset F(u) = target, by bisection: F the piece's
 * cubic (s) or the Bezier curve's frame less its first key's (s NULL) */
static double tab_inverse(const struct dbl_curve *c, const struct dbl_seg *s, double target)
{
	double lo = 0, hi = 1, f, df;
	int i;

	for (i = 0; i < 60; i++) {
		double mid = (lo + hi) / 2;

		if (s)
			f = poly_eval(s->fc, mid);
		else
			frame_at(c, &c->seg[0], mid, &f, &df);
		if (f < target)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}

/* Fit ut[16] for a chord fraction t = t0 + tw (chord of the part) on the
 * frame offsets f0w + t w: both halves */
static bool tab_part(const struct dbl_curve *c, const struct dbl_seg *s, double fa, double w,
		     float ut[16])
{
	double y[8];
	unsigned h, i;

	for (h = 0; h < 2; h++) {
		for (i = 0; i < 8; i++)
			y[i] = tab_inverse(c, s, fa + w * (2 * h + 1 + tab_node(i)) / 4);
		if (!tab_fit(y, ut + 8 * h))
			return false;
	}
	return true;
}

/* curve_approx.c's tab_start() on a spline piece (a curve without eases) */
static void tab_start(const struct dbl_curve *c, struct dbl_seg *s)
{
	double w = s->fc[1] + s->fc[2] + s->fc[3];

	if (s->start != START_CHORD || c->seg_ease || !(w > 0))
		return;
	if (tab_part(c, s, s->fc[0], w, s->ut))
		s->start = START_TAB;
}

/* and on a Bezier curve in power form without eases: entry j's table on
 * part j of m of the chord fraction; false where a part does not fit */
static bool bezier_tab(struct dbl_curve *c)
{
	uint32_t m = c->nkeys - 1, j;
	double w, df;

	if (!c->pw || c->seg_ease)
		return false;
	frame_at(c, &c->seg[0], 1, &w, &df);
	if (!(w > 0))
		return false;
	for (j = 0; j < m; j++)
		if (!tab_part(c, NULL, w * j / m, w / m, c->seg[j].ut))
			return false;
	c->seg[0].start = START_TAB;
	return true;
}

/* curve_solve.c's bez_tab62() */
static inline double bezier_tab_eval(const struct dbl_curve *c, double t)
{
	uint32_t m = c->nkeys - 1, j = (uint32_t)(t * m);
	double x = t * m - j;

	if (j >= m) {
		j = m - 1;
		x = 1;
	}
	return tab_eval(c->seg[j].ut, x);
}

/* (START_INV, where bezier_tab() cannot: eased or de Casteljau curves)
 * curve_solve.c's mot_cv_bezier_start(): the same table, in the same slots (in doubles
 * too a Bezier curve's step costs more than the table: 69.5 -> 67.5 ns a joint) */
static void bezier_start(struct dbl_curve *c)
{
	uint32_t m = c->nkeys - 1, nt = 4 * m, i, j;
	double uk[4 * (MOT_BEZIER_MAX_KEYS - 1) + 1], q[4 * (MOT_BEZIER_MAX_KEYS - 1) + 1];
	double w, f, df, prev = 0, step;

	frame_at(c, &c->seg[0], 1, &w, &df);
	if (!(w > 0))
		return;
	step = w / nt;
	uk[0] = 0;
	uk[nt] = 1;
	for (i = 1; i < nt; i++) {
		double lo = prev, hi = 1;

		for (j = 0; j < 40; j++) {
			double mid = (lo + hi) / 2;

			frame_at(c, &c->seg[0], mid, &f, &df);
			if (f < step * i)
				lo = mid;
			else
				hi = mid;
		}
		uk[i] = prev = lo;
	}
	for (i = 0; i <= nt; i++) {
		frame_at(c, &c->seg[0], uk[i], &f, &df);
		if (!(df > 0))
			return;
		q[i] = step / df;
		if (q[i] > 3 || (i > 0 && q[i] > 3 * (uk[i] - uk[i - 1])) ||
		    (i < nt && q[i] > 3 * (uk[i + 1] - uk[i])))
			return;
	}
	for (i = 1; i < nt; i++)
		c->seg[(i - 1) / 4].us[(i - 1) % 4] = (uint16_t)lround(uk[i] * 32768);
	for (i = 0; i <= nt; i++) {
		uint16_t *p = i == nt ? &c->seg[(nt - 1) / 4].us[3] : &c->seg[i / 4].us[4 + i % 4];

		*p = (uint16_t)lround(q[i] * 16384);
	}
	c->seg[0].start = START_INV;
}

/* curve_solve.c's bez_inv62() */
static double bezier_inv(const struct dbl_curve *c, double t)
{
	const struct dbl_seg *sg = c->seg;
	uint32_t nt = 4 * (c->nkeys - 1), j = t >= 1 ? nt - 1 : (uint32_t)(t * nt);
	double x = t * nt - j, u0 = j ? sg[(j - 1) / 4].us[(j - 1) % 4] / 32768.0 : 0;
	double u1 = j + 1 < nt ? sg[j / 4].us[j % 4] / 32768.0 : 1;
	double m0 = sg[j / 4].us[4 + j % 4] / 16384.0, du = u1 - u0, u;
	double m1 = (j + 1 < nt ? sg[(j + 1) / 4].us[4 + (j + 1) % 4] : sg[(nt - 1) / 4].us[3]) /
		    16384.0;

	u = u0 + x * (m0 + x * (3 * du - 2 * m0 - m1 + x * (m0 + m1 - 2 * du)));
	return u < 0 ? 0 : u > 1 ? 1 : u;
}

/* frame(u) = fref + d on piece s: curve_solve.c's Newton solve (rtsafe), the same
 * bracket, safeguards and stopping rule, with a plain division for the step */
static double solve_u(const struct dbl_curve *c, const struct dbl_seg *s, double d, double u,
		      int *it)
{
	bool lo_known = false, hi_known = false;
	double lo = 0, hi = 1, dx = 1, dxold = 1;

	for (*it = 1; *it <= NEWTON_MAX_IT; ++*it) {
		double f, df, du = 0, un = 0, tol;
		bool newton;

		frame_at(c, s, u, &f, &df);
		f -= d;
		if (f == 0)
			return u;
		if (f < 0) {
			lo = u;
			lo_known = true;
		} else {
			hi = u;
			hi_known = true;
		}
		if (lo >= hi)
			return u;
		newton = df > 0;
		if (newton) {
			du = f / df;
			if (fabs(du) > dxold / 2)
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
			dx = fabs(u - un);
			tol = s->tol;
		} else {
			dx = (hi - lo) / 2;
			un = lo + dx;
			tol = BISECT_TOL;
		}
		if (dx <= tol)
			return un;
		u = un;
	}
	*it = NEWTON_MAX_IT;
	return u;
}

static double approx_eval(const struct dbl_curve *c, struct dbl_cursor *cur, double f, int *it)
{
	const struct dbl_seg *s;
	double u, w[MOT_BEZIER_MAX_KEYS];

	s = c->kind == MOT_INTERP_BEZIER ? &c->seg[0] : &c->seg[locate_seg(c, cur, f)];
	u = frac(f - s->f0, s->inv_w);
	if (s->start == START_TAB)
		u = c->kind == MOT_INTERP_BEZIER ? bezier_tab_eval(c, u) : tab_eval(s->ut, u);
	else if (s->start == START_INV)
		u = bezier_inv(c, u);
	else if (s->start == START_CUBE0)
		u = cbrt(u);
	else if (s->start == START_CUBE1)
		u = 1 - cbrt(1 - u);
	u = solve_u(c, s, f - s->fref, u, it);
	if (c->pw)
		return s->vref + power_value(c->pw + c->nkeys - 1, c->nkeys - 1, u);
	if (c->kind != MOT_INTERP_BEZIER)
		return s->vref + poly_eval(s->c, u);
	bezier_reduce(c, c->value, u, 1, w);
	return s->vref + w[0];
}

/* ---- evaluation (curve.c's eval()) ----------------------------------------------- */

static inline __attribute__((always_inline)) double eval(const struct dbl_curve *c,
							   struct dbl_cursor *cur, double f, int *it)
{
	const struct dbl_seg *s;
	uint32_t n = c->nkeys;
	double u;

	if (f <= c->span_f0)
		return c->value[0];
	if (f >= c->span_f1)
		return c->value[n - 1];
	if (c->span_ease) {
		f = dbl_span_warp(c, f);
		if (f <= c->span_f0)
			return c->value[0];
		if (f >= c->span_f1)
			return c->value[n - 1];
	}
	if (c->kind >= MOT_INTERP_BSPLINE) {
		if (c->seg_ease) {
			uint32_t i = locate_key(c, cur, f);

			s = &c->seg[i];
			if (!dbl_ease_is_identity(&s->ease)) {
				u = dbl_ease_apply(&s->ease, frac(f - c->frame[i], s->inv_h));
				f = c->frame[i] + u * (c->frame[i + 1] - c->frame[i]);
				if (f <= c->span_f0)
					return c->value[0];
				if (f >= c->span_f1)
					return c->value[n - 1];
			}
		}
		return approx_eval(c, cur, f, it);
	}
	s = &c->seg[locate_seg(c, cur, f)];
	if (c->kind == MOT_INTERP_STEP)
		return s->vref;
	if (c->seg_ease && !dbl_ease_is_identity(&s->ease)) {
		u = dbl_eased_u(s, f - s->f0);
		u = u < 0 ? 0 : u > 1 ? 1 : u;
	} else {
		u = frac(f - s->f0, s->inv_w);
	}
	if (c->kind == MOT_INTERP_LINEAR)
		return s->vref + s->c[1] * u;
	return s->vref + poly_eval(s->c, u);
}

/* dbl_eased_u() off the plateau, out of line as the core's profile is */
double dbl_eased_off(const struct dbl_seg *s, double x)
{
	double u = x * s->inv_w;

	return dbl_ease_apply(&s->ease, u < 0 ? 0 : u > 1 ? 1 : u);
}

double dbl_curve_eval(const struct dbl_curve *c, struct dbl_cursor *cur, double f)
{
	int it;

	return eval(c, cur, f, &it);
}

int dbl_curve_newton_iterations(const struct dbl_curve *c, double f)
{
	int it = 0;

	eval(c, NULL, f, &it);
	return it;
}

void dbl_piece_learn(struct dbl_piece *p, const struct dbl_curve *c, struct dbl_cursor *cur,
		     double f)
{
	const struct dbl_seg *s;
	double *lo = &p->lo, *hi = &p->hi;

	p->lo = p->glo = 1;
	p->hi = p->ghi = 0;
	p->seg = NULL;
	p->warp = NULL;
	p->whole = false;
	if (c->kind > MOT_INTERP_HERMITE || c->nkeys < 2) {
		p->lo = -INFINITY;
		p->hi = INFINITY;
		p->whole = true;
		return;
	}
	if (f > c->span_f0 && f < c->span_f1 && c->span_ease) {
		p->warp = c;
		p->lo = nextafter(c->span_f0, INFINITY);
		p->hi = c->span_f1;
		f = dbl_span_warp(c, f);
		lo = &p->glo;
		hi = &p->ghi;
	}
	if (f <= c->span_f0) {
		*lo = -INFINITY;
		*hi = nextafter(c->span_f0, INFINITY);
		p->held = c->value[0];
		return;
	}
	if (f >= c->span_f1) {
		*lo = c->span_f1;
		*hi = INFINITY;
		p->held = c->value[c->nkeys - 1];
		return;
	}
	s = &c->seg[locate_seg(c, cur, f)];
	*lo = s->f0 > c->span_f0 ? s->f0 : nextafter(c->span_f0, INFINITY);
	*hi = s->f1;
	if (c->kind == MOT_INTERP_STEP) {
		p->held = s->vref;
		return;
	}
	p->seg = s;
	p->linear = c->kind == MOT_INTERP_LINEAR;
	p->eased = c->seg_ease && !dbl_ease_is_identity(&s->ease);
}

/* Integral over [f0, f0 + e] of interpolating piece i at parameter s */
static double seg_integral(const struct dbl_curve *c, uint32_t i, double e, double s)
{
	const struct dbl_seg *sg = &c->seg[i];
	double a = e * sg->vref;

	if (c->kind == MOT_INTERP_LINEAR)
		return a + sg->c[1] * e * e * sg->inv_w / 2;
	if (c->kind == MOT_INTERP_HERMITE)
		return a + e * poly_eval(sg->fc, s);
	return a;
}

double dbl_curve_integral(const struct dbl_curve *c, struct dbl_cursor *cur, double f)
{
	uint32_t n = c->nkeys, i;
	const struct dbl_seg *s;

	if (f < c->frame[0])
		return c->area_first + c->value[0] * (f - c->frame[0]);
	if (f >= c->frame[n - 1])
		return c->area_last + c->value[n - 1] * (f - c->frame[n - 1]);
	i = locate_seg(c, cur, f);
	s = &c->seg[i];
	return s->area + seg_integral(c, i, f - s->f0, frac(f - s->f0, s->inv_w));
}

/* ---- preparation ---------------------------------------------------------------- */

/* curve_bezier.c's power form: the power form's coefficients, exact in raw
 * Q32.32 units, and the same rule for taking it (sum k |a_k| and sum |a_k|
 * below 2^53; no |a_k| of 2^54 or more) */
static void prep_power(struct dbl_curve *c)
{
	uint32_t n = c->nkeys, m = n - 1, i, j, side;
	double a[2][MOT_BEZIER_MAX_KEYS - 1];

	for (side = 0; side < 2; side++) {
		const double *x = side ? c->value : c->frame;
		__int128 d[MOT_BEZIER_MAX_KEYS];
		uint64_t b = 1;
		unsigned __int128 sum = 0;

		for (i = 0; i < n; i++)
			d[i] = (__int128)((x[i] - x[0]) * 4294967296.0); /* exact: quantised */
		for (j = 1; j <= m; j++) {
			__int128 aj;

			for (i = 0; i + j < n; i++)
				d[i] = d[i + 1] - d[i];
			b = b * (m - j + 1) / j;
			aj = d[0] * (__int128)b;
			if (aj >= (__int128)1 << 54 || aj <= -((__int128)1 << 54))
				return;
			sum += (side ? 1 : j) * (unsigned __int128)(aj < 0 ? -aj : aj);
			a[side][j - 1] = (double)aj / 4294967296.0;
		}
		if (sum >= (unsigned __int128)1 << 53)
			return;
	}
	c->pw = (double *)(c->seg + c->nseg); /* dbl_curve_size() counts them */
	for (side = 0; side < 2; side++)
		for (j = 0; j < m; j++)
			c->pw[side * m + j] = a[side][j];
}

/* curve_approx.c's basis: weights of E(j)..E(j+3) on u^p over den */
static void basis(const struct dbl_curve *c, double b1, double b2, double nb[4][4], double *den)
{
	static const double bsp[4][4] = {
		{ 1, -3, 3, -1 }, { 4, 0, -6, 3 }, { 1, 3, 3, -3 }, { 0, 0, 0, 1 },
	};
	double t3 = 2 * b1 * b1 * b1, t2 = 2 * b1 * b1, t1 = 2 * b1;
	int p;

	if (c->kind == MOT_INTERP_BSPLINE) {
		memcpy(nb, bsp, sizeof(bsp));
		*den = 6;
		return;
	}
	*den = t3 + 2 * t2 + 2 * t1 + b2 + 2;
	nb[1][0] = 2 * t2 + 2 * t1 + b2;
	nb[1][1] = 3 * (t3 - t1);
	nb[1][2] = -3 * (t3 + t2 + b2);
	nb[1][3] = t3 + t2 + t1 + 2 * b2;
	for (p = 0; p < 4; p++) {
		nb[0][p] = t3 * bsp[0][p];
		nb[3][p] = p == 3 ? 2 : 0;
		nb[2][p] = (p == 0 ? *den : 0) - nb[0][p] - nb[1][p] - nb[3][p];
	}
}

/* bit length of a magnitude given in frames, as the core's bitlen64() of the
 * same number in raw units (2^-32 frames): floor(log2(x 2^32)) + 1, 0 for 0 */
static int raw_bitlen(double x)
{
	int e;

	if (!(x > 0))
		return 0;
	frexp(x, &e); /* x = f 2^e, f in [0.5, 1) */
	return e + 32;
}

/* curve_approx.c's newton_bits(), in frames: the frame's residual after the
 * last step h, |F(u') - d| <= (2^-29 Dmax + 4) |h| + M h^2 with M =
 * max(|fc2|, |fc2 + 3 fc3|) and the core's quotient error 2^-29 (doubles
 * have none, but the twin stops where the core does), each term within 2^-5
 * of a raw unit (2^-37 frames); the 4 units of the core's own rounding are
 * at its scale, which the twin does not have: left out. 2^-16 at most,
 * 2^-31 at least, for every piece (the cube-root ones too) */
static double newton_tol(const double fc[4])
{
	double m2 = fmax(fabs(fc[2]), fabs(fc[2] + 3 * fc[3]));
	double dmax = fabs(fc[1]) + 2 * fabs(fc[2]) + 3 * fabs(fc[3]);
	int k = (raw_bitlen(m2) + 6) / 2, kr = raw_bitlen(dmax) - 29 + 6;

	k = k > kr ? k : kr;
	k = k < 16 ? 16 : k > 31 ? 31 : k;
	return ldexp(1, -k);
}

/* curve_bezier.c's bezier_ntol(): from the keys' first and second frame
 * differences (Bernstein bounds of F' and F''), the same integers from the
 * same raw frames, the core's scale of the frame (bezier_shift()) included */
static double bezier_tol(const struct dbl_curve *c)
{
	uint32_t m = c->nkeys - 1, i;
	uint64_t dmin = UINT64_MAX, dmax = 0, d2 = 0;
	int64_t raw[MOT_BEZIER_MAX_KEYS];
	int b, br, fsh;

	if (m == 0)
		return NEWTON_TOL;
	for (i = 0; i <= m; i++)
		raw[i] = (int64_t)llround(c->frame[i] * 4294967296.0);
	for (i = 0; i < m; i++) {
		uint64_t dx = (uint64_t)(raw[i + 1] - raw[i]);

		dmin = dx < dmin ? dx : dmin;
		dmax = dx > dmax ? dx : dmax;
		if (i + 1 < m) {
			int64_t e = (raw[i + 2] - raw[i + 1]) - (int64_t)dx;
			uint64_t ae = e < 0 ? 0 - (uint64_t)e : (uint64_t)e;

			d2 = ae > d2 ? ae : d2;
		}
	}
	fsh = 58 - (64 - __builtin_clzll((uint64_t)(raw[m] - raw[0])));
	if ((64 - __builtin_clzll(dmin)) + fsh < 48)
		return NEWTON_TOL;
	b = d2 ? ((64 - __builtin_clzll((uint64_t)m * (m - 1))) + (64 - __builtin_clzll(d2)) + 5) /
			 2 :
		 0;
	br = (64 - __builtin_clzll(m)) + (64 - __builtin_clzll(dmax)) - 24;
	b = b > br ? b : br;
	b = b < 16 ? 16 : b > 31 ? 31 : b;
	return ldexp(1, -b);
}

static void prep_spline(struct dbl_curve *c, uint32_t j, double nb[4][4], double den)
{
	struct dbl_seg *s = &c->seg[j];
	int64_t n1 = (int64_t)c->nkeys - 1;
	double df[4], dv[4], nf[4], big = 0;
	int m, p;

	for (m = 0; m < 4; m++) {
		int64_t e = (int64_t)j + m - 2;

		e = e < 0 ? 0 : e > n1 ? n1 : e;
		if (m == 1) {
			s->fref = c->frame[e];
			s->vref = c->value[e];
		}
		df[m] = c->frame[e];
		dv[m] = c->value[e];
	}
	for (m = 0; m < 4; m++) {
		df[m] -= s->fref;
		dv[m] -= s->vref;
	}
	for (p = 0; p < 4; p++) {
		double v = 0;

		nf[p] = 0;
		for (m = 0; m < 4; m++) {
			nf[p] += nb[m][p] * df[m];
			v += nb[m][p] * dv[m];
		}
		s->fc[p] = nf[p] / den;
		s->c[p] = v / den;
		big += fabs(nf[p]);
	}
	s->f0 = s->fref + s->fc[0];
	/* the start rules, on the numerators as curve_solve.c tests them (up to the
	 * rounding of double, which the core's exact sums do not have) */
	s->start = START_CHORD;
	if (fabs(nf[1]) + fabs(nf[2]) <= 1e-12 * big)
		s->start = START_CUBE0;
	else if (fabs(nf[1] - 3 * nf[3]) + fabs(nf[2] + 3 * nf[3]) <= 1e-12 * big)
		s->start = START_CUBE1;
	s->tol = newton_tol(s->fc);
}

/* Hermite piece j: Catmull-Rom tangents times h (one-sided at the ends),
 * then the cubic in s and its mean-value coefficients, as curve_approx.c does */
static void prep_hermite(struct dbl_curve *c, uint32_t j, double h, double dv)
{
	struct dbl_seg *s = &c->seg[j];
	uint32_t n = c->nkeys, t, p;
	double tm[2];

	for (t = 0; t < 2; t++) {
		uint32_t i = j + t, a = i == 0 ? 0 : i - 1, b = i == n - 1 ? i : i + 1;

		tm[t] = h * (c->value[b] - c->value[a]) / (c->frame[b] - c->frame[a]);
	}
	s->c[1] = tm[0];
	s->c[2] = 3 * dv - 2 * tm[0] - tm[1];
	s->c[3] = -2 * dv + tm[0] + tm[1];
	for (p = 1; p < 4; p++)
		s->fc[p] = s->c[p] / (p + 1);
}

static void prep_pieces(struct dbl_curve *c, double b1, double b2)
{
	uint32_t n = c->nkeys, j;
	const char *tab = getenv("DBL_SPLINE_TAB");
	bool spline_tab = tab && *tab == '1';

	if (n == 1)
		return;
	if (c->kind == MOT_INTERP_BEZIER) {
		struct dbl_seg *s = &c->seg[0];

		s->fref = s->f0 = c->frame[0];
		s->vref = c->value[0];
		s->f1 = c->frame[n - 1];
		s->inv_w = 1 / (s->f1 - s->f0);
		s->start = START_CHORD;
		s->tol = bezier_tol(c);
		prep_power(c);
		if (!bezier_tab(c))
			bezier_start(c);
		return;
	}
	if (c->kind >= MOT_INTERP_BSPLINE) {
		double nb[4][4], den;

		basis(c, b1, b2, nb, &den);
		for (j = 0; j < c->nseg; j++)
			prep_spline(c, j, nb, den);
		for (j = 0; j < c->nseg; j++) {
			struct dbl_seg *s = &c->seg[j];

			s->f1 = j + 1 < c->nseg ? c->seg[j + 1].f0 : c->frame[n - 1];
			/* the chord start, where the core takes START_TAB (or its
			 * Hermite quarters, START_INV, on an eased curve): in
			 * doubles either table costs more time than the Newton
			 * steps it saves. The quarters: B-spline keys 62 -> 69 ns
			 * a joint, Beta 65 -> 69; START_TAB (tab_start(), kept for
			 * the comparison: DBL_SPLINE_TAB=1 in the environment),
			 * 21 interleaved runs: B-spline 74.2 -> 80.0 ns, Beta
			 * 73.3 -> 80.7, with fewer instructions (573 -> 530, 581
			 * -> 531). The twin takes whichever is faster */
			s->inv_w = s->f1 > s->f0 ? 1 / (s->f1 - s->f0) : 0;
			if (s->f1 > s->f0 && spline_tab)
				tab_start(c, s);
		}
		return;
	}
	for (j = 0; j + 1 < n; j++) {
		struct dbl_seg *s = &c->seg[j];
		double h = c->frame[j + 1] - c->frame[j], dv = c->value[j + 1] - c->value[j];

		s->f0 = s->fref = c->frame[j];
		s->f1 = c->frame[j + 1];
		s->vref = c->value[j];
		s->inv_w = 1 / h;
		if (c->kind == MOT_INTERP_LINEAR)
			s->c[1] = dv;
		if (c->kind == MOT_INTERP_HERMITE)
			prep_hermite(c, j, h, dv);
	}
}

static void prep_area(struct dbl_curve *c)
{
	uint32_t n = c->nkeys, j;
	double a = 0, zero;

	c->area_first = 0;
	for (j = 0; j + 1 < n; j++) {
		c->seg[j].area = a;
		a += seg_integral(c, j, c->frame[j + 1] - c->frame[j], 1);
	}
	c->area_last = a;
	zero = dbl_curve_integral(c, NULL, 0);
	c->area_first -= zero;
	c->area_last -= zero;
	for (j = 0; j + 1 < n; j++)
		c->seg[j].area -= zero;
}

size_t dbl_curve_size(const struct sd_curve *sd)
{
	uint32_t nseg = mot_curve_seg_count(sd->interp, sd->nkeys);

	uint32_t npw = sd->interp == MOT_INTERP_BEZIER && sd->nkeys > 1 ? 2 * (sd->nkeys - 1) : 0;

	return (2 * sd->nkeys + npw) * sizeof(double) + nseg * sizeof(struct dbl_seg);
}

int dbl_curve_init(struct dbl_curve *c, const struct sd_curve *sd, double scale, bool integral,
		   void *mem)
{
	uint32_t n = sd->nkeys, i;
	double b1, b2, e_in, e_out;

	memset(c, 0, sizeof(*c));
	if (n == 0 || (sd->interp == MOT_INTERP_BEZIER && n > MOT_BEZIER_MAX_KEYS))
		return -1;
	c->kind = sd->interp;
	c->nkeys = n;
	c->nseg = mot_curve_seg_count(sd->interp, n);
	c->frame = mem;
	c->value = c->frame + n;
	c->seg = (struct dbl_seg *)(c->value + n);
	memset(c->seg, 0, c->nseg * sizeof(*c->seg));
	c->pw = NULL;
	for (i = 0; i < n; i++)
		if (!dbl_quantize(sd->keys[i].frame, &c->frame[i]) ||
		    !dbl_quantize(sd->keys[i].value * scale, &c->value[i]))
			return -1;
	if (!dbl_quantize(sd->beta1, &b1) || !dbl_quantize(sd->beta2, &b2) ||
	    !dbl_quantize(sd->ease_in, &e_in) || !dbl_quantize(sd->ease_out, &e_out))
		return -1;
	for (i = 0; i < c->nseg; i++) {
		struct dbl_seg *s = &c->seg[i];
		double a = 0, b = 0;

		if (i + 1 < n && (!dbl_quantize(sd->keys[i].ease_out, &a) ||
				  !dbl_quantize(sd->keys[i + 1].ease_in, &b)))
			return -1;
		dbl_ease_init(&s->ease, a, b);
		s->inv_h = i + 1 < n ? 1 / (c->frame[i + 1] - c->frame[i]) : 0;
		c->seg_ease = c->seg_ease || !dbl_ease_is_identity(&s->ease);
	}
	c->span_f0 = c->frame[0];
	c->span_f1 = c->frame[n - 1];
	c->span_ease = e_in != 0 || e_out != 0;
	if (c->span_ease) {
		double span = c->span_f1 - c->span_f0;
		struct dbl_ease_span *e = &c->span;

		e->a = e_out;
		e->d = span - e_in;
		e->w = span;
		e->v = 2 * span / (2 * span - e_out - e_in);
		e->c = e->v * e_out / 2;
		e->ka = e_out > 0 ? e->v / (2 * e_out) : 0;
		e->kb = e_in > 0 ? e->v / (2 * e_in) : 0;
	}
	prep_pieces(c, b1, b2);
	for (i = 0; c->seg_ease && (c->kind == MOT_INTERP_LINEAR || c->kind == MOT_INTERP_HERMITE) &&
		    i + 1 < n; i++) {
		struct dbl_seg *s = &c->seg[i];
		const struct dbl_ease *e = &s->ease;
		double h = s->f1 - s->f0;

		s->ef.xa = e->a * h;
		s->ef.xd = (1 - e->b) * h;
		s->ef.vw = e->v * s->inv_w;
		s->ef.c = e->v * e->a / 2;
	}
	c->integral = integral;
	if (integral)
		prep_area(c);
	return 0;
}
