/* SPDX-License-Identifier: MIT */
/*
 * test_decomp.c - motion/decomp.c against the Gram-Schmidt of FORMULAS
 * section 2 in double (tests/ref_mat.c): random S.H.R.T keys with scales
 * 0.01..100 (some negative: reflections), shears, rotations and translations
 * of +-100 m; the round trip compose(decompose(M)); the singular threshold.
 */
#include <string.h>

#include "motion/trig.h"
#include "ref_mat.h"

#define N 100000
#define LSB (1.0 / 4294967296.0)
#define REACH 100.0 /* m */

static void test_decompose_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst ws = { 0, 0 }, wh = { 0, 0 }, wr = { 0, 0 }, wm = { 0, 0 }, wt = { 0, 0 };
	long sign_bad = 0, improper = 0, reflections = 0;
	int i, k;

	tu_seed(&rng, 41);
	for (i = 0; i < N; i++) {
		struct ref_mat r, f, rr;
		struct mot_mat m, rot, back;
		struct mot_decomp d;
		struct ref_decomp rd;
		struct ref_quat rq;
		uint32_t sat = 0;

		ref_rand_affine(&r, &rng, 0.01, 100, 1, REACH, true);
		ref_to_mat(&m, &r);
		ref_from_mat(&r, &m);
		assert_int_equal(mot_mat_decompose(&d, &rot, &m, &sat), MOT_OK);
		assert_int_equal(ref_decompose(&rd, &r), 0);
		reflections += rd.scale[0] < 0;
		for (k = 0; k < 3; k++) {
			tu_worst_add(&ws, (q2d(d.scale[k]) - rd.scale[k]) / LSB, rd.scale[k]);
			tu_worst_add(&wh, (q2d(d.shear[k]) - rd.shear[k]) / LSB, rd.shear[k]);
			sign_bad += (d.scale[k] < 0) != (rd.scale[k] < 0);
			assert_int_equal(d.translate[k], m.m[3][k]);
		}
		/* R as rows and as the quaternion */
		ref_from_mat(&f, &rot);
		memset(&rr, 0, sizeof(rr));
		for (k = 0; k < 9; k++)
			rr.m[k / 3][k % 3] = rd.rot[k / 3][k % 3];
		tu_worst_add(&wm, ref_lin_diff(&f, &rr) / LSB, i);
		improper += ref_det3(&f) < 0;
		ref_quat_from_mat(&rq, &rr);
		{
			struct ref_quat fq;

			ref_from_quat(&fq, &d.rot);
			tu_worst_add(&wr, ref_quat_angle(&fq, &rq), i);
			assert_true(d.rot.w >= 0);
		}
		/* round trip: the quaternion's resolution (~5e-10 rad) times the
		 * lever arm, so per unit of the largest scale */
		mot_mat_compose(&back, &d, &sat);
		ref_from_mat(&f, &back);
		tu_worst_add(&wt, ref_point_diff(&f, &r, REACH) /
				      fmax(1, fmax(fabs(rd.scale[0]), fmax(fabs(rd.scale[1]), fabs(rd.scale[2])))),
			     i);
		assert_int_equal(sat, 0);
	}
	assert_int_equal(sign_bad, 0);
	assert_int_equal(improper, 0);
	assert_true(reflections > N / 4);
	tu_bound("decomp.scale (0.01..100)", &ws, 0.6, "LSB");
	tu_bound("decomp.shear", &wh, 0.6, "LSB");
	tu_bound("decomp.rot_mat entry", &wm, 0.6, "LSB");
	tu_bound("decomp.rot quaternion", &wr, 2e-9, "rad");
	tu_bound("decomp.compose(decompose(M)) point / max(1, |s|max)", &wt, 5e-7, "m");
}

static void test_compose_ref(void **state)
{
	struct tu_rng rng;
	struct tu_worst w = { 0, 0 };
	int i, k;

	tu_seed(&rng, 42);
	for (i = 0; i < N; i++) {
		struct mot_decomp d;
		struct ref_decomp rd;
		struct ref_quat q;
		struct ref_mat rm, f;
		struct mot_mat m;
		uint32_t sat = 0;

		ref_rand_quat(&q, &rng);
		if (q.w < 0)
			q = (struct ref_quat){ -q.w, -q.x, -q.y, -q.z };
		ref_to_quat(&d.rot, &q);
		ref_from_quat(&q, &d.rot);
		ref_quat_to_mat(&rm, &q);
		for (k = 0; k < 9; k++)
			rd.rot[k / 3][k % 3] = rm.m[k / 3][k % 3];
		for (k = 0; k < 3; k++) {
			d.scale[k] = d2q(exp(tu_uniform(&rng, log(0.01), log(100))));
			d.shear[k] = d2q(tu_uniform(&rng, -1, 1));
			d.translate[k] = d2q(tu_uniform(&rng, -REACH, REACH));
			rd.scale[k] = q2d(d.scale[k]);
			rd.shear[k] = q2d(d.shear[k]);
			rd.translate[k] = q2d(d.translate[k]);
		}
		mot_mat_compose(&m, &d, &sat);
		ref_compose(&rm, &rd);
		ref_from_mat(&f, &m);
		tu_worst_add(&w, ref_point_diff(&f, &rm, REACH), i);
		assert_int_equal(sat, 0);
	}
	tu_bound("decomp.compose point (s 0.01..100, shear +-1)", &w, 1e-7, "m");
}

static void test_singular(void **state)
{
	const mot_q32 one = MOT_Q32_ONE;
	struct mot_decomp d, sentinel;
	struct mot_mat m, rot;
	uint32_t sat = 0;
	int k;

	memset(&sentinel, 0x5a, sizeof(sentinel));
	d = sentinel;
	memset(&m, 0, sizeof(m));
	assert_int_equal(mot_mat_decompose(&d, NULL, &m, &sat), MOT_E_SINGULAR);
	/* a zero row, dependent rows */
	mot_mat_scale(&m, (const mot_q32[3]){ 0, one, one });
	assert_int_equal(mot_mat_decompose(&d, NULL, &m, &sat), MOT_E_SINGULAR);
	mot_mat_identity(&m);
	m.m[2][0] = 2 * one, m.m[2][1] = 3 * one, m.m[2][2] = 0;
	assert_int_equal(mot_mat_decompose(&d, NULL, &m, &sat), MOT_E_SINGULAR);
	assert_memory_equal(&d, &sentinel, sizeof(d));
	/* the threshold, 1e-9 of the largest row norm (here 1, and 1000):
	 * 4 LSB = 0.93e-9 is singular, 5 LSB = 1.16e-9 is not, and stays 5 */
	mot_mat_scale(&m, (const mot_q32[3]){ one, -one, 4 });
	assert_int_equal(mot_mat_decompose(&d, NULL, &m, &sat), MOT_E_SINGULAR);
	mot_mat_scale(&m, (const mot_q32[3]){ one, -one, 5 });
	assert_int_equal(mot_mat_decompose(&d, NULL, &m, &sat), MOT_OK);
	assert_true(d.scale[0] == -one && d.scale[1] == -one && d.scale[2] == -5);
	mot_mat_scale(&m, (const mot_q32[3]){ 1000 * one, one, 4294 });
	assert_int_equal(mot_mat_decompose(&d, NULL, &m, &sat), MOT_E_SINGULAR);
	mot_mat_scale(&m, (const mot_q32[3]){ 1000 * one, one, 4295 });
	assert_int_equal(mot_mat_decompose(&d, &rot, &m, &sat), MOT_OK);
	assert_true(d.scale[0] == 1000 * one && d.scale[1] == one && d.scale[2] == 4295);
	for (k = 0; k < 3; k++)
		assert_true(d.shear[k] == 0 && rot.m[k][k] == one && rot.m[3][k] == 0);
	assert_true(d.rot.w == one && d.rot.x == 0 && d.rot.y == 0 && d.rot.z == 0);
	assert_int_equal(sat, 0);
}

static void test_rotation_only(void **state)
{
	struct tu_rng rng;
	struct tu_worst ws = { 0, 0 }, wh = { 0, 0 };
	int i, k;

	tu_seed(&rng, 43);
	for (i = 0; i < N; i++) {
		mot_q32 e[3];
		struct mot_mat m;
		struct mot_decomp d;
		uint32_t sat = 0;

		for (k = 0; k < 3; k++)
			e[k] = d2q(tu_uniform(&rng, -1, 1));
		mot_mat_euler(&m, e, &sat);
		assert_int_equal(mot_mat_decompose(&d, NULL, &m, &sat), MOT_OK);
		for (k = 0; k < 3; k++) {
			tu_worst_add(&ws, (q2d(d.scale[k]) - 1) / LSB, i);
			tu_worst_add(&wh, q2d(d.shear[k]) / LSB, i);
		}
	}
	tu_bound("decomp of a rotation: scale - 1", &ws, 2, "LSB");
	tu_bound("decomp of a rotation: shear", &wh, 3, "LSB");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_decompose_ref),
		cmocka_unit_test(test_compose_ref),
		cmocka_unit_test(test_singular),
		cmocka_unit_test(test_rotation_only),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
