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
	const struct chan *c;
	const struct sd_limits *lim;
	bool revolute; /* an angle */
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
					     "stopping distance", "pool" };

	return names[k];
}

static double tick_frame(const struct mot_timing *t, int64_t k)
{
	return chan_q32(mot_timing_tick_frame(t, k));
}

static void close_run(struct checker *c, struct joint *j, enum lim_kind k)
{
	const struct sd_limits *lim = j->lim;
	struct run *r = &j->run[k];
	struct lim_violation v;

	if (!r->open)
		return;
	r->open = false;
	v.node = j->c->kind == CHAN_VALUE ? (int32_t)j->c->index : -1;
	v.channel = j->c->name;
	v.angle = j->revolute;
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
	const struct sd_limits *lim = j->lim;

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
	const struct sd_limits *lim = j->lim;
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
	return l && (l->has_min || l->has_max || l->has_vel || l->has_acc);
}

/* Particle systems whose pool ran out by frame `to`: one violation each. */
static void pools(struct checker *c, const struct mot_scene *sc, int64_t to)
{
	uint32_t i, sat = 0;

	for (i = 0; i < sc->nsys; i++) {
		const struct mot_particles *p = sc->sys[i].particles;
		struct lim_violation v;
		mot_q32 f;

		if (sc->sys[i].kind != MOT_SYS_PARTICLES || p->first_drop < 0)
			continue;
		f = mot_steps_frame(&p->steps, p->first_drop * MOT_Q32_ONE, &sat);
		if ((f >> 32) > to)
			continue;
		memset(&v, 0, sizeof(v));
		v.node = -1;
		v.channel = sd_sys_name(&c->d->sys[i]);
		v.kind = LIM_POOL;
		v.worst = (double)p->dropped;
		v.limit = p->npool;
		v.frame_first = v.frame_last = chan_q32(f);
		v.tick_first = v.tick_last = mot_timing_next_frame(c->t, 0);
		c->res->violations++;
		c->report(c->ctx, &v);
	}
}

int lim_check(const struct scene_desc *d, const struct mot_scene *sc, int64_t from, int64_t to,
	      lim_report_fn report, void *ctx, struct lim_result *res)
{
	const struct mot_timing *t = &sc->timing;
	uint32_t h = (t->tick_hz + 999) / 1000, nj = 0, i, kind;
	double rate = (double)t->tick_hz / h;
	struct checker c = { d, t, report, ctx, res };
	struct joint *joints;
	struct chan_list ch;
	struct mot_eval ev;
	struct mot_pose pose;
	int64_t k, k0, k1;
	double *rings;
	int err;

	memset(res, 0, sizeof(*res));
	if (chan_list_make(&ch, d))
		return -ENOMEM;
	joints = calloc(ch.n ? ch.n : 1, sizeof(*joints));
	rings = calloc((size_t)(ch.n ? ch.n : 1) * (2 * h + 1), sizeof(*rings));
	if (!joints || !rings) {
		free(joints);
		free(rings);
		chan_list_free(&ch);
		return -ENOMEM;
	}
	/* every channel with limits of its own in the scene: joints, the
	 * systems' items, the aims */
	for (i = 0; i < ch.n; i++) {
		const struct sd_limits *lim = chan_limits(&ch.c[i], d);

		if (!has_limits(lim))
			continue;
		joints[nj].c = &ch.c[i];
		joints[nj].lim = lim;
		joints[nj].revolute = chan_is_angle(&ch.c[i]);
		joints[nj].ring = rings + (size_t)nj * (2 * h + 1);
		res->joints += ch.c[i].kind == CHAN_VALUE;
		res->channels += ch.c[i].kind != CHAN_VALUE;
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
		chan_list_free(&ch);
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

			joint_tick(&c, j, k, k0, h, chan_value(j->c, &pose), rate,
				   j->revolute ? 360.0 / 4294967296.0 : 1.0 / 4294967296.0);
		}
	}
	for (i = 0; i < nj; i++)
		for (kind = 0; kind < LIM_NKINDS; kind++)
			close_run(&c, &joints[i], (enum lim_kind)kind);
	pools(&c, sc, to);
	res->ticks = k1 - k0 + 1;
	scene_pose_free(&pose);
	scene_eval_free(&ev);
	free(joints);
	free(rings);
	chan_list_free(&ch);
	return 0;
}
