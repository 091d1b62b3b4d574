/* SPDX-License-Identifier: MIT */
/*
 * test_mat.c - motion/mat.c against the double reference (tests/ref_mat.c)
 * and against exact __int128 sums: rotations, products, point transforms,
 * determinant and inverse, and the editing operations of the seed paper's
 * section 4 checked by their properties.
 *
 * Length errors are in metres: ref_point_diff() is the worst displacement of
 * a point of the +-100 m cube between the fixed-point and the reference
 * transform.
 */
#include <string.h>

#include "motion/trig.h"
#include "ref_mat.h"

#define N 100000
#define LSB (1.0 / 4294967296.0)
#define REACH 100.0 /* m */

typedef __int128 i128;

/* round(sum a[i] b[i] / 2^32) exactly, saturated, without the code under
 * test: S = H 2^64 + L with H the sum of the high words, L of the low. */
static mot_q32 exact_sum(const int64_t *a, const int64_t *b, int n, int *ovf)
{
	i128 h = 0, l = 0, r;
	int i;

	for (i = 0; i < n; i++) {
		i128 p = (i128)a[i] * b[i];

		h += p >> 64;
		l += (i128)(uint64_t)p;
	}
	r = h * ((i128)1 << 32) + ((l + ((i128)1 << 31)) >> 32);
	*ovf = r > INT64_MAX || r < INT64_MIN;
	if (*ovf)
		return r > 0 ? INT64_MAX : INT64_MIN;
	return (mot_q32)r;
}

static void exact_mul(struct mot_mat *out, const struct mot_mat *a, const struct mot_mat *b,
		      int *ovf)
{
	int i, j, o;

	*ovf = 0;
	for (i = 0; i < 4; i++)
		for (j = 0; j < 3; j++) {
			int64_t x[4] = { a->m[i][0], a->m[i][1], a->m[i][2], b->m[3][j] };
			int64_t y[4] = { b->m[0][j], b->m[1][j], b->m[2][j], MOT_Q32_ONE };

			out->m[i][j] = exact_sum(x, y, i == 3 ? 4 : 3, &o);
			*ovf |= o;
		}
}

static void rand_affine(struct mot_mat *m, struct tu_rng *r)
{
	struct ref_mat d;

	ref_rand_affine(&d, r, 0.01, 100, 1, REACH, true);
	ref_to_mat(m, &d);
}

/* an editing increment: scales 0.5..2, shears +-0.5, a rotation, t +-1 m */
static void rand_delta(struct mot_mat *m, struct tu_rng *r)
{
	struct ref_mat d;

	ref_rand_affine(&d, r, 0.5, 2, 0.5, 1, false);
	ref_to_mat(m, &d);
}

static void rand_point(mot_q32 p[3], double pd[3], struct tu_rng *r, double reach)
{
	int i;

	for (i = 0; i < 3; i++) {
		p[i] = d2q(tu_uniform(r, -reach, reach));
		pd[i] = q2d(p[i]);
	}
}

static double vec_diff(const mot_q32 a[3], const double b[3])
{
	return fmax(fmax(fabs(q2d(a[0]) - b[0]), fabs(q2d(a[1]) - b[1])), fabs(q2d(a[2]) - b[2]));
}

/* the exact phase of a Q32.32 turn count, in radians */
static double phase_rad(mot_q32 turns)
{
	return (double)(uint32_t)turns / 4294967296.0 * 2 * M_PI;
}

static void test_structure(void **state)
{
	const mot_q32 one = MOT_Q32_ONE, quarter = MOT_Q32_ONE / 4;
	const mot_q32 ex[3] = { one, 0, 0 }, ey[3] = { 0, one, 0 }, ez[3] = { 0, 0, one };
	const mot_q32 t[3] = { 1, -2, 3 }, s[3] = { 2 * one, 3 * one, -one }, h[3] = { 5, 6, 7 };
	struct mot_mat m;
	mot_q32 v[3];
	uint32_t sat = 0;

	mot_mat_rot_z(&m, quarter);
	mot_mat_apply(v, ex, &m, &sat);
	assert_true(v[0] == 0 && v[1] == one && v[2] == 0);
	mot_mat_rot_x(&m, quarter);
	mot_mat_apply(v, ey, &m, &sat);
	assert_true(v[0] == 0 && v[1] == 0 && v[2] == one);
	mot_mat_rot_y(&m, quarter);
	mot_mat_apply(v, ez, &m, &sat);
	assert_true(v[0] == one && v[1] == 0 && v[2] == 0);

	mot_mat_translate(&m, t);
	mot_mat_apply(v, ex, &m, &sat);
	assert_true(v[0] == one + 1 && v[1] == -2 && v[2] == 3);
	mot_mat_apply_dir(v, ex, &m, &sat);
	assert_true(v[0] == one && v[1] == 0 && v[2] == 0);
	mot_mat_scale(&m, s);
	mot_mat_apply(v, ez, &m, &sat);
	assert_true(v[0] == 0 && v[1] == 0 && v[2] == -one);
	mot_mat_shear(&m, h);
	assert_true(m.m[1][0] == 5 && m.m[2][0] == 6 && m.m[2][1] == 7 && m.m[0][1] == 0);
	assert_true(m.m[0][0] == one && m.m[1][1] == one && m.m[2][2] == one);
	mot_mat_identity(&m);
	mot_mat_apply(v, t, &m, &sat);
	assert_true(v[0] == 1 && v[1] == -2 && v[2] == 3);
	assert_int_equal(sat, 0);
}

static void test_rot_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int i, ax;

	tu_seed(&rng, 11);
	for (i = 0; i < N; i++) {
		mot_q32 turns = (mot_q32)(tu_u64(&rng) >> 20) - ((mot_q32)1 << 43); /* +-2048 turns */
		double a = phase_rad(turns);
		struct mot_mat m;
		struct ref_mat f, r;

		for (ax = 0; ax < 3; ax++) {
			if (ax == 0) {
				mot_mat_rot_x(&m, turns);
				ref_rot_x(&r, a);
			} else if (ax == 1) {
				mot_mat_rot_y(&m, turns);
				ref_rot_y(&r, a);
			} else {
				mot_mat_rot_z(&m, turns);
				ref_rot_z(&r, a);
			}
			ref_from_mat(&f, &m);
			tu_worst_add(&w, ref_lin_diff(&f, &r), q2d(turns));
		}
	}
	tu_bound("mat.rot_xyz entry", &w, 3e-10, "(1)");
}

static void test_euler_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int i, k;

	tu_seed(&rng, 12);
	for (i = 0; i < N; i++) {
		mot_q32 e[3];
		double a[3];
		struct mot_mat m;
		struct ref_mat f, r;
		uint32_t sat = 0;

		for (k = 0; k < 3; k++) {
			e[k] = d2q(tu_uniform(&rng, -1.5, 1.5));
			a[k] = phase_rad(e[k]);
		}
		mot_mat_euler(&m, e, &sat);
		ref_euler(&r, a[0], a[1], a[2]);
		ref_from_mat(&f, &m);
		tu_worst_add(&w, ref_lin_diff(&f, &r), q2d(e[0]));
		assert_int_equal(sat, 0);
	}
	tu_bound("mat.euler entry", &w, 1e-9, "(1)");
}

static void test_rot_axis_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wx = { 0, 0 };
	int i, k;

	tu_seed(&rng, 13);
	for (i = 0; i < N; i++) {
		double ad[3];
		mot_q32 axis[3], turns = d2q(tu_uniform(&rng, -3, 3));
		const mot_q32 ex[3] = { MOT_Q32_ONE, 0, 0 };
		struct mot_mat m, mx;
		struct ref_mat f, r, fx;
		struct ref_quat q;
		uint32_t sat = 0;

		ref_rand_axis(ad, &rng);
		for (k = 0; k < 3; k++) {
			axis[k] = d2q(ad[k]);
			ad[k] = q2d(axis[k]);
		}
		mot_mat_rot_axis(&m, axis, turns, &sat);
		ref_quat_axis_angle(&q, ad, q2d(turns) * 2 * M_PI);
		ref_quat_to_mat(&r, &q);
		ref_from_mat(&f, &m);
		tu_worst_add(&w, ref_lin_diff(&f, &r), q2d(turns));
		/* about x it is Rx, up to the half-angle rounding */
		mot_mat_rot_axis(&m, ex, turns, &sat);
		mot_mat_rot_x(&mx, turns);
		ref_from_mat(&f, &m);
		ref_from_mat(&fx, &mx);
		tu_worst_add(&wx, ref_lin_diff(&f, &fx), q2d(turns));
		assert_int_equal(sat, 0);
	}
	tu_bound("mat.rot_axis entry", &w, 3e-9, "(1)");
	tu_bound("mat.rot_axis(x) vs rot_x entry", &wx, 2e-9, "(1)");
}

static void test_mul_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	long inexact = 0;
	int i;

	tu_seed(&rng, 14);
	for (i = 0; i < N; i++) {
		struct mot_mat a, b, m, x;
		struct ref_mat ra, rb, r, f;
		uint32_t sat = 0;
		int ovf;

		rand_affine(&a, &rng);
		rand_affine(&b, &rng);
		mot_mat_mul(&m, &a, &b, &sat);
		exact_mul(&x, &a, &b, &ovf);
		inexact += memcmp(&m, &x, sizeof(m)) != 0;
		ref_from_mat(&ra, &a);
		ref_from_mat(&rb, &b);
		ref_mul(&r, &ra, &rb);
		ref_from_mat(&f, &m);
		tu_worst_add(&w, ref_point_diff(&f, &r, REACH), i);
		assert_int_equal(sat, 0);
	}
	assert_int_equal(inexact, 0);
	tu_bound("mat.mul point (S.H.R.T, s 0.01..100, t +-100 m)", &w, 1e-7, "m");
}

static void test_mul_extreme(void **state)
{
	struct tu_rng rng;
	long bad = 0;
	int i, j, k;
	struct mot_mat a, b, m;
	uint32_t sat = 0;

	tu_seed(&rng, 15);
	for (i = 0; i < N; i++) {
		struct mot_mat x;
		int ovf;

		for (j = 0; j < 4; j++)
			for (k = 0; k < 3; k++) {
				a.m[j][k] = tu_i64(&rng);
				b.m[j][k] = tu_i64(&rng);
			}
		sat = 0;
		mot_mat_mul(&m, &a, &b, &sat);
		exact_mul(&x, &a, &b, &ovf);
		bad += memcmp(&m, &x, sizeof(m)) != 0 || (sat != 0) != ovf;
	}
	assert_int_equal(bad, 0);
	/* three products of 2^126 wrap a plain 128-bit sum to -2^126: the
	 * result must still saturate upward */
	for (j = 0; j < 4; j++)
		for (k = 0; k < 3; k++)
			a.m[j][k] = b.m[j][k] = MOT_Q32_MIN;
	sat = 0;
	mot_mat_mul(&m, &a, &b, &sat);
	assert_true(m.m[0][0] == MOT_Q32_MAX && m.m[3][2] == MOT_Q32_MAX);
	assert_true(sat & MOT_SAT_OVERFLOW);
}

static void test_mul_alias(void **state)
{
	struct tu_rng rng;
	struct mot_mat a, b, ab, aa, t;
	int i;

	tu_seed(&rng, 16);
	for (i = 0; i < 1000; i++) {
		rand_affine(&a, &rng);
		rand_affine(&b, &rng);
		mot_mat_mul(&ab, &a, &b, NULL);
		mot_mat_mul(&aa, &a, &a, NULL);
		t = a;
		mot_mat_mul(&t, &t, &b, NULL);
		assert_memory_equal(&t, &ab, sizeof(t));
		t = b;
		mot_mat_mul(&t, &a, &t, NULL);
		assert_memory_equal(&t, &ab, sizeof(t));
		t = a;
		mot_mat_mul(&t, &t, &t, NULL);
		assert_memory_equal(&t, &aa, sizeof(t));
	}
}

static void test_apply_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wd = { 0, 0 };
	long inexact = 0;
	int i, j;

	tu_seed(&rng, 17);
	for (i = 0; i < N; i++) {
		struct mot_mat m;
		struct ref_mat r;
		mot_q32 p[3], out[3], dir[3];
		double pd[3], o[3];
		uint32_t sat = 0;

		rand_affine(&m, &rng);
		ref_from_mat(&r, &m);
		rand_point(p, pd, &rng, REACH);
		mot_mat_apply(out, p, &m, &sat);
		mot_mat_apply_dir(dir, p, &m, &sat);
		ref_apply(o, pd, &r);
		tu_worst_add(&w, vec_diff(out, o), i);
		ref_apply_dir(o, pd, &r);
		tu_worst_add(&wd, vec_diff(dir, o), i);
		for (j = 0; j < 3; j++) {
			int64_t x[4] = { p[0], p[1], p[2], m.m[3][j] };
			int64_t y[4] = { m.m[0][j], m.m[1][j], m.m[2][j], MOT_Q32_ONE };
			int ovf;

			inexact += out[j] != exact_sum(x, y, 4, &ovf);
			inexact += dir[j] != exact_sum(x, y, 3, &ovf);
		}
		mot_mat_apply(p, p, &m, &sat); /* in place */
		inexact += memcmp(p, out, sizeof(out)) != 0;
		assert_int_equal(sat, 0);
	}
	assert_int_equal(inexact, 0);
	tu_bound("mat.apply point (+-100 m)", &w, 2e-10, "m");
	tu_bound("mat.apply_dir (+-100 m)", &wd, 2e-10, "m");
}

static void test_inverse_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wr = { 0, 0 }, wdet = { 0, 0 };
	int i;

	tu_seed(&rng, 18);
	for (i = 0; i < N; i++) {
		struct mot_mat m, mr, inv, mi, id;
		struct ref_mat r, rinv, f, fi;
		uint32_t sat = 0;
		long double det;

		rand_affine(&m, &rng);
		ref_from_mat(&r, &m);
		assert_int_equal(mot_mat_inverse(&inv, &m, &sat), MOT_OK);
		assert_int_equal(ref_inverse(&rinv, &r), 0);
		ref_from_mat(&f, &inv);
		tu_worst_add(&w, ref_point_diff(&f, &rinv, REACH), i);
		/* M . M^-1 = I for moderate conditioning (scales 0.1..10); the
		 * error grows with |M| |M^-1|, not with the inverse's own error */
		ref_rand_affine(&r, &rng, 0.1, 10, 1, REACH, true);
		ref_to_mat(&mr, &r);
		assert_int_equal(mot_mat_inverse(&inv, &mr, &sat), MOT_OK);
		mot_mat_mul(&mi, &mr, &inv, &sat);
		mot_mat_identity(&id);
		ref_from_mat(&f, &mi);
		ref_from_mat(&fi, &id);
		tu_worst_add(&wr, ref_point_diff(&f, &fi, REACH), i);
		ref_from_mat(&r, &m);
		det = ref_det3(&r);
		tu_worst_add(&wdet, (double)(((long double)mot_mat_det(&m, &sat) - det * 4294967296.0L)),
			     (double)det);
		assert_int_equal(sat, 0);
	}
	tu_bound("mat.inverse point (s 0.01..100, t +-100 m)", &w, 2e-7, "m");
	tu_bound("mat.mul(M, inverse) point vs identity (s 0.1..10)", &wr, 1e-6, "m");
	tu_bound("mat.det (rounded once)", &wdet, 0.501, "LSB");
}

static void test_inverse_singular(void **state)
{
	const mot_q32 one = MOT_Q32_ONE;
	struct mot_mat m, out, sentinel;
	struct ref_mat f, fi;
	uint32_t sat = 0;
	int i, j;

	memset(&sentinel, 0x5a, sizeof(sentinel));
	/* a zero scale */
	mot_mat_scale(&m, (const mot_q32[3]){ one, 0, one });
	out = sentinel;
	assert_int_equal(mot_mat_inverse(&out, &m, &sat), MOT_E_SINGULAR);
	assert_memory_equal(&out, &sentinel, sizeof(out));
	/* dependent rows */
	mot_mat_identity(&m);
	m.m[2][0] = 3 * one, m.m[2][1] = -2 * one, m.m[2][2] = 0;
	m.m[1][0] = -3 * one, m.m[1][1] = 2 * one, m.m[1][2] = 0;
	assert_int_equal(mot_mat_inverse(&out, &m, &sat), MOT_E_SINGULAR);
	assert_memory_equal(&out, &sentinel, sizeof(out));
	assert_int_equal(mot_mat_det(&m, &sat), 0);
	/* 1/scale at the limit of 2^30: rejected at 2^-30, exact at 2^-29 */
	mot_mat_scale(&m, (const mot_q32[3]){ one, 4, one });
	assert_int_equal(mot_mat_inverse(&out, &m, &sat), MOT_E_SINGULAR);
	mot_mat_scale(&m, (const mot_q32[3]){ one, 8, -one });
	assert_int_equal(mot_mat_inverse(&out, &m, &sat), MOT_OK);
	assert_true(out.m[1][1] == (mot_q32)1 << 61 && out.m[2][2] == -one && out.m[0][0] == one);
	assert_int_equal(sat, 0);
	/* determinants with entries beyond 2^30 (halved inside), and one that
	 * cannot fit */
	mot_mat_scale(&m, (const mot_q32[3]){ MOT_Q32_MAX, one, 2 });
	assert_int_equal(mot_mat_det(&m, &sat), one);
	mot_mat_scale(&m, (const mot_q32[3]){ MOT_Q32_MIN, one / 2, 4 });
	assert_int_equal(mot_mat_det(&m, &sat), -one);
	assert_int_equal(sat, 0);
	mot_mat_scale(&m, (const mot_q32[3]){ MOT_Q32_MIN, MOT_Q32_MAX, one });
	assert_int_equal(mot_mat_det(&m, &sat), MOT_Q32_MIN);
	assert_true(sat & MOT_SAT_OVERFLOW);
	sat = 0;
	/* entries near the top of the range: no trap, and the inverse (entries
	 * of a few LSB) is the reference's within an LSB */
	for (i = 0; i < 4; i++)
		for (j = 0; j < 3; j++)
			m.m[i][j] = i == j ? MOT_Q32_MAX - i : (mot_q32)1 << (40 + i + j);
	assert_int_equal(mot_mat_inverse(&out, &m, &sat), MOT_OK);
	ref_from_mat(&f, &m);
	assert_int_equal(ref_inverse(&fi, &f), 0);
	ref_from_mat(&f, &out);
	assert_true(ref_lin_diff(&f, &fi) <= LSB);
	for (j = 0; j < 3; j++)
		assert_true(fabs(f.m[3][j] - fi.m[3][j]) <= 4 * LSB);
	assert_int_equal(sat, 0);
}

/* (p, 1) . M as doubles */
static void ref_point(double out[3], const mot_q32 p[3], const struct mot_mat *m)
{
	struct ref_mat r;
	double pd[3] = { q2d(p[0]), q2d(p[1]), q2d(p[2]) };

	ref_from_mat(&r, m);
	ref_apply(out, pd, &r);
}

static void rand_rotation(struct mot_mat *d, struct tu_rng *rng)
{
	struct ref_quat q;
	struct ref_mat r;

	ref_rand_quat(&q, rng);
	ref_quat_to_mat(&r, &q);
	ref_to_mat(d, &r);
}

static void test_edit_local(void **state)
{
	struct tu_rng rng;
	struct tu_worst wp = { 0, 0 }, w = { 0, 0 };
	int i;

	tu_seed(&rng, 19);
	for (i = 0; i < N; i++) {
		struct mot_mat m, d, e;
		struct ref_mat rm, rd, tp, tn, tt, x, f;
		mot_q32 p[3], t[3];
		double pd[3], td[3], a[3], b[3];
		uint32_t sat = 0;

		rand_affine(&m, &rng);
		rand_point(p, pd, &rng, 10);
		/* a pure rotation leaves the pivot where it was */
		rand_rotation(&d, &rng);
		e = m;
		mot_mat_edit_local(&e, &d, p, &sat);
		ref_point(a, p, &m);
		ref_point(b, p, &e);
		tu_worst_add(&wp, fmax(fmax(fabs(a[0] - b[0]), fabs(a[1] - b[1])), fabs(a[2] - b[2])),
			     i);
		/* with scale and translation, against T(-p).D.T(p).T(t).M */
		rand_delta(&d, &rng);
		rand_point(t, td, &rng, 1);
		d.m[3][0] = t[0], d.m[3][1] = t[1], d.m[3][2] = t[2];
		e = m;
		mot_mat_edit_local(&e, &d, p, &sat);
		ref_from_mat(&rm, &m);
		ref_from_mat(&rd, &d);
		rd.m[3][0] = rd.m[3][1] = rd.m[3][2] = 0;
		ref_translate(&tn, -pd[0], -pd[1], -pd[2]);
		ref_translate(&tp, pd[0], pd[1], pd[2]);
		ref_translate(&tt, td[0], td[1], td[2]);
		ref_mul(&x, &tn, &rd);
		ref_mul(&x, &x, &tp);
		ref_mul(&x, &x, &tt);
		ref_mul(&x, &x, &rm);
		ref_from_mat(&f, &e);
		tu_worst_add(&w, ref_point_diff(&f, &x, REACH), i);
		assert_int_equal(sat, 0);
	}
	tu_bound("mat.edit_local rotation keeps the pivot", &wp, 5e-8, "m");
	tu_bound("mat.edit_local point vs T(-p).D.T(p).T(t).M", &w, 1e-7, "m");
}

static void test_edit_world(void **state)
{
	struct tu_rng rng;
	struct tu_worst wp = { 0, 0 }, w = { 0, 0 };
	int i, k;

	tu_seed(&rng, 20);
	for (i = 0; i < N; i++) {
		struct mot_mat m, d, e;
		struct ref_mat rm, rd, tw, tn, tt, x, f;
		mot_q32 wv[3], q[3], t[3];
		double wd[3], qd[3], td[3], a[3], b[3], s = tu_uniform(&rng, 0.5, 0.99);
		uint32_t sat = 0;

		rand_affine(&m, &rng);
		rand_point(wv, wd, &rng, REACH);
		rand_point(q, qd, &rng, 1);
		/* a uniform scale s about the world pivot pulls every point
		 * toward it: |q.M' - w| = s |q.M - w|, direction kept */
		mot_mat_scale(&d, (const mot_q32[3]){ d2q(s), d2q(s), d2q(s) });
		e = m;
		mot_mat_edit_world(&e, &d, wv, &sat);
		ref_point(a, q, &m);
		ref_point(b, q, &e);
		for (k = 0; k < 3; k++)
			tu_worst_add(&wp, (b[k] - wd[k]) - q2d(d2q(s)) * (a[k] - wd[k]), s);
		/* against M.T(t).T(-w).D.T(w) */
		rand_delta(&d, &rng);
		rand_point(t, td, &rng, 1);
		d.m[3][0] = t[0], d.m[3][1] = t[1], d.m[3][2] = t[2];
		e = m;
		mot_mat_edit_world(&e, &d, wv, &sat);
		ref_from_mat(&rm, &m);
		ref_from_mat(&rd, &d);
		rd.m[3][0] = rd.m[3][1] = rd.m[3][2] = 0;
		ref_translate(&tn, -wd[0], -wd[1], -wd[2]);
		ref_translate(&tw, wd[0], wd[1], wd[2]);
		ref_translate(&tt, td[0], td[1], td[2]);
		ref_mul(&x, &rm, &tt);
		ref_mul(&x, &x, &tn);
		ref_mul(&x, &x, &rd);
		ref_mul(&x, &x, &tw);
		ref_from_mat(&f, &e);
		tu_worst_add(&w, ref_point_diff(&f, &x, REACH), i);
		assert_int_equal(sat, 0);
	}
	tu_bound("mat.edit_world scale pulls toward the world pivot", &wp, 2e-9, "m");
	tu_bound("mat.edit_world point vs M.T(t).T(-w).D.T(w)", &w, 1e-7, "m");
}

static void test_switch_space(void **state)
{
	struct tu_rng rng;
	struct tu_worst wl = { 0, 0 }, ww = { 0, 0 }, wa = { 0, 0 };
	long bad = 0;
	int i;

	tu_seed(&rng, 21);
	for (i = 0; i < N; i++) {
		struct mot_mat m, l, drawn, back;
		struct ref_mat rm, f, tn, tp, x;
		mot_q32 p[3];
		double pd[3];
		uint32_t sat = 0;

		rand_affine(&m, &rng);
		rand_point(p, pd, &rng, REACH);
		/* world -> local: the local matrix drawn about the pivot,
		 * T(-p).M'.T(p), is the world matrix drawn as it is */
		l = m;
		mot_mat_to_local(&l, p, &sat);
		mot_mat_about_pivot(&drawn, &l, p, &sat);
		ref_from_mat(&rm, &m);
		ref_from_mat(&f, &drawn);
		tu_worst_add(&wl, ref_point_diff(&f, &rm, REACH), i);
		/* and back to world: where it started */
		back = l;
		mot_mat_to_world(&back, p, &sat);
		ref_from_mat(&f, &back);
		tu_worst_add(&ww, ref_point_diff(&f, &rm, REACH), i);
		bad += memcmp(back.m, m.m, sizeof(m.m[0]) * 3) != 0; /* linear part untouched */
		/* about_pivot against T(-p).M.T(p) */
		mot_mat_about_pivot(&drawn, &m, p, &sat);
		ref_translate(&tn, -pd[0], -pd[1], -pd[2]);
		ref_translate(&tp, pd[0], pd[1], pd[2]);
		ref_mul(&x, &tn, &rm);
		ref_mul(&x, &x, &tp);
		ref_from_mat(&f, &drawn);
		tu_worst_add(&wa, ref_point_diff(&f, &x, REACH), i);
		assert_int_equal(sat, 0);
	}
	assert_int_equal(bad, 0);
	tu_bound("mat.to_local drawn about the pivot = M", &wl, 2e-10, "m");
	tu_bound("mat.to_world(to_local(M)) = M", &ww, 2e-10, "m");
	tu_bound("mat.about_pivot vs T(-p).M.T(p)", &wa, 2e-10, "m");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_structure),   cmocka_unit_test(test_rot_ref),
		cmocka_unit_test(test_euler_ref),   cmocka_unit_test(test_rot_axis_ref),
		cmocka_unit_test(test_mul_ref),     cmocka_unit_test(test_mul_extreme),
		cmocka_unit_test(test_mul_alias),   cmocka_unit_test(test_apply_ref),
		cmocka_unit_test(test_inverse_ref), cmocka_unit_test(test_inverse_singular),
		cmocka_unit_test(test_edit_local),  cmocka_unit_test(test_edit_world),
		cmocka_unit_test(test_switch_space),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
