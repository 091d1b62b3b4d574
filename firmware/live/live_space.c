/* SPDX-License-Identifier: MIT */
/*
 * live_space.c - jog the camera or a free node in its own space or in world
 * space about its pivot (live.h: live_jog_space), as the seed's section 4
 * edits a node: the increment D (a translation along an axis, or a rotation
 * about one) applied to the node's matrix M by the core's edit functions,
 *
 *     local  M' = T(-p) . D . T(p) . M     the node's own axes, about its pivot
 *     world  M' = M . T(-w) . D . T(w)     the world's axes, about the pivot w
 *                                          where the node stands
 *
 * (mot_mat_edit_local, mot_mat_edit_world), and the outputs carried along
 * as the scene's evaluation carries them: the camera's eye and pan, tilt
 * and roll (camera.x|y|z|pan|tilt|roll) from M' = Rz(roll) . Rx(tilt) .
 * Ry(pan) . T(eye) taken apart again; a free node's pivot and every
 * descendant's (<node>.x|y|z) through the scene's own local matrices below
 * it (mot_node_local, mot_mat_mul).
 *
 * That gives each output's rate per unit of the increment, by central
 * differences (exact for translations; for rotations within a few parts in
 * 10^7 of the derivative); the loop jogs every output at that rate, scaled
 * so that the fastest of them runs at the commanded fraction of its speed
 * limit, with its ramps, limits and dead-man (loop_live.h: a vector jog).
 * The rates are made again from where the rig stands at every refresh of
 * the jog, so a rotation keeps to its axis as the orientation changes.
 *
 * Where the rig is: the camera's channels that outputs drive are the
 * outputs' setpoints; the rest are the scene's at the frame the rig was
 * last at. No output says how a free node is turned: its world matrix is
 * the scene's at that frame, then as its jogs left it, each refresh
 * editing it by as much of the last increment as the outputs went (they
 * move in proportion) - until something else moves the rig.
 */
#define _GNU_SOURCE
#include "live_priv.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "motion/mat.h"
#include "scene/channel.h"

/* The increment of the finite differences: 1e-4 scene units or turns. */
#define SPACE_STEP 1e-4

struct space_axis {
	const char *name;
	int k;        /* 0..2 translate along x, y, z; 3..5 rotate about x, y, z */
	double sign;
};

static const struct space_axis space_axes[] = {
	{ "x", 0, 1 },	   { "y", 1, 1 },     { "z", 2, 1 },	 { "rx", 3, 1 },
	{ "ry", 4, 1 },	   { "rz", 5, 1 },    { "truck", 0, 1 }, { "boom", 1, 1 },
	/* the camera looks down its -z */
	{ "dolly", 2, -1 }, { "tilt", 3, 1 }, { "pan", 4, 1 },	 { "roll", 5, 1 },
};

static mot_q32 q32(double x)
{
	return (mot_q32)llround(x * 4294967296.0);
}

static double dbl(mot_q32 x)
{
	return (double)x / 4294967296.0;
}

/* D: amount (units or turns) along or about axis k. */
static void increment(struct mot_mat *d, int k, double amount)
{
	if (k < 3) {
		mot_mat_identity(d);
		d->m[3][k] = q32(amount);
	} else if (k == 3) {
		mot_mat_rot_x(d, q32(amount));
	} else if (k == 4) {
		mot_mat_rot_y(d, q32(amount));
	} else {
		mot_mat_rot_z(d, q32(amount));
	}
}

/* ---- the camera ---- */

/* q: eye x, y, z (units), pan, tilt, roll (turns) -> M, as camera.c makes it. */
static void camera_mat(struct mot_mat *m, const double q[6], uint32_t *sat)
{
	struct mot_mat r, t;
	mot_q32 eye[3] = { q32(q[0]), q32(q[1]), q32(q[2]) };

	mot_mat_rot_z(m, q32(q[5]));
	mot_mat_rot_x(&r, q32(q[4]));
	mot_mat_mul(m, m, &r, sat);
	mot_mat_rot_y(&r, q32(q[3]));
	mot_mat_mul(m, m, &r, sat);
	mot_mat_translate(&t, eye);
	mot_mat_mul(m, m, &t, sat);
}

/*
 * M = Rz(roll) . Rx(tilt) . Ry(pan) . T(eye) apart (row vectors, mat.h):
 * its last row is (cos t sin p, -sin t, cos t cos p), and its first two
 * rows' y entries are (sin r cos t, cos r cos t); pan is taken on the turn
 * nearest pan_near (a head never swings a full turn back).
 */
static void camera_apart(double q[6], const struct mot_mat *m, double pan_near)
{
	double r20 = dbl(m->m[2][0]), r21 = dbl(m->m[2][1]), r22 = dbl(m->m[2][2]);
	double p = atan2(r20, r22) / (2 * M_PI);

	q[0] = dbl(m->m[3][0]);
	q[1] = dbl(m->m[3][1]);
	q[2] = dbl(m->m[3][2]);
	q[3] = p + round(pan_near - p);
	q[4] = atan2(-r21, hypot(r20, r22)) / (2 * M_PI);
	q[5] = atan2(dbl(m->m[0][1]), dbl(m->m[1][1])) / (2 * M_PI);
}

static void camera_moved(double out[6], const double q[6], int k, double amount, bool local,
			 uint32_t *sat)
{
	static const mot_q32 origin[3] = { 0, 0, 0 };
	mot_q32 eye[3] = { q32(q[0]), q32(q[1]), q32(q[2]) };
	struct mot_mat m, d;

	camera_mat(&m, q, sat);
	increment(&d, k, amount);
	/* local: about the camera's own origin, the eye */
	if (local)
		mot_mat_edit_local(&m, &d, origin, sat);
	else
		mot_mat_edit_world(&m, &d, eye, sat);
	camera_apart(out, &m, q[3]);
}

/* ---- a free node ---- */

/* Whether node k is n or below it. */
static bool below(const struct mot_scene *sc, uint32_t k, uint32_t n)
{
	int32_t i = (int32_t)k;

	while (i > (int32_t)n)
		i = sc->nodes[i].parent;
	return i == (int32_t)n;
}

/* m edited by the increment, about node n's pivot p (local) or where m
 * puts it (world). */
static void node_edit(struct mot_mat *m, const struct mot_scene *sc, uint32_t n, int k,
		      double amount, bool local, uint32_t *sat)
{
	struct mot_mat d;
	mot_q32 w[3];

	increment(&d, k, amount);
	if (local) {
		mot_mat_edit_local(m, &d, sc->nodes[n].pivot, sat);
	} else {
		mot_mat_apply(w, sc->nodes[n].pivot, m, sat);
		mot_mat_edit_world(m, &d, w, sat);
	}
}

/* The pivots of n and of every node below it (pos[k], units) with n's
 * world matrix wn edited; the others' untouched. The pose: at frame. */
static void node_moved(struct source_scene *ss, uint32_t n, const struct mot_mat *wn, int k,
		       double amount, bool local, mot_q32 frame, struct mot_mat *w,
		       double (*pos)[3], uint32_t *sat)
{
	const struct mot_scene *sc = ss->sc;
	struct mot_mat l;
	mot_q32 v, rpm, p[3];
	uint32_t i, c;

	memcpy(w, ss->pose.world, sc->nnodes * sizeof(*w));
	w[n] = *wn;
	node_edit(&w[n], sc, n, k, amount, local, sat);
	for (i = n; i < sc->nnodes; i++) {
		if (!below(sc, i, n))
			continue;
		if (i > n) { /* W = L . W(parent), parents first */
			mot_node_local(&l, sc, &ss->ev, i, frame, &v, &rpm);
			mot_mat_mul(&w[i], &l, &w[sc->nodes[i].parent], sat);
		}
		mot_mat_apply(p, sc->nodes[i].pivot, &w[i], sat);
		for (c = 0; c < 3; c++)
			pos[i][c] = dbl(p[c]);
	}
}

/* ---- the rates ---- */

/* The frame whose pose stands for what no output says. */
static int64_t pose_frame(const struct live *lv)
{
	const struct play_source *s = &lv->sc->twin.s;

	int64_t f = atomic_load(&lv->last_frame);

	return f >= 0 ? f : s->frame_first;
}

/* Output i's channel. */
static const struct chan *out_chan(struct live *lv, uint32_t i)
{
	return &lv->sc->twin.all.c[lv->rig.out[i].src];
}

/* Where the rig holds its outputs, core units: the newest sample, moved
 * on at its speed for as long as it has been in (a few milliseconds). */
static void outputs_now(struct live *lv, double *at)
{
	struct live_snap snap;
	double age;
	uint32_t i;

	live_snapshot(lv, &snap);
	age = lv->running ? (hal_mono_ns() - snap.taken_ns) * 1e-9 : 0;
	for (i = 0; i < lv->rig.nout && i < snap.nout; i++) {
		double v = snap.out[i].sp + snap.out[i].vel * age;

		at[i] = lv->rig.out[i].unit == SRC_UNIT_TURNS ? v / 360.0 : v;
	}
}

/*
 * Free node n's world matrix, as the jogs since the rig was last at a frame
 * left it: the scene's there at first; then, at each refresh, edited by as
 * much of the last increment as the outputs went (their change projected
 * on its rates: they move in proportion, a vector jog).
 */
static void node_now(struct live *lv, uint32_t n, struct mot_mat *w, uint32_t *sat)
{
	struct live_space *t = &lv->space;
	struct source_scene *ss = &lv->sc->twin;
	double at[LOOP_LIVE_OUT_MAX], num = 0, den = 0;
	uint32_t i;

	if (!t->valid || t->node != (int32_t)n) {
		*w = ss->pose.world[n];
		return;
	}
	outputs_now(lv, at);
	for (i = 0; i < lv->rig.nout; i++) {
		num += (at[i] - t->at[i]) * t->rate[i];
		den += t->rate[i] * t->rate[i];
	}
	if (den > 0)
		node_edit(&t->w, ss->sc, n, t->k, num / den, t->local, sat);
	*w = t->w;
}

/*
 * rate[i]: output i's change, core units, per unit of the increment along
 * or about axis k of the camera (node < 0) or node n. 0, or a negative
 * errno with msg.
 */
static int rates(struct live *lv, int32_t node, int k, bool local, double *rate, char *msg,
		 size_t size)
{
	struct source_scene *ss = &lv->sc->twin;
	const struct mot_scene *sc = ss->sc;
	mot_q32 frame = (mot_q32)pose_frame(lv) * MOT_Q32_ONE;
	mot_q32 tmp[LOOP_LIVE_OUT_MAX];
	uint32_t sat = 0, i, nn = sc->nnodes;
	double h = SPACE_STEP;

	/* the scene at the frame: the pose (world matrices, the camera) */
	src_eval(&ss->s, frame, tmp, &sat);
	if (node < 0) {
		double q[6], a[6], b[6], at[LOOP_LIVE_OUT_MAX];

		q[0] = dbl(ss->pose.cam.eye[0]);
		q[1] = dbl(ss->pose.cam.eye[1]);
		q[2] = dbl(ss->pose.cam.eye[2]);
		q[3] = dbl(ss->pose.cam.pan);
		q[4] = dbl(ss->pose.cam.tilt);
		q[5] = dbl(ss->pose.cam.roll);
		outputs_now(lv, at);
		for (i = 0; i < lv->rig.nout; i++) {
			const struct chan *c = out_chan(lv, i);

			/* where the rig holds it */
			if (c->kind == CHAN_CAMERA)
				q[c->comp] = at[i];
		}
		camera_moved(a, q, k, h, local, &sat);
		camera_moved(b, q, k, -h, local, &sat);
		for (i = 0; i < lv->rig.nout; i++) {
			const struct chan *c = out_chan(lv, i);

			rate[i] = c->kind == CHAN_CAMERA ? (a[c->comp] - b[c->comp]) / (2 * h) : 0;
		}
	} else {
		struct mot_mat *w = calloc(nn, sizeof(*w));
		double (*pa)[3] = calloc(nn, sizeof(*pa)), (*pb)[3] = calloc(nn, sizeof(*pb));
		struct mot_mat wn;

		if (!w || !pa || !pb) {
			free(w);
			free(pa);
			free(pb);
			snprintf(msg, size, "out of memory");
			return -ENOMEM;
		}
		node_now(lv, (uint32_t)node, &wn, &sat);
		node_moved(ss, (uint32_t)node, &wn, k, h, local, frame, w, pa, &sat);
		node_moved(ss, (uint32_t)node, &wn, k, -h, local, frame, w, pb, &sat);
		for (i = 0; i < lv->rig.nout; i++) {
			const struct chan *c = out_chan(lv, i);

			const double *a = pa[c->index], *b = pb[c->index];

			rate[i] = c->kind == CHAN_POS && below(sc, c->index, (uint32_t)node) ?
					  (a[c->comp] - b[c->comp]) / (2 * h) : 0;
		}
		/* what the next refresh measures the motion by */
		lv->space = (struct live_space){ .valid = true, .node = node, .w = wn, .k = k,
						 .local = local };
		memcpy(lv->space.rate, rate, sizeof(lv->space.rate));
		outputs_now(lv, lv->space.at);
		free(w);
		free(pa);
		free(pb);
	}
	if (sat) {
		snprintf(msg, size, "the scene's arithmetic saturates where the rig stands");
		return -ERANGE;
	}
	return 0;
}

/* The loop's fractions for a jog of the camera (node < 0) or a node along
 * or about axis k (sign: its direction) at speed: 0, or a negative errno. */
static int space_vector(struct live *lv, int32_t node, int k, bool local, double sign,
			double speed, double *vec, char *msg, size_t size)
{
	double rate[LOOP_LIVE_OUT_MAX], top = 0;
	uint32_t i;
	int rc = rates(lv, node, k, local, rate, msg, size);

	if (rc)
		return rc;
	for (i = 0; i < lv->rig.nout; i++) {
		const struct rig_out *o = &lv->rig.out[i];

		rate[i] *= sign;
		if (o->vel_mode)
			rate[i] = 0;
		top = fmax(top, fabs(rate[i]) / o->vmax);
	}
	if (!(top > 1e-12)) {
		snprintf(msg, size, "no output of the rig follows that motion");
		return -ENOENT;
	}
	/* the fastest output at the commanded fraction of its limit */
	for (i = 0; i < lv->rig.nout; i++)
		vec[i] = speed * rate[i] / lv->rig.out[i].vmax / top;
	return 0;
}

static int jog_space(struct live *lv, uint64_t client, const char *name, const char *space,
		     const char *axis, double speed, uint64_t seq, char *msg, size_t size)
{
	const struct scene_desc *d = &lv->sc->sf.desc;
	struct loop_cmd c = { .kind = LOOP_CMD_JOG_VEC };
	const struct space_axis *ax = NULL;
	struct live_space_jog *j = &lv->space_jog;
	struct loop_ack a;
	int32_t node = -1;
	uint32_t i;
	int rc;

	for (i = 0; i < sizeof(space_axes) / sizeof(space_axes[0]); i++)
		if (!strcmp(space_axes[i].name, axis))
			ax = &space_axes[i];
	if (!ax || (strcmp(space, "local") && strcmp(space, "world"))) {
		snprintf(msg, size, "space %s, axis %s: local or world; x, y, z, rx, ry, rz "
			 "(truck, boom, dolly, tilt, pan, roll)", space, axis);
		return -EINVAL;
	}
	if (!(fabs(speed) <= 1)) {
		snprintf(msg, size, "speed %g: a fraction of the velocity limits, -1 to 1", speed);
		return -ERANGE;
	}
	if (strcmp(name, "camera")) {
		for (i = 0; i < d->nnodes; i++)
			if (!strcmp(d->nodes[i].name, name))
				node = (int32_t)i;
		if (node < 0 || d->nodes[node].kind != MOT_NODE_FREE) {
			snprintf(msg, size, "'%s': the camera or a free node of the scene (a joint "
				 "is jogged by its output)", name);
			return -ENOENT;
		}
	} else if (!d->has_camera) {
		snprintf(msg, size, "the scene has no camera");
		return -ENOENT;
	}
	if (client != lv->jog_client) {
		lv->jog_client = client;
		memset(lv->jog_seq, 0, sizeof(lv->jog_seq));
		lv->space_seq = 0;
	}
	if (seq <= lv->space_seq)
		return 0; /* doubled or stale: ignored */
	lv->space_seq = seq;
	if (!lv->running)
		return live_send(lv, &c, &a, msg, size); /* says why not */
	if (speed != 0) {
		rc = space_vector(lv, node, ax->k, !strcmp(space, "local"), ax->sign, speed, c.vec,
				  msg, size);
		if (rc == -ENOENT)
			snprintf(msg, size, "no output of the rig follows %s's %s in %s space",
				 name, axis, space);
		if (rc)
			return rc;
	}
	rc = live_send(lv, &c, &a, msg, size);
	/* between this refresh and the dead-man's time, live_service turns
	 * the direction as the node turns */
	*j = (struct live_space_jog){ .active = !rc && speed != 0, .node = node, .k = ax->k,
				      .local = !strcmp(space, "local"), .sign = ax->sign,
				      .speed = speed, .last_ns = hal_mono_ns() };
	j->until_ns = j->last_ns + (int64_t)(lv->o.deadman_ms * 1e6);
	return rc;
}

/* Every LIVE_SPACE_NS: the direction again, from where the rig is now. */
#define LIVE_SPACE_NS 10000000LL

void live_space_follow(struct live *lv)
{
	struct live_space_jog *j = &lv->space_jog;
	struct loop_cmd c = { .kind = LOOP_CMD_JOG_VEC, .keep = true };
	struct loop_ack a;
	int64_t now = hal_mono_ns();
	char msg[LIVE_MSG];

	if (!j->active || !lv->running || now - j->last_ns < LIVE_SPACE_NS)
		return;
	if (now > j->until_ns) {
		j->active = false; /* the loop's dead-man ends it */
		return;
	}
	j->last_ns = now;
	if (space_vector(lv, j->node, j->k, j->local, j->sign, j->speed, c.vec, msg,
			 sizeof(msg)))
		return;
	/* not waited for: its answer is dropped by the next command's wait,
	 * or here */
	c.seq = ++lv->seq;
	c.arrival_ns = now;
	atomic_store(&lv->cmd_sent, c.seq);
	hal_ring_push(&lv->cmds, &c);
	while (hal_ring_pop(&lv->acks, &a))
		;
}

int live_jog_space(struct live *lv, uint64_t client, const char *node, const char *space,
		   const char *axis, double speed, uint64_t seq, char *msg, size_t size)
{
	int rc;

	pthread_mutex_lock(&lv->mu);
	rc = lv->sc ? jog_space(lv, client, node, space, axis, speed, seq, msg, size) :
		      live_no_scene(msg, size);
	pthread_mutex_unlock(&lv->mu);
	return rc;
}
