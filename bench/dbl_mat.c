/* SPDX-License-Identifier: MIT */
/* dbl_mat.c - double-precision twin of the core's matrices and quaternions
 * (see dbl_mat.h; the comments of motion/mat.c, quat.c and decomp.c say why
 * each algorithm is the one it is). */
#include "dbl_mat.h"

#include <math.h>

void dbl_mat_identity(struct dbl_mat *out)
{
	*out = (struct dbl_mat){ { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0, 0, 0 } } };
}

void dbl_mat_mul(struct dbl_mat *out, const struct dbl_mat *a, const struct dbl_mat *b)
{
	struct dbl_mat r;
	int i, j;

	for (i = 0; i < 4; i++)
		for (j = 0; j < 3; j++)
			r.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] +
				    a->m[i][2] * b->m[2][j] + (i == 3 ? b->m[3][j] : 0);
	*out = r;
}

void dbl_mat_apply(double out[3], const double p[3], const struct dbl_mat *m)
{
	double r[3];
	int j;

	for (j = 0; j < 3; j++)
		r[j] = p[0] * m->m[0][j] + p[1] * m->m[1][j] + p[2] * m->m[2][j] + m->m[3][j];
	out[0] = r[0];
	out[1] = r[1];
	out[2] = r[2];
}

void dbl_mat_about_pivot(struct dbl_mat *out, const struct dbl_mat *a, const double p[3])
{
	/* linear part a's, translation -p.A + t + p */
	struct dbl_mat r = *a;
	int j;

	for (j = 0; j < 3; j++)
		r.m[3][j] = a->m[3][j] + p[j] -
			    (p[0] * a->m[0][j] + p[1] * a->m[1][j] + p[2] * a->m[2][j]);
	*out = r;
}

void dbl_quat_from_axis_angle(struct dbl_quat *out, const double axis[3], double rad)
{
	double s, c;

	sincos(rad / 2, &s, &c);
	*out = (struct dbl_quat){ c, axis[0] * s, axis[1] * s, axis[2] * s };
}

void dbl_quat_to_mat(struct dbl_mat *out, const struct dbl_quat *q)
{
	const double w = q->w, x = q->x, y = q->y, z = q->z;

	*out = (struct dbl_mat){ {
		{ 1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y) },
		{ 2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x) },
		{ 2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y) },
		{ 0, 0, 0 },
	} };
}

double dbl_quat_dot(const struct dbl_quat *a, const struct dbl_quat *b)
{
	return a->w * b->w + a->x * b->x + a->y * b->y + a->z * b->z;
}

void dbl_quat_normalize(struct dbl_quat *out, const struct dbl_quat *q)
{
	double k = 1 / sqrt(dbl_quat_dot(q, q));

	*out = (struct dbl_quat){ q->w * k, q->x * k, q->y * k, q->z * k };
}

void dbl_quat_from_mat(struct dbl_quat *out, const struct dbl_mat *mat)
{
	/* Shoemake, with the same branches as mot_quat_from_mat */
	const double(*m)[3] = mat->m;
	double d0 = m[0][0], d1 = m[1][1], d2 = m[2][2], tr = d0 + d1 + d2;
	double wx = m[1][2] - m[2][1], xy = m[0][1] + m[1][0];
	double wy = m[2][0] - m[0][2], xz = m[0][2] + m[2][0];
	double wz = m[0][1] - m[1][0], yz = m[1][2] + m[2][1];
	struct dbl_quat q;

	if (tr > 0)
		q = (struct dbl_quat){ 1 + tr, wx, wy, wz };
	else if (d0 >= d1 && d0 >= d2)
		q = (struct dbl_quat){ wx, 1 + d0 - d1 - d2, xy, xz };
	else if (d1 >= d2)
		q = (struct dbl_quat){ wy, xy, 1 + d1 - d2 - d0, yz };
	else
		q = (struct dbl_quat){ wz, xz, yz, 1 + d2 - d0 - d1 };
	if (q.w < 0)
		q = (struct dbl_quat){ -q.w, -q.x, -q.y, -q.z };
	dbl_quat_normalize(out, &q);
}

/* ---- slerp and squad --------------------------------------------------------- */

void dbl_slerp_prepare(struct dbl_slerp *s, const struct dbl_quat *a, const struct dbl_quat *b)
{
	struct dbl_quat bb = *b, u;
	double d = dbl_quat_dot(a, b), len;

	if (d < 0) {
		bb = (struct dbl_quat){ -b->w, -b->x, -b->y, -b->z };
		d = -d;
	}
	/* Gram-Schmidt of b against a; one pass is enough in double */
	u = (struct dbl_quat){ bb.w - d * a->w, bb.x - d * a->x, bb.y - d * a->y, bb.z - d * a->z };
	len = sqrt(dbl_quat_dot(&u, &u));
	s->a = *a;
	s->b = bb;
	s->theta = atan2(len, d);
	s->nlerp = len < 1.0 / 1024;
	if (s->nlerp)
		s->c = (struct dbl_quat){ 0, 0, 0, 0 };
	else
		s->c = (struct dbl_quat){ u.w / len, u.x / len, u.y / len, u.z / len };
}

void dbl_slerp_eval(struct dbl_quat *out, const struct dbl_slerp *s, double t)
{
	double sn, cs;

	if (t <= 0 || t >= 1) {
		*out = t <= 0 ? s->a : s->b;
		return;
	}
	if (s->nlerp) {
		const struct dbl_quat *a = &s->a, *b = &s->b;
		struct dbl_quat q = { a->w + t * (b->w - a->w), a->x + t * (b->x - a->x),
				      a->y + t * (b->y - a->y), a->z + t * (b->z - a->z) };

		dbl_quat_normalize(out, &q);
		return;
	}
	sincos(t * s->theta, &sn, &cs);
	*out = (struct dbl_quat){ s->a.w * cs + s->c.w * sn, s->a.x * cs + s->c.x * sn,
				  s->a.y * cs + s->c.y * sn, s->a.z * cs + s->c.z * sn };
}

static void quat_mul(struct dbl_quat *out, const struct dbl_quat *a, const struct dbl_quat *b)
{
	*out = (struct dbl_quat){
		a->w * b->w - a->x * b->x - a->y * b->y - a->z * b->z,
		a->w * b->x + a->x * b->w + a->y * b->z - a->z * b->y,
		a->w * b->y - a->x * b->z + a->y * b->w + a->z * b->x,
		a->w * b->z + a->x * b->y - a->y * b->x + a->z * b->w,
	};
}

/* log(cur^-1 * other) on the shorter arc, radians of quaternion arc */
static void rel_log(double out[3], const struct dbl_quat *cur, const struct dbl_quat *other)
{
	struct dbl_quat inv = { cur->w, -cur->x, -cur->y, -cur->z }, r;
	double len, k;

	quat_mul(&r, &inv, other);
	if (r.w < 0)
		r = (struct dbl_quat){ -r.w, -r.x, -r.y, -r.z };
	len = sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
	k = len > 0 ? atan2(len, r.w) / len : 0;
	out[0] = r.x * k;
	out[1] = r.y * k;
	out[2] = r.z * k;
}

void dbl_squad_inner(struct dbl_quat *out, const struct dbl_quat *prev,
		     const struct dbl_quat *cur, const struct dbl_quat *next)
{
	double ln[3], lp[3], l[3], len, s, c;
	struct dbl_quat e, q;
	int i;

	rel_log(ln, cur, next);
	rel_log(lp, cur, prev);
	for (i = 0; i < 3; i++)
		l[i] = -(ln[i] + lp[i]) / 4;
	len = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
	if (len == 0) {
		e = (struct dbl_quat){ 1, 0, 0, 0 };
	} else {
		sincos(len, &s, &c);
		e = (struct dbl_quat){ c, l[0] * s / len, l[1] * s / len, l[2] * s / len };
	}
	quat_mul(&q, cur, &e);
	dbl_quat_normalize(out, &q);
}

/* ---- decomposition --------------------------------------------------------------- */

static double dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int dbl_mat_decompose(struct dbl_decomp *out, const struct dbl_mat *m)
{
	double r[3][3], s[3], h[3] = { 0, 0, 0 }, nmax = 0, det;
	struct dbl_mat rm;
	int i, j, k;

	for (i = 0; i < 3; i++) {
		double u[3] = { m->m[i][0], m->m[i][1], m->m[i][2] }, n = sqrt(dot3(u, u));

		nmax = n > nmax ? n : nmax;
		/* minus the projections on the rows before, collected as shears */
		for (j = 0; j < i; j++) {
			double p = dot3(r[j], u);

			h[i + j - 1] = p;
			for (k = 0; k < 3; k++)
				u[k] -= p * r[j][k];
		}
		s[i] = sqrt(dot3(u, u));
		if (!(s[i] * 1e9 >= nmax) || s[i] == 0)
			return -1;
		for (k = 0; k < 3; k++)
			r[i][k] = u[k] / s[i];
	}
	h[0] /= s[1];
	h[1] /= s[2];
	h[2] /= s[2];
	det = r[2][0] * (r[0][1] * r[1][2] - r[0][2] * r[1][1]) +
	      r[2][1] * (r[0][2] * r[1][0] - r[0][0] * r[1][2]) +
	      r[2][2] * (r[0][0] * r[1][1] - r[0][1] * r[1][0]);
	for (i = 0; i < 3; i++) {
		if (det < 0) {
			s[i] = -s[i];
			for (k = 0; k < 3; k++)
				r[i][k] = -r[i][k];
		}
		for (k = 0; k < 3; k++)
			rm.m[i][k] = r[i][k];
		out->scale[i] = s[i];
		out->shear[i] = h[i];
		out->translate[i] = m->m[3][i];
	}
	dbl_quat_from_mat(&out->rot, &rm);
	return 0;
}

void dbl_mat_compose(struct dbl_mat *out, const struct dbl_decomp *d)
{
	struct dbl_mat r;

	dbl_quat_to_mat(&r, &d->rot);
	dbl_mat_compose_r(out, d, &r);
}

void dbl_mat_compose_r(struct dbl_mat *out, const struct dbl_decomp *d, const struct dbl_mat *r)
{
	const double *s = d->scale, *h = d->shear;
	int j;

	for (j = 0; j < 3; j++) {
		double r0 = r->m[0][j], r1 = r->m[1][j], r2 = r->m[2][j];

		out->m[0][j] = s[0] * r0;
		out->m[1][j] = s[1] * (h[0] * r0 + r1);
		out->m[2][j] = s[2] * (h[1] * r0 + h[2] * r1 + r2);
		out->m[3][j] = d->translate[j];
	}
}
