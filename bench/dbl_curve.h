/* SPDX-License-Identifier: MIT */
/*
 * dbl_curve.h - the double-precision twin of motion/curve.h and ease.h for
 * the benchmarks: the same preparation (per-segment cubic coefficients in
 * power form relative to a reference key, reciprocals of widths, ease
 * factors, running integrals) and the same evaluation (cursor lookup, the
 * safeguarded Newton solve of the approximating kinds from the same start,
 * Bezier in power form where curve_bezier.c uses it and by de Casteljau's
 * algorithm elsewhere), in double and libm. Keys come from a scene
 * description, quantised to Q32.32 first exactly as scene_build() does, so
 * that the twin, the core and tests/ref_curve.c all see the same inputs.
 */
#ifndef DBL_CURVE_H
#define DBL_CURVE_H

#include <stdbool.h>
#include <stdint.h>

#include "motion/curve.h"
#include "scene/scene_desc.h"

/* The trapezoidal slow-in/slow-out of ease.h, prepared. */
struct dbl_ease {
	double a, b, v; /* fractions and peak speed 1 / (1 - a/2 - b/2) */
	double ka, kb;  /* v / (2a), v / (2b); 0 when a (b) is 0 */
};

/* The same over a span in frames, as ease.h's struct mot_ease_span: g(x)
 * for an offset x into the span, three polynomials in x. */
struct dbl_ease_span {
	double a, d, w;   /* A, W - B, W */
	double v, c;      /* peak speed 2W / (2W - A - B), and v A / 2 */
	double ka, kb;    /* v / (2A), v / (2B); 0 when A (B) is 0 */
};

/* Entry j: piece j of the curve and key interval j, as struct mot_curve_seg. */
struct dbl_seg {
	double f0, f1, vref, fref;
	double c[4];  /* value(u) = vref + c(u) */
	double fc[4]; /* bspline/beta: frame(u) = fref + fc(u); hermite: c[p] / (p + 1) */
	double inv_w; /* 1 / (f1 - f0) */
	double inv_h; /* 1 / width of key interval j */
	int start;    /* Newton start rule */
	double tol;   /* a Newton step below it is the last (curve_approx.c's ntol) */
	struct dbl_ease ease;
	union {
		double area;  /* integral from frame 0 to key j */
		uint16_t us[8]; /* bezier's START_INV: curve_solve.c's table */
		float ut[16];   /* START_TAB: curve_approx.c's degree-7 inverse on
				 * each half, coefficients in x, x^0 first (float
				 * holds them to 2^-24, the start needs 2^-20) */
		struct {
			double xa, xd, vw, c; /* an eased linear or hermite piece: the
					       * plateau a w <= x <= (1 - b) w, there
					       * u = x v / w - v a / 2 (ease.h's
					       * struct mot_ease_fused) */
		} ef;
	};
};

struct dbl_curve {
	enum mot_interp kind;
	uint32_t nkeys, nseg;
	bool seg_ease, span_ease, integral;
	double *frame, *value; /* the keys */
	struct dbl_seg *seg;
	double *pw;            /* bezier in power form (curve_bezier.c's rule), else NULL:
				* the frame's a_1 .. a_m, then the value's */
	double span_f0, span_f1;
	struct dbl_ease_span span;
	double area_first, area_last;
};

struct dbl_cursor {
	uint32_t seg, key;
};

/* Bytes dbl_curve_init() takes from its block for this description. */
size_t dbl_curve_size(const struct sd_curve *sd);

/* Prepare from a description whose values are scaled by `scale` (1/360 for
 * degrees to turns). mem: dbl_curve_size() bytes, 8-aligned, owned by the
 * caller. -1 when the description does not fit Q32.32 or the curve needs
 * more than the core allows (the core would refuse it too). */
int dbl_curve_init(struct dbl_curve *c, const struct sd_curve *sd, double scale, bool integral,
		   void *mem);

double dbl_curve_eval(const struct dbl_curve *c, struct dbl_cursor *cur, double f);
/* The Newton iterations dbl_curve_eval() takes at f (0 where it solves
 * nothing), as mot_curve_newton_iterations(): the two must be close for the
 * twin to do the core's work. */
int dbl_curve_newton_iterations(const struct dbl_curve *c, double f);
/* Integral from frame 0 to f, value x frames (step, linear, hermite). */
double dbl_curve_integral(const struct dbl_curve *c, struct dbl_cursor *cur, double f);

void dbl_ease_init(struct dbl_ease *e, double a, double b);

static inline double dbl_ease_apply(const struct dbl_ease *e, double s)
{
	double r, t;

	if (s <= 0)
		return 0;
	if (s >= 1)
		return 1;
	if (s < e->a)
		return s * e->ka * s;
	r = 1 - s;
	if (r < e->b)
		return 1 - r * e->kb * r;
	t = e->v * (2 * s - e->a) / 2;
	return t < 0 ? 0 : t > 1 ? 1 : t;
}

static inline bool dbl_ease_is_identity(const struct dbl_ease *e)
{
	return e->a == 0 && e->b == 0;
}

/*
 * scene.c's piece memo (struct mot_node_memo): what a joint's curve is
 * between the frames lo (included) and hi (excluded), the held value or
 * one piece of an interpolating curve without a strand-wide ease;
 * dbl_piece_learn() finds it at a frame (an empty span where it cannot).
 */
struct dbl_piece {
	double lo, hi, held;
	const struct dbl_seg *seg; /* NULL: held */
	bool linear, eased;
	const struct dbl_curve *warp; /* a strand-wide ease: the piece between glo and ghi */
	double glo, ghi;
	bool whole; /* no piece: dbl_curve_eval() every time */
};

void dbl_piece_learn(struct dbl_piece *p, const struct dbl_curve *c, struct dbl_cursor *cur,
		     double f);

/* curve.c's span_warp(), for span_f0 < f < span_f1 */
static inline double dbl_span_warp(const struct dbl_curve *c, double f)
{
	const struct dbl_ease_span *e = &c->span;
	double x = f - c->span_f0, r, g;

	if (x < e->a)
		return c->span_f0 + x * e->ka * x;
	if (x > e->d) {
		r = e->w - x;
		return c->span_f0 + (e->w - r * e->kb * r);
	}
	g = e->v * x - e->c;
	return c->span_f0 + (g < 0 ? 0 : g > e->w ? e->w : g);
}

/* curve_priv.h's eased_u(): on the plateau x v / w - v a / 2, else the
 * fraction and the profile; for the caller to clamp to [0, 1] */
double dbl_eased_off(const struct dbl_seg *s, double x);

static inline double dbl_eased_u(const struct dbl_seg *s, double x)
{
	if (x >= s->ef.xa && x <= s->ef.xd)
		return x * s->ef.vw - s->ef.c;
	return dbl_eased_off(s, x);
}

/* The piece at a frame of its span (curve.c's piece_value()); false where
 * the warped frame leaves it */
static inline bool dbl_piece_at(const struct dbl_piece *p, double f, double *out)
{
	const struct dbl_seg *s = p->seg;
	double u;

	if (p->warp) {
		f = dbl_span_warp(p->warp, f);
		if (f < p->glo || f >= p->ghi)
			return false;
	}
	if (!s) {
		*out = p->held;
		return !p->whole;
	}
	u = p->eased ? dbl_eased_u(s, f - s->f0) : (f - s->f0) * s->inv_w;
	u = u < 0 ? 0 : u > 1 ? 1 : u;
	if (p->linear)
		*out = s->vref + s->c[1] * u;
	else
		*out = s->vref + ((s->c[3] * u + s->c[2]) * u + s->c[1]) * u + s->c[0];
	return true;
}

/* A double as scene_build() quantises it (Q32.32), false when out of range. */
bool dbl_quantize(double v, double *out);

#endif /* DBL_CURVE_H */
