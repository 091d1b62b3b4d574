/* SPDX-License-Identifier: MIT */
/* limit_check.c - joint limits over a timeline at tick resolution (see limit_check.h). */
#include "limit_check.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/channel.h"

/* An open run of ticks breaking one limit. */
struct run {
	bool open;
	int64_t first, last;
	double worst;
};

struct joint {
	uint32_t node;
	bool revolute;
	double *ring; /* the last 2h + 1 values */
	struct run run[LIM_NKINDS];
};

struct checker {
	const struct scene_desc *d;
	const struct mot_timing *t;
	lim_report_fn report;
	void *ctx;
	struct lim_result *res;
};

const char *lim_kind_name(enum lim_kind k)
{
	static const char *const names[] = { "min", "max", "velocity", "acceleration",
					     "stopping distance" };

	return names[k];
}

static double tick_frame(const struct mot_timing *t, int64_t k)
{
	return chan_q32(mot_timing_tick_frame(t, k));
}

static void close_run(struct checker *c, struct joint *j, enum lim_kind k)
{
	const struct sd_limits *lim = &c->d->nodes[j->node].limits;
	struct run *r = &j->run[k];
	struct lim_violation v;

	if (!r->open)
		return;
	r->open = false;
	v.node = j->node;
	v.kind = k;
	v.worst = r->worst;
	v.limit = k == LIM_MIN ? lim->min : k == LIM_MAX ? lim->max :
		  k == LIM_VEL ? copysign(lim->vel, r->worst) :
		  k == LIM_ACC ? copysign(lim->acc, r->worst) :
		  lim->has_max && r->worst > lim->max ? lim->max : lim->min;
	v.tick_first = r->first;
	v.tick_last = r->last;
	v.frame_first = tick_frame(c->t, r->first);
	v.frame_last = tick_frame(c->t, r->last);
	c->res->violations++;
	c->report(c->ctx, &v);
}

/* The position limit a stopping point lies beyond. */
static double stop_bound(const struct checker *c, const struct joint *j, double at)
{
	const struct sd_limits *lim = &c->d->nodes[j->node].limits;

	return lim->has_max && at > lim->max ? lim->max : lim->min;
}

/* Tick k breaks (bad) or keeps limit kind with this value. */
static void step(struct checker *c, struct joint *j, enum lim_kind k, int64_t tick, bool bad,
		 double value)
{
	struct run *r = &j->run[k];

	if (!bad) {
		close_run(c, j, k);
		return;
	}
	if (!r->open) {
		r->open = true;
		r->first = tick;
		r->worst = value;
	} else if (k == LIM_STOP ? fabs(value - stop_bound(c, j, value)) >
					   fabs(r->worst - stop_bound(c, j, r->worst)) :
		   fabs(value) > fabs(r->worst) || (k == LIM_MIN && value < r->worst) ||
		   (k == LIM_MAX && value > r->worst)) {
		r->worst = value;
	}
	r->last = tick;
}

static void joint_tick(struct checker *c, struct joint *j, int64_t k, int64_t k0, uint32_t h,
		       double value, double rate, double lsb)
{
	const struct sd_limits *lim = &c->d->nodes[j->node].limits;
	uint32_t n = 2 * h + 1;
	double *ring = j->ring;

	memmove(ring, ring + 1, (n - 1) * sizeof(*ring));
	ring[n - 1] = value;
	/* values within a step of the limit are the limit, rounded */
	if (lim->has_min)
		step(c, j, LIM_MIN, k, value < lim->min - lsb, value);
	if (lim->has_max)
		step(c, j, LIM_MAX, k, value > lim->max + lsb, value);
	if (lim->has_vel && k - k0 >= h) {
		double v = (ring[n - 1] - ring[n - 1 - h]) * rate;

		step(c, j, LIM_VEL, k, fabs(v) > lim->vel + 4 * lsb * rate, v);
	}
	if (lim->has_acc && lim->acc > 0 && (lim->has_min || lim->has_max) && k - k0 >= h) {
		double v = (ring[n - 1] - ring[n - 1 - h]) * rate;
		double d = v * v / (2 * lim->acc) + fabs(v) / (rate * h);
		double at = value + copysign(d, v);
		bool bad = (lim->has_min && at < lim->min - lsb) ||
			   (lim->has_max && at > lim->max + lsb);

		step(c, j, LIM_STOP, k, bad, at);
	}
	if (lim->has_acc && k - k0 >= 2 * h) {
		double a = (ring[n - 1] - 2 * ring[h] + ring[0]) * rate * rate;

		step(c, j, LIM_ACC, k - h, fabs(a) > lim->acc + 4 * lsb * rate * rate, a);
	}
}

static bool has_limits(const struct sd_limits *l)
{
	return l->has_min || l->has_max || l->has_vel || l->has_acc;
}

int lim_check(const struct scene_desc *d, const struct mot_scene *sc, int64_t from, int64_t to,
	      lim_report_fn report, void *ctx, struct lim_result *res)
{
	const struct mot_timing *t = &sc->timing;
	uint32_t h = (t->tick_hz + 999) / 1000, nj = 0, i, kind;
	double rate = (double)t->tick_hz / h;
	struct checker c = { d, t, report, ctx, res };
	struct joint *joints;
	struct mot_eval ev;
	struct mot_pose pose;
	int64_t k, k0, k1;
	double *rings;
	int err;

	memset(res, 0, sizeof(*res));
	joints = calloc(d->nnodes ? d->nnodes : 1, sizeof(*joints));
	rings = calloc((size_t)(d->nnodes ? d->nnodes : 1) * (2 * h + 1), sizeof(*rings));
	if (!joints || !rings) {
		free(joints);
		free(rings);
		return -ENOMEM;
	}
	for (i = 0; i < d->nnodes; i++) {
		if (d->nodes[i].kind == MOT_NODE_FREE || !has_limits(&d->nodes[i].limits))
			continue;
		joints[nj].node = i;
		joints[nj].revolute = d->nodes[i].kind == MOT_NODE_REVOLUTE;
		joints[nj].ring = rings + (size_t)nj * (2 * h + 1);
		nj++;
	}
	err = scene_eval_new(&ev, sc);
	if (!err) {
		err = scene_pose_new(&pose, sc);
		if (err)
			scene_eval_free(&ev);
	}
	if (err) {
		free(joints);
		free(rings);
		return err;
	}
	k0 = mot_timing_trigger_tick(t, from);
	k1 = mot_timing_trigger_tick(t, to);
	for (k = k0; k <= k1; k++) {
		mot_scene_eval(sc, &ev, mot_timing_tick_frame(t, k), &pose);
		if (ev.sat && !res->sat) {
			res->sat = ev.sat;
			res->sat_frame = tick_frame(t, k);
		}
		for (i = 0; i < nj; i++) {
			struct joint *j = &joints[i];
			mot_q32 q = pose.value[j->node];

			joint_tick(&c, j, k, k0, h,
				   j->revolute ? chan_turns_deg(q) : chan_q32(q), rate,
				   j->revolute ? 360.0 / 4294967296.0 : 1.0 / 4294967296.0);
		}
	}
	for (i = 0; i < nj; i++)
		for (kind = 0; kind < LIM_NKINDS; kind++)
			close_run(&c, &joints[i], (enum lim_kind)kind);
	res->ticks = k1 - k0 + 1;
	scene_pose_free(&pose);
	scene_eval_free(&ev);
	free(joints);
	free(rings);
	return 0;
}
