/* SPDX-License-Identifier: MIT */
/* affine.c - double-precision rotations and decomposition (see affine.h). */
#include "affine.h"

#include <math.h>
#include <string.h>

void affine_quat_mat(double m[3][3], const double q[4])
{
	double w = q[0], x = q[1], y = q[2], z = q[3];

	m[0][0] = 1 - 2 * (y * y + z * z);
	m[0][1] = 2 * (x * y + w * z);
	m[0][2] = 2 * (x * z - w * y);
	m[1][0] = 2 * (x * y - w * z);
	m[1][1] = 1 - 2 * (x * x + z * z);
	m[1][2] = 2 * (y * z + w * x);
	m[2][0] = 2 * (x * z + w * y);
	m[2][1] = 2 * (y * z - w * x);
	m[2][2] = 1 - 2 * (x * x + y * y);
}

/*
 * Shoemake, "Animating rotation with quaternion curves" (1985), with the
 * index pattern of the row-vector matrix above: m[1][2] - m[2][1] = 4wx,
 * m[2][0] - m[0][2] = 4wy, m[0][1] - m[1][0] = 4wz, and the symmetric sums
 * m[0][1] + m[1][0] = 4xy and so on. Dividing by the largest of the four
 * components keeps every division well conditioned.
 */
void affine_mat_quat(double q[4], const double m[3][3])
{
	double tr = m[0][0] + m[1][1] + m[2][2], s, n;
	int i;

	if (tr > 0) {
		s = 2 * sqrt(1 + tr); /* 4w */
		q[0] = s / 4;
		q[1] = (m[1][2] - m[2][1]) / s;
		q[2] = (m[2][0] - m[0][2]) / s;
		q[3] = (m[0][1] - m[1][0]) / s;
	} else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
		s = 2 * sqrt(1 + m[0][0] - m[1][1] - m[2][2]); /* 4x */
		q[0] = (m[1][2] - m[2][1]) / s;
		q[1] = s / 4;
		q[2] = (m[0][1] + m[1][0]) / s;
		q[3] = (m[0][2] + m[2][0]) / s;
	} else if (m[1][1] >= m[2][2]) {
		s = 2 * sqrt(1 + m[1][1] - m[0][0] - m[2][2]); /* 4y */
		q[0] = (m[2][0] - m[0][2]) / s;
		q[1] = (m[0][1] + m[1][0]) / s;
		q[2] = s / 4;
		q[3] = (m[1][2] + m[2][1]) / s;
	} else {
		s = 2 * sqrt(1 + m[2][2] - m[0][0] - m[1][1]); /* 4z */
		q[0] = (m[0][1] - m[1][0]) / s;
		q[1] = (m[0][2] + m[2][0]) / s;
		q[2] = (m[1][2] + m[2][1]) / s;
		q[3] = s / 4;
	}
	n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
	if (q[0] < 0)
		n = -n;
	for (i = 0; i < 4; i++)
		q[i] /= n;
}

/* Hamilton product a * b. */
static void quat_mul(double out[4], const double a[4], const double b[4])
{
	double r[4];

	r[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
	r[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
	r[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
	r[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
	memcpy(out, r, sizeof(r));
}

/* With row vectors R(q1) . R(q2) = R(q2 * q1), so Rx . Ry . Rz is the
 * quaternion qz * qy * qx. */
void affine_euler_quat(double q[4], const double deg[3])
{
	double h[3], qx[4], qy[4], qz[4];
	int i;

	for (i = 0; i < 3; i++)
		h[i] = deg[i] * (M_PI / 360.0); /* half angle, radians */
	qx[0] = cos(h[0]), qx[1] = sin(h[0]), qx[2] = 0, qx[3] = 0;
	qy[0] = cos(h[1]), qy[1] = 0, qy[2] = sin(h[1]), qy[3] = 0;
	qz[0] = cos(h[2]), qz[1] = 0, qz[2] = 0, qz[3] = sin(h[2]);
	quat_mul(q, qz, qy);
	quat_mul(q, q, qx);
}

static double dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double norm3(const double a[3])
{
	return sqrt(dot3(a, a));
}

int affine_decompose(struct affine_decomp *out, const double m[4][4], int *axis)
{
	double r[3][3], u[3], maxn = 0, a, b, c, det, (*R)[3] = out->rot;
	int i, j;

	for (i = 0; i < 4; i++)
		if (fabs(m[i][3] - (i == 3 ? 1.0 : 0.0)) > 1e-9)
			return AFFINE_E_NOT_AFFINE;
	for (i = 0; i < 3; i++) {
		for (j = 0; j < 3; j++)
			r[i][j] = m[i][j];
		maxn = fmax(maxn, norm3(r[i]));
		out->translate[i] = m[3][i];
	}
	/* Gram-Schmidt on the rows, FORMULAS section 2 */
	out->scale[0] = norm3(r[0]);
	if (!(out->scale[0] > 1e-9 * maxn))
		return *axis = 0, AFFINE_E_SINGULAR;
	for (j = 0; j < 3; j++)
		R[0][j] = r[0][j] / out->scale[0];
	a = dot3(R[0], r[1]);
	for (j = 0; j < 3; j++)
		u[j] = r[1][j] - a * R[0][j];
	out->scale[1] = norm3(u);
	if (!(out->scale[1] > 1e-9 * maxn))
		return *axis = 1, AFFINE_E_SINGULAR;
	for (j = 0; j < 3; j++)
		R[1][j] = u[j] / out->scale[1];
	out->shear[0] = a / out->scale[1];
	b = dot3(R[0], r[2]);
	c = dot3(R[1], r[2]);
	for (j = 0; j < 3; j++)
		u[j] = r[2][j] - b * R[0][j] - c * R[1][j];
	out->scale[2] = norm3(u);
	if (!(out->scale[2] > 1e-9 * maxn))
		return *axis = 2, AFFINE_E_SINGULAR;
	for (j = 0; j < 3; j++)
		R[2][j] = u[j] / out->scale[2];
	out->shear[1] = b / out->scale[2];
	out->shear[2] = c / out->scale[2];
	det = R[0][0] * (R[1][1] * R[2][2] - R[1][2] * R[2][1]) -
	      R[0][1] * (R[1][0] * R[2][2] - R[1][2] * R[2][0]) +
	      R[0][2] * (R[1][0] * R[2][1] - R[1][1] * R[2][0]);
	if (det < 0) {
		/* S.H.R = (-S).H.(-R): the shear is unchanged */
		for (i = 0; i < 3; i++) {
			out->scale[i] = -out->scale[i];
			for (j = 0; j < 3; j++)
				R[i][j] = -R[i][j];
		}
	}
	affine_mat_quat(out->q, (const double(*)[3])R);
	return AFFINE_OK;
}

void affine_compose(double m[4][4], const struct affine_decomp *d)
{
	const double(*R)[3] = d->rot;
	int j;

	for (j = 0; j < 3; j++) {
		m[0][j] = d->scale[0] * R[0][j];
		m[1][j] = d->scale[1] * (d->shear[0] * R[0][j] + R[1][j]);
		m[2][j] = d->scale[2] * (d->shear[1] * R[0][j] + d->shear[2] * R[1][j] + R[2][j]);
		m[3][j] = d->translate[j];
	}
	m[0][3] = m[1][3] = m[2][3] = 0;
	m[3][3] = 1;
}
