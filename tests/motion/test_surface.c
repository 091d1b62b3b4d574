/* SPDX-License-Identifier: MIT */
/*
 * test_surface.c - soft surfaces (motion/surface.h): the basis weights by
 * hand, random nets of both bases against a long double evaluation of the
 * same control values, keyed control points against their exact linear
 * keys, the corners the surfaces pass through, and the nets refused.
 */
#include <stdlib.h>
#include <string.h>

#include "motion/surface.h"
#include "testutil.h"

#define LSB (1.0 / TU_Q32)

static void test_weights(void **state)
{
	struct mot_surface_w w;
	int k;

	/* B-spline, 4 control points, parameter 0: the first point, tripled,
	 * and the second with weight 0 */
	mot_surface_weights(&w, MOT_SURFACE_BSPLINE, 4, 0, 11);
	for (k = 0; k < 3; k++)
		assert_int_equal(w.idx[k], 0);
	assert_int_equal(w.w[3], 0);
	/* u = 1: the last point */
	mot_surface_weights(&w, MOT_SURFACE_BSPLINE, 4, 10, 11);
	for (k = 1; k < 4; k++)
		assert_int_equal(w.idx[k], 3);
	assert_int_equal(w.w[0], 0);
	/* Bezier, one patch, u = 1/2: 1/8 3/8 3/8 1/8 */
	mot_surface_weights(&w, MOT_SURFACE_BEZIER, 4, 1, 3);
	assert_true(w.w[0] == (int64_t)1 << 59 && w.w[1] == 3 * ((int64_t)1 << 59) &&
		    w.w[2] == 3 * ((int64_t)1 << 59) && w.w[3] == (int64_t)1 << 59);
	/* two patches, u = 1/2 is the second patch's start: its corner */
	mot_surface_weights(&w, MOT_SURFACE_BEZIER, 7, 2, 5);
	assert_int_equal(w.idx[0], 3);
	assert_true(w.w[0] == (int64_t)1 << 62 && !w.w[1] && !w.w[2] && !w.w[3]);
	/* a B-spline's interior: 1/6 4/6 1/6 0 at a knot */
	mot_surface_weights(&w, MOT_SURFACE_BSPLINE, 5, 1, 7); /* t = 6/6: knot 1 */
	assert_true(llabs(w.w[0] - ((int64_t)1 << 62) / 6) <= 2);
	assert_true(llabs(w.w[1] - (((int64_t)1 << 62) / 6) * 4) <= 4);
	assert_int_equal(w.idx[0], 0);
	assert_int_equal(w.idx[1], 0);
	assert_int_equal(w.idx[2], 1);
}

/* The exact surface of the control values, in long double. */
static long double bern(int basis, int k, long double t)
{
	long double s = 1 - t;

	if (basis == MOT_SURFACE_BEZIER) {
		static const int c[4] = { 1, 3, 3, 1 };

		return c[k] * powl(s, 3 - k) * powl(t, k);
	}
	switch (k) {
	case 0:
		return s * s * s / 6;
	case 1:
		return (3 * t * t * t - 6 * t * t + 4) / 6;
	case 2:
		return (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
	default:
		return t * t * t / 6;
	}
}

/* index and weight of control k for parameter u over m points */
static void ref_w(int basis, int m, long double u, int idx[4], long double w[4])
{
	int segs = basis == MOT_SURFACE_BEZIER ? (m - 1) / 3 : m + 1, k;
	long double t = u * segs;
	int s = (int)floorl(t);

	if (s >= segs)
		s = segs - 1;
	t -= s;
	for (k = 0; k < 4; k++) {
		int j = basis == MOT_SURFACE_BEZIER ? 3 * s + k : s + k - 2;

		idx[k] = j < 0 ? 0 : j >= m ? m - 1 : j;
		w[k] = bern(basis, k, t);
	}
}

static long double ref_sample(const struct mot_surface *s, const mot_q32 *ctl, int i, int j,
			      int k)
{
	long double u = s->nsu < 2 ? 0.5L : (long double)i / (s->nsu - 1);
	long double v = s->nsv < 2 ? 0.5L : (long double)j / (s->nsv - 1);
	long double wu[4], wv[4], sum = 0;
	int iu[4], iv[4], a, b;

	ref_w((int)s->basis, (int)s->ncu, u, iu, wu);
	ref_w((int)s->basis, (int)s->ncv, v, iv, wv);
	for (a = 0; a < 4; a++)
		for (b = 0; b < 4; b++)
			sum += wu[a] * wv[b] * (long double)ctl[(iu[a] * s->ncv + iv[b]) * 3 + k];
	return sum / TU_Q32;
}

struct net {
	struct mot_surface s;
	int32_t *curve;
	mot_q32 *rest;
	struct mot_surface_w *wu, *wv;
	mot_q32 *fixed, *out, *scratch;
};

static void net_new(struct net *n, int basis, uint32_t ncu, uint32_t ncv, uint32_t nsu,
		    uint32_t nsv)
{
	memset(n, 0, sizeof(*n));
	n->s.basis = (uint32_t)basis;
	n->s.ncu = ncu;
	n->s.ncv = ncv;
	n->s.nsu = nsu;
	n->s.nsv = nsv;
	n->curve = calloc((size_t)ncu * ncv * 3, sizeof(*n->curve));
	n->rest = calloc((size_t)ncu * ncv * 3, sizeof(*n->rest));
	n->wu = calloc(nsu, sizeof(*n->wu));
	n->wv = calloc(nsv, sizeof(*n->wv));
	n->fixed = calloc((size_t)nsu * nsv * 3, sizeof(*n->fixed));
	n->out = calloc((size_t)nsu * nsv * 3, sizeof(*n->out));
	n->scratch = calloc((size_t)ncu * ncv * 3 + ncv, sizeof(*n->scratch));
	n->s.curve = n->curve;
	n->s.rest = n->rest;
	n->s.wu = n->wu;
	n->s.wv = n->wv;
	n->s.fixed = n->fixed;
	for (uint32_t i = 0; i < ncu * ncv * 3; i++)
		n->curve[i] = -1;
}

static void net_free(struct net *n)
{
	free(n->curve);
	free(n->rest);
	free(n->wu);
	free(n->wv);
	free(n->fixed);
	free(n->out);
	free(n->scratch);
}

/* Random nets, every coordinate constant: the samples against the exact
 * surface of the same Q32.32 control values. */
static void test_random_static(void **state)
{
	struct tu_worst w = { 0, 0 };
	struct tu_rng r;
	int trial;

	tu_seed(&r, 16);
	for (trial = 0; trial < 60; trial++) {
		int basis = trial & 1;
		uint32_t ncu = basis == MOT_SURFACE_BEZIER ? 3 * (1 + trial % 3) + 1 : 2 + trial % 7;
		uint32_t ncv = basis == MOT_SURFACE_BEZIER ? 3 * (1 + trial % 2) + 1 : 2 + trial % 5;
		uint32_t nsu = 1 + (uint32_t)(tu_u64(&r) % 20), nsv = 1 + (uint32_t)(tu_u64(&r) % 20);
		struct net n;
		uint32_t i, j, k, sat = 0;

		net_new(&n, basis, ncu, ncv, nsu, nsv);
		for (i = 0; i < ncu * ncv * 3; i++)
			n.rest[i] = d2q(tu_uniform(&r, -100, 100));
		assert_int_equal(mot_surface_init(&n.s, 0, &sat), MOT_OK);
		mot_surface_eval(&n.s, NULL, NULL, 0, n.scratch, n.out, &sat);
		assert_int_equal(sat, 0);
		for (i = 0; i < nsu; i++)
			for (j = 0; j < nsv; j++)
				for (k = 0; k < 3; k++) {
					long double ref = ref_sample(&n.s, n.rest, (int)i, (int)j,
								     (int)k);

					tu_worst_add(&w, (double)((long double)q2d(
						n.out[(i * nsv + j) * 3 + k]) - ref) / LSB, trial);
				}
		net_free(&n);
	}
	/* one rounding of the 16-term sum, weights within 2^-61 */
	tu_bound("surface_static_lsb", &w, 0.51, "LSB");
}

/* Keyed control points: linear keys, every third coordinate moving; the
 * samples at random frames against the exact surface of the exact keyed
 * values (long double). */
static void test_keyed(void **state)
{
	enum { NCU = 7, NCV = 5, NK = 3 };
	struct tu_worst w = { 0, 0 };
	struct mot_curve curves[NCU * NCV];
	struct mot_key keys[NCU * NCV][NK];
	struct mot_curve_seg seg[NCU * NCV][NK];
	double kv[NCU * NCV][NK];
	struct mot_cursor cur[NCU * NCV];
	struct tu_rng r;
	struct net n;
	uint32_t i, j, sat = 0;
	int basis, t;

	tu_seed(&r, 61);
	for (basis = 0; basis < 2; basis++) {
		net_new(&n, basis, NCU, basis == MOT_SURFACE_BEZIER ? 4 : NCV, 9, 13);
		memset(cur, 0, sizeof(cur));
		for (i = 0; i < n.s.ncu * n.s.ncv; i++) {
			for (j = 0; j < NK; j++) {
				kv[i][j] = tu_uniform(&r, -2, 2);
				keys[i][j] = (struct mot_key){ MOT_Q32_INT(24 * (int)j), d2q(kv[i][j]),
							       0, 0 };
				kv[i][j] = q2d(keys[i][j].value);
			}
			assert_int_equal(mot_curve_init(&curves[i], MOT_INTERP_LINEAR, keys[i], NK,
							NULL, seg[i], NK, &sat), MOT_OK);
			n.curve[i * 3 + 1] = (int32_t)i; /* the heights move */
			n.rest[i * 3] = d2q((double)(i / n.s.ncv) * 0.1);
			n.rest[i * 3 + 2] = d2q((double)(i % n.s.ncv) * 0.1);
		}
		assert_int_equal(mot_surface_init(&n.s, NCU * NCV, &sat), MOT_OK);
		assert_true(n.s.moving[1] && !n.s.moving[0] && !n.s.moving[2]);
		for (t = 0; t < 200; t++) {
			double f = tu_uniform(&r, -5, 53);
			mot_q32 fq = d2q(f);

			mot_surface_eval(&n.s, curves, (t & 1) ? cur : NULL, fq, n.scratch, n.out,
					 &sat);
			for (i = 0; i < n.s.nsu; i++)
				for (j = 0; j < n.s.nsv; j++) {
					long double wu[4], wv[4], sum = 0, ff = (long double)fq / TU_Q32;
					int iu[4], iv[4], a, b;

					ref_w(basis, (int)n.s.ncu, n.s.nsu < 2 ? 0.5L :
						  (long double)i / (n.s.nsu - 1), iu, wu);
					ref_w(basis, (int)n.s.ncv, n.s.nsv < 2 ? 0.5L :
						  (long double)j / (n.s.nsv - 1), iv, wv);
					for (a = 0; a < 4; a++)
						for (b = 0; b < 4; b++) {
							int c = iu[a] * (int)n.s.ncv + iv[b], s;
							long double v;

							if (ff <= 0) {
								v = kv[c][0];
							} else if (ff >= 48) {
								v = kv[c][2];
							} else {
								s = ff >= 24;
								v = kv[c][s] + (kv[c][s + 1] - kv[c][s]) *
									       (ff - 24 * s) / 24;
							}
							sum += wu[a] * wv[b] * v;
						}
					tu_worst_add(&w, (double)((long double)q2d(
						n.out[(i * n.s.nsv + j) * 3 + 1]) - sum) / LSB, f);
				}
		}
		assert_int_equal(sat, 0);
		net_free(&n);
	}
	/* the curves' half LSB, the row's rounding and the sample's */
	tu_bound("surface_keyed_lsb", &w, 1.6, "LSB");
}

/* Through the corners: a B-spline net's four corners, every Bezier patch's. */
static void test_corners(void **state)
{
	struct net n;
	uint32_t i, sat = 0;

	net_new(&n, MOT_SURFACE_BSPLINE, 5, 6, 3, 4);
	for (i = 0; i < 5 * 6 * 3; i++)
		n.rest[i] = MOT_Q32_INT((int)i) / 7;
	assert_int_equal(mot_surface_init(&n.s, 0, &sat), MOT_OK);
	mot_surface_eval(&n.s, NULL, NULL, 0, n.scratch, n.out, &sat);
	for (i = 0; i < 3; i++) {
		assert_int_equal(n.out[i], n.rest[i]);                              /* (0, 0) */
		assert_int_equal(n.out[(2 * 4 + 3) * 3 + i], n.rest[(4 * 6 + 5) * 3 + i]); /* (1, 1) */
		assert_int_equal(n.out[3 * 3 + i], n.rest[5 * 3 + i]);              /* (0, 1) */
	}
	net_free(&n);
	net_new(&n, MOT_SURFACE_BEZIER, 7, 4, 5, 2); /* two patches along u */
	for (i = 0; i < 7 * 4 * 3; i++)
		n.rest[i] = MOT_Q32_INT((int)i % 11) / 3;
	assert_int_equal(mot_surface_init(&n.s, 0, &sat), MOT_OK);
	mot_surface_eval(&n.s, NULL, NULL, 0, n.scratch, n.out, &sat);
	for (i = 0; i < 3; i++) {
		assert_int_equal(n.out[(2 * 2 + 0) * 3 + i], n.rest[(3 * 4 + 0) * 3 + i]); /* u = 1/2 */
		assert_int_equal(n.out[(4 * 2 + 1) * 3 + i], n.rest[(6 * 4 + 3) * 3 + i]);
	}
	net_free(&n);
}

static void test_refused(void **state)
{
	struct net n;
	uint32_t sat = 0;

	net_new(&n, MOT_SURFACE_BEZIER, 5, 4, 2, 2); /* 5 is not 3p + 1 */
	assert_int_equal(mot_surface_init(&n.s, 0, &sat), MOT_E_INVAL);
	net_free(&n);
	net_new(&n, MOT_SURFACE_BSPLINE, 3, 3, 2, 2);
	n.curve[4] = 7; /* beyond the curves */
	assert_int_equal(mot_surface_init(&n.s, 3, &sat), MOT_E_INVAL);
	n.curve[4] = 2;
	assert_int_equal(mot_surface_init(&n.s, 3, &sat), MOT_OK);
	n.s.nsu = 0;
	assert_int_equal(mot_surface_init(&n.s, 3, &sat), MOT_E_INVAL);
	net_free(&n);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_weights),
		cmocka_unit_test(test_random_static),
		cmocka_unit_test(test_keyed),
		cmocka_unit_test(test_corners),
		cmocka_unit_test(test_refused),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
