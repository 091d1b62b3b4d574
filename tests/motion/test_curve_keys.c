/* SPDX-License-Identifier: MIT */
/*
 * test_curve_keys.c - what the importers added to the core, against long
 * double references: hermite curves with explicit tangents (curve.h's
 * mot_tangent), compact curves and rotation tracks (keys only, for sampled
 * motion), and a rotation kept as four curves normalised (strand.h); and
 * the matrices of the end keys that rotation tracks hold.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "motion/curve.h"
#include "motion/strand.h"
#include "scene/scene_desc.h"
#include "ref_curve.h"
#include "ref_mat.h"
#include "testutil.h"

#include <cmocka.h>

#define NK 24
#define LSB (1.0 / 4294967296.0)

/* Random keys: frames apart by 1/8 to 40, values within +-1000. */
static void rand_keys(struct tu_rng *r, struct mot_key *k, uint32_t n)
{
	double f = tu_uniform(r, -50, 50);
	uint32_t i;

	for (i = 0; i < n; i++) {
		f += tu_uniform(r, 0.125, 40);
		k[i].frame = (mot_q32)llround(f * 4294967296.0);
		k[i].value = (mot_q32)llround(tu_uniform(r, -1000, 1000) * 4294967296.0);
		k[i].ease_in = k[i].ease_out = 0;
	}
}

/* The hermite cubic of interval i with the tangents the curve uses: the
 * key's explicit one where set, else Catmull-Rom (FORMULAS section 6). */
static ref_t ref_tangent(const struct mot_key *k, const struct mot_tangent *t, uint32_t n,
			 uint32_t j, uint32_t side)
{
	uint32_t a = j == 0 ? 0 : j - 1, b = j == n - 1 ? j : j + 1;

	if (t[j].set & side)
		return ref_q(side == MOT_TANGENT_IN ? t[j].in : t[j].out);
	return (ref_q(k[b].value) - ref_q(k[a].value)) / (ref_q(k[b].frame) - ref_q(k[a].frame));
}

static ref_t ref_hermite(const struct mot_key *k, const struct mot_tangent *t, uint32_t n,
			 ref_t f)
{
	uint32_t i = 0;
	ref_t h, s, s2, s3;

	if (f <= ref_q(k[0].frame))
		return ref_q(k[0].value);
	if (f >= ref_q(k[n - 1].frame))
		return ref_q(k[n - 1].value);
	while (f >= ref_q(k[i + 1].frame))
		i++;
	h = ref_q(k[i + 1].frame) - ref_q(k[i].frame);
	s = (f - ref_q(k[i].frame)) / h;
	s2 = s * s;
	s3 = s2 * s;
	return (2 * s3 - 3 * s2 + 1) * ref_q(k[i].value) +
	       (s3 - 2 * s2 + s) * h * ref_tangent(k, t, n, i, MOT_TANGENT_OUT) +
	       (-2 * s3 + 3 * s2) * ref_q(k[i + 1].value) +
	       (s3 - s2) * h * ref_tangent(k, t, n, i + 1, MOT_TANGENT_IN);
}

/* Explicit tangents (some keys, some sides) against the cubic they define. */
static void test_tangents(void **state)
{
	struct tu_rng r;
	struct tu_worst w = { 0, 0 };
	int trial;

	(void)state;
	tu_seed(&r, 15);
	for (trial = 0; trial < 400; trial++) {
		struct mot_key k[NK];
		struct mot_tangent t[NK];
		struct mot_curve_seg seg[NK];
		struct mot_curve_opts o;
		struct mot_cursor cur = { 0, 0 };
		struct mot_curve c;
		uint32_t n = 2 + (uint32_t)(tu_u64(&r) % (NK - 1)), i, sat = 0;
		int s;

		rand_keys(&r, k, n);
		for (i = 0; i < n; i++) {
			t[i].set = (uint32_t)(tu_u64(&r) % 4);
			t[i].in = (mot_q32)llround(tu_uniform(&r, -200, 200) * 4294967296.0);
			t[i].out = (trial & 1) ? t[i].in :
				   (mot_q32)llround(tu_uniform(&r, -200, 200) * 4294967296.0);
		}
		memset(&o, 0, sizeof(o));
		o.tangents = t;
		o.integral = trial & 2;
		assert_int_equal(mot_curve_init(&c, MOT_INTERP_HERMITE, k, n, &o, seg, NK, &sat),
				 MOT_OK);
		for (s = -20; s < 2000; s++) {
			ref_t f = ref_q(k[0].frame) +
				  (ref_q(k[n - 1].frame) - ref_q(k[0].frame) + 4) * s / 1980.0L - 2;
			mot_q32 qf = (mot_q32)llroundl(f * 4294967296.0L);
			mot_q32 v = mot_curve_eval(&c, &cur, qf, &sat);

			tu_worst_add(&w, (double)((ref_q(v) - ref_hermite(k, t, n, ref_q(qf))) /
						  LSB), ref_q(qf));
			if (s % 7 == 0)
				assert_int_equal(v, mot_curve_eval(&c, NULL, qf, &sat));
		}
		assert_int_equal(sat, 0);
	}
	tu_bound("curve_tangent_hermite", &w, 0.6, "LSB");
}

/* What curve.h refuses: tangents on another kind, bad set bits, a handle
 * beyond the core's range. */
static void test_tangent_errors(void **state)
{
	struct mot_key k[3] = { { 0, 0, 0, 0 }, { MOT_Q32_INT(10), MOT_Q32_INT(1), 0, 0 },
				{ MOT_Q32_INT(1 << 20), 0, 0, 0 } };
	struct mot_tangent t[3] = { { 0, 0, MOT_TANGENT_OUT }, { 0, 0, 0 }, { 0, 0, 0 } };
	struct mot_curve_seg seg[4];
	struct mot_curve_opts o;
	struct mot_curve c;
	uint32_t sat = 0;

	(void)state;
	memset(&o, 0, sizeof(o));
	o.tangents = t;
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_HERMITE, k, 3, &o, seg, 4, &sat), MOT_OK);
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_LINEAR, k, 3, &o, seg, 4, &sat),
			 MOT_E_INVAL);
	t[1].set = 4;
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_HERMITE, k, 3, &o, seg, 4, &sat),
			 MOT_E_INVAL);
	t[1].set = MOT_TANGENT_OUT;
	t[1].out = MOT_Q32_INT(1 << 12); /* h m = 2^20 2^12 = 2^32 units */
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_HERMITE, k, 3, &o, seg, 4, &sat),
			 MOT_E_RANGE);
	t[1].out = MOT_Q32_INT(1 << 10) - 1; /* below 2^30 units: fine */
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_HERMITE, k, 3, &o, seg, 4, &sat), MOT_OK);
	t[1].out = MOT_LEN_LIMIT;
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_HERMITE, k, 3, &o, seg, 4, &sat),
			 MOT_E_RANGE);
}

/* Compact step and linear curves: keys only, no segments; the exact value
 * within 1/2 LSB, and within 1 LSB of the prepared curve's. */
static void test_compact(void **state)
{
	struct tu_rng r;
	struct tu_worst w = { 0, 0 }, wp = { 0, 0 };
	int trial;

	(void)state;
	tu_seed(&r, 16);
	for (trial = 0; trial < 400; trial++) {
		enum mot_interp kind = (trial & 1) ? MOT_INTERP_LINEAR : MOT_INTERP_STEP;
		struct mot_key k[NK];
		struct mot_curve_seg seg[NK];
		struct mot_curve_opts o, plain;
		struct mot_cursor cur = { 0, 0 }, cur2 = { 0, 0 };
		struct mot_curve c, p;
		uint32_t n = 1 + (uint32_t)(tu_u64(&r) % NK), sat = 0;
		int s;

		rand_keys(&r, k, n);
		memset(&o, 0, sizeof(o));
		memset(&plain, 0, sizeof(plain));
		plain.beta1 = MOT_Q32_ONE;
		o.compact = true;
		assert_int_equal(mot_curve_init(&c, kind, k, n, &o, NULL, 0, &sat), MOT_OK);
		assert_int_equal(c.nseg, 0);
		assert_int_equal(mot_curve_init(&p, kind, k, n, NULL, seg, NK, &sat), MOT_OK);
		for (s = -20; s < 2000; s++) {
			ref_t f = ref_q(k[0].frame) +
				  (ref_q(k[n - 1].frame) - ref_q(k[0].frame) + 4) * s / 1980.0L - 2;
			mot_q32 qf = (mot_q32)llroundl(f * 4294967296.0L);
			mot_q32 v = mot_curve_eval(&c, &cur, qf, &sat);
			ref_t ref = ref_curve_eval(kind, k, n, &plain, ref_q(qf));

			tu_worst_add(&w, (double)((ref_q(v) - ref) / LSB), ref_q(qf));
			tu_worst_add(&wp, (double)(v - mot_curve_eval(&p, &cur2, qf, &sat)),
				     ref_q(qf));
			if (s % 5 == 0)
				assert_int_equal(v, mot_curve_eval(&c, NULL, qf, &sat));
		}
		assert_int_equal(sat, 0);
	}
	tu_bound("curve_compact", &w, 0.51, "LSB");
	tu_bound("curve_compact_vs_prepared", &wp, 1.0, "LSB");
}

/* Compact needs step or linear and no ease, integral or tangents. */
static void test_compact_errors(void **state)
{
	struct mot_key k[2] = { { 0, 0, 0, 0 }, { MOT_Q32_INT(10), MOT_Q32_INT(1), 0, 0 } };
	struct mot_curve_opts o;
	struct mot_curve c;
	uint32_t sat = 0;

	(void)state;
	memset(&o, 0, sizeof(o));
	o.compact = true;
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_HERMITE, k, 2, &o, NULL, 0, &sat),
			 MOT_E_INVAL);
	o.integral = true;
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_LINEAR, k, 2, &o, NULL, 0, &sat),
			 MOT_E_INVAL);
	o.integral = false;
	k[0].ease_out = MOT_Q32_ONE / 2;
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_LINEAR, k, 2, &o, NULL, 0, &sat),
			 MOT_E_INVAL);
	k[0].ease_out = 0;
	o.ease_in_frames = MOT_Q32_ONE;
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_LINEAR, k, 2, &o, NULL, 0, &sat),
			 MOT_E_INVAL);
	assert_int_equal(mot_curve_eval(&c, NULL, MOT_Q32_INT(5), &sat), 0);
	assert_true(sat & MOT_SAT_DOMAIN);
}

static double quat_angle_fix(const struct mot_quat *a, const struct ref_quat *b)
{
	struct ref_quat f;

	ref_from_quat(&f, a);
	return ref_quat_angle(&f, b);
}

/* A compact slerp track against the double slerp the short way. */
static void test_rot_compact(void **state)
{
	struct tu_rng r;
	struct tu_worst w = { 0, 0 }, wn = { 0, 0 };
	int trial;

	(void)state;
	tu_seed(&r, 17);
	for (trial = 0; trial < 200; trial++) {
		struct mot_rot_key k[NK];
		struct ref_quat rq[NK];
		struct mot_rot_track t;
		struct mot_cursor cur = { 0, 0 };
		uint32_t n = 1 + (uint32_t)(tu_u64(&r) % NK), i, sat = 0;
		double f = 0;
		int s;

		for (i = 0; i < n; i++) {
			f += tu_uniform(&r, 0.125, 30);
			k[i].frame = (mot_q32)llround(f * 4294967296.0);
			ref_rand_quat(&rq[i], &r);
			ref_to_quat(&k[i].q, &rq[i]);
			ref_from_quat(&rq[i], &k[i].q);
			k[i].ease_in = k[i].ease_out = 0;
		}
		assert_int_equal(mot_rot_track_init_compact(&t, k, n), MOT_OK);
		for (s = -10; s < 1000; s++) {
			double ff = ref_q(k[0].frame) +
				    (ref_q(k[n - 1].frame) - ref_q(k[0].frame) + 2) * s / 990.0 - 1;
			mot_q32 qf = (mot_q32)llround(ff * 4294967296.0);
			struct mot_quat q;
			struct ref_quat ref, fq;
			double fr = ref_q(qf);

			mot_rot_track_eval(&q, &t, &cur, qf, &sat);
			if (fr <= ref_q(k[0].frame)) {
				ref = rq[0];
			} else if (fr >= ref_q(k[n - 1].frame)) {
				ref = rq[n - 1];
			} else {
				i = 0;
				while (fr >= ref_q(k[i + 1].frame))
					i++;
				ref_slerp(&ref, &rq[i], &rq[i + 1],
					  (fr - ref_q(k[i].frame)) /
					  (ref_q(k[i + 1].frame) - ref_q(k[i].frame)));
			}
			tu_worst_add(&w, quat_angle_fix(&q, &ref), fr);
			ref_from_quat(&fq, &q);
			tu_worst_add(&wn, ref_quat_norm(&fq) - 1, fr);
		}
		assert_int_equal(sat, 0);
	}
	tu_bound("rot_compact_slerp", &w, 4e-9, "rad");
	tu_bound("rot_compact_norm", &wn, 1e-9, "");
	{
		struct mot_rot_key k[2] = { { 0, { MOT_Q32_ONE, 0, 0, 0 }, 0, MOT_Q32_ONE / 2 },
					    { MOT_Q32_ONE, { MOT_Q32_ONE, 0, 0, 0 }, 0, 0 } };
		struct mot_rot_track t;

		assert_int_equal(mot_rot_track_init_compact(&t, k, 2), MOT_E_INVAL);
		k[0].ease_out = 0;
		k[1].frame = 0;
		assert_int_equal(mot_rot_track_init_compact(&t, k, 2), MOT_E_ORDER);
		assert_int_equal(mot_rot_track_init_compact(&t, k, 0), MOT_E_NOKEYS);
	}
}

/* Outside its keys a track returns the held key's matrix made at init
 * (strand.h): exactly mot_quat_to_rot_q62() of the quaternion it returns,
 * for prepared slerp and squad tracks and compact ones, keys on either side
 * of the sphere (a prepared track holds its last key as its last arc has
 * it), and NULL inside the keys; never for keys whose matrix saturates. */
static void test_rot_ends(void **state)
{
	static const struct mot_quat bad[2] = {
		{ MOT_Q32_ONE + MOT_Q32_ONE / 4, MOT_Q32_ONE + MOT_Q32_ONE / 4, 0, 0 }, /* saturates */
		{ (mot_q32)1 << 62, 0, 0, 0 },                                          /* out of range */
	};
	struct tu_rng r;
	int trial, mode, s;
	unsigned b;

	(void)state;
	tu_seed(&r, 23);
	for (trial = 0; trial < 300; trial++) {
		struct mot_rot_key k[NK];
		struct mot_rot_seg seg[NK];
		uint32_t n = 1 + (uint32_t)(tu_u64(&r) % NK), i;
		double f = 0;

		for (i = 0; i < n; i++) {
			struct ref_quat rq;

			f += tu_uniform(&r, 0.125, 30);
			k[i].frame = (mot_q32)llround(f * 4294967296.0);
			ref_rand_quat(&rq, &r);
			ref_to_quat(&k[i].q, &rq);
			k[i].ease_in = k[i].ease_out = 0;
		}
		for (mode = 0; mode < 3; mode++) {
			struct mot_rot_track t;
			struct mot_cursor cur = { 0, 0 };
			uint32_t sat = 0;

			if (mode < 2)
				assert_int_equal(mot_rot_track_init(&t, k, n, mode == 1, seg, NK, &sat),
						 MOT_OK);
			else
				assert_int_equal(mot_rot_track_init_compact(&t, k, n), MOT_OK);
			for (s = -20; s <= 1020; s++) {
				mot_q32 qf = k[0].frame + (k[n - 1].frame - k[0].frame) / 1000 * s +
					     (s < 0 ? s : s > 1000 ? s - 1000 : 0) * MOT_Q32_ONE;
				const struct mot_rot_q62 *held;
				struct mot_quat q;
				int64_t m[3][3];
				uint32_t sat2 = 0;

				if (s == 1000)
					qf = k[n - 1].frame;
				held = mot_rot_track_eval(&q, &t, &cur, qf, &sat);
				if (n > 1 && qf > k[0].frame && qf < k[n - 1].frame) {
					assert_null(held);
					continue;
				}
				assert_non_null(held);
				assert_int_equal(mot_quat_to_rot_q62(m, &q, &sat2), MOT_OK);
				assert_int_equal(sat2, 0);
				assert_memory_equal(m, held->r, sizeof(m));
			}
			assert_int_equal(sat, 0);
		}
	}
	for (b = 0; b < 2; b++) {
		struct mot_rot_key k[2] = { { 0, { MOT_Q32_ONE, 0, 0, 0 }, 0, 0 },
					    { MOT_Q32_ONE, bad[b], 0, 0 } };
		struct mot_rot_seg seg[1];
		struct mot_rot_track t;
		struct mot_quat q;
		uint32_t sat = 0;

		assert_int_equal(mot_rot_track_init_compact(&t, k, 2), MOT_OK);
		assert_null(mot_rot_track_eval(&q, &t, NULL, -MOT_Q32_ONE, &sat));
		assert_int_equal(mot_rot_track_init(&t, k, 2, false, seg, 1, &sat), MOT_OK);
		assert_null(mot_rot_track_eval(&q, &t, NULL, 2 * MOT_Q32_ONE, &sat));
	}
}

static mot_q32 q32(double x)
{
	return (mot_q32)llround(x * 4294967296.0);
}

/* A free node whose rotation is four hermite curves with tangents (glTF's
 * CUBICSPLINE rotation), normalised, against the same in long double: the
 * world matrix's entries. */
static void test_quat_curves(void **state)
{
	struct tu_rng r;
	struct tu_worst w = { 0, 0 };
	int trial;

	(void)state;
	tu_seed(&r, 18);
	for (trial = 0; trial < 40; trial++) {
		struct sd_key qk[4][8];
		struct sd_node node;
		struct scene_desc d;
		struct scene_built b;
		struct scene_build_err e;
		struct mot_eval ev;
		struct mot_pose pose;
		uint32_t n = 2 + (uint32_t)(tu_u64(&r) % 7), i, c;
		double f = 0;
		int s;

		for (i = 0; i < n; i++) {
			struct ref_quat q;

			f += tu_uniform(&r, 0.5, 12);
			ref_rand_quat(&q, &r);
			for (c = 0; c < 4; c++) {
				struct sd_key *k = &qk[c][i];

				memset(k, 0, sizeof(*k));
				k->frame = f;
				k->value = c == 0 ? q.w : c == 1 ? q.x : c == 2 ? q.y : q.z;
				k->tan_in = tu_uniform(&r, -0.2, 0.2);
				k->tan_out = tu_uniform(&r, -0.2, 0.2);
				k->tan_set = MOT_TANGENT_IN | MOT_TANGENT_OUT;
			}
		}
		memset(&node, 0, sizeof(node));
		node.name = "n";
		node.parent = -1;
		node.kind = MOT_NODE_FREE;
		node.has_free = true;
		for (c = 0; c < 4; c++)
			node.free.quat[c] = (struct sd_curve){
				.interp = MOT_INTERP_HERMITE, .nkeys = n, .keys = qk[c], .beta1 = 1
			};
		memset(&d, 0, sizeof(d));
		d.rate_num = 24;
		d.rate_den = 1;
		d.tick_hz = 1000;
		d.nnodes = 1;
		d.nodes = &node;
		assert_int_equal(scene_build(&b, &d, &e), 0);
		assert_int_equal(scene_eval_new(&ev, &b.sc), 0);
		assert_int_equal(scene_pose_new(&pose, &b.sc), 0);
		for (s = -5; s < 400; s++) {
			double fr = f * s / 390.0;
			mot_q32 qf = (mot_q32)llround(fr * 4294967296.0);
			struct ref_quat q;
			struct ref_mat m;
			double v[4];
			uint32_t row, col;

			mot_scene_eval(&b.sc, &ev, qf, &pose);
			for (c = 0; c < 4; c++) {
				struct mot_key mk[8];
				struct mot_tangent mt[8];

				for (i = 0; i < n; i++) {
					const struct sd_key *sk = &qk[c][i];

					mk[i] = (struct mot_key){ q32(sk->frame), q32(sk->value),
								  0, 0 };
					mt[i] = (struct mot_tangent){ q32(sk->tan_in),
								      q32(sk->tan_out),
								      sk->tan_set };
				}
				v[c] = (double)ref_hermite(mk, mt, n, ref_q(qf));
			}
			q = (struct ref_quat){ v[0], v[1], v[2], v[3] };
			ref_quat_normalize(&q, &q);
			ref_quat_to_mat(&m, &q);
			for (row = 0; row < 3; row++)
				for (col = 0; col < 3; col++)
					tu_worst_add(&w, ref_q(pose.world[0].m[row][col]) -
								 m.m[row][col], fr);
		}
		assert_int_equal(ev.sat, 0);
		scene_pose_free(&pose);
		scene_eval_free(&ev);
		scene_built_free(&b);
	}
	tu_bound("rot_quat_curves", &w, 1e-8, "");
}

/* A key interval's t (mot_rot_seg_t(), strand.h) is mot_recip_ratio()'s
 * clamped to 1, bit for bit, for every offset in [0, h): widths of 1 to 3
 * LSB, powers of two and their neighbours, random ones up to 2^62, each at
 * its first and last offsets, its middle and random ones. */
static void test_rot_seg_t(void **state)
{
	struct tu_rng r;
	long n = 0;
	int trial, j;

	(void)state;
	tu_seed(&r, 29);
	for (trial = 0; trial < 3000; trial++) {
		struct mot_rot_seg sg;
		int64_t h;

		if (trial < 3)
			h = trial + 1;
		else if (trial < 3 + 3 * 62)
			h = ((int64_t)1 << ((trial - 3) / 3 + 1)) + (trial - 3) % 3 - 1;
		else
			h = 1 + (int64_t)(tu_u64(&r) >> (2 + tu_u64(&r) % 62));
		assert_int_equal(mot_recip_init(&sg.inv_h, h), MOT_OK);
		for (j = 0; j < 40; j++) {
			int64_t x = j == 0 ? 0 : j == 1 ? h - 1 : j == 2 ? h / 2 :
				    (int64_t)(tu_u64(&r) % (uint64_t)h);
			mot_q32 want = mot_recip_ratio(x, &sg.inv_h, NULL);

			want = want > MOT_Q32_ONE ? MOT_Q32_ONE : want;
			assert_int_equal(mot_rot_seg_t(&sg, x), want);
			n++;
		}
	}
	printf("rot_seg_t: %ld offsets, all mot_recip_ratio()'s\n", n);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_tangents),	cmocka_unit_test(test_tangent_errors),
		cmocka_unit_test(test_compact),		cmocka_unit_test(test_compact_errors),
		cmocka_unit_test(test_rot_compact),	cmocka_unit_test(test_quat_curves),
		cmocka_unit_test(test_rot_ends),	cmocka_unit_test(test_rot_seg_t),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
