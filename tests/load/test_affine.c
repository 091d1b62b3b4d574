/* SPDX-License-Identifier: MIT */
/*
 * test_affine.c - the loader's double-precision rotations and matrix
 * decomposition (firmware/affine.c) against FORMULAS sections 1, 2 and 4
 * written out directly.
 */
#include <math.h>
#include <string.h>

#include "load/affine.h"
#include "testutil.h"

typedef double m3[3][3];

static void mul3(m3 out, const m3 a, const m3 b)
{
	m3 r;
	int i, j, k;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			for (r[i][j] = 0, k = 0; k < 3; k++)
				r[i][j] += a[i][k] * b[k][j];
	memcpy(out, r, sizeof(r));
}

/* FORMULAS section 1, row-vector rotations by degrees. */
static void rot(m3 m, int axis, double deg)
{
	double c = cos(deg * M_PI / 180), s = sin(deg * M_PI / 180);
	int a = (axis + 1) % 3, b = (axis + 2) % 3;

	memset(m, 0, sizeof(m3));
	m[axis][axis] = 1;
	m[a][a] = c, m[a][b] = s;
	m[b][a] = -s, m[b][b] = c;
}

static double mat_err(const m3 a, const m3 b)
{
	double e = 0;
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			e = fmax(e, fabs(a[i][j] - b[i][j]));
	return e;
}

static void test_axes(void **state)
{
	double x[3] = { 1, 0, 0 }, q[4], deg[3] = { 0, 0, 90 };
	m3 m;

	/* (1,0,0) . Rz(90) = (0,1,0), and Rz(theta) is (cos theta/2, 0, 0, sin theta/2) */
	affine_euler_quat(q, deg);
	assert_true(fabs(q[0] - cos(M_PI / 4)) < 1e-15 && fabs(q[3] - sin(M_PI / 4)) < 1e-15);
	affine_quat_mat(m, q);
	assert_true(fabs(x[0] * m[0][1] - 1) < 1e-15 && fabs(m[0][0]) < 1e-15);
}

/* Euler R = Rx . Ry . Rz, through the quaternion, equals the product. */
static void test_euler(void **state)
{
	struct tu_rng r;
	struct tu_worst w = { 0, 0 };
	int i;

	tu_seed(&r, 11);
	for (i = 0; i < 20000; i++) {
		double deg[3], q[4];
		m3 rx, ry, rz, want, got;

		deg[0] = tu_uniform(&r, -400, 400);
		deg[1] = tu_uniform(&r, -400, 400);
		deg[2] = tu_uniform(&r, -400, 400);
		rot(rx, 0, deg[0]);
		rot(ry, 1, deg[1]);
		rot(rz, 2, deg[2]);
		mul3(want, rx, ry);
		mul3(want, want, rz);
		affine_euler_quat(q, deg);
		affine_quat_mat(got, q);
		tu_worst_add(&w, mat_err(want, got), i);
	}
	tu_bound("affine_euler_quat vs Rx.Ry.Rz", &w, 1e-14, "");
}

/* Shoemake's matrix-to-quaternion on every branch: back to the same matrix. */
static void test_mat_quat(void **state)
{
	struct tu_rng r;
	struct tu_worst w = { 0, 0 };
	int i;

	tu_seed(&r, 12);
	for (i = 0; i < 20000; i++) {
		double q[4], back[4], n = 0;
		m3 m, m2;
		int k;

		for (k = 0; k < 4; k++)
			q[k] = tu_uniform(&r, -1, 1), n += q[k] * q[k];
		/* force the small-trace branches often: near half turns */
		if (i % 3 == 0)
			q[0] *= 1e-3, n = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
		for (k = 0; k < 4; k++)
			q[k] /= sqrt(n);
		affine_quat_mat(m, q);
		affine_mat_quat(back, m);
		affine_quat_mat(m2, back);
		assert_true(back[0] >= 0);
		tu_worst_add(&w, mat_err(m, m2), i);
	}
	tu_bound("affine_mat_quat round trip", &w, 1e-14, "");
}

/* Compose random S, H, R, t; decompose; recompose: the same matrix, and the
 * same parts when the scales are positive. */
static void test_decompose(void **state)
{
	struct tu_rng r;
	struct tu_worst wm = { 0, 0 }, wp = { 0, 0 };
	int i, k, axis;

	tu_seed(&r, 13);
	for (i = 0; i < 20000; i++) {
		struct affine_decomp d, e;
		double m[4][4], m2[4][4], deg[3], err = 0;
		bool flip = i % 4 == 0;

		for (k = 0; k < 3; k++) {
			d.scale[k] = tu_uniform(&r, 0.1, 3) * (flip ? -1 : 1);
			d.shear[k] = tu_uniform(&r, -1, 1);
			d.translate[k] = tu_uniform(&r, -100, 100);
			deg[k] = tu_uniform(&r, -180, 180);
		}
		affine_euler_quat(d.q, deg);
		affine_quat_mat(d.rot, d.q);
		affine_compose(m, &d);
		assert_int_equal(affine_decompose(&e, (const double(*)[4])m, &axis), AFFINE_OK);
		affine_compose(m2, &e);
		for (k = 0; k < 16; k++)
			err = fmax(err, fabs(m[k / 4][k % 4] - m2[k / 4][k % 4]));
		tu_worst_add(&wm, err / 100, i);
		for (k = 0, err = 0; k < 3; k++)
			err = fmax(err, fmax(fabs(d.scale[k] - e.scale[k]),
					     fabs(d.shear[k] - e.shear[k])));
		tu_worst_add(&wp, err, i);
	}
	tu_bound("affine_decompose recomposes (relative to |t| = 100)", &wm, 1e-14, "");
	tu_bound("affine_decompose recovers scale and shear", &wp, 1e-11, "");
}

static void test_singular(void **state)
{
	const double flat[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 1, 1, 0, 0 }, { 0, 0, 0, 1 } };
	const double tiny[4][4] = { { 1, 0, 0, 0 }, { 0, 1e-10, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } };
	const double ok[4][4] = { { 1, 0, 0, 0 }, { 0, 1e-8, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 } };
	const double proj[4][4] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 1 }, { 0, 0, 0, 1 } };
	const double zero[4][4] = { { 0 } };
	struct affine_decomp d;
	int axis = -1;

	assert_int_equal(affine_decompose(&d, flat, &axis), AFFINE_E_SINGULAR);
	assert_int_equal(axis, 2);
	assert_int_equal(affine_decompose(&d, tiny, &axis), AFFINE_E_SINGULAR);
	assert_int_equal(axis, 1);
	assert_int_equal(affine_decompose(&d, ok, &axis), AFFINE_OK);
	assert_int_equal(affine_decompose(&d, proj, &axis), AFFINE_E_NOT_AFFINE);
	assert_int_equal(affine_decompose(&d, zero, &axis), AFFINE_E_NOT_AFFINE);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_axes),	  cmocka_unit_test(test_euler),
		cmocka_unit_test(test_mat_quat),  cmocka_unit_test(test_decompose),
		cmocka_unit_test(test_singular),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
