/* SPDX-License-Identifier: MIT */
/* ref_scene.c - floating-point reference of a whole scene (see ref_scene.h). */
#include "ref_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_curve.h"

struct ref_curve {
	enum mot_interp kind;
	uint32_t n; /* 0: none */
	struct mot_key *keys;
	struct mot_curve_opts opts;
};

struct ref_rot {
	uint32_t n;
	bool squad;
	double *frame, *ease_in, *ease_out;
	struct ref_quat *q; /* sign-aligned along the track */
	struct ref_quat *s; /* squad inner points */
};

struct ref_warp {
	bool on;
	double f0, f1, a, b;
};

struct ref_node {
	const struct sd_node *d;
	double pivot[3], axis[3], rest;
	struct ref_curve value, spin, ch[MOT_FREE_NCHANNELS];
	struct ref_rot rot;
	struct ref_warp warp;
};

struct ref_scene {
	const struct scene_desc *d;
	struct ref_node *nodes;
	struct ref_curve cam[MOT_CAM_NCHANNELS];
	struct ref_warp cam_warp;
	struct mot_cycle *cycles;
	struct ref_curve *attr;
};

static double q(mot_q32 x)
{
	return (double)x / 4294967296.0;
}

/* a double quantised as scene_build does it */
static bool qd(double v, double *out)
{
	mot_q32 x;

	if (!sd_to_q32(v, &x))
		return false;
	*out = q(x);
	return true;
}

static bool q32(double v, mot_q32 *out)
{
	return sd_to_q32(v, out);
}

static bool curve_new(struct ref_curve *c, const struct sd_curve *s, double scale)
{
	uint32_t i;

	memset(c, 0, sizeof(*c));
	c->kind = s->interp;
	c->n = s->nkeys;
	if (!c->n)
		return true;
	c->keys = calloc(c->n, sizeof(*c->keys));
	for (i = 0; i < c->n; i++)
		if (!q32(s->keys[i].frame, &c->keys[i].frame) ||
		    !q32(s->keys[i].value * scale, &c->keys[i].value) ||
		    !q32(s->keys[i].ease_in, &c->keys[i].ease_in) ||
		    !q32(s->keys[i].ease_out, &c->keys[i].ease_out))
			return false;
	return q32(s->beta1, &c->opts.beta1) && q32(s->beta2, &c->opts.beta2) &&
	       q32(s->ease_in, &c->opts.ease_in_frames) && q32(s->ease_out, &c->opts.ease_out_frames);
}

static long double curve_eval(const struct ref_curve *c, long double f)
{
	return ref_curve_eval(c->kind, c->keys, c->n, &c->opts, f);
}

static bool warp_new(struct ref_warp *w, double f0, double f1, double out, double in)
{
	double span;

	memset(w, 0, sizeof(*w));
	if (!qd(f0, &w->f0) || !qd(f1, &w->f1) || !qd(out, &out) || !qd(in, &in))
		return false;
	span = w->f1 - w->f0;
	if ((out == 0 && in == 0) || span <= 0)
		return true;
	w->on = true;
	w->a = out / span;
	w->b = in / span;
	return true;
}

static long double warp(const struct ref_warp *w, long double f)
{
	long double s;

	if (!w->on || f <= w->f0 || f >= w->f1)
		return f;
	s = (f - w->f0) / (w->f1 - w->f0);
	return w->f0 + ref_ease(w->a, w->b, s) * (w->f1 - w->f0);
}

static bool rot_new(struct ref_rot *r, const struct sd_free *f)
{
	uint32_t i;

	memset(r, 0, sizeof(*r));
	r->n = f->nrot;
	r->squad = f->squad;
	if (!r->n)
		return true;
	r->frame = calloc(r->n, sizeof(double));
	r->ease_in = calloc(r->n, sizeof(double));
	r->ease_out = calloc(r->n, sizeof(double));
	r->q = calloc(r->n, sizeof(*r->q));
	r->s = calloc(r->n, sizeof(*r->s));
	for (i = 0; i < r->n; i++) {
		const struct sd_rot_key *k = &f->rot[i];
		double n = sqrt(k->q[0] * k->q[0] + k->q[1] * k->q[1] + k->q[2] * k->q[2] +
				k->q[3] * k->q[3]);

		if (!qd(k->frame, &r->frame[i]) || !qd(k->ease_in, &r->ease_in[i]) ||
		    !qd(k->ease_out, &r->ease_out[i]) || !qd(k->q[0] / n, &r->q[i].w) ||
		    !qd(k->q[1] / n, &r->q[i].x) || !qd(k->q[2] / n, &r->q[i].y) ||
		    !qd(k->q[3] / n, &r->q[i].z))
			return false;
		if (i > 0 && ref_quat_dot(&r->q[i - 1], &r->q[i]) < 0) {
			r->q[i].w = -r->q[i].w;
			r->q[i].x = -r->q[i].x;
			r->q[i].y = -r->q[i].y;
			r->q[i].z = -r->q[i].z;
		}
	}
	for (i = 0; i < r->n; i++)
		ref_squad_inner(&r->s[i], &r->q[i ? i - 1 : 0], &r->q[i],
				&r->q[i + 1 < r->n ? i + 1 : i]);
	return true;
}

static void rot_eval(struct ref_quat *out, const struct ref_rot *r, long double f)
{
	uint32_t i;
	double s, a, b;

	if (r->n == 1 || f <= r->frame[0]) {
		*out = r->q[0];
		return;
	}
	if (f >= r->frame[r->n - 1]) {
		*out = r->q[r->n - 1];
		return;
	}
	for (i = 0; i + 2 < r->n && f >= r->frame[i + 1]; i++)
		;
	s = (double)((f - r->frame[i]) / (r->frame[i + 1] - r->frame[i]));
	a = r->ease_out[i];
	b = r->ease_in[i + 1];
	if (a > 0 || b > 0)
		s = (double)ref_ease(a, b, s);
	if (r->squad)
		ref_squad(out, &r->q[i], &r->q[i + 1], &r->s[i], &r->s[i + 1], s);
	else
		ref_slerp(out, &r->q[i], &r->q[i + 1], s);
}

struct ref_scene *ref_scene_new(const struct scene_desc *d)
{
	struct ref_scene *r = calloc(1, sizeof(*r));
	uint32_t i, k;
	bool ok = true;

	r->d = d;
	r->nodes = calloc(d->nnodes ? d->nnodes : 1, sizeof(*r->nodes));
	for (i = 0; i < d->nnodes; i++) {
		const struct sd_node *sn = &d->nodes[i];
		struct ref_node *n = &r->nodes[i];
		double scale = sn->kind == MOT_NODE_REVOLUTE ? 1.0 / 360.0 : 1.0;
		double len = sqrt(sn->axis[0] * sn->axis[0] + sn->axis[1] * sn->axis[1] +
				  sn->axis[2] * sn->axis[2]);

		n->d = sn;
		for (k = 0; k < 3; k++) {
			ok &= qd(sn->pivot[k], &n->pivot[k]);
			if (sn->axis_id != MOT_AXIS_VEC)
				n->axis[k] = k == (uint32_t)sn->axis_id;
			else
				ok &= qd(sn->axis[k] / len, &n->axis[k]);
		}
		ok &= qd(sn->rest * scale, &n->rest);
		ok &= curve_new(&n->value, &sn->value, scale);
		ok &= curve_new(&n->spin, &sn->spin, 1.0);
		if (sn->kind == MOT_NODE_FREE && sn->has_free) {
			double lo = INFINITY, hi = -INFINITY;

			for (k = 0; k < MOT_FREE_NCHANNELS; k++) {
				const struct sd_curve *c = &sn->free.ch[k];

				ok &= curve_new(&n->ch[k], c, 1.0);
				if (c->nkeys) {
					lo = fmin(lo, c->keys[0].frame);
					hi = fmax(hi, c->keys[c->nkeys - 1].frame);
				}
			}
			ok &= rot_new(&n->rot, &sn->free);
			if (sn->free.nrot) {
				lo = fmin(lo, sn->free.rot[0].frame);
				hi = fmax(hi, sn->free.rot[sn->free.nrot - 1].frame);
			}
			if (lo > hi)
				lo = hi = 0;
			ok &= warp_new(&n->warp, lo, hi, sn->free.ease_out, sn->free.ease_in);
		}
	}
	if (d->has_camera) {
		const struct sd_curve *c0 = &d->camera.ch[0];

		for (k = 0; k < MOT_CAM_NCHANNELS; k++)
			ok &= curve_new(&r->cam[k], &d->camera.ch[k],
					k == MOT_CAM_TWIST ? 1.0 / 360.0 : 1.0);
		ok &= c0->nkeys > 0 &&
		      warp_new(&r->cam_warp, c0->keys[0].frame, c0->keys[c0->nkeys - 1].frame,
			       d->camera.ease_out, d->camera.ease_in);
	}
	r->cycles = calloc(d->ncycles ? d->ncycles : 1, sizeof(*r->cycles));
	for (i = 0; i < d->ncycles; i++) {
		const struct sd_cycle *c = &d->cycles[i];

		ok &= mot_cycle_init(&r->cycles[i], c->first, c->last, c->skip, c->mode,
				     c->frames_per_step, c->start_frame) == 0;
	}
	r->attr = calloc(d->nattrs ? d->nattrs : 1, sizeof(*r->attr));
	for (i = 0; i < d->nattrs; i++)
		ok &= curve_new(&r->attr[i], &d->attrs[i].curve, 1.0);
	if (!ok) {
		ref_scene_free(r);
		return NULL;
	}
	return r;
}

static void curve_free(struct ref_curve *c)
{
	free(c->keys);
}

void ref_scene_free(struct ref_scene *r)
{
	uint32_t i, k;

	if (!r)
		return;
	for (i = 0; i < r->d->nnodes; i++) {
		struct ref_node *n = &r->nodes[i];

		curve_free(&n->value);
		curve_free(&n->spin);
		for (k = 0; k < MOT_FREE_NCHANNELS; k++)
			curve_free(&n->ch[k]);
		free(n->rot.frame);
		free(n->rot.ease_in);
		free(n->rot.ease_out);
		free(n->rot.q);
		free(n->rot.s);
	}
	for (k = 0; k < MOT_CAM_NCHANNELS; k++)
		curve_free(&r->cam[k]);
	for (i = 0; i < r->d->nattrs; i++)
		curve_free(&r->attr[i]);
	free(r->attr);
	free(r->cycles);
	free(r->nodes);
	free(r);
}

int ref_pose_new(struct ref_pose *p, const struct scene_desc *d)
{
	size_t n = d->nnodes ? d->nnodes : 1;

	memset(p, 0, sizeof(*p));
	p->world = calloc(n, sizeof(*p->world));
	p->pos = calloc(n, sizeof(*p->pos));
	p->value = calloc(n, sizeof(*p->value));
	p->rpm = calloc(n, sizeof(*p->rpm));
	p->cycle = calloc(d->ncycles ? d->ncycles : 1, sizeof(*p->cycle));
	p->attr = calloc(d->nattrs ? d->nattrs : 1, sizeof(*p->attr));
	return p->world && p->pos && p->value && p->rpm && p->cycle && p->attr ? 0 : -1;
}

void ref_pose_free(struct ref_pose *p)
{
	free(p->world);
	free(p->pos);
	free(p->value);
	free(p->rpm);
	free(p->cycle);
	free(p->attr);
	memset(p, 0, sizeof(*p));
}

/* L = T(-p) . A . T(p) . T(t) for a linear part A (translation row ignored) */
static void about_pivot(struct ref_mat *out, const struct ref_mat *a, const double p[3],
			const double t[3])
{
	struct ref_mat m1, m2;

	ref_translate(&m1, -p[0], -p[1], -p[2]);
	m2 = *a;
	m2.m[3][0] = m2.m[3][1] = m2.m[3][2] = 0;
	ref_mul(&m1, &m1, &m2);
	ref_translate(&m2, p[0] + t[0], p[1] + t[1], p[2] + t[2]);
	ref_mul(out, &m1, &m2);
}

static void node_local(struct ref_mat *l, double *value, double *rpm, const struct ref_scene *r,
		       const struct ref_node *n, long double f)
{
	static const double zero[3];
	const struct scene_desc *d = r->d;

	*value = 0;
	*rpm = 0;
	if (n->d->kind != MOT_NODE_FREE) {
		double v = n->rest;
		struct ref_mat rot;

		if (n->value.n) {
			v = (double)curve_eval(&n->value, f);
		} else if (n->spin.n) {
			long double integ = ref_curve_integral(n->spin.kind, n->spin.keys, n->spin.n, f);

			*rpm = (double)curve_eval(&n->spin, f);
			v = (double)(n->rest + integ * d->rate_den / (60.0L * d->rate_num));
		}
		*value = v;
		if (n->d->kind == MOT_NODE_PRISMATIC) {
			ref_translate(l, v * n->axis[0], v * n->axis[1], v * n->axis[2]);
			return;
		}
		/* reduce whole turns first: sin(2 pi v) for large v loses nothing
		 * the core keeps */
		v = v - floor(v);
		switch (n->d->axis_id) {
		case MOT_AXIS_X:
			ref_rot_x(&rot, 2 * M_PI * v);
			break;
		case MOT_AXIS_Y:
			ref_rot_y(&rot, 2 * M_PI * v);
			break;
		case MOT_AXIS_Z:
			ref_rot_z(&rot, 2 * M_PI * v);
			break;
		default: {
			struct ref_quat qq;

			ref_quat_axis_angle(&qq, n->axis, 2 * M_PI * v);
			ref_quat_to_mat(&rot, &qq);
			break;
		}
		}
		about_pivot(l, &rot, n->pivot, zero);
		return;
	}
	if (!n->d->has_free) {
		ref_identity(l);
		return;
	}
	{
		long double g = warp(&n->warp, f);
		double v[MOT_FREE_NCHANNELS], t[3];
		struct ref_decomp dc;
		struct ref_quat qq = { 1, 0, 0, 0 };
		struct ref_mat rm, m;
		int k, j;

		for (k = 0; k < MOT_FREE_NCHANNELS; k++)
			v[k] = n->ch[k].n ? (double)curve_eval(&n->ch[k], g) :
					    (k >= MOT_FREE_SX && k <= MOT_FREE_SZ);
		if (n->rot.n)
			rot_eval(&qq, &n->rot, g);
		ref_quat_to_mat(&rm, &qq);
		for (k = 0; k < 3; k++) {
			dc.scale[k] = v[MOT_FREE_SX + k];
			dc.shear[k] = v[MOT_FREE_HXY + k];
			dc.translate[k] = 0;
			t[k] = v[MOT_FREE_TX + k];
			for (j = 0; j < 3; j++)
				dc.rot[k][j] = rm.m[k][j];
		}
		ref_compose(&m, &dc);
		about_pivot(l, &m, n->pivot, t);
	}
}

void ref_scene_eval(const struct ref_scene *r, mot_q32 frame, struct ref_pose *out)
{
	const struct scene_desc *d = r->d;
	long double f = (long double)frame / 4294967296.0L;
	uint32_t i;
	int k;

	for (i = 0; i < d->nnodes; i++) {
		const struct ref_node *n = &r->nodes[i];
		struct ref_mat l;

		node_local(&l, &out->value[i], &out->rpm[i], r, n, f);
		if (n->d->parent >= 0)
			ref_mul(&out->world[i], &l, &out->world[n->d->parent]);
		else
			out->world[i] = l;
		ref_apply(out->pos[i], n->pivot, &out->world[i]);
	}
	if (d->has_camera) {
		long double g = warp(&r->cam_warp, f);
		double v[MOT_CAM_NCHANNELS], dx, dy, dz;

		for (k = 0; k < MOT_CAM_NCHANNELS; k++)
			v[k] = (double)curve_eval(&r->cam[k], g);
		for (k = 0; k < 3; k++) {
			out->eye[k] = v[MOT_CAM_EYE_X + k];
			out->look[k] = v[MOT_CAM_LOOK_X + k];
		}
		dx = out->look[0] - out->eye[0];
		dy = out->look[1] - out->eye[1];
		dz = out->look[2] - out->eye[2];
		out->pan = atan2(-dx, -dz) / (2 * M_PI);
		out->tilt = atan2(dy, sqrt(dx * dx + dz * dz)) / (2 * M_PI);
		out->roll = v[MOT_CAM_TWIST];
	}
	for (i = 0; i < d->ncycles; i++)
		out->cycle[i] = mot_cycle_index(&r->cycles[i], (int64_t)floorl(f));
	for (i = 0; i < d->nattrs; i++)
		out->attr[i] = (double)curve_eval(&r->attr[i], f);
}

double ref_rot_angle_diff(const struct ref_mat *a, const struct ref_mat *b)
{
	/* M = A^T B (rows are the basis vectors); the skew part of M is
	 * sin(angle) times the axis, exact to first order for small angles */
	double m[3][3], wx, wy, wz;
	int i, j, k;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++) {
			m[i][j] = 0;
			for (k = 0; k < 3; k++)
				m[i][j] += a->m[k][i] * b->m[k][j];
		}
	wx = (m[1][2] - m[2][1]) / 2;
	wy = (m[2][0] - m[0][2]) / 2;
	wz = (m[0][1] - m[1][0]) / 2;
	return asin(fmin(1.0, sqrt(wx * wx + wy * wy + wz * wz)));
}
