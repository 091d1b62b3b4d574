/* SPDX-License-Identifier: MIT */
/* ref_mat.c - see ref_mat.h. Plain double arithmetic, written for clarity. */
#include <math.h>
#include <string.h>

#include "ref_mat.h"

#define RQ 4294967296.0

void ref_from_mat(struct ref_mat *out, const struct mot_mat *m)
{
	int i, j;

	for (i = 0; i < 4; i++) {
		for (j = 0; j < 3; j++)
			out->m[i][j] = (double)m->m[i][j] / RQ;
		out->m[i][3] = i == 3 ? 1.0 : 0.0;
	}
}

void ref_to_mat(struct mot_mat *out, const struct ref_mat *m)
{
	int i, j;

	for (i = 0; i < 4; i++)
		for (j = 0; j < 3; j++)
			out->m[i][j] = (mot_q32)llround(m->m[i][j] * RQ);
}

void ref_from_quat(struct ref_quat *out, const struct mot_quat *q)
{
	out->w = (double)q->w / RQ;
	out->x = (double)q->x / RQ;
	out->y = (double)q->y / RQ;
	out->z = (double)q->z / RQ;
}

void ref_to_quat(struct mot_quat *out, const struct ref_quat *q)
{
	out->w = (mot_q32)llround(q->w * RQ);
	out->x = (mot_q32)llround(q->x * RQ);
	out->y = (mot_q32)llround(q->y * RQ);
	out->z = (mot_q32)llround(q->z * RQ);
}

void ref_identity(struct ref_mat *out)
{
	int i, j;

	for (i = 0; i < 4; i++)
		for (j = 0; j < 4; j++)
			out->m[i][j] = i == j;
}

void ref_translate(struct ref_mat *out, double x, double y, double z)
{
	ref_identity(out);
	out->m[3][0] = x;
	out->m[3][1] = y;
	out->m[3][2] = z;
}

void ref_scale(struct ref_mat *out, double x, double y, double z)
{
	ref_identity(out);
	out->m[0][0] = x;
	out->m[1][1] = y;
	out->m[2][2] = z;
}

void ref_shear(struct ref_mat *out, double hxy, double hxz, double hyz)
{
	ref_identity(out);
	out->m[1][0] = hxy;
	out->m[2][0] = hxz;
	out->m[2][1] = hyz;
}

void ref_rot_x(struct ref_mat *out, double rad)
{
	double c = cos(rad), s = sin(rad);

	ref_identity(out);
	out->m[1][1] = c, out->m[1][2] = s;
	out->m[2][1] = -s, out->m[2][2] = c;
}

void ref_rot_y(struct ref_mat *out, double rad)
{
	double c = cos(rad), s = sin(rad);

	ref_identity(out);
	out->m[0][0] = c, out->m[0][2] = -s;
	out->m[2][0] = s, out->m[2][2] = c;
}

void ref_rot_z(struct ref_mat *out, double rad)
{
	double c = cos(rad), s = sin(rad);

	ref_identity(out);
	out->m[0][0] = c, out->m[0][1] = s;
	out->m[1][0] = -s, out->m[1][1] = c;
}

void ref_euler(struct ref_mat *out, double rx, double ry, double rz)
{
	struct ref_mat a, b, c, ab;

	ref_rot_x(&a, rx);
	ref_rot_y(&b, ry);
	ref_rot_z(&c, rz);
	ref_mul(&ab, &a, &b);
	ref_mul(out, &ab, &c);
}

void ref_mul(struct ref_mat *out, const struct ref_mat *a, const struct ref_mat *b)
{
	struct ref_mat r;
	int i, j, k;

	for (i = 0; i < 4; i++)
		for (j = 0; j < 4; j++) {
			double s = 0;

			for (k = 0; k < 4; k++)
				s += a->m[i][k] * b->m[k][j];
			r.m[i][j] = s;
		}
	*out = r;
}

int ref_inverse(struct ref_mat *out, const struct ref_mat *a)
{
	double m[4][8];
	int i, j, k;

	for (i = 0; i < 4; i++)
		for (j = 0; j < 8; j++)
			m[i][j] = j < 4 ? a->m[i][j] : (j - 4 == i);
	for (k = 0; k < 4; k++) {
		int p = k;

		for (i = k + 1; i < 4; i++)
			if (fabs(m[i][k]) > fabs(m[p][k]))
				p = i;
		if (m[p][k] == 0)
			return -1;
		for (j = 0; j < 8; j++) {
			double t = m[k][j];

			m[k][j] = m[p][j];
			m[p][j] = t;
		}
		for (i = 0; i < 4; i++) {
			double f = m[i][k] / m[k][k];

			if (i == k)
				continue;
			for (j = 0; j < 8; j++)
				m[i][j] -= f * m[k][j];
		}
	}
	for (i = 0; i < 4; i++)
		for (j = 0; j < 4; j++)
			out->m[i][j] = m[i][j + 4] / m[i][i];
	return 0;
}

long double ref_det3(const struct ref_mat *a)
{
	long double m[3][3];
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			m[i][j] = a->m[i][j];

	return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
	       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
	       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

void ref_apply(double out[3], const double p[3], const struct ref_mat *m)
{
	double r[3];
	int j;

	for (j = 0; j < 3; j++)
		r[j] = p[0] * m->m[0][j] + p[1] * m->m[1][j] + p[2] * m->m[2][j] + m->m[3][j];
	memcpy(out, r, sizeof(r));
}

void ref_apply_dir(double out[3], const double v[3], const struct ref_mat *m)
{
	double r[3];
	int j;

	for (j = 0; j < 3; j++)
		r[j] = v[0] * m->m[0][j] + v[1] * m->m[1][j] + v[2] * m->m[2][j];
	memcpy(out, r, sizeof(r));
}

double ref_lin_diff(const struct ref_mat *a, const struct ref_mat *b)
{
	double w = 0;
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			w = fmax(w, fabs(a->m[i][j] - b->m[i][j]));
	return w;
}

double ref_point_diff(const struct ref_mat *a, const struct ref_mat *b, double reach)
{
	double w = 0;
	int j;

	/* |(p,1).(A - B)| per column is largest at a corner of the cube */
	for (j = 0; j < 3; j++) {
		double e = fabs(a->m[3][j] - b->m[3][j]);
		int i;

		for (i = 0; i < 3; i++)
			e += reach * fabs(a->m[i][j] - b->m[i][j]);
		w = fmax(w, e);
	}
	return w;
}

void ref_quat_axis_angle(struct ref_quat *out, const double axis[3], double rad)
{
	double s = sin(rad / 2);

	*out = (struct ref_quat){ cos(rad / 2), axis[0] * s, axis[1] * s, axis[2] * s };
}

void ref_quat_to_mat(struct ref_mat *out, const struct ref_quat *q)
{
	double w = q->w, x = q->x, y = q->y, z = q->z;

	ref_identity(out);
	out->m[0][0] = 1 - 2 * (y * y + z * z);
	out->m[0][1] = 2 * (x * y + w * z);
	out->m[0][2] = 2 * (x * z - w * y);
	out->m[1][0] = 2 * (x * y - w * z);
	out->m[1][1] = 1 - 2 * (x * x + z * z);
	out->m[1][2] = 2 * (y * z + w * x);
	out->m[2][0] = 2 * (x * z + w * y);
	out->m[2][1] = 2 * (y * z - w * x);
	out->m[2][2] = 1 - 2 * (x * x + y * y);
}

void ref_quat_from_mat(struct ref_quat *out, const struct ref_mat *mat)
{
	const double(*m)[4] = mat->m;
	double tr = m[0][0] + m[1][1] + m[2][2], s;
	struct ref_quat q;

	if (tr > 0) {
		s = sqrt(tr + 1);
		q.w = s / 2;
		s = 0.5 / s;
		q.x = (m[1][2] - m[2][1]) * s;
		q.y = (m[2][0] - m[0][2]) * s;
		q.z = (m[0][1] - m[1][0]) * s;
	} else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
		s = sqrt(1 + m[0][0] - m[1][1] - m[2][2]);
		q.x = s / 2;
		s = 0.5 / s;
		q.w = (m[1][2] - m[2][1]) * s;
		q.y = (m[0][1] + m[1][0]) * s;
		q.z = (m[0][2] + m[2][0]) * s;
	} else if (m[1][1] >= m[2][2]) {
		s = sqrt(1 + m[1][1] - m[2][2] - m[0][0]);
		q.y = s / 2;
		s = 0.5 / s;
		q.w = (m[2][0] - m[0][2]) * s;
		q.x = (m[0][1] + m[1][0]) * s;
		q.z = (m[1][2] + m[2][1]) * s;
	} else {
		s = sqrt(1 + m[2][2] - m[0][0] - m[1][1]);
		q.z = s / 2;
		s = 0.5 / s;
		q.w = (m[0][1] - m[1][0]) * s;
		q.x = (m[0][2] + m[2][0]) * s;
		q.y = (m[1][2] + m[2][1]) * s;
	}
	if (q.w < 0)
		q = (struct ref_quat){ -q.w, -q.x, -q.y, -q.z };
	ref_quat_normalize(out, &q);
}

void ref_quat_mul(struct ref_quat *out, const struct ref_quat *a, const struct ref_quat *b)
{
	struct ref_quat r = {
		a->w * b->w - a->x * b->x - a->y * b->y - a->z * b->z,
		a->w * b->x + a->x * b->w + a->y * b->z - a->z * b->y,
		a->w * b->y - a->x * b->z + a->y * b->w + a->z * b->x,
		a->w * b->z + a->x * b->y - a->y * b->x + a->z * b->w,
	};

	*out = r;
}

double ref_quat_dot(const struct ref_quat *a, const struct ref_quat *b)
{
	return a->w * b->w + a->x * b->x + a->y * b->y + a->z * b->z;
}

double ref_quat_norm(const struct ref_quat *q)
{
	return sqrt(ref_quat_dot(q, q));
}

void ref_quat_normalize(struct ref_quat *out, const struct ref_quat *q)
{
	double n = ref_quat_norm(q);

	*out = (struct ref_quat){ q->w / n, q->x / n, q->y / n, q->z / n };
}

double ref_quat_angle(const struct ref_quat *a, const struct ref_quat *b)
{
	struct ref_quat ia = { a->w, -a->x, -a->y, -a->z }, r;

	ref_quat_mul(&r, &ia, b);
	return 2 * atan2(sqrt(r.x * r.x + r.y * r.y + r.z * r.z), fabs(r.w));
}

void ref_slerp(struct ref_quat *out, const struct ref_quat *a, const struct ref_quat *b, double t)
{
	struct ref_quat c = *b;
	double d = ref_quat_dot(a, b), th, s, ka, kb;

	if (d < 0) {
		c = (struct ref_quat){ -c.w, -c.x, -c.y, -c.z };
		d = -d;
	}
	th = acos(fmin(d, 1.0));
	s = sin(th);
	if (s < 1e-12) {
		ka = 1 - t, kb = t;
	} else {
		ka = sin((1 - t) * th) / s;
		kb = sin(t * th) / s;
	}
	*out = (struct ref_quat){ ka * a->w + kb * c.w, ka * a->x + kb * c.x, ka * a->y + kb * c.y,
				  ka * a->z + kb * c.z };
}

void ref_quat_log(double out[3], const struct ref_quat *q)
{
	double n = sqrt(q->x * q->x + q->y * q->y + q->z * q->z);
	double k = n > 0 ? atan2(n, q->w) / n : 0;

	out[0] = q->x * k;
	out[1] = q->y * k;
	out[2] = q->z * k;
}

void ref_quat_exp(struct ref_quat *out, const double v[3])
{
	double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
	double k = n > 0 ? sin(n) / n : 1;

	*out = (struct ref_quat){ cos(n), v[0] * k, v[1] * k, v[2] * k };
}

static void ref_rel_log(double out[3], const struct ref_quat *cur, const struct ref_quat *other)
{
	struct ref_quat inv = { cur->w, -cur->x, -cur->y, -cur->z }, r;

	ref_quat_mul(&r, &inv, other);
	if (r.w < 0)
		r = (struct ref_quat){ -r.w, -r.x, -r.y, -r.z };
	ref_quat_log(out, &r);
}

void ref_squad_inner(struct ref_quat *out, const struct ref_quat *prev,
		     const struct ref_quat *cur, const struct ref_quat *next)
{
	double a[3], b[3], l[3];
	struct ref_quat e;
	int i;

	ref_rel_log(a, cur, next);
	ref_rel_log(b, cur, prev);
	for (i = 0; i < 3; i++)
		l[i] = -(a[i] + b[i]) / 4;
	ref_quat_exp(&e, l);
	ref_quat_mul(out, cur, &e);
	ref_quat_normalize(out, out);
}

void ref_squad(struct ref_quat *out, const struct ref_quat *q0, const struct ref_quat *q1,
	       const struct ref_quat *s0, const struct ref_quat *s1, double t)
{
	struct ref_quat b = *q1, sb = *s1, p, r;

	if (ref_quat_dot(q0, q1) < 0) {
		b = (struct ref_quat){ -b.w, -b.x, -b.y, -b.z };
		sb = (struct ref_quat){ -sb.w, -sb.x, -sb.y, -sb.z };
	}
	ref_slerp(&p, q0, &b, t);
	ref_slerp(&r, s0, &sb, t);
	ref_slerp(out, &p, &r, 2 * t * (1 - t));
}

static double dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int ref_decompose(struct ref_decomp *out, const struct ref_mat *m)
{
	double r[3][3], R[3][3], u[3], a, b, c, s[3], nmax = 0, det;
	int i, j;

	for (i = 0; i < 3; i++) {
		for (j = 0; j < 3; j++)
			r[i][j] = m->m[i][j];
		nmax = fmax(nmax, sqrt(dot3(r[i], r[i])));
	}
	s[0] = sqrt(dot3(r[0], r[0]));
	if (!(s[0] >= 1e-9 * nmax) || nmax == 0)
		return -1;
	for (j = 0; j < 3; j++)
		R[0][j] = r[0][j] / s[0];
	a = dot3(R[0], r[1]);
	for (j = 0; j < 3; j++)
		u[j] = r[1][j] - a * R[0][j];
	s[1] = sqrt(dot3(u, u));
	if (!(s[1] >= 1e-9 * nmax))
		return -1;
	for (j = 0; j < 3; j++)
		R[1][j] = u[j] / s[1];
	b = dot3(R[0], r[2]);
	c = dot3(R[1], r[2]);
	for (j = 0; j < 3; j++)
		u[j] = r[2][j] - b * R[0][j] - c * R[1][j];
	s[2] = sqrt(dot3(u, u));
	if (!(s[2] >= 1e-9 * nmax))
		return -1;
	for (j = 0; j < 3; j++)
		R[2][j] = u[j] / s[2];
	out->shear[0] = a / s[1];
	out->shear[1] = b / s[2];
	out->shear[2] = c / s[2];
	det = R[0][0] * (R[1][1] * R[2][2] - R[1][2] * R[2][1]) -
	      R[0][1] * (R[1][0] * R[2][2] - R[1][2] * R[2][0]) +
	      R[0][2] * (R[1][0] * R[2][1] - R[1][1] * R[2][0]);
	for (i = 0; i < 3; i++) {
		double k = det < 0 ? -1 : 1;

		out->scale[i] = k * s[i];
		for (j = 0; j < 3; j++)
			out->rot[i][j] = k * R[i][j];
		out->translate[i] = m->m[3][i];
	}
	return 0;
}

void ref_compose(struct ref_mat *out, const struct ref_decomp *d)
{
	const double *s = d->scale, *h = d->shear;
	int j;

	ref_identity(out);
	for (j = 0; j < 3; j++) {
		out->m[0][j] = s[0] * d->rot[0][j];
		out->m[1][j] = s[1] * (h[0] * d->rot[0][j] + d->rot[1][j]);
		out->m[2][j] = s[2] * (h[1] * d->rot[0][j] + h[2] * d->rot[1][j] + d->rot[2][j]);
		out->m[3][j] = d->translate[j];
	}
}

void ref_rand_quat(struct ref_quat *q, struct tu_rng *r)
{
	/* Shoemake's uniform rotation: three uniforms in [0, 1) */
	double u1 = tu_uniform(r, 0, 1), u2 = tu_uniform(r, 0, 2 * M_PI);
	double u3 = tu_uniform(r, 0, 2 * M_PI), a = sqrt(1 - u1), b = sqrt(u1);

	*q = (struct ref_quat){ a * sin(u2), a * cos(u2), b * sin(u3), b * cos(u3) };
}

void ref_rand_axis(double axis[3], struct tu_rng *r)
{
	double z = tu_uniform(r, -1, 1), p = tu_uniform(r, 0, 2 * M_PI), s = sqrt(1 - z * z);

	axis[0] = s * cos(p);
	axis[1] = s * sin(p);
	axis[2] = z;
}

void ref_rand_affine(struct ref_mat *m, struct tu_rng *r, double smin, double smax, double hmax,
		     double tmax, bool reflect)
{
	struct ref_mat s, h, rot, t, sh, shr;
	struct ref_quat q;
	double sc[3];
	int i;

	for (i = 0; i < 3; i++) {
		sc[i] = exp(tu_uniform(r, log(smin), log(smax)));
		if (reflect && (tu_u64(r) & 1))
			sc[i] = -sc[i];
	}
	ref_scale(&s, sc[0], sc[1], sc[2]);
	ref_shear(&h, tu_uniform(r, -hmax, hmax), tu_uniform(r, -hmax, hmax),
		  tu_uniform(r, -hmax, hmax));
	ref_rand_quat(&q, r);
	ref_quat_to_mat(&rot, &q);
	ref_translate(&t, tu_uniform(r, -tmax, tmax), tu_uniform(r, -tmax, tmax),
		      tu_uniform(r, -tmax, tmax));
	ref_mul(&sh, &s, &h);
	ref_mul(&shr, &sh, &rot);
	ref_mul(m, &shr, &t);
}

void ref_quantize(struct ref_mat *m)
{
	struct mot_mat q;

	ref_to_mat(&q, m);
	ref_from_mat(m, &q);
}
