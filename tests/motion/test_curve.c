/* SPDX-License-Identifier: MIT */
/*
 * test_curve.c - motion/curve*.c against the floating-point reference of
 * tests/ref_curve.c (FORMULAS.md sections 6 to 8), on seeded random key sets
 * with uneven key times: accuracy of every kind with and without ease,
 * passing through keys, convex hulls, Hermite's overshoot, the Beta-spline's
 * limits (B-spline, polyline), sequential versus random access, integrals
 * (against the reference, exact rationals, a 24-hour hold), the argument
 * checks, and the portable (no __int128) build bit for bit.
 *
 * Error units: LSB = 2^-32 of a value or frame. Where the reference's slope
 * dv/df matters (a solve in frames, a warped frame rounded to Q32.32) the
 * error is stated per (1 + |dv/df|): the bound then reads "B LSB of value
 * plus B LSB of frame times the slope".
 */
#include <stdio.h>

#include "curve_portable.h"
#include "motion/curve.h"
#include "ref_curve.h"
#include "testutil.h"

#define LSB 4294967296.0L
#define MAXK 40

static const char *const kind_name[] = { "step", "linear", "hermite", "bspline", "beta", "bezier" };

struct keyset {
	struct mot_key k[MAXK];
	uint32_t n;
	struct mot_curve_opts o;
	struct mot_curve_seg seg[MAXK + 2];
	struct mot_curve c;
};

/* Frame scales of the random key sets: gaps between keys (frames). */
static const double gap_lo[] = { 0.01, 1, 1e3, 0.01 };
static const double gap_hi[] = { 2, 100, 1e6, 1e4 };

static double log_uniform(struct tu_rng *r, double lo, double hi)
{
	return exp(tu_uniform(r, log(lo), log(hi)));
}

/*
 * A random key set for kind: 2..16 keys (bezier 2..12), gaps log-uniform in
 * one of the scales above (the last one very uneven), values in +-1000.
 * ease: random key fractions on about half the keys and a strand ease on
 * half the sets. beta: beta1 in (0, 4], beta2 in [0, 10].
 */
static void gen(struct tu_rng *r, struct keyset *ks, enum mot_interp kind, bool ease)
{
	unsigned cls = (unsigned)(tu_u64(r) % 4);
	uint32_t i, nmax = kind == MOT_INTERP_BEZIER ? 12 : 16;
	double f = tu_uniform(r, -1000, 1000) * (cls == 2 ? 1000 : 1);

	ks->n = 2 + (uint32_t)(tu_u64(r) % (nmax - 1));
	for (i = 0; i < ks->n; i++) {
		ks->k[i].frame = d2q(f);
		ks->k[i].value = d2q(tu_uniform(r, -1000, 1000));
		ks->k[i].ease_in = ks->k[i].ease_out = 0;
		if (ease && tu_u64(r) % 2) {
			ks->k[i].ease_in = d2q(tu_uniform(r, 0, 0.5));
			ks->k[i].ease_out = d2q(tu_uniform(r, 0, 0.5));
		}
		f += log_uniform(r, gap_lo[cls], gap_hi[cls]);
	}
	ks->o.beta1 = MOT_Q32_ONE;
	ks->o.beta2 = 0;
	if (kind == MOT_INTERP_BETA) {
		ks->o.beta1 = d2q(tu_uniform(r, 0.01, 4));
		ks->o.beta2 = d2q(tu_uniform(r, 0, 10));
	}
	ks->o.ease_in_frames = ks->o.ease_out_frames = 0;
	if (ease && tu_u64(r) % 2) {
		mot_q32 span = ks->k[ks->n - 1].frame - ks->k[0].frame;

		ks->o.ease_in_frames = (mot_q32)((double)span * tu_uniform(r, 0, 0.45));
		ks->o.ease_out_frames = (mot_q32)((double)span * tu_uniform(r, 0, 0.45));
	}
	ks->o.integral = false;
}

static void init_ok(struct keyset *ks, enum mot_interp kind)
{
	uint32_t sat = 0;

	assert_true(mot_curve_seg_count(kind, ks->n) <= MAXK + 2);
	assert_int_equal(
		mot_curve_init(&ks->c, kind, ks->k, ks->n, &ks->o, ks->seg, MAXK + 2, &sat),
		MOT_OK);
	assert_int_equal(sat, 0);
}

/* A sample frame: mostly uniform over the span and 2% beyond each end,
 * sometimes exactly on a key or one LSB either side of it. */
static mot_q32 sample(struct tu_rng *r, const struct keyset *ks)
{
	mot_q32 f0 = ks->k[0].frame, fn = ks->k[ks->n - 1].frame;
	unsigned mode = (unsigned)(tu_u64(r) % 10);

	if (mode == 0) {
		const struct mot_key *k = &ks->k[tu_u64(r) % ks->n];

		return k->frame + (mot_q32)(tu_u64(r) % 3) - 1;
	}
	return f0 + (mot_q32)((double)(fn - f0) * tu_uniform(r, -0.02, 1.02));
}

/*
 * The slope an error in frames turns into an error in value: the eased
 * curve's own at f and, since a warped frame is a Q32.32 frame like any
 * other, the slope of the curve that is evaluated at the warped frame (the
 * strand warp rounds its frame; the approximating kinds round the key
 * interval's too).
 */
static ref_t error_slope(enum mot_interp kind, const struct keyset *ks, ref_t f)
{
	static struct mot_key plain[MAXK];
	const ref_t df = 1.0L / (1 << 20);
	struct mot_curve_opts o = ks->o;
	ref_t s = ref_curve_slope(kind, ks->k, ks->n, &ks->o, f, df), t;
	uint32_t i;

	o.ease_in_frames = o.ease_out_frames = 0;
	t = ref_curve_slope(kind, ks->k, ks->n, &o, ref_curve_warp(ks->k, ks->n, &ks->o, f, false),
			    df);
	s = t > s ? t : s;
	for (i = 0; i < ks->n; i++) {
		plain[i] = ks->k[i];
		plain[i].ease_in = plain[i].ease_out = 0;
	}
	t = ref_curve_slope(kind, plain, ks->n, &o, ref_curve_warp(ks->k, ks->n, &ks->o, f, true),
			    df);
	return t > s ? t : s;
}

/*
 * Each kind against the reference over >= 10^5 sample frames on random key
 * sets, plain and eased. Reported: the absolute error in LSB where the
 * computation has no frame rounding (interpolating kinds without a strand
 * ease), else the error per (1 + |dv/df|).
 */
static void accuracy(enum mot_interp kind, bool ease, double bound)
{
	static struct keyset ks;
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	char name[64];
	bool per_slope = ease || kind >= MOT_INTERP_BSPLINE;
	int set, i, total = 0, maxit = 0;

	tu_seed(&rng, 100 + (uint64_t)kind * 2 + ease);
	for (set = 0; set < 500; set++) {
		uint32_t sat = 0;
		uint64_t vmax;

		gen(&rng, &ks, kind, ease);
		init_ok(&ks, kind);
		/* mot_curve_bound() holds every value, and says something */
		vmax = mot_curve_bound(&ks.c);
		assert_true(vmax < (uint64_t)1 << 63);
		for (i = 0; i < 240; i++, total++) {
			mot_q32 f = sample(&rng, &ks), v = mot_curve_eval(&ks.c, NULL, f, &sat);
			ref_t want = ref_curve_eval(kind, ks.k, ks.n, &ks.o, ref_q(f));
			ref_t err = (ref_q(v) - want) * LSB;
			int it = mot_curve_newton_iterations(&ks.c, f);

			assert_true((uint64_t)(v < 0 ? -v : v) <= vmax);
			maxit = it > maxit ? it : maxit;
			if (per_slope && fabsl(err) > 0.5L)
				err /= 1 + error_slope(kind, &ks, ref_q(f));
			tu_worst_add(&w, (double)err, (double)ref_q(f));
		}
		assert_int_equal(sat, 0);
	}
	assert_true(total >= 100000);
	snprintf(name, sizeof(name), "curve.%s%s_vs_ref", kind_name[kind], ease ? "_eased" : "");
	tu_bound(name, &w, bound, per_slope ? "LSB per (1 + |dv/df|)" : "LSB");
	if (kind >= MOT_INTERP_BSPLINE)
		printf("INFO curve.%s%s newton iterations: max %d of %d\n", kind_name[kind],
		       ease ? "_eased" : "", maxit, 64);
}

static void test_step(void **state)
{
	accuracy(MOT_INTERP_STEP, false, 0);
	accuracy(MOT_INTERP_STEP, true, 0.5);
}

static void test_linear(void **state)
{
	accuracy(MOT_INTERP_LINEAR, false, 1);
	accuracy(MOT_INTERP_LINEAR, true, 1);
}

static void test_hermite(void **state)
{
	accuracy(MOT_INTERP_HERMITE, false, 1);
	accuracy(MOT_INTERP_HERMITE, true, 1);
}

static void test_bspline(void **state)
{
	accuracy(MOT_INTERP_BSPLINE, false, 1);
	accuracy(MOT_INTERP_BSPLINE, true, 1);
}

static void test_beta(void **state)
{
	accuracy(MOT_INTERP_BETA, false, 1);
	accuracy(MOT_INTERP_BETA, true, 1);
}

static void test_bezier(void **state)
{
	accuracy(MOT_INTERP_BEZIER, false, 1);
	accuracy(MOT_INTERP_BEZIER, true, 1);
}

/* The largest Bezier curve, 32 keys: fewer samples (the reference's
 * de Casteljau bisection is slow), same bound. */
static void test_bezier_max(void **state)
{
	static struct keyset ks;
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int set, i, maxit = 0;

	tu_seed(&rng, 140);
	for (set = 0; set < 40; set++) {
		gen(&rng, &ks, MOT_INTERP_BEZIER, false);
		ks.n = MOT_BEZIER_MAX_KEYS;
		for (i = 1; i < (int)ks.n; i++)
			ks.k[i].frame = ks.k[i - 1].frame +
					d2q(log_uniform(&rng, 0.01, 1000));
		for (i = 0; i < (int)ks.n; i++)
			ks.k[i].value = d2q(tu_uniform(&rng, -1000, 1000));
		init_ok(&ks, MOT_INTERP_BEZIER);
		for (i = 0; i < 100; i++) {
			mot_q32 f = sample(&rng, &ks);
			ref_t want = ref_curve_eval(MOT_INTERP_BEZIER, ks.k, ks.n, &ks.o, ref_q(f));
			ref_t err = (ref_q(mot_curve_eval(&ks.c, NULL, f, NULL)) - want) * LSB;
			int it = mot_curve_newton_iterations(&ks.c, f);

			maxit = it > maxit ? it : maxit;
			if (fabsl(err) > 0.5L)
				err /= 1 + error_slope(MOT_INTERP_BEZIER, &ks, ref_q(f));
			tu_worst_add(&w, (double)err, (double)ref_q(f));
		}
	}
	tu_bound("curve.bezier32_vs_ref", &w, 1, "LSB per (1 + |dv/df|)");
	printf("INFO curve.bezier32 newton iterations: max %d of 64\n", maxit);
}

/*
 * Bezier curves that the core evaluates in power form (the form's range: a
 * few keys close together; test_bezier's sets mostly fall outside it)
 * against the reference, with the same bound, and the power form taken for
 * most of these sets.
 */
static void test_bezier_power(void **state)
{
	static struct keyset ks;
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int set, i, npower = 0;

	tu_seed(&rng, 141);
	for (set = 0; set < 400; set++) {
		gen(&rng, &ks, MOT_INTERP_BEZIER, set % 2);
		ks.n = 2 + (uint32_t)(tu_u64(&rng) % 9);
		for (i = 1; i < (int)ks.n; i++)
			ks.k[i].frame = ks.k[i - 1].frame + d2q(log_uniform(&rng, 0.1, 100));
		for (i = 0; i < (int)ks.n; i++)
			ks.k[i].value = d2q(tu_uniform(&rng, -10, 10));
		ks.o.ease_in_frames = ks.o.ease_out_frames = 0;
		init_ok(&ks, MOT_INTERP_BEZIER);
		npower += ks.c.power;
		for (i = 0; i < 250; i++) {
			mot_q32 f = sample(&rng, &ks);
			ref_t want = ref_curve_eval(MOT_INTERP_BEZIER, ks.k, ks.n, &ks.o, ref_q(f));
			ref_t err = (ref_q(mot_curve_eval(&ks.c, NULL, f, NULL)) - want) * LSB;

			if (fabsl(err) > 0.5L)
				err /= 1 + error_slope(MOT_INTERP_BEZIER, &ks, ref_q(f));
			tu_worst_add(&w, (double)err, (double)ref_q(f));
		}
	}
	tu_bound("curve.bezier_power_vs_ref", &w, 1, "LSB per (1 + |dv/df|)");
	printf("INFO curve.bezier_power: %d of 400 key sets in power form\n", npower);
	assert_true(npower >= 300);
}

/*
 * Adversarial pieces for the Newton solve: key gaps log-uniform over 12
 * decades (1e-6 to 1e6 frames next to each other) and Beta-spline shapes at
 * their extremes (beta1 in {0, 1e-6, 0.01, 1, 5, 256}, beta2 in {0, 1e-6,
 * 1, 100, 2^24}), which flatten a piece's frame near one or both ends. The
 * solve must stay accurate and never run into its iteration cap (64).
 */
static void test_newton_adversarial(void **state)
{
	static const double b1s[6] = { 0, 1e-6, 0.01, 1, 5, 256 };
	static const double b2s[5] = { 0, 1e-6, 1, 100, 16777216 };
	static struct keyset ks;
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, it = { 0, 0 };
	int set, i;

	tu_seed(&rng, 145);
	for (set = 0; set < 1200; set++) {
		enum mot_interp kind = (enum mot_interp)(MOT_INTERP_BSPLINE + set % 3);
		double f = tu_uniform(&rng, -1e5, 1e5);
		uint32_t j;

		ks.n = 2 + (uint32_t)(tu_u64(&rng) % (kind == MOT_INTERP_BEZIER ? 10 : 14));
		for (j = 0; j < ks.n; j++) {
			ks.k[j] = (struct mot_key){ d2q(f), d2q(tu_uniform(&rng, -1000, 1000)), 0,
						    0 };
			f += log_uniform(&rng, 1e-6, 1e6);
		}
		ks.o = (struct mot_curve_opts){ d2q(b1s[tu_u64(&rng) % 6]),
						d2q(b2s[tu_u64(&rng) % 5]), 0, 0, false,
						NULL, false };
		init_ok(&ks, kind);
		for (i = 0; i < 100; i++) {
			mot_q32 x = i % 3 ? sample(&rng, &ks)
					  : ks.k[tu_u64(&rng) % ks.n].frame +
						    (mot_q32)(tu_u64(&rng) % 2001) - 1000;
			ref_t err = (ref_q(mot_curve_eval(&ks.c, NULL, x, NULL)) -
				     ref_curve_eval(kind, ks.k, ks.n, &ks.o, ref_q(x))) *
				    LSB;

			if (fabsl(err) > 0.5L)
				err /= 1 + ref_curve_slope(kind, ks.k, ks.n, &ks.o, ref_q(x),
							   1.0L / (1 << 24));
			tu_worst_add(&w, (double)err, (double)ref_q(x));
			tu_worst_add(&it, mot_curve_newton_iterations(&ks.c, x), kind);
		}
	}
	tu_bound("curve.adversarial_vs_ref", &w, 1, "LSB per (1 + |dv/df|)");
	tu_bound("curve.adversarial_newton_iterations", &it, 48, "iterations (cap 64)");
}

/* Interpolating kinds hit every key exactly; every kind starts on the first
 * key and ends on the last, and holds them outside. */
static void test_through_keys(void **state)
{
	static struct keyset ks;
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int kind, set;
	uint32_t i;

	tu_seed(&rng, 150);
	for (kind = 0; kind <= MOT_INTERP_BEZIER; kind++) {
		for (set = 0; set < 300; set++) {
			struct mot_cursor cur = { 0, 0 };
			mot_q32 f0, fn;

			/* key ease keeps the keys where they are, a strand ease moves them */
			gen(&rng, &ks, (enum mot_interp)kind, set % 2);
			ks.o.ease_in_frames = ks.o.ease_out_frames = 0;
			init_ok(&ks, (enum mot_interp)kind);
			f0 = ks.k[0].frame;
			fn = ks.k[ks.n - 1].frame;
			if (kind <= MOT_INTERP_HERMITE)
				for (i = 0; i < ks.n; i++) {
					assert_int_equal(
						mot_curve_eval(&ks.c, NULL, ks.k[i].frame, NULL),
						ks.k[i].value);
					assert_int_equal(
						mot_curve_eval(&ks.c, &cur, ks.k[i].frame, NULL),
						ks.k[i].value);
				}
			assert_int_equal(mot_curve_eval(&ks.c, NULL, f0, NULL), ks.k[0].value);
			assert_int_equal(mot_curve_eval(&ks.c, NULL, fn, NULL),
					 ks.k[ks.n - 1].value);
			assert_int_equal(mot_curve_eval(&ks.c, NULL, MOT_Q32_MIN, NULL),
					 ks.k[0].value);
			assert_int_equal(mot_curve_eval(&ks.c, NULL, MOT_Q32_MAX, NULL),
					 ks.k[ks.n - 1].value);
			/* continuity into the held ends: one LSB inside, within the slope */
			if (kind != MOT_INTERP_STEP) {
				mot_q32 in0 = mot_curve_eval(&ks.c, NULL, f0 + 1, NULL);
				mot_q32 in1 = mot_curve_eval(&ks.c, NULL, fn - 1, NULL);
				ref_t s0 = ref_curve_slope((enum mot_interp)kind, ks.k, ks.n, &ks.o,
							   ref_q(f0 + 1), 1.0L / (1 << 20));
				ref_t s1 = ref_curve_slope((enum mot_interp)kind, ks.k, ks.n, &ks.o,
							   ref_q(fn - 1), 1.0L / (1 << 20));

				tu_worst_add(
					&w,
					(double)(fabsl((ref_t)(in0 - ks.k[0].value)) / (1 + s0)),
					kind);
				tu_worst_add(&w,
					     (double)(fabsl((ref_t)(in1 - ks.k[ks.n - 1].value)) /
						      (1 + s1)),
					     kind);
			}
		}
	}
	tu_bound("curve.ends_continuity", &w, 2, "LSB per (1 + |dv/df|) one LSB inside an end");
}

/* B-spline, Beta-spline (beta1 > 0, beta2 >= 0) and Bezier stay inside the
 * convex hull of their keys: the value between the smallest and largest key
 * value. */
static void test_convex_hull(void **state)
{
	static struct keyset ks;
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int kind, set, i;

	tu_seed(&rng, 160);
	for (kind = MOT_INTERP_BSPLINE; kind <= MOT_INTERP_BEZIER; kind++)
		for (set = 0; set < 400; set++) {
			mot_q32 lo = MOT_Q32_MAX, hi = MOT_Q32_MIN;
			uint32_t j;

			gen(&rng, &ks, (enum mot_interp)kind, set % 2);
			if (kind == MOT_INTERP_BETA && set % 4 == 0)
				ks.o.beta1 = d2q(tu_uniform(&rng, 4, 200)); /* strong bias */
			if (kind == MOT_INTERP_BETA && set % 4 == 1)
				ks.o.beta2 = d2q(tu_uniform(&rng, 10, 1e5)); /* high tension */
			init_ok(&ks, (enum mot_interp)kind);
			for (j = 0; j < ks.n; j++) {
				lo = ks.k[j].value < lo ? ks.k[j].value : lo;
				hi = ks.k[j].value > hi ? ks.k[j].value : hi;
			}
			for (i = 0; i < 100; i++) {
				mot_q32 v = mot_curve_eval(&ks.c, NULL, sample(&rng, &ks), NULL);

				tu_worst_add(&w,
					     v < lo   ? (double)(lo - v)
					     : v > hi ? (double)(v - hi)
						      : 0,
					     kind);
			}
		}
	tu_bound("curve.convex_hull_excess", &w, 1, "LSB");
}

/*
 * mot_curve_bound() on random curves of every kind, sampled densely: 97
 * frames a key interval evenly (its ends included), a key's frame and one
 * LSB either side, random frames and frames beyond the span; every value
 * within the bound. Key sets: gen()'s (values in +-1000, half of them
 * eased), values in [0.7, 1.4] (a scale channel, scene.c's case), values
 * near +-2^29 and tiny ones; hermite with random explicit tangents on a
 * third of its sets; Beta shapes at their extremes; Bezier curves in power
 * form (a few keys close together) and up to MOT_BEZIER_MAX_KEYS keys by de
 * Casteljau; compact step and linear curves. Reported: the bound's slack
 * over the largest |value| sampled, relative (per set: bound / max - 1,
 * the worst set whose values reach a unit) and in LSB (the worst).
 */
static void test_bound_dense(void **state)
{
	static struct keyset ks;
	static struct mot_tangent tan[MAXK];
	static const double beta1x[] = { 0, 1e-6, 0.01, 1, 5, 256 };
	static const double beta2x[] = { 0, 1e-6, 1, 100, 16777216 };
	struct tu_rng rng;
	int kind, set, i, sets = 0;
	long samples = 0;

	tu_seed(&rng, 230);
	for (kind = 0; kind <= MOT_INTERP_BEZIER; kind++) {
		double rel = 0, lsb = 0;
		int npower = 0;

		for (set = 0; set < 300; set++) {
			unsigned vcls = (unsigned)(tu_u64(&rng) % 4);
			uint32_t j, sat = 0;
			uint64_t b, vmax = 0;
			struct mot_cursor cur = { 0, 0 };
			int err;

			gen(&rng, &ks, (enum mot_interp)kind, set % 2);
			if (kind == MOT_INTERP_BEZIER && set % 3 != 2) /* new frames: no span ease */
				ks.o.ease_in_frames = ks.o.ease_out_frames = 0;
			for (j = ks.n; j < MAXK; j++) /* keys beyond gen()'s: no ease */
				ks.k[j].ease_in = ks.k[j].ease_out = 0;
			if (kind == MOT_INTERP_BEZIER && set % 3 != 2) { /* power form */
				ks.n = 2 + (uint32_t)(tu_u64(&rng) % 9);
				for (j = 1; j < ks.n; j++)
					ks.k[j].frame = ks.k[j - 1].frame +
							d2q(log_uniform(&rng, 0.1, 100));
			} else if (kind == MOT_INTERP_BEZIER && set % 6 == 5) {
				ks.n = MOT_BEZIER_MAX_KEYS;
				ks.o.ease_in_frames = ks.o.ease_out_frames = 0;
				for (j = 1; j < ks.n; j++)
					ks.k[j].frame = ks.k[j - 1].frame +
							d2q(log_uniform(&rng, 0.01, 1000));
				for (j = 0; j < ks.n; j++)
					ks.k[j].ease_in = ks.k[j].ease_out = 0;
			}
			for (j = 0; j < ks.n && vcls; j++)
				ks.k[j].value = vcls == 1 ? d2q(tu_uniform(&rng, 0.7, 1.4)) :
						vcls == 2 ? (mot_q32)((double)(MOT_LEN_LIMIT - 1) *
								      tu_uniform(&rng, -1, 1)) :
							    (mot_q32)(tu_u64(&rng) % 2001) - 1000;
			if (kind == MOT_INTERP_BETA && set % 3 == 0) {
				ks.o.beta1 = d2q(beta1x[tu_u64(&rng) % 6]);
				ks.o.beta2 = d2q(beta2x[tu_u64(&rng) % 5]);
			}
			ks.o.tangents = NULL;
			ks.o.compact = kind <= MOT_INTERP_LINEAR && set % 4 == 3;
			if (ks.o.compact) {
				ks.o.ease_in_frames = ks.o.ease_out_frames = 0;
				for (j = 0; j < ks.n; j++)
					ks.k[j].ease_in = ks.k[j].ease_out = 0;
			}
			if (kind == MOT_INTERP_HERMITE && set % 3 == 0 && vcls != 2) {
				ks.o.tangents = tan;
				for (j = 0; j < ks.n; j++) {
					/* up to 4 times the keys' slopes, either way */
					int64_t h = ks.k[j + (j + 1 < ks.n)].frame -
						    ks.k[j - (j + 1 == ks.n)].frame;
					double m = (double)(ks.k[j + (j + 1 < ks.n)].value -
							    ks.k[j - (j + 1 == ks.n)].value) /
						   (double)h;

					tan[j].in = d2q(m * tu_uniform(&rng, -4, 4));
					tan[j].out = d2q(m * tu_uniform(&rng, -4, 4));
					tan[j].set = (uint32_t)(tu_u64(&rng) % 4);
				}
			}
			err = mot_curve_init(&ks.c, (enum mot_interp)kind, ks.k, ks.n, &ks.o,
					     ks.seg, MAXK + 2, &sat);
			ks.o.tangents = NULL;
			ks.o.compact = false;
			if (err == MOT_E_RANGE && kind == MOT_INTERP_HERMITE)
				continue; /* a tangent beyond the core's range */
			assert_int_equal(err, MOT_OK);
			npower += ks.c.power;
			b = mot_curve_bound(&ks.c);
			assert_true(b < (uint64_t)1 << 63);
			for (j = 0; j + 1 < ks.n; j++) {
				mot_q32 f0 = ks.k[j].frame, f1 = ks.k[j + 1].frame;

				for (i = -1; i <= 97; i++) {
					mot_q32 f = i < 0    ? f0 - 1 :
						    i == 97 ? f0 + 1 :
							      f0 + (mot_q32)((double)(f1 - f0) * i / 96);
					mot_q32 v = mot_curve_eval(&ks.c, &cur, f, &sat);
					uint64_t a = mot_mag(v);

					assert_true(a <= b);
					vmax = a > vmax ? a : vmax;
					samples++;
				}
			}
			for (i = 0; i < 200; i++) {
				uint64_t a = mot_mag(mot_curve_eval(&ks.c, NULL, sample(&rng, &ks), &sat));

				assert_true(a <= b);
				vmax = a > vmax ? a : vmax;
				samples++;
			}
			assert_int_equal(sat, 0);
			if (vmax >= (uint64_t)1 << 32 && (double)(b - vmax) / (double)vmax > rel)
				rel = (double)(b - vmax) / (double)vmax;
			lsb = (double)(b - vmax) > lsb ? (double)(b - vmax) : lsb;
			sets++;
		}
		printf("INFO curve.bound_%s: slack over the largest |value| sampled at most "
		       "%.3g of it (values of a unit or more), %.4g LSB\n",
		       kind_name[kind], rel, lsb);
		if (kind == MOT_INTERP_BEZIER)
			printf("INFO curve.bound_bezier: %d sets in power form\n", npower);
	}
	assert_true(sets >= 1700);
	assert_true(samples >= 1000000);
}

/* The paper's "exaggerated path": Catmull-Rom swings beyond the keys. Keys
 * (0, 0), (1, 10), (2, 10), (10, 0): between frames 1 and 2 the curve rises
 * above 10 (to 10.76 near 1.5) and matches the reference there. */
static void test_hermite_overshoot(void **state)
{
	static const double fr[4] = { 0, 1, 2, 10 }, va[4] = { 0, 10, 10, 0 };
	struct mot_key k[4];
	struct mot_curve_seg seg[5];
	struct mot_curve c;
	struct tu_worst w = { 0, 0 };
	mot_q32 top = MOT_Q32_MIN;
	ref_t rtop = -1e9;
	int i;

	for (i = 0; i < 4; i++) {
		k[i].frame = d2q(fr[i]);
		k[i].value = d2q(va[i]);
		k[i].ease_in = k[i].ease_out = 0;
	}
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_HERMITE, k, 4, NULL, seg, 4, NULL), MOT_OK);
	for (i = 0; i <= 10000; i++) {
		mot_q32 f = d2q(1 + i / 10000.0);
		mot_q32 v = mot_curve_eval(&c, NULL, f, NULL);
		ref_t r = ref_curve_eval(MOT_INTERP_HERMITE, k, 4, &(struct mot_curve_opts){ 0 },
					 ref_q(f));

		top = v > top ? v : top;
		rtop = r > rtop ? r : rtop;
		tu_worst_add(&w, (double)((ref_q(v) - r) * LSB), (double)ref_q(f));
	}
	assert_true(ref_q(top) > 10.7L);
	assert_true(rtop > 10.7L);
	assert_true(fabsl(ref_q(top) - rtop) * LSB <= 1);
	tu_bound("curve.hermite_overshoot_vs_ref", &w, 1, "LSB");
	/* the same keys as a B-spline stay at or below 10 */
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_BSPLINE, k, 4, NULL, seg, 5, NULL), MOT_OK);
	for (i = 0; i <= 10000; i++)
		assert_true(mot_curve_eval(&c, NULL, d2q(i / 1000.0), NULL) <= d2q(10));
}

/* beta1 = 1, beta2 = 0 is the uniform B-spline: bit for bit. beta1 = 0,
 * beta2 = 0 runs straight between the keys: the linear kind. */
static void test_beta_limits(void **state)
{
	static struct keyset ks, kl;
	struct tu_rng rng;
	struct tu_worst wb = { 0, 0 }, wl = { 0, 0 };
	int set, i, maxit = 0;

	tu_seed(&rng, 170);
	for (set = 0; set < 500; set++) {
		gen(&rng, &ks, MOT_INTERP_BSPLINE, set % 2);
		kl = ks;
		init_ok(&ks, MOT_INTERP_BSPLINE);
		kl.o.beta1 = MOT_Q32_ONE;
		kl.o.beta2 = 0;
		init_ok(&kl, MOT_INTERP_BETA);
		for (i = 0; i < 200; i++) {
			mot_q32 f = sample(&rng, &ks);

			tu_worst_add(&wb,
				     (double)(mot_curve_eval(&ks.c, NULL, f, NULL) -
					      mot_curve_eval(&kl.c, NULL, f, NULL)),
				     (double)ref_q(f));
		}
		/* no key ease: the warped frame would be rounded for beta only */
		for (i = 0; i < (int)ks.n; i++)
			ks.k[i].ease_in = ks.k[i].ease_out = kl.k[i].ease_in = kl.k[i].ease_out = 0;
		kl.o.beta1 = kl.o.beta2 = 0;
		init_ok(&kl, MOT_INTERP_BETA);
		init_ok(&ks, MOT_INTERP_LINEAR);
		for (i = 0; i < 200; i++) {
			mot_q32 f = sample(&rng, &ks);
			int it = mot_curve_newton_iterations(&kl.c, f);

			maxit = it > maxit ? it : maxit;
			tu_worst_add(&wl,
				     (double)(mot_curve_eval(&ks.c, NULL, f, NULL) -
					      mot_curve_eval(&kl.c, NULL, f, NULL)),
				     (double)ref_q(f));
		}
	}
	tu_bound("curve.beta_1_0_minus_bspline", &wb, 0, "LSB");
	tu_bound("curve.beta_0_0_minus_linear", &wl, 2, "LSB");
	printf("INFO curve.beta_0_0 newton iterations: max %d of 64\n", maxit);
}

/* Sequential playback with a cursor gives the random-access bits: a long
 * run of small steps across every key set, eased and not, then random jumps
 * (forward, backward, far) with the same cursor. */
static void test_sequential_random(void **state)
{
	static struct keyset ks;
	struct tu_rng rng;
	long differ = 0, evals = 0;
	int kind, set;

	tu_seed(&rng, 180);
	for (kind = 0; kind <= MOT_INTERP_BEZIER; kind++)
		for (set = 0; set < 4; set++) {
			struct mot_cursor cur = { 0, 0 };
			mot_q32 f0, fn, f, step;
			int i;

			gen(&rng, &ks, (enum mot_interp)kind, set >= 2);
			init_ok(&ks, (enum mot_interp)kind);
			f0 = ks.k[0].frame;
			fn = ks.k[ks.n - 1].frame;
			step = (fn - f0) / 100000 + 1;
			for (f = f0 - 1000 * step; f < fn + 1000 * step; f += step, evals++)
				differ += mot_curve_eval(&ks.c, &cur, f, NULL) !=
					  mot_curve_eval(&ks.c, NULL, f, NULL);
			for (i = 0; i < 20000; i++, evals++) {
				f = sample(&rng, &ks);
				differ += mot_curve_eval(&ks.c, &cur, f, NULL) !=
					  mot_curve_eval(&ks.c, NULL, f, NULL);
			}
			/* a foreign cursor is only a slow hint */
			cur.seg = cur.key = UINT32_MAX - 1;
			f = sample(&rng, &ks);
			differ += mot_curve_eval(&ks.c, &cur, f, NULL) !=
				  mot_curve_eval(&ks.c, NULL, f, NULL);
		}
	assert_true(evals > 2000000);
	assert_int_equal(differ, 0);
}

/* The portable build (MOT_NO_INT128, the armhf and Cortex-M path, compiled
 * in tests/curve_portable.c) against this one: every value and integral
 * bit for bit. */
static void test_portable(void **state)
{
	static struct keyset ks;
	struct tu_rng rng;
	long differ = 0;
	int kind, set, i;

	tu_seed(&rng, 190);
	for (kind = 0; kind <= MOT_INTERP_BEZIER; kind++)
		for (set = 0; set < 100; set++) {
			mot_q32 f[64], got[64];
			uint64_t hi[64], lo[64];

			gen(&rng, &ks, (enum mot_interp)kind, set % 2);
			if (kind <= MOT_INTERP_HERMITE && set % 2 == 0)
				ks.o.integral = true;
			init_ok(&ks, (enum mot_interp)kind);
			for (i = 0; i < 64; i++)
				f[i] = sample(&rng, &ks);
			assert_int_equal(cvp_eval(kind, ks.k, ks.n, &ks.o, f, got, 64), MOT_OK);
			for (i = 0; i < 64; i++)
				differ += got[i] != mot_curve_eval(&ks.c, NULL, f[i], NULL);
			if (!ks.o.integral)
				continue;
			assert_int_equal(cvp_integral(kind, ks.k, ks.n, f, hi, lo, 64), MOT_OK);
			for (i = 0; i < 64; i++) {
				mot_acc a;

				assert_int_equal(mot_curve_integral(&a, &ks.c, NULL, f[i], NULL),
						 MOT_OK);
				differ += hi[i] != mot_acc_hi(a) || lo[i] != mot_acc_lo(a);
			}
		}
	assert_int_equal(differ, 0);
}

/* ---- integrals ------------------------------------------------------------------ */

static ref_t acc_to_ref(mot_acc a)
{
	return (ref_t)(__int128)(((unsigned __int128)mot_acc_hi(a) << 64) | mot_acc_lo(a)) /
	       (LSB * LSB);
}

static __int128 acc_to_i128(mot_acc a)
{
	return (__int128)(((unsigned __int128)mot_acc_hi(a) << 64) | mot_acc_lo(a));
}

/*
 * Against the reference's closed form, relative to the size of the terms:
 * (|f| + |f(first)| + |f(last)|) x max |v(i)|. The reference's long double
 * resolves 2^-64 of that; step and linear are exact in the core (tested
 * below), Hermite's partial interval rounds its mean value once in a block
 * scale of its coefficients.
 */
static void test_integral_vs_ref(void **state)
{
	static struct keyset ks;
	struct tu_rng rng;
	struct tu_worst w[3] = { { 0, 0 }, { 0, 0 }, { 0, 0 } };
	int kind, set, i;

	tu_seed(&rng, 200);
	for (kind = 0; kind <= MOT_INTERP_HERMITE; kind++) {
		struct mot_cursor cur = { 0, 0 };

		for (set = 0; set < 300; set++) {
			ref_t vmax = 0, size;
			uint32_t j;

			gen(&rng, &ks, (enum mot_interp)kind, false);
			ks.o.integral = true;
			init_ok(&ks, (enum mot_interp)kind);
			for (j = 0; j < ks.n; j++)
				vmax = fmaxl(vmax, fabsl(ref_q(ks.k[j].value)));
			for (i = 0; i < 120; i++) {
				mot_q32 f = sample(&rng, &ks);
				mot_acc a;
				ref_t want;

				if (i % 3 == 0)
					f = (mot_q32)((double)f * tu_uniform(&rng, -2, 2));
				want = ref_curve_integral((enum mot_interp)kind, ks.k, ks.n,
							  ref_q(f));
				assert_int_equal(
					mot_curve_integral(&a, &ks.c, i % 2 ? &cur : NULL, f, NULL),
					MOT_OK);
				size = (fabsl(ref_q(f)) + fabsl(ref_q(ks.k[0].frame)) +
					fabsl(ref_q(ks.k[ks.n - 1].frame))) * vmax;
				tu_worst_add(&w[kind],
					     (double)((acc_to_ref(a) - want) / size * 0x1p60L),
					     (double)ref_q(f));
			}
		}
	}
	tu_bound("curve.integral_step_vs_ref", &w[0], 0.5, "2^-60 relative");
	tu_bound("curve.integral_linear_vs_ref", &w[1], 0.5, "2^-60 relative");
	tu_bound("curve.integral_hermite_vs_ref", &w[2], 16, "2^-60 relative");
}

/*
 * Exactness. On small key sets (frames < 2^8, values < 2^10, so that every
 * product fits __int128) the partial integral over a key interval,
 * P = I(f) - I(f(i)), is checked against the exact rational
 *   step:   e v(i)                       (equal)
 *   linear: e v(i) + dv e^2 / (2h)       (|2h P - 2h e v - dv e^2| <= h: half a unit)
 * in units of 2^-64 value x frames.
 */
static void test_integral_exact(void **state)
{
	static struct keyset ks;
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int kind, set, i;

	tu_seed(&rng, 210);
	for (kind = 0; kind <= MOT_INTERP_LINEAR; kind++)
		for (set = 0; set < 500; set++) {
			uint32_t j;

			ks.n = 2 + (uint32_t)(tu_u64(&rng) % 8);
			for (j = 0; j < ks.n; j++) {
				ks.k[j].frame =
					(j ? ks.k[j - 1].frame : -(mot_q32)(tu_u64(&rng) >> 30)) +
					1 + (mot_q32)(tu_u64(&rng) >> 34);
				ks.k[j].value = (mot_q32)(tu_u64(&rng) >> 22) - ((mot_q32)1 << 41);
				ks.k[j].ease_in = ks.k[j].ease_out = 0;
			}
			ks.o = (struct mot_curve_opts){ .integral = true };
			init_ok(&ks, (enum mot_interp)kind);
			for (i = 0; i < 200; i++) {
				mot_acc a, b;
				__int128 p, e, h, dv, v, lhs;

				j = (uint32_t)(tu_u64(&rng) % (ks.n - 1));
				h = ks.k[j + 1].frame - ks.k[j].frame;
				e = (__int128)(tu_u64(&rng) % (uint64_t)h);
				v = ks.k[j].value;
				dv = ks.k[j + 1].value - ks.k[j].value;
				assert_int_equal(mot_curve_integral(&a, &ks.c, NULL,
								    ks.k[j].frame + (mot_q32)e,
								    NULL),
						 MOT_OK);
				assert_int_equal(
					mot_curve_integral(&b, &ks.c, NULL, ks.k[j].frame, NULL),
					MOT_OK);
				p = acc_to_i128(a) - acc_to_i128(b);
				if (kind == MOT_INTERP_STEP) {
					assert_true(p == e * v);
					continue;
				}
				lhs = 2 * h * p - 2 * h * e * v - dv * e * e;
				tu_worst_add(&w, (double)lhs / (double)(2 * h), (double)j);
			}
		}
	tu_bound("curve.integral_linear_exact", &w, 0.5, "units of 2^-64 value x frames");
}

/*
 * Section 8's promise: 1200 rpm held for 24 hours at 60 frames/s after a
 * 10-second linear (and step) spin-up is exact. The integral in value x
 * frames is 1200 * 600 / 2 + 1200 * (f - 600) exactly (step: 0 over the
 * spin-up and 1200 after); for every kind the part after the last key is
 * 1200 * (f - f(last)) exactly. Also a constant strand everywhere, inside a
 * key interval too, and frames before 0 (negative integrals).
 */
static void test_integral_day(void **state)
{
	const mot_q32 day = MOT_Q32_INT(24 * 3600 * 60);
	struct mot_key k[3] = {
		{ 0, 0, 0, 0 },
		{ MOT_Q32_INT(600), MOT_Q32_INT(1200), 0, 0 },
		{ MOT_Q32_INT(700), MOT_Q32_INT(1200), 0, 0 },
	};
	struct mot_curve_opts o = { .integral = true };
	struct mot_curve_seg seg[3];
	struct mot_curve c;
	struct mot_cursor cur = { 0, 0 };
	mot_acc a;
	int kind;
	mot_q32 f;

	for (kind = MOT_INTERP_STEP; kind <= MOT_INTERP_HERMITE; kind++) {
		__int128 want = (__int128)1200 * (24 * 3600 * 60 - 600) +
				(kind == MOT_INTERP_STEP ? 0 : (__int128)1200 * 600 / 2);

		assert_int_equal(mot_curve_init(&c, (enum mot_interp)kind, k, 3, &o, seg, 3, NULL),
				 MOT_OK);
		assert_int_equal(mot_curve_integral(&a, &c, &cur, day, NULL), MOT_OK);
		/* (the Hermite spin-up has Catmull-Rom tangents: not this ramp) */
		if (kind != MOT_INTERP_HERMITE)
			assert_true(acc_to_i128(a) == want << 64);
		/* the hold after the last key, for every kind */
		{
			mot_acc b;

			assert_int_equal(mot_curve_integral(&b, &c, &cur, k[2].frame, NULL),
					 MOT_OK);
			assert_true(acc_to_i128(a) - acc_to_i128(b) ==
				    (__int128)1200 * (24 * 3600 * 60 - 700) << 64);
		}
		/* frame 0 integrates to exactly 0, frames before it go negative */
		assert_int_equal(mot_curve_integral(&a, &c, NULL, 0, NULL), MOT_OK);
		assert_true(acc_to_i128(a) == 0);
	}
	/* constant 1200 rpm from frame 10, everywhere exact, also at -1 day */
	k[0].frame = MOT_Q32_INT(10);
	k[0].value = MOT_Q32_INT(1200);
	for (kind = MOT_INTERP_STEP; kind <= MOT_INTERP_HERMITE; kind++) {
		assert_int_equal(mot_curve_init(&c, (enum mot_interp)kind, k, 3, &o, seg, 3, NULL),
				 MOT_OK);
		for (f = -day; f <= day; f += day / 1000 + 12345) {
			assert_int_equal(mot_curve_integral(&a, &c, &cur, f, NULL), MOT_OK);
			assert_true(acc_to_i128(a) == (__int128)1200 * f * ((__int128)1 << 32));
		}
	}
	/* a single key: the constant integrates linearly */
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_LINEAR, k, 1, &o, seg, 1, NULL), MOT_OK);
	assert_int_equal(mot_curve_integral(&a, &c, NULL, -day, NULL), MOT_OK);
	assert_true(acc_to_i128(a) == (__int128)1200 * -day * ((__int128)1 << 32));
}

/* ---- argument checks ---------------------------------------------------------------- */

static void test_errors(void **state)
{
	struct mot_key k[MOT_BEZIER_MAX_KEYS + 1];
	struct mot_curve_seg seg[MOT_BEZIER_MAX_KEYS + 2];
	struct mot_curve c;
	struct mot_curve_opts o = { MOT_Q32_ONE, 0, 0, 0, false, NULL, false };
	mot_acc a;
	uint32_t sat = 0, i;

	for (i = 0; i <= MOT_BEZIER_MAX_KEYS; i++) {
		k[i].frame = MOT_Q32_INT(i);
		k[i].value = MOT_Q32_INT(i % 3);
		k[i].ease_in = k[i].ease_out = 0;
	}
#define INIT(kind, n, nseg) mot_curve_init(&c, kind, k, n, &o, seg, nseg, NULL)
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_OK);
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 0, 3), MOT_E_NOKEYS);
	assert_int_equal(mot_curve_seg_count(MOT_INTERP_LINEAR, 0), 0);
	/* a failed init leaves a curve that evaluates to 0 and says so */
	assert_int_equal(mot_curve_eval(&c, NULL, 0, &sat), 0);
	assert_true(sat & MOT_SAT_DOMAIN);
	assert_int_equal(mot_curve_init(&c, (enum mot_interp)6, k, 4, &o, seg, 9, NULL),
			 MOT_E_INVAL);
	assert_int_equal(mot_curve_seg_count((enum mot_interp)6, 4), 0);
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_LINEAR, NULL, 4, &o, seg, 9, NULL),
			 MOT_E_INVAL);
	assert_int_equal(mot_curve_init(NULL, MOT_INTERP_LINEAR, k, 4, &o, seg, 9, NULL),
			 MOT_E_INVAL);
	/* capacity */
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 2), MOT_E_CAPACITY);
	assert_int_equal(INIT(MOT_INTERP_BSPLINE, 4, 4), MOT_E_CAPACITY);
	assert_int_equal(INIT(MOT_INTERP_BSPLINE, 4, 5), MOT_OK);
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_STEP, k, 4, &o, NULL, 9, NULL),
			 MOT_E_CAPACITY);
	assert_int_equal(INIT(MOT_INTERP_BEZIER, MOT_BEZIER_MAX_KEYS, MOT_BEZIER_MAX_KEYS),
			 MOT_OK);
	assert_int_equal(INIT(MOT_INTERP_BEZIER, MOT_BEZIER_MAX_KEYS + 1, MOT_BEZIER_MAX_KEYS + 2),
			 MOT_E_CAPACITY);
	/* order */
	k[2].frame = k[1].frame;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_E_ORDER);
	k[2].frame = k[1].frame - 1;
	assert_int_equal(INIT(MOT_INTERP_HERMITE, 4, 3), MOT_E_ORDER);
	k[2].frame = MOT_Q32_INT(2);
	/* range: |frame|, |value| below 2^30 */
	k[3].frame = MOT_LEN_LIMIT;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_E_RANGE);
	k[3].frame = MOT_Q32_INT(3);
	k[0].value = -MOT_LEN_LIMIT;
	assert_int_equal(INIT(MOT_INTERP_BSPLINE, 4, 5), MOT_E_RANGE);
	k[0].value = MOT_Q32_MIN;
	assert_int_equal(INIT(MOT_INTERP_BSPLINE, 4, 5), MOT_E_RANGE);
	k[0].value = MOT_LEN_LIMIT - 1;
	k[1].value = -MOT_LEN_LIMIT + 1;
	assert_int_equal(INIT(MOT_INTERP_HERMITE, 4, 3), MOT_OK);
	k[0].value = 0;
	k[1].value = MOT_Q32_ONE;
	/* ease fractions */
	k[1].ease_out = -1;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_E_INVAL);
	k[1].ease_out = MOT_Q32_ONE + 1;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_E_INVAL);
	k[1].ease_out = MOT_Q32_HALF;
	k[2].ease_in = MOT_Q32_HALF + 1;
	assert_int_equal(INIT(MOT_INTERP_BEZIER, 4, 3), MOT_E_INVAL);
	k[2].ease_in = MOT_Q32_HALF;
	assert_int_equal(INIT(MOT_INTERP_BEZIER, 4, 3), MOT_OK);
	/* ... and with an integral */
	o.integral = true;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_E_INVAL);
	k[1].ease_out = k[2].ease_in = 0;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_OK);
	assert_int_equal(INIT(MOT_INTERP_BSPLINE, 4, 5), MOT_E_INVAL);
	assert_int_equal(INIT(MOT_INTERP_BEZIER, 4, 3), MOT_E_INVAL);
	o.ease_in_frames = MOT_Q32_ONE;
	assert_int_equal(INIT(MOT_INTERP_HERMITE, 4, 3), MOT_E_INVAL);
	o.integral = false;
	assert_int_equal(INIT(MOT_INTERP_HERMITE, 4, 3), MOT_OK);
	assert_int_equal(mot_curve_integral(&a, &c, NULL, 0, NULL), MOT_E_INVAL);
	assert_int_equal(mot_curve_integral(NULL, &c, NULL, 0, NULL), MOT_E_INVAL);
	/* strand ease: non-negative, in + out within the span (3 frames) */
	o.ease_in_frames = -1;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_E_INVAL);
	o.ease_in_frames = MOT_Q32_INT(2);
	o.ease_out_frames = MOT_Q32_INT(1);
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_OK);
	o.ease_out_frames = MOT_Q32_INT(1) + 1;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_E_INVAL);
	o.ease_in_frames = MOT_Q32_MAX;
	o.ease_out_frames = MOT_Q32_MAX;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 4, 3), MOT_E_INVAL);
	o.ease_in_frames = MOT_Q32_ONE;
	o.ease_out_frames = 0;
	assert_int_equal(INIT(MOT_INTERP_LINEAR, 1, 1), MOT_E_INVAL); /* span 0 */
	o.ease_in_frames = 0;
	/* beta shape */
	o.beta1 = -1;
	assert_int_equal(INIT(MOT_INTERP_BETA, 4, 5), MOT_E_INVAL);
	assert_int_equal(INIT(MOT_INTERP_BSPLINE, 4, 5), MOT_OK); /* not used there */
	o.beta1 = MOT_BETA1_MAX + 1;
	assert_int_equal(INIT(MOT_INTERP_BETA, 4, 5), MOT_E_INVAL);
	o.beta1 = MOT_BETA1_MAX;
	o.beta2 = MOT_BETA2_MAX;
	assert_int_equal(INIT(MOT_INTERP_BETA, 4, 5), MOT_OK);
	o.beta2 = -1;
	assert_int_equal(INIT(MOT_INTERP_BETA, 4, 5), MOT_E_INVAL);
	o.beta2 = MOT_BETA2_MAX + 1;
	assert_int_equal(INIT(MOT_INTERP_BETA, 4, 5), MOT_E_INVAL);
	o.beta1 = 0;
	o.beta2 = 0;
	assert_int_equal(INIT(MOT_INTERP_BETA, 4, 5), MOT_OK);
#undef INIT
	/* NULL opts are the defaults; one key is a constant for every kind */
	for (i = 0; i <= MOT_INTERP_BEZIER; i++) {
		assert_int_equal(mot_curve_seg_count((enum mot_interp)i, 1), 1);
		assert_int_equal(mot_curve_init(&c, (enum mot_interp)i, k, 1, NULL, seg, 1, NULL),
				 MOT_OK);
		assert_int_equal(mot_curve_eval(&c, NULL, MOT_Q32_INT(-5), NULL), k[0].value);
		assert_int_equal(mot_curve_eval(&c, NULL, MOT_Q32_INT(5), NULL), k[0].value);
	}
}

/* Extreme but valid key sets evaluate without saturating, trapping or
 * reading out of bounds (the sanitizers watch): values and frames at the
 * limits, a key gap of one LSB next to one of 2^31 frames, the largest
 * beta1 and beta2. */
static void test_extremes(void **state)
{
	struct mot_key k[5];
	struct mot_curve_seg seg[6];
	struct mot_curve c;
	struct mot_curve_opts o = { MOT_BETA1_MAX, MOT_BETA2_MAX, 0, 0, false, NULL, false };
	struct tu_rng rng;
	int kind, i;

	tu_seed(&rng, 220);
	k[0] = (struct mot_key){ -MOT_LEN_LIMIT + 1, MOT_LEN_LIMIT - 1, 0, 0 };
	k[1] = (struct mot_key){ -MOT_LEN_LIMIT + 2, -MOT_LEN_LIMIT + 1, 0, 0 };
	k[2] = (struct mot_key){ 0, MOT_LEN_LIMIT - 1, 0, MOT_Q32_HALF };
	k[3] = (struct mot_key){ MOT_LEN_LIMIT - 2, -MOT_LEN_LIMIT + 1, MOT_Q32_HALF, 0 };
	k[4] = (struct mot_key){ MOT_LEN_LIMIT - 1, 0, 0, 0 };
	for (kind = 0; kind <= MOT_INTERP_BEZIER; kind++) {
		uint32_t sat = 0;

		assert_int_equal(mot_curve_init(&c, (enum mot_interp)kind, k, 5, &o, seg, 6, &sat),
				 MOT_OK);
		for (i = 0; i < 20000; i++) {
			mot_q32 f = (mot_q32)tu_u64(&rng) >> 1;

			if (i % 4 == 0)
				f = k[i / 4 % 5].frame + (mot_q32)(tu_u64(&rng) % 64) - 32;
			(void)mot_curve_eval(&c, NULL, f, &sat);
		}
		assert_int_equal(sat, 0);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_step),
		cmocka_unit_test(test_linear),
		cmocka_unit_test(test_hermite),
		cmocka_unit_test(test_bspline),
		cmocka_unit_test(test_beta),
		cmocka_unit_test(test_bezier),
		cmocka_unit_test(test_bezier_max),
		cmocka_unit_test(test_bezier_power),
		cmocka_unit_test(test_newton_adversarial),
		cmocka_unit_test(test_through_keys),
		cmocka_unit_test(test_convex_hull),
		cmocka_unit_test(test_bound_dense),
		cmocka_unit_test(test_hermite_overshoot),
		cmocka_unit_test(test_beta_limits),
		cmocka_unit_test(test_sequential_random),
		cmocka_unit_test(test_portable),
		cmocka_unit_test(test_integral_vs_ref),
		cmocka_unit_test(test_integral_exact),
		cmocka_unit_test(test_integral_day),
		cmocka_unit_test(test_errors),
		cmocka_unit_test(test_extremes),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
