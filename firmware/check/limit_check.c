/* SPDX-License-Identifier: MIT */
/* limit_check.c - a run's whole timeline against its limits (see limit_check.h). */
#include "limit_check.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>

#include "plan/gomo.h"
#include "plan/move.h"
#include "plan/pass.h"
#include "plan/runup.h"
#include "plan/timeline.h"

/* The longest run-up or post-roll walked sample by sample: one longer (an
 * acceleration limit of a crawl) has its ends checked instead, its start
 * for the position limits, and the stopping point of the scene's last
 * sample (LIM_STOP) for where it comes to rest; between them it moves
 * within the limits by construction (runup.h, move.h). */
#define WALK_MAX (INT64_C(1) << 22)

/* An open run of samples breaking one limit of one channel. */
struct run {
	bool open;
	int64_t first, last;
	double worst, limit;
};

struct walk {
	struct play_source *src;
	const struct lim_channel *ch;
	uint32_t n;
	const struct lim_run *run;
	lim_report_fn report;
	void *ctx;
	struct lim_result *res;
	const struct mot_timing *t;
	struct lim_stencil st;
	/* per channel */
	struct lim_meter *meter;
	struct runup_ramp *ramp;
	mot_q32 *x, *prev, *start, *end, *next, *tl_mem;
	bool *extend;
	double *vel;
	struct run *runs; /* n * LIM_NKINDS */
	/* the segment being walked */
	enum lim_segment seg;
	struct pass_span sp;
	bool gomo;        /* a go-motion frame's */
};

const char *lim_kind_name(enum lim_kind k)
{
	static const char *const names[] = { "min", "max", "velocity", "acceleration",
					     "stopping distance" };

	return k < LIM_NKINDS ? names[k] : "?";
}

static double frame_of(const struct walk *w, int64_t k)
{
	return (double)mot_timing_tick_frame(w->t, k) / 4294967296.0;
}

static void close_run(struct walk *w, uint32_t i, enum lim_kind k)
{
	struct run *r = &w->runs[i * LIM_NKINDS + k];
	struct lim_violation v;

	if (!r->open)
		return;
	r->open = false;
	v.channel = i;
	v.kind = k;
	v.seg = w->seg;
	v.dir = w->sp.dir;
	v.gomo = w->gomo;
	v.worst = r->worst;
	v.limit = r->limit;
	v.tick_first = r->first;
	v.tick_last = r->last;
	if (w->seg == LIM_SEG_SCENE) {
		v.frame_first = frame_of(w, r->first);
		v.frame_last = frame_of(w, r->last);
	} else if (w->seg == LIM_SEG_FRAME) {
		v.frame_first = (double)r->first;
		v.frame_last = (double)r->last;
	} else {
		v.frame_first = v.frame_last =
			(double)(w->seg == LIM_SEG_RUNUP ? w->sp.first : w->sp.last);
	}
	w->res->violations++;
	w->report(w->ctx, &v);
}

static void close_all(struct walk *w)
{
	uint32_t i, k;

	for (i = 0; i < w->n; i++)
		for (k = 0; k < LIM_NKINDS; k++)
			close_run(w, i, (enum lim_kind)k);
}

/* How far beyond its limit a hit is: the worse of two in one run. */
static double beyond(const struct lim_hit *h)
{
	switch (h->kind) {
	case LIM_MIN:
		return h->limit - h->value;
	case LIM_MAX:
		return h->value - h->limit;
	case LIM_STOP:
		return fabs(h->value - h->limit);
	default:
		return fabs(h->value);
	}
}

/* The hits of sample `at` (a scene tick or a step) of channel i; an
 * acceleration is the one centred at `at_acc` (h samples earlier). */
static void record(struct walk *w, uint32_t i, int64_t at, int64_t at_acc,
		   const struct lim_hit *hit, uint32_t nh)
{
	uint32_t k, j;

	for (k = 0; k < LIM_NKINDS; k++) {
		struct run *r = &w->runs[i * LIM_NKINDS + k];
		int64_t when = k == LIM_ACC ? at_acc : at;

		for (j = 0; j < nh && hit[j].kind != (enum lim_kind)k; j++)
			;
		if (j == nh) {
			close_run(w, i, (enum lim_kind)k);
			continue;
		}
		if (!r->open) {
			r->open = true;
			r->first = when;
			r->worst = hit[j].value;
			r->limit = hit[j].limit;
		} else if (beyond(&hit[j]) > beyond(&(struct lim_hit){ (enum lim_kind)k, r->worst,
									 r->limit })) {
			r->worst = hit[j].value;
			r->limit = hit[j].limit;
		}
		r->last = when;
	}
}

/* Channel i's next sample x, at scene tick or step `at`. */
static void sample(struct walk *w, uint32_t i, int64_t at, mot_q32 x)
{
	struct lim_hit hit[LIM_NKINDS];
	struct lim_measure me;
	uint32_t nh, j, k;

	lim_measure(&w->meter[i], &w->st, x, &me);
	nh = lim_test(&w->st, &w->ch[i].lim, &me, hit);
	/* a ramp's speed grows to the scene's at the pass's first tick and
	 * no further: a speed too high is the scene's, reported there */
	for (j = k = 0; w->seg == LIM_SEG_RUNUP && j < nh; j++)
		if (hit[j].kind != LIM_VEL)
			hit[k++] = hit[j];
	if (w->seg == LIM_SEG_RUNUP)
		nh = k;
	record(w, i, at, at - (w->seg == LIM_SEG_SCENE ? w->sp.dir : 1) * (int64_t)w->st.h, hit,
	       nh);
	lim_meter_push(&w->meter[i], x);
	w->prev[i] = w->x[i];
	w->x[i] = x;
	w->res->samples++;
}

static void saturated(struct walk *w, uint32_t sat, double frame)
{
	if (sat && !w->res->sat) {
		w->res->sat = sat;
		w->res->sat_frame = frame;
	}
}

/* A position alone, without a speed (a ramp's start, a frame's pose). */
static void position(struct walk *w, uint32_t i, int64_t at, mot_q32 q)
{
	struct lim_hit hit[LIM_NKINDS];
	double x = move_q2d(q);
	struct lim_measure me = {
		.x = x, .noise = 1.0 / 4294967296.0 + fabs(x) / 4503599627370496.0,
	};

	record(w, i, at, at, hit, lim_test(&w->st, &w->ch[i].lim, &me, hit));
	w->res->samples++;
}

/* The run-up into the pass. A ramp that cannot be planned (a crawl beyond
 * the core's range) is reported as starting beyond its position limit. */
static void runup(struct walk *w, struct timeline *tl)
{
	uint32_t i, sat = 0;
	int64_t ticks = 0, j;

	w->seg = LIM_SEG_RUNUP;
	timeline_eval(tl, w->sp.begin, w->end, &sat);
	timeline_eval(tl, w->sp.begin + w->sp.dir, w->next, &sat);
	saturated(w, sat, (double)w->sp.first);
	for (i = 0; i < w->n; i++) {
		const struct lim_bounds *b = &w->ch[i].lim;
		int rc = runup_plan(&w->ramp[i], w->end[i], w->next[i], w->t->tick_hz, b->acc,
				    &w->start[i]);

		if (rc) {
			/* a crawl of a ramp: as far off as the core's range */
			struct lim_hit h = { w->ramp[i].v > 0 ? LIM_MIN : LIM_MAX,
					     w->ramp[i].v > 0 ? -INFINITY : INFINITY,
					     w->ramp[i].v > 0 ? b->min : b->max };

			record(w, i, 0, 0, &h, 1);
			w->ramp[i].n = 0;
			w->start[i] = w->end[i];
		}
		if (w->ramp[i].n > ticks)
			ticks = w->ramp[i].n;
		/* at rest where the ramp starts, as the pre-roll, a bridge or a
		 * go-motion frame's move leaves it */
		lim_meter_reset(&w->meter[i], &w->st, w->meter[i].ring, w->start[i], true);
		w->x[i] = w->prev[i] = w->start[i];
	}
	/* go-motion waits at rest for a trigger that fires early (gomo.h) */
	if (w->gomo && ticks < w->run->lead)
		ticks = w->run->lead;
	if (ticks > WALK_MAX) {
		for (i = 0; i < w->n; i++)
			position(w, i, 0, w->start[i]);
		ticks = 0;
	}
	for (j = 0; j < ticks; j++)
		for (i = 0; i < w->n; i++)
			sample(w, i, j, runup_at(&w->ramp[i], w->end[i], ticks, j, w->t->tick_hz));
	close_all(w);
}

static void scene(struct walk *w, struct timeline *tl)
{
	uint32_t i, sat = 0;
	int64_t k;

	w->seg = LIM_SEG_SCENE;
	for (k = w->sp.begin; (k - w->sp.end) * w->sp.dir <= 0; k += w->sp.dir) {
		timeline_eval(tl, k, w->next, &sat);
		saturated(w, sat, frame_of(w, k));
		for (i = 0; i < w->n; i++)
			sample(w, i, k, w->next[i]);
	}
	close_all(w);
}

/* From the last tick's speed to rest, as the loop's post-roll brakes. */
static void postroll(struct walk *w)
{
	const double hz = w->t->tick_hz;
	uint32_t i, moving;
	int64_t j;

	w->seg = LIM_SEG_POSTROLL;
	for (i = 0; i < w->n; i++)
		w->vel[i] = (move_q2d(w->x[i]) - move_q2d(w->prev[i])) * hz;
	for (j = 0, moving = w->n; moving && j < WALK_MAX; j++) {
		moving = 0;
		for (i = 0; i < w->n; i++) {
			const struct lim_bounds *b = &w->ch[i].lim;
			mot_q32 x = w->x[i];

			/* without an acceleration limit there is none to keep
			 * while braking: the channel stops at once */
			if (!isfinite(b->acc) || (b->vel_ch && !isfinite(b->vel)))
				continue;
			if (move_stop_step(&x, &w->vel[i], b->vel_ch, b->vel, b->acc,
					   w->t->tick_hz) && x == w->x[i])
				continue;
			sample(w, i, j, x);
			moving++;
		}
	}
	close_all(w);
}

/* Step mode: every frame's pose, where the rig stands still for it. */
static void frames(struct walk *w)
{
	uint32_t i, sat = 0;
	int64_t f;

	w->seg = LIM_SEG_FRAME;
	w->sp.dir = 1;
	for (f = w->run->from; f <= w->run->to; f++) {
		src_eval(w->src, f * MOT_Q32_ONE, w->next, &sat);
		saturated(w, sat, (double)f);
		for (i = 0; i < w->n; i++)
			position(w, i, f, w->next[i]);
	}
	close_all(w);
}

/* Go-motion: each frame exposed, a pass over the ticks of its exposure on
 * the timeline of the run's range (gomo.h). */
static int gomo(struct walk *w)
{
	const struct lim_run *r = w->run;
	int64_t lo = r->from < r->to ? r->from : r->to, hi = r->from ^ r->to ^ lo;
	int64_t f0 = r->expose_first < r->expose_last ? r->expose_first : r->expose_last;
	int64_t f1 = r->expose_first ^ r->expose_last ^ f0, f;
	struct timeline tl;
	uint32_t sat = 0;

	/* step mode's frames go either way (240..0): the same range */
	timeline_init(&tl, w->src, w->n, w->extend, lo, hi, w->tl_mem, &sat);
	saturated(w, sat, (double)lo);
	w->gomo = true;
	for (f = f0; f <= f1; f++) {
		w->sp = (struct pass_span){ .dir = 1, .first = f, .last = f, .lo = f, .hi = f };
		if (gomo_window(w->t, f, r->shutter, &w->sp.begin, &w->sp.end))
			return -EINVAL;
		runup(w, &tl);
		scene(w, &tl);
		postroll(w);
	}
	return 0;
}

static void pass(struct walk *w, int64_t p)
{
	const struct lim_run *r = w->run;
	struct timeline tl;
	uint32_t sat = 0;

	pass_span(&w->sp, w->t, r->from, r->to, r->ping_pong, p, r->lead, r->tail);
	timeline_init(&tl, w->src, w->n, w->extend, w->sp.lo, w->sp.hi, w->tl_mem, &sat);
	saturated(w, sat, (double)w->sp.first);
	runup(w, &tl);
	scene(w, &tl);
	postroll(w);
}

int lim_check(struct play_source *src, const struct lim_channel *ch, uint32_t n,
	      const struct lim_run *run, lim_report_fn report, void *ctx, struct lim_result *res)
{
	struct walk w = { .src = src, .ch = ch, .n = n, .run = run, .report = report,
			  .ctx = ctx, .res = res, .t = &src->timing };
	size_t m = n ? n : 1, len;
	uint32_t *sel, i;
	mot_q32 *q;
	int rc;

	*res = (struct lim_result){ 0 };
	lim_stencil_init(&w.st, src->timing.tick_hz);
	len = LIM_METER_LEN(w.st.h);
	sel = calloc(m, sizeof(*sel));
	q = calloc(m * (6 + TIMELINE_WORDS(1) + len), sizeof(*q));
	w.meter = calloc(m, sizeof(*w.meter));
	w.ramp = calloc(m, sizeof(*w.ramp));
	w.extend = calloc(m, sizeof(*w.extend));
	w.vel = calloc(m, sizeof(*w.vel));
	w.runs = calloc(m * LIM_NKINDS, sizeof(*w.runs));
	rc = -ENOMEM;
	if (!sel || !q || !w.meter || !w.ramp || !w.extend || !w.vel || !w.runs)
		goto out;
	w.x = q;
	w.prev = q + m;
	w.start = q + 2 * m;
	w.end = q + 3 * m;
	w.next = q + 4 * m;
	/* q + 5m: spare */
	w.tl_mem = q + 6 * m;
	for (i = 0; i < n; i++) {
		sel[i] = ch[i].src;
		w.extend[i] = timeline_extends(ch[i].unit);
		w.meter[i].ring = q + 6 * m + TIMELINE_WORDS(m) + i * len;
	}
	rc = src_select(src, sel, n);
	if (!rc && !n) {
		/* no channel with limits: the scene is still evaluated at every
		 * tick, for its arithmetic's saturation, through its first
		 * channel held to nothing (a scene without one has nothing to
		 * evaluate) */
		static const struct lim_channel none = {
			.lim = { -INFINITY, INFINITY, INFINITY, INFINITY, false },
		};

		if (!src_select(src, sel, 1)) {
			w.ch = &none;
			w.n = 1;
			w.meter[0].ring = q + 6 * m + TIMELINE_WORDS(m);
		}
	}
	if (rc)
		goto out;
	if (run->step && run->shutter) {
		rc = gomo(&w);
	} else if (run->step) {
		frames(&w);
	} else {
		pass(&w, 0);
		if (run->ping_pong && run->to > run->from && run->passes != 1)
			pass(&w, 1);
		if (run->ping_pong && run->to > run->from && (run->passes == 0 || run->passes > 2))
			pass(&w, 2);
	}
out:
	free(sel);
	free(q);
	free(w.meter);
	free(w.ramp);
	free(w.extend);
	free(w.vel);
	free(w.runs);
	return rc;
}
