/* SPDX-License-Identifier: MIT */
/* surface.c - soft surfaces: Bezier and B-spline patches, sampled (see surface.h). */
#include "surface.h"

#define Q62 ((int64_t)1 << 62)

static int64_t m62(int64_t a, int64_t b)
{
	return mot_acc_round(mot_acc_mul(a, b), 62, NULL);
}

/*
 * The cubic bases at local parameter t (Q2.62, [0, 1]):
 *   Bernstein: (1-t)^3, 3t(1-t)^2, 3t^2(1-t), t^3
 *   uniform B-spline: (1-t)^3/6, (3t^3 - 6t^2 + 4)/6, (-3t^3 + 3t^2 + 3t + 1)/6, t^3/6
 * each weight rounded from exact 128-bit products; the last is 1 minus the
 * others, so that they sum to 1 exactly (a flat net stays flat).
 */
static void basis4(int64_t w[4], uint32_t basis, int64_t t)
{
	int64_t s = Q62 - t, t2 = m62(t, t), t3 = m62(t2, t), s2 = m62(s, s), s3 = m62(s2, s);

	if (basis == MOT_SURFACE_BEZIER) {
		w[0] = s3;
		w[1] = 3 * m62(t, s2);
		w[2] = 3 * m62(t2, s);
	} else {
		w[0] = s3 / 6;
		/* (3t^3 - 6t^2 + 4)/6 = t^3/2 - t^2 + 2/3 */
		w[1] = t3 / 2 - t2 + (Q62 - (Q62 + 1) / 3);
		/* (-3t^3 + 3t^2 + 3t + 1)/6 = -t^3/2 + t^2/2 + t/2 + 1/6 */
		w[2] = -t3 / 2 + t2 / 2 + t / 2 + (Q62 + 3) / 6;
	}
	w[3] = Q62 - w[0] - w[1] - w[2];
}

static uint32_t clampi(int64_t x, uint32_t n)
{
	return x < 0 ? 0 : x >= (int64_t)n ? n - 1 : (uint32_t)x;
}

void mot_surface_weights(struct mot_surface_w *w, uint32_t basis, uint32_t m, uint32_t i,
			 uint32_t n)
{
	/* segments along the parameter: pu patches, or m + 1 B-spline spans */
	uint32_t segs = basis == MOT_SURFACE_BEZIER ? (m - 1) / 3 : m + 1, k;
	uint64_t num, den;
	int64_t s, t;

	if (n < 2) {
		num = segs;
		den = 2;
	} else {
		num = (uint64_t)i * segs;
		den = n - 1;
	}
	s = (int64_t)(num / den);
	t = mot_muldiv((int64_t)(num % den), Q62, (int64_t)den, NULL);
	if (s >= segs) { /* u = 1: the end of the last segment */
		s = segs - 1;
		t = Q62;
	}
	basis4(w->w, basis, t);
	for (k = 0; k < 4; k++)
		w->idx[k] = basis == MOT_SURFACE_BEZIER ? (uint32_t)(3 * s + k) :
							  clampi(s + (int64_t)k - 2, m);
}

/* round(sum w[a] x[idx[a] * stride]) for weights in Q2.62 */
static mot_q32 combine(const struct mot_surface_w *w, const mot_q32 *x, uint32_t stride,
		       uint32_t *sat)
{
	mot_acc acc = mot_acc_mul(w->w[0], x[(size_t)w->idx[0] * stride]);

	acc = mot_acc_mac(acc, w->w[1], x[(size_t)w->idx[1] * stride]);
	acc = mot_acc_mac(acc, w->w[2], x[(size_t)w->idx[2] * stride]);
	acc = mot_acc_mac(acc, w->w[3], x[(size_t)w->idx[3] * stride]);
	return mot_acc_round(acc, 62, sat);
}

/* Coordinate k of every sample from the control values ctl (stride 3),
 * with row[] (ncv values) as scratch. */
static void sample_coord(const struct mot_surface *s, const mot_q32 *ctl, uint32_t k,
			 mot_q32 *row, mot_q32 *out, uint32_t *sat)
{
	uint32_t i, j, b;

	for (i = 0; i < s->nsu; i++) {
		const struct mot_surface_w *wu = &s->wu[i];

		for (b = 0; b < s->ncv; b++)
			row[b] = combine(wu, ctl + (size_t)b * 3 + k, s->ncv * 3, sat);
		for (j = 0; j < s->nsv; j++)
			out[((size_t)i * s->nsv + j) * 3 + k] = combine(&s->wv[j], row, 1, sat);
	}
}

int mot_surface_init(struct mot_surface *s, uint32_t ncurves, uint32_t *sat)
{
	uint32_t n, i, k;

	if (s->basis > MOT_SURFACE_BSPLINE || !s->ncu || !s->ncv || s->ncu > MOT_SURFACE_MAX_CTL ||
	    s->ncv > MOT_SURFACE_MAX_CTL || !s->nsu || !s->nsv ||
	    s->nsu > MOT_SURFACE_MAX_SAMPLES || s->nsv > MOT_SURFACE_MAX_SAMPLES || !s->curve ||
	    !s->rest || !s->wu || !s->wv || !s->fixed)
		return MOT_E_INVAL;
	if (s->basis == MOT_SURFACE_BEZIER &&
	    (s->ncu < 4 || (s->ncu - 1) % 3 || s->ncv < 4 || (s->ncv - 1) % 3))
		return MOT_E_INVAL;
	n = s->ncu * s->ncv;
	s->moving[0] = s->moving[1] = s->moving[2] = false;
	for (i = 0; i < n * 3; i++) {
		if (s->curve[i] < -1 || (s->curve[i] >= 0 && (uint32_t)s->curve[i] >= ncurves))
			return MOT_E_INVAL;
		if (s->curve[i] >= 0)
			s->moving[i % 3] = true;
	}
	for (i = 0; i < s->nsu; i++)
		mot_surface_weights(&s->wu[i], s->basis, s->ncu, i, s->nsu);
	for (i = 0; i < s->nsv; i++)
		mot_surface_weights(&s->wv[i], s->basis, s->ncv, i, s->nsv);
	/* the coordinates no curve moves, once: each sample the whole
	 * 16-term sum of the rest values, rounded once */
	for (k = 0; k < 3; k++) {
		uint32_t j, b;

		if (s->moving[k])
			continue;
		for (i = 0; i < s->nsu; i++)
			for (j = 0; j < s->nsv; j++) {
				mot_acc acc = mot_acc_zero();

				for (b = 0; b < 4; b++) {
					uint32_t a;

					for (a = 0; a < 4; a++) {
						int64_t w = m62(s->wu[i].w[a], s->wv[j].w[b]);
						size_t c = ((size_t)s->wu[i].idx[a] * s->ncv +
							    s->wv[j].idx[b]) * 3 + k;

						acc = mot_acc_mac(acc, w, s->rest[c]);
					}
				}
				s->fixed[((size_t)i * s->nsv + j) * 3 + k] =
					mot_acc_round(acc, 62, sat);
			}
	}
	return MOT_OK;
}

void mot_surface_eval(const struct mot_surface *s, const struct mot_curve *curves,
		      struct mot_cursor *cursors, mot_q32 frame, mot_q32 *scratch, mot_q32 *out,
		      uint32_t *sat)
{
	uint32_t n = s->ncu * s->ncv * 3, i, k;
	mot_q32 *ctl = scratch, *row = scratch + n;

	for (i = 0; i < n; i++) {
		int32_t c = s->curve[i];

		ctl[i] = c < 0 ? s->rest[i] :
			 mot_curve_eval(&curves[c], cursors ? &cursors[c] : NULL, frame, sat);
	}
	for (k = 0; k < 3; k++) {
		if (s->moving[k]) {
			sample_coord(s, ctl, k, row, out, sat);
			continue;
		}
		for (i = 0; i < s->nsu * s->nsv; i++)
			out[(size_t)i * 3 + k] = s->fixed[(size_t)i * 3 + k];
	}
}
