/* SPDX-License-Identifier: MIT */
/*
 * test_quat.c - motion/quat.c against the double reference (tests/ref_mat.c):
 * quaternion <-> matrix (the Q2.62 matrix against exact integers), products, normalisation, slerp, prepared and
 * one-shot (end points, unit norm, shortest arc, constant speed, the nlerp
 * fallback) and squad (keys, inner points, continuity of the angular
 * velocity across a key).
 *
 * Rotation errors are angles in radians between the fixed-point and the
 * reference rotation (ref_quat_angle, sign-blind as rotations are).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "motion/trig.h"
#include "ref_mat.h"

#define N 100000
#define LSB (1.0 / 4294967296.0)

static void rand_quat(struct mot_quat *q, struct ref_quat *r, struct tu_rng *rng)
{
	ref_rand_quat(r, rng);
	ref_to_quat(q, r);
	ref_from_quat(r, q);
}

static double quat_diff(const struct mot_quat *a, const struct ref_quat *b)
{
	struct ref_quat f;

	ref_from_quat(&f, a);
	return fmax(fmax(fabs(f.w - b->w), fabs(f.x - b->x)), fmax(fabs(f.y - b->y), fabs(f.z - b->z)));
}

static double fix_angle(const struct mot_quat *a, const struct ref_quat *b)
{
	struct ref_quat f;

	ref_from_quat(&f, a);
	return ref_quat_angle(&f, b);
}

static double fix_norm_err(const struct mot_quat *a)
{
	struct ref_quat f;

	ref_from_quat(&f, a);
	return ref_quat_norm(&f) - 1;
}

static void test_to_mat_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int i;

	tu_seed(&rng, 31);
	for (i = 0; i < N; i++) {
		struct mot_quat q;
		struct ref_quat r;
		struct mot_mat m;
		struct ref_mat rm, f;
		uint32_t sat = 0;

		rand_quat(&q, &r, &rng);
		mot_quat_to_mat(&m, &q, &sat);
		ref_quat_to_mat(&rm, &r);
		ref_from_mat(&f, &m);
		tu_worst_add(&w, ref_lin_diff(&f, &rm) / LSB, i);
		assert_int_equal(sat, 0);
		assert_true(m.m[3][0] == 0 && m.m[3][1] == 0 && m.m[3][2] == 0);
	}
	tu_bound("quat.to_mat entry (rounded once)", &w, 0.501, "LSB");
}

/* round((v + 1) / 2) saturated to int64, in exact 128-bit integers */
static int64_t q62_entry(__int128 v, bool *satd)
{
	__int128 r = (v + 1) >> 1;

	if (r > INT64_MAX || r < INT64_MIN) {
		*satd = true;
		return r > 0 ? INT64_MAX : INT64_MIN;
	}
	return (int64_t)r;
}

/* The Q2.62 matrix bit for bit against exact 128-bit sums: unit
 * quaternions, quaternions scaled across |q|^2 = 3/2 (where the test-free
 * path ends) and far beyond (saturating entries), components of any size
 * (MOT_E_RANGE from 2^62, r untouched). */
static void test_to_rot_q62(void **state)
{
	static const double scale[] = { 1, 1.2247448713915889, 1.2247448713915892, 1.3 };
	struct tu_rng rng;
	long wrong = 0, satd_n = 0, range_n = 0;
	int i, j;

	tu_seed(&rng, 39);
	for (i = 0; i < N; i++) {
		struct mot_quat q;
		struct ref_quat rq;
		int64_t r[3][3], e[9];
		__int128 w, x, y, z, h = (__int128)1 << 63;
		uint32_t sat = 0;
		bool satd = false, big;
		int rc;

		if (i % 5 == 4) {
			q = (struct mot_quat){ tu_i64(&rng), tu_i64(&rng), tu_i64(&rng), tu_i64(&rng) };
		} else {
			double k = i % 5 < 4 ? scale[i % 4] : 1;

			if (i % 5 == 3)
				k = tu_uniform(&rng, 0, 1e6);
			ref_rand_quat(&rq, &rng);
			q = (struct mot_quat){ d2q(rq.w * k), d2q(rq.x * k), d2q(rq.y * k),
					       d2q(rq.z * k) };
		}
		w = q.w, x = q.x, y = q.y, z = q.z;
		big = q.w >= (int64_t)1 << 62 || q.w <= -((int64_t)1 << 62) ||
		      q.x >= (int64_t)1 << 62 || q.x <= -((int64_t)1 << 62) ||
		      q.y >= (int64_t)1 << 62 || q.y <= -((int64_t)1 << 62) ||
		      q.z >= (int64_t)1 << 62 || q.z <= -((int64_t)1 << 62);
		for (j = 0; j < 9; j++)
			r[j / 3][j % 3] = 12345;
		rc = mot_quat_to_rot_q62(r, &q, &sat);
		if (big) {
			range_n++;
			assert_int_equal(rc, MOT_E_RANGE);
			for (j = 0; j < 9; j++)
				assert_true(r[j / 3][j % 3] == 12345);
			continue;
		}
		assert_int_equal(rc, MOT_OK);
		e[0] = q62_entry(h - y * y - z * z, &satd);
		e[1] = q62_entry(x * y + w * z, &satd);
		e[2] = q62_entry(x * z - w * y, &satd);
		e[3] = q62_entry(x * y - w * z, &satd);
		e[4] = q62_entry(h - x * x - z * z, &satd);
		e[5] = q62_entry(y * z + w * x, &satd);
		e[6] = q62_entry(x * z + w * y, &satd);
		e[7] = q62_entry(y * z - w * x, &satd);
		e[8] = q62_entry(h - x * x - y * y, &satd);
		for (j = 0; j < 9; j++)
			wrong += r[j / 3][j % 3] != e[j];
		wrong += satd != (sat == MOT_SAT_OVERFLOW);
		satd_n += satd;
	}
	printf("quat.to_rot_q62: %d quaternions, %ld saturating, %ld out of range, %ld wrong\n",
	       N, satd_n, range_n, wrong);
	assert_int_equal(wrong, 0);
	assert_true(satd_n > N / 20 && range_n > N / 500);
}

/* a random unit quaternion, now and then one of the hard cases: a half turn
 * about a random or a coordinate axis (w = 0), or a tiny rotation */
static void rand_quat_hard(struct mot_quat *q, struct ref_quat *r, struct tu_rng *rng, int i)
{
	double ax[3], a;

	switch (i % 8) {
	case 0:
		ref_rand_axis(ax, rng);
		a = M_PI + tu_uniform(rng, -1e-6, 1e-6);
		break;
	case 1:
		ax[0] = ax[1] = ax[2] = 0;
		ax[tu_u64(rng) % 3] = (tu_u64(rng) & 1) ? 1 : -1;
		a = M_PI;
		break;
	case 2:
		ref_rand_axis(ax, rng);
		a = tu_uniform(rng, -1e-5, 1e-5);
		break;
	default:
		rand_quat(q, r, rng);
		return;
	}
	ref_quat_axis_angle(r, ax, a);
	ref_to_quat(q, r);
	ref_from_quat(r, q);
}

static void test_from_mat(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wr = { 0, 0 }, wn = { 0, 0 };
	long neg_w = 0;
	int i;

	tu_seed(&rng, 32);
	for (i = 0; i < N; i++) {
		struct mot_quat q, p;
		struct ref_quat r, rp;
		struct mot_mat m;
		struct ref_mat rm;
		uint32_t sat = 0;

		rand_quat_hard(&q, &r, &rng, i);
		/* the round trip quaternion -> matrix -> quaternion */
		mot_quat_to_mat(&m, &q, &sat);
		mot_quat_from_mat(&p, &m, &sat);
		tu_worst_add(&wr, fix_angle(&p, &r), i);
		tu_worst_add(&wn, fix_norm_err(&p), i);
		neg_w += p.w < 0;
		/* from the same matrix as the reference */
		ref_from_mat(&rm, &m);
		ref_quat_from_mat(&rp, &rm);
		tu_worst_add(&w, fix_angle(&p, &rp), i);
		assert_int_equal(sat, 0);
	}
	assert_int_equal(neg_w, 0);
	tu_bound("quat.from_mat(to_mat(q)) round trip", &wr, 2e-9, "rad");
	tu_bound("quat.from_mat vs Shoemake in double", &w, 2e-9, "rad");
	tu_bound("quat.from_mat |q| - 1", &wn, 3 * LSB, "(1)");
}

static void test_mul_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wc = { 0, 0 };
	int i;

	tu_seed(&rng, 33);
	for (i = 0; i < N; i++) {
		struct mot_quat a, b, ab, ba;
		struct ref_quat ra, rb, r;
		struct mot_mat ma, mb, mab, mba;
		struct ref_mat f1, f2;
		uint32_t sat = 0;

		rand_quat(&a, &ra, &rng);
		rand_quat(&b, &rb, &rng);
		mot_quat_mul(&ab, &a, &b, &sat);
		ref_quat_mul(&r, &ra, &rb);
		tu_worst_add(&w, quat_diff(&ab, &r) / LSB, i);
		/* applying a then b is R(a).R(b) = R(b * a) */
		mot_quat_mul(&ba, &b, &a, &sat);
		mot_quat_to_mat(&ma, &a, &sat);
		mot_quat_to_mat(&mb, &b, &sat);
		mot_mat_mul(&mab, &ma, &mb, &sat);
		mot_quat_to_mat(&mba, &ba, &sat);
		ref_from_mat(&f1, &mab);
		ref_from_mat(&f2, &mba);
		tu_worst_add(&wc, ref_lin_diff(&f1, &f2), i);
		/* in place */
		mot_quat_mul(&a, &a, &b, &sat);
		assert_memory_equal(&a, &ab, sizeof(a));
		assert_int_equal(sat, 0);
	}
	tu_bound("quat.mul component (rounded once)", &w, 0.501, "LSB");
	tu_bound("quat R(a).R(b) = R(b*a) entry", &wc, 2e-9, "(1)");
}

static void test_normalize(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wn = { 0, 0 };
	struct mot_quat q, out, zero = { 0, 0, 0, 0 }, sentinel = { 1, 2, 3, 4 };
	uint32_t sat = 0;
	int i;

	tu_seed(&rng, 34);
	for (i = 0; i < N; i++) {
		struct ref_quat r, rn;
		double mag = exp(tu_uniform(&rng, log(1e-6), log(1e6)));

		ref_rand_quat(&r, &rng);
		r = (struct ref_quat){ r.w * mag, r.x * mag, r.y * mag, r.z * mag };
		ref_to_quat(&q, &r);
		ref_from_quat(&r, &q);
		assert_int_equal(mot_quat_normalize(&out, &q, &sat), MOT_OK);
		ref_quat_normalize(&rn, &r);
		tu_worst_add(&w, quat_diff(&out, &rn) / LSB, mag);
		tu_worst_add(&wn, fix_norm_err(&out) / LSB, mag);
	}
	assert_int_equal(sat, 0);
	tu_bound("quat.normalize component (|q| 1e-6..1e6)", &w, 1.5, "LSB");
	tu_bound("quat.normalize |q| - 1", &wn, 2, "LSB");
	out = sentinel;
	assert_int_equal(mot_quat_normalize(&out, &zero, &sat), MOT_E_INVAL);
	assert_memory_equal(&out, &sentinel, sizeof(out));
	/* one LSB, and the largest magnitudes */
	q = (struct mot_quat){ 0, 0, -1, 0 };
	assert_int_equal(mot_quat_normalize(&out, &q, &sat), MOT_OK);
	assert_true(out.w == 0 && out.x == 0 && out.y == -MOT_Q32_ONE && out.z == 0);
	q = (struct mot_quat){ MOT_Q32_MIN, MOT_Q32_MAX, MOT_Q32_MIN, MOT_Q32_MAX };
	assert_int_equal(mot_quat_normalize(&out, &q, &sat), MOT_OK);
	assert_true(llabs(out.w + MOT_Q32_HALF) <= 1 && llabs(out.x - MOT_Q32_HALF) <= 1);
	assert_int_equal(sat, 0);
}

static void test_axis_euler(void **state)
{
	struct tu_rng rng;
	struct tu_worst wa = { 0, 0 }, we = { 0, 0 }, wm = { 0, 0 };
	int i, k;

	tu_seed(&rng, 35);
	for (i = 0; i < N; i++) {
		double ad[3], ed[3];
		mot_q32 axis[3], e[3], turns = d2q(tu_uniform(&rng, -2, 2));
		struct mot_quat q;
		struct ref_quat r;
		struct mot_mat m, me;
		struct ref_mat rm, f1, f2;
		uint32_t sat = 0;

		ref_rand_axis(ad, &rng);
		for (k = 0; k < 3; k++) {
			axis[k] = d2q(ad[k]);
			ad[k] = q2d(axis[k]);
			e[k] = d2q(tu_uniform(&rng, -1, 1));
			ed[k] = q2d(e[k]) * 2 * M_PI;
		}
		mot_quat_from_axis_angle(&q, axis, turns, &sat);
		ref_quat_axis_angle(&r, ad, q2d(turns) * 2 * M_PI);
		tu_worst_add(&wa, quat_diff(&q, &r), q2d(turns));
		mot_quat_from_euler(&q, e, &sat);
		ref_euler(&rm, ed[0], ed[1], ed[2]);
		ref_quat_from_mat(&r, &rm);
		tu_worst_add(&we, fix_angle(&q, &r), q2d(e[0]));
		/* the same rotation as mot_mat_euler */
		mot_quat_to_mat(&m, &q, &sat);
		mot_mat_euler(&me, e, &sat);
		ref_from_mat(&f1, &m);
		ref_from_mat(&f2, &me);
		tu_worst_add(&wm, ref_lin_diff(&f1, &f2), q2d(e[0]));
		assert_int_equal(sat, 0);
	}
	tu_bound("quat.from_axis_angle component", &wa, 2e-9, "(1)");
	tu_bound("quat.from_euler vs Rx.Ry.Rz", &we, 3e-9, "rad");
	tu_bound("quat.to_mat(from_euler) vs mat.euler entry", &wm, 4e-9, "(1)");
}

static void test_slerp_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wn = { 0, 0 }, ws = { 0, 0 };
	struct tu_worst w1 = { 0, 0 }, wn1 = { 0, 0 }, ws1 = { 0, 0 };
	long ends = 0, flips = 0;
	int i;

	tu_seed(&rng, 36);
	for (i = 0; i < N; i++) {
		struct mot_quat a, b, q, nb;
		struct ref_quat ra, rb, r;
		struct mot_slerp s;
		mot_q32 t = (mot_q32)(tu_u64(&rng) >> 32); /* [0, 1) */
		uint32_t sat = 0;

		rand_quat(&a, &ra, &rng);
		rand_quat(&b, &rb, &rng);
		flips += ref_quat_dot(&ra, &rb) < 0;
		mot_slerp_prepare(&s, &a, &b, &sat);
		mot_slerp_eval(&q, &s, t, &sat);
		ref_slerp(&r, &ra, &rb, q2d(t));
		tu_worst_add(&w, fix_angle(&q, &r), q2d(t));
		tu_worst_add(&wn, fix_norm_err(&q) / LSB, q2d(t));
		/* shortest arc at constant speed: the rotation from a to q(t) is
		 * t times the (at most half-turn) rotation from a to b */
		tu_worst_add(&ws, fix_angle(&q, &ra) - q2d(t) * ref_quat_angle(&ra, &rb), q2d(t));
		/* end points, exactly: a, and b or -b */
		mot_slerp_eval(&q, &s, 0, &sat);
		ends += memcmp(&q, &a, sizeof(q)) != 0;
		mot_slerp_eval(&q, &s, MOT_Q32_ONE, &sat);
		nb = (struct mot_quat){ -b.w, -b.x, -b.y, -b.z };
		ends += memcmp(&q, &b, sizeof(q)) != 0 && memcmp(&q, &nb, sizeof(q)) != 0;
		/* the one-shot slerp (no unit c), the same ends */
		mot_quat_slerp(&q, &a, &b, t, &sat);
		tu_worst_add(&w1, fix_angle(&q, &r), q2d(t));
		tu_worst_add(&wn1, fix_norm_err(&q) / LSB, q2d(t));
		tu_worst_add(&ws1, fix_angle(&q, &ra) - q2d(t) * ref_quat_angle(&ra, &rb), q2d(t));
		mot_quat_slerp(&q, &a, &b, 0, &sat);
		ends += memcmp(&q, &a, sizeof(q)) != 0;
		mot_quat_slerp(&q, &a, &b, MOT_Q32_ONE, &sat);
		ends += memcmp(&q, &b, sizeof(q)) != 0 && memcmp(&q, &nb, sizeof(q)) != 0;
		assert_int_equal(sat, 0);
	}
	assert_int_equal(ends, 0);
	assert_true(flips > N / 3); /* the shorter-arc branch was exercised */
	tu_bound("quat.slerp vs textbook slerp", &w, 4e-9, "rad");
	tu_bound("quat.slerp |q(t)| - 1", &wn, 4, "LSB");
	tu_bound("quat.slerp angle(a, q(t)) - t angle(a, b)", &ws, 3e-9, "rad");
	tu_bound("quat.slerp one-shot vs textbook slerp", &w1, 4e-9, "rad");
	tu_bound("quat.slerp one-shot |q(t)| - 1", &wn1, 4, "LSB");
	tu_bound("quat.slerp one-shot angle(a, q(t)) - t angle(a, b)", &ws1, 3e-9, "rad");
}

static void test_slerp_nlerp(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 }, wn = { 0, 0 }, w1 = { 0, 0 }, wn1 = { 0, 0 };
	long nl = 0, sl = 0;
	int i;

	tu_seed(&rng, 37);
	for (i = 0; i < N; i++) {
		/* keys 1e-10 .. 1e-1 rad apart, across the fallback threshold */
		double ax[3], ang = exp(tu_uniform(&rng, log(1e-10), log(1e-1)));
		struct mot_quat a, b, q;
		struct ref_quat ra, rb, rd, r;
		struct mot_slerp s;
		mot_q32 t = (mot_q32)(tu_u64(&rng) >> 32);
		uint32_t sat = 0;

		rand_quat(&a, &ra, &rng);
		ref_rand_axis(ax, &rng);
		ref_quat_axis_angle(&rd, ax, ang);
		ref_quat_mul(&rb, &ra, &rd);
		ref_to_quat(&b, &rb);
		ref_from_quat(&rb, &b);
		mot_slerp_prepare(&s, &a, &b, &sat);
		nl += s.nlerp;
		sl += !s.nlerp;
		mot_slerp_eval(&q, &s, t, &sat);
		ref_slerp(&r, &ra, &rb, q2d(t));
		tu_worst_add(&w, fix_angle(&q, &r), ang);
		tu_worst_add(&wn, fix_norm_err(&q) / LSB, ang);
		mot_quat_slerp(&q, &a, &b, t, &sat);
		tu_worst_add(&w1, fix_angle(&q, &r), ang);
		tu_worst_add(&wn1, fix_norm_err(&q) / LSB, ang);
		/* equal keys */
		mot_slerp_prepare(&s, &a, &a, &sat);
		assert_true(s.nlerp);
		mot_slerp_eval(&q, &s, t, &sat);
		tu_worst_add(&w, fix_angle(&q, &ra), 0);
		mot_quat_slerp(&q, &a, &a, t, &sat);
		tu_worst_add(&w1, fix_angle(&q, &ra), 0);
		assert_int_equal(sat, 0);
	}
	assert_true(nl > N / 10 && sl > N / 10);
	tu_bound("quat.slerp near-equal keys (nlerp below 2^-10) vs slerp", &w, 4e-9, "rad");
	tu_bound("quat.slerp near-equal keys |q| - 1", &wn, 4, "LSB");
	tu_bound("quat.slerp one-shot near-equal keys vs slerp", &w1, 4e-9, "rad");
	tu_bound("quat.slerp one-shot near-equal keys |q| - 1", &wn1, 4, "LSB");
}

/* ---- squad ---------------------------------------------------------------------- */

/* log(k^-1 q) in radians, for finite differences around the key k */
static void chart(double out[3], const struct mot_quat *k, const struct mot_quat *q)
{
	struct ref_quat rk, rq, ik, r;

	ref_from_quat(&rk, k);
	ref_from_quat(&rq, q);
	ik = (struct ref_quat){ rk.w, -rk.x, -rk.y, -rk.z };
	ref_quat_mul(&r, &ik, &rq);
	if (r.w < 0)
		r = (struct ref_quat){ -r.w, -r.x, -r.y, -r.z };
	ref_quat_log(out, &r);
}

/* squad or, for the control, plain slerp through keys[i] .. keys[i+1] */
static void curve(struct mot_quat *out, const struct mot_quat *keys, const struct mot_quat *inner,
		  int i, double t, bool squad)
{
	mot_q32 tq = d2q(t);

	if (squad)
		mot_quat_squad(out, &keys[i], &keys[i + 1], &inner[i], &inner[i + 1], tq, NULL);
	else
		mot_quat_slerp(out, &keys[i], &keys[i + 1], tq, NULL);
}

/* |w_left - w_right| at key 1 (between segments 0 and 1), second-order
 * one-sided differences of the chart at the key, radians per unit t */
static double velocity_jump(const struct mot_quat *keys, const struct mot_quat *inner, bool squad)
{
	const double h = 1.0 / 1024;
	struct mot_quat q1, q2;
	double l1[3], l2[3], r1[3], r2[3], jump = 0;
	int k;

	curve(&q1, keys, inner, 0, 1 - h, squad);
	curve(&q2, keys, inner, 0, 1 - 2 * h, squad);
	chart(l1, &keys[1], &q1);
	chart(l2, &keys[1], &q2);
	curve(&q1, keys, inner, 1, h, squad);
	curve(&q2, keys, inner, 1, 2 * h, squad);
	chart(r1, &keys[1], &q1);
	chart(r2, &keys[1], &q2);
	for (k = 0; k < 3; k++) {
		double wl = (-4 * l1[k] + l2[k]) / (2 * h), wr = (4 * r1[k] - r2[k]) / (2 * h);

		jump = fmax(jump, fabs(wl - wr));
	}
	return jump;
}

/* keys a random step of up to 100 degrees apart, every other sequence
 * (odd i) with a key on the far side of the sphere, and their inner points
 * s (wi: their angle from the double ones) */
static void squad_keys(struct mot_quat q[4], struct mot_quat s[4], struct ref_quat rq[4],
		       struct ref_quat rs[4], struct tu_rng *rng, int i, struct tu_worst *wi,
		       uint32_t *sat)
{
	struct ref_quat d;
	double ax[3];
	int k;

	rand_quat(&q[0], &rq[0], rng);
	for (k = 1; k < 4; k++) {
		ref_rand_axis(ax, rng);
		ref_quat_axis_angle(&d, ax, tu_uniform(rng, 0.2, 1.75));
		ref_quat_mul(&rq[k], &rq[k - 1], &d);
		if (k == 2 && (i & 1))
			rq[k] = (struct ref_quat){ -rq[k].w, -rq[k].x, -rq[k].y, -rq[k].z };
		ref_to_quat(&q[k], &rq[k]);
		ref_from_quat(&rq[k], &q[k]);
	}
	for (k = 0; k < 4; k++) {
		const int p = k ? k - 1 : 0, n = k < 3 ? k + 1 : 3;

		mot_squad_inner(&s[k], &q[p], &q[k], &q[n], sat);
		ref_squad_inner(&rs[k], &rq[p], &rq[k], &rq[n]);
		tu_worst_add(wi, fix_angle(&s[k], &rs[k]), k);
	}
}

static void test_squad(void **state)
{
	struct tu_rng rng;
	struct tu_worst wi = { 0, 0 }, w = { 0, 0 }, wj = { 0, 0 }, wn = { 0, 0 };
	long keys_missed = 0, smooth_slerp = 0;
	int i, k;

	tu_seed(&rng, 38);
	for (i = 0; i < N / 3; i++) {
		struct mot_quat q[4], s[4], out;
		struct ref_quat rq[4], rs[4], r;
		uint32_t sat = 0;

		squad_keys(q, s, rq, rs, &rng, i, &wi, &sat);
		for (k = 0; k < 3; k++) {
			mot_q32 t = (mot_q32)(tu_u64(&rng) >> 32);
			struct mot_quat nq = { -q[k + 1].w, -q[k + 1].x, -q[k + 1].y, -q[k + 1].z };

			mot_quat_squad(&out, &q[k], &q[k + 1], &s[k], &s[k + 1], t, &sat);
			ref_squad(&r, &rq[k], &rq[k + 1], &rs[k], &rs[k + 1], q2d(t));
			tu_worst_add(&w, fix_angle(&out, &r), q2d(t));
			tu_worst_add(&wn, fix_norm_err(&out) / LSB, q2d(t));
			/* through the keys, exactly (the far key as -q) */
			mot_quat_squad(&out, &q[k], &q[k + 1], &s[k], &s[k + 1], 0, &sat);
			keys_missed += memcmp(&out, &q[k], sizeof(out)) != 0;
			mot_quat_squad(&out, &q[k], &q[k + 1], &s[k], &s[k + 1], MOT_Q32_ONE, &sat);
			keys_missed += memcmp(&out, &q[k + 1], sizeof(out)) != 0 &&
				       memcmp(&out, &nq, sizeof(out)) != 0;
		}
		tu_worst_add(&wj, velocity_jump(q, s, true), i);
		smooth_slerp += velocity_jump(q, s, false) < 10 * 1e-4;
		assert_int_equal(sat, 0);
	}
	assert_int_equal(keys_missed, 0);
	tu_bound("quat.squad_inner vs double", &wi, 6e-9, "rad");
	tu_bound("quat.squad vs double", &w, 1e-8, "rad");
	tu_bound("quat.squad |q| - 1", &wn, 4, "LSB");
	tu_bound("quat.squad angular velocity jump across a key (h = 1/1024)", &wj, 1e-4, "rad/t");
	/* the finite differences do see a corner: plain slerp through the
	 * same keys jumps by more than ten times the squad bound at (nearly)
	 * every key */
	printf("control: slerp chain below 10x the bound at %ld of %d keys\n", smooth_slerp, N / 3);
	assert_true(smooth_slerp < N / 3 / 100);
}

/* squad of prepared arcs (mot_squad_eval(), as a rotation track makes it):
 * the same keys and bounds as the one-shot squad above */
static void test_squad_prepared(void **state)
{
	struct tu_rng rng;
	struct tu_worst wi = { 0, 0 }, w = { 0, 0 }, wn = { 0, 0 };
	long small = 0, keys_missed = 0;
	int i, k;

	(void)state;
	tu_seed(&rng, 39);
	for (i = 0; i < N / 3; i++) {
		struct mot_quat q[4], s[4], out;
		struct ref_quat rq[4], rs[4], r;
		uint32_t sat = 0;

		squad_keys(q, s, rq, rs, &rng, i, &wi, &sat);
		for (k = 0; k < 3; k++) {
			struct mot_quat b = q[k + 1], sb = s[k + 1];
			struct mot_slerp arc, inner;
			int j;

			if (mot_quat_dot(&q[k], &b, NULL) < 0) {
				b = (struct mot_quat){ -b.w, -b.x, -b.y, -b.z };
				sb = (struct mot_quat){ -sb.w, -sb.x, -sb.y, -sb.z };
			}
			mot_slerp_prepare(&arc, &q[k], &b, &sat);
			mot_slerp_prepare(&inner, &s[k], &sb, &sat);
			small += arc.small && inner.small;
			for (j = 0; j < 4; j++) {
				mot_q32 t = (mot_q32)(tu_u64(&rng) >> 32);

				mot_squad_eval(&out, &arc, &inner, t, &sat);
				ref_squad(&r, &rq[k], &rq[k + 1], &rs[k], &rs[k + 1], q2d(t));
				tu_worst_add(&w, fix_angle(&out, &r), q2d(t));
				tu_worst_add(&wn, fix_norm_err(&out) / LSB, q2d(t));
			}
			mot_squad_eval(&out, &arc, &inner, 0, &sat);
			keys_missed += memcmp(&out, &q[k], sizeof(out)) != 0;
			mot_squad_eval(&out, &arc, &inner, MOT_Q32_ONE, &sat);
			keys_missed += memcmp(&out, &b, sizeof(out)) != 0;
		}
		assert_int_equal(sat, 0);
	}
	assert_int_equal(keys_missed, 0);
	/* every segment's arcs within +-1: slerp_near() */
	printf("prepared squad: %ld of %d segments with arcs within +-1\n", small, N / 3 * 3);
	tu_bound("quat.squad prepared vs double", &w, 1e-8, "rad");
	tu_bound("quat.squad prepared |q| - 1", &wn, 4, "LSB");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_to_mat_ref), cmocka_unit_test(test_to_rot_q62),
		cmocka_unit_test(test_from_mat),
		cmocka_unit_test(test_mul_ref),    cmocka_unit_test(test_normalize),
		cmocka_unit_test(test_axis_euler), cmocka_unit_test(test_slerp_ref),
		cmocka_unit_test(test_slerp_nlerp), cmocka_unit_test(test_squad),
		cmocka_unit_test(test_squad_prepared),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
