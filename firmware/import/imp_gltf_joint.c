/* SPDX-License-Identifier: MIT */
/*
 * imp_gltf_joint.c - a glTF animation onto an existing scene's joints, by
 * name (strand import FILE.gltf --merge ROBOT.yaml; see imp.h).
 *
 * A revolute joint takes the rotation channel of the node of its name: the
 * node's rotation relative to its rest rotation, d = q_rest^-1 q, must turn
 * about one axis u (in the node's rest frame), which the file's rest pose
 * carries into its world coordinates, R_world(parent) R(q_rest) u; that must
 * be the joint's axis (either way round: the sign of the angle follows),
 * the file's world coordinates being the scene's. The angle of each key is
 * 2 atan2(d.u, d.w), unwrapped from key to key along the shorter arc, which
 * is the arc slerp takes: a LINEAR rotation about a fixed axis is an angle
 * linear in time, and a STEP one a held angle, exactly. A CUBICSPLINE
 * rotation is a normalised cubic of the components, which no cubic in the
 * angle is: it is refused (export it sampled).
 *
 * A prismatic joint takes the translation channel: the node's displacement
 * from its rest translation, carried into world coordinates by its
 * parent's rest linear part, must lie along the joint's axis; its length
 * with the sign of the axis is the position. Linear in the keys, so every
 * interpolation, tangents included, comes across exactly.
 */
#include "imp.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gltf.h"

#define DEG (180.0 / M_PI)
#define AXIS_TOL 1e-6

/* Column-vector rotation matrix of a unit quaternion (x, y, z, w). */
static void quat_mat(double r[3][3], const double q[4])
{
	double x = q[0], y = q[1], z = q[2], w = q[3];

	r[0][0] = 1 - 2 * (y * y + z * z);
	r[0][1] = 2 * (x * y - w * z);
	r[0][2] = 2 * (x * z + w * y);
	r[1][0] = 2 * (x * y + w * z);
	r[1][1] = 1 - 2 * (x * x + z * z);
	r[1][2] = 2 * (y * z - w * x);
	r[2][0] = 2 * (x * z - w * y);
	r[2][1] = 2 * (y * z + w * x);
	r[2][2] = 1 - 2 * (x * x + y * y);
}

static void mat3_mul(double o[3][3], double a[3][3], double b[3][3])
{
	double t[3][3];
	int i, j, k;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			for (t[i][j] = 0, k = 0; k < 3; k++)
				t[i][j] += a[i][k] * b[k][j];
	memcpy(o, t, sizeof(t));
}

static void mat3_apply(double o[3], double m[3][3], const double v[3])
{
	int i;

	for (i = 0; i < 3; i++)
		o[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}

/* The rest linear part (R S) of node i in world coordinates. */
static void world_rest(double o[3][3], const struct gltf *g, int32_t i)
{
	const struct gltf_node *n;
	double r[3][3], q[4];
	int a, b;

	if (i < 0) {
		memset(o, 0, 9 * sizeof(double));
		o[0][0] = o[1][1] = o[2][2] = 1;
		return;
	}
	n = &g->nodes[i];
	world_rest(o, g, n->parent);
	if (n->has_matrix) {
		for (a = 0; a < 3; a++)
			for (b = 0; b < 3; b++)
				r[a][b] = n->matrix[b * 4 + a];
	} else {
		double len = sqrt(n->r[0] * n->r[0] + n->r[1] * n->r[1] + n->r[2] * n->r[2] +
				  n->r[3] * n->r[3]);

		for (a = 0; a < 4; a++)
			q[a] = n->r[a] / len;
		quat_mat(r, q);
		for (a = 0; a < 3; a++)
			for (b = 0; b < 3; b++)
				r[a][b] *= n->s[b];
	}
	mat3_mul(o, o, r);
}

static double dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The one direction of the vectors v[k * stride .. + 3] (k < n): of the
 * longest; false when one is off it. *zero when all are (near) zero. */
static bool one_direction(const double *v, uint32_t n, uint32_t stride, double u[3], bool *zero)
{
	double best = 0, len;
	uint32_t k, i;

	*zero = true;
	for (k = 0; k < n; k++) {
		len = sqrt(dot3(v + k * stride, v + k * stride));
		if (len > best) {
			best = len;
			memcpy(u, v + k * stride, 3 * sizeof(double));
		}
	}
	if (best < 1e-12)
		return true;
	*zero = false;
	for (i = 0; i < 3; i++)
		u[i] /= best;
	for (k = 0; k < n; k++) {
		const double *x = v + k * stride;
		double p = dot3(x, u), off[3];

		for (i = 0; i < 3; i++)
			off[i] = x[i] - p * u[i];
		if (sqrt(dot3(off, off)) > AXIS_TOL * fmax(1, sqrt(dot3(x, x))))
			return false;
	}
	return true;
}

/* The sign that takes direction d (world) onto the joint's axis a; 0 when
 * d is not along a. */
static int along(const double d[3], const double a[3])
{
	double n = sqrt(dot3(d, d)), c = n > 0 ? dot3(d, a) / n : 0;

	return c > 1 - AXIS_TOL ? 1 : c < -1 + AXIS_TOL ? -1 : 0;
}

static int revolute(struct imp_chan *ch, const struct gltf *g, const struct gltf_channel *c,
		    const struct imp_joint *j, const char *name, char *err, size_t errsize,
		    const struct imp_opts *op)
{
	const struct gltf_node *n = &g->nodes[c->node];
	double qr[4], *d, u[3], uw[3], pr[3][3], rr[3][3], len;
	uint32_t k;
	bool zero;
	int sign, rc, a;

	if (c->interp == GLTF_CUBIC) {
		snprintf(err, errsize,
			 "node '%s': a CUBICSPLINE rotation is no cubic in its angle, so it cannot drive revolute joint '%s' exactly; export the animation sampled",
			 name, j->name);
		return -EINVAL;
	}
	d = malloc((size_t)c->n * 4 * sizeof(double));
	if (!d)
		return -ENOMEM;
	len = sqrt(n->r[0] * n->r[0] + n->r[1] * n->r[1] + n->r[2] * n->r[2] + n->r[3] * n->r[3]);
	for (a = 0; a < 4; a++)
		qr[a] = n->r[a] / len;
	for (k = 0; k < c->n; k++) {
		const double *q = c->v + k * 4;
		double *o = d + k * 4, w = qr[3], x = -qr[0], y = -qr[1], z = -qr[2];
		double ql = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);

		/* conj(q_rest) * q, Hamilton product, (x, y, z, w) */
		o[0] = (w * q[0] + x * q[3] + y * q[2] - z * q[1]) / ql;
		o[1] = (w * q[1] - x * q[2] + y * q[3] + z * q[0]) / ql;
		o[2] = (w * q[2] + x * q[1] - y * q[0] + z * q[3]) / ql;
		o[3] = (w * q[3] - x * q[0] - y * q[1] - z * q[2]) / ql;
	}
	if (!one_direction(d, c->n, 4, u, &zero)) {
		snprintf(err, errsize, "node '%s' turns about more than one axis, and revolute joint '%s' about one",
			 name, j->name);
		free(d);
		return -EINVAL;
	}
	sign = 1;
	if (!zero) {
		world_rest(pr, g, n->parent);
		quat_mat(rr, qr);
		mat3_mul(pr, pr, rr);
		mat3_apply(uw, pr, u);
		sign = along(uw, j->axis);
		if (!sign) {
			snprintf(err, errsize,
				 "node '%s' turns about (%.6g, %.6g, %.6g) in the file's axes, not about revolute joint '%s''s axis (%.6g, %.6g, %.6g)",
				 name, uw[0], uw[1], uw[2], j->name, j->axis[0], j->axis[1],
				 j->axis[2]);
			free(d);
			return -EINVAL;
		}
	}
	rc = imp_chan_alloc(ch, c->n, 1, c->interp == GLTF_STEP ? IMP_STEP : IMP_LINEAR);
	for (k = 0; !rc && k < c->n; k++) {
		const double *o = d + k * 4;
		double th = zero ? 0 : 2 * atan2(dot3(o, u), o[3]) * DEG * sign;

		if (k) {
			/* the shorter arc from the previous key: slerp's */
			double prev = ch->v[k - 1];

			th = prev + remainder(th - prev, 360.0);
		}
		ch->frame[k] = imp_gltf_frame(c->time[k], op->rate_num, op->rate_den);
		ch->v[k] = th;
	}
	free(d);
	return rc;
}

static int prismatic(struct imp_chan *ch, const struct gltf *g, const struct gltf_channel *c,
		     const struct imp_joint *j, const char *name, char *err, size_t errsize,
		     const struct imp_opts *op)
{
	const struct gltf_node *n = &g->nodes[c->node];
	double fps = (double)op->rate_num / op->rate_den;
	uint32_t per = c->interp == GLTF_CUBIC ? 3 : 1, k, e;
	double pw[3][3], *dw, u[3];
	bool zero;
	int sign = 1, rc;

	dw = malloc((size_t)c->n * per * 3 * sizeof(double));
	if (!dw)
		return -ENOMEM;
	world_rest(pw, g, n->parent);
	for (k = 0; k < c->n * per; k++) {
		double dt[3];

		for (e = 0; e < 3; e++)
			/* values less the rest translation; tangents as they are */
			dt[e] = c->v[k * 3 + e] - (per == 1 || k % 3 == 1 ? n->t[e] : 0);
		mat3_apply(dw + k * 3, pw, dt);
	}
	if (!one_direction(dw, c->n * per, 3, u, &zero) || (!zero && !(sign = along(u, j->axis)))) {
		snprintf(err, errsize, "node '%s' moves off prismatic joint '%s''s axis (%.6g, %.6g, %.6g)",
			 name, j->name, j->axis[0], j->axis[1], j->axis[2]);
		free(dw);
		return -EINVAL;
	}
	rc = imp_chan_alloc(ch, c->n, 1, per == 3 ? IMP_CUBIC : c->interp == GLTF_STEP ? IMP_STEP :
					 IMP_LINEAR);
	for (k = 0; !rc && k < c->n; k++) {
		ch->frame[k] = imp_gltf_frame(c->time[k], op->rate_num, op->rate_den);
		ch->v[k] = dot3(dw + (k * per + (per == 3)) * 3, j->axis);
		if (per == 3) {
			/* per second to per frame */
			ch->in[k] = dot3(dw + k * 9, j->axis) / fps;
			ch->out[k] = dot3(dw + k * 9 + 6, j->axis) / fps;
		}
	}
	free(dw);
	return rc;
}

int imp_gltf_joints(struct imp_model *m, const char *path, const uint8_t *buf, size_t len,
		    const struct imp_opts *o, const struct imp_joint *joints, uint32_t njoints,
		    uint32_t *matched, FILE *warn, char *err, size_t errsize)
{
	struct gltf g;
	uint32_t c, j, other = 0;
	int rc = gltf_read(&g, path, buf, len, o->anim, err, errsize);

	*matched = 0;
	if (rc)
		return rc;
	m->rate_num = o->rate_num;
	m->rate_den = o->rate_den;
	m->tick_hz = o->tick_hz;
	for (c = 0; c < g.nchannels && !rc; c++) {
		const struct gltf_channel *ch = &g.channels[c];
		const char *raw = g.nodes[ch->node].name;
		char *name = strdup(raw ? raw : "");
		int idx;

		if (!name) {
			rc = -ENOMEM;
			break;
		}
		imp_name_clean(name);
		for (j = 0; j < njoints; j++)
			if (!strcmp(joints[j].name, name))
				break;
		if (j == njoints || (joints[j].kind == IMP_REVOLUTE ? ch->path != GLTF_R :
				     ch->path != GLTF_T)) {
			other++;
			free(name);
			continue;
		}
		idx = imp_node_add(m, joints[j].name);
		if (idx < 0) {
			rc = -ENOMEM;
		} else {
			struct imp_node *n = &m->nodes[idx];

			n->kind = joints[j].kind;
			memcpy(n->axis, joints[j].axis, sizeof(n->axis));
			if (n->kind == IMP_REVOLUTE)
				rc = revolute(&n->ch[0], &g, ch, &joints[j], name, err, errsize, o);
			else
				rc = prismatic(&n->ch[0], &g, ch, &joints[j], name, err, errsize,
					       o);
			(*matched)++;
		}
		free(name);
	}
	if (!rc && *matched) {
		imp_note(m, "the animation of %s (glTF 2.0, animation %u%s%s%s) on %u joints by name",
			 path, g.anim_index, g.anim_name ? " '" : "", g.anim_name ? g.anim_name : "",
			 g.anim_name ? "'" : "", *matched);
		if (warn && other)
			fprintf(warn, "%s: %u channels drive no joint of the scene (no joint of their node's name, or not its rotation or translation)\n",
				path, other);
	}
	gltf_free(&g);
	return rc;
}
