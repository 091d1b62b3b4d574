/* SPDX-License-Identifier: MIT */
/*
 * loop_safety.c - what the loop checks every tick (loop.h, "Safety"): the
 * inputs (e-stop, stop, camera-ready), the drives' feedback and faults, the
 * runtime limits; and why the run ends, with its one rule of precedence.
 * Every function here is [rt], but for the stop requests at the end, which
 * any thread (and a signal handler) may make.
 */
#include "loop_priv.h"
#include "hal/rt.h"

#include <math.h>
#include <string.h>

static const struct loop_where nowhere = { .channel = -1, .out = -1 };

/* The report, copied where loop_report_now reads it: a sequence lock (the
 * loop is the only writer; a reader retries while the count is odd or has
 * moved). */
static void STRAND_RT publish(struct loop *L)
{
	struct loop_safety *s = &L->safety;
	uint32_t n = atomic_load_explicit(&s->rep_seq, memory_order_relaxed);

	atomic_store_explicit(&s->rep_seq, n + 1, memory_order_relaxed);
	atomic_thread_fence(memory_order_release);
	memcpy(&s->rep_pub, &L->res->rep, sizeof(s->rep_pub));
	atomic_store_explicit(&s->rep_seq, n + 2, memory_order_release);
}

void STRAND_RT loop_fail(struct loop *L, enum loop_end end, enum loop_cause cause,
	       const struct loop_where *w)
{
	struct loop_report *r = &L->res->rep;

	if (r->end != LOOP_END_NONE && end != LOOP_END_ESTOP)
		return;
	if (!w)
		w = &nowhere;
	r->end = end;
	r->cause = cause;
	r->tick = L->tick;
	r->frame = L->res->last_frame;
	r->device = w->device;
	r->channel = w->channel;
	r->out = w->out;
	r->what = w->what;
	r->code = w->code;
	r->detail = w->detail;
	r->value = w->value;
	r->bound = w->bound;
	r->has_edge = w->has_edge;
	r->edge_ns = w->edge_ns;
	r->acted_ns = w->acted_ns;
	publish(L);
}

void STRAND_RT loop_halt(struct loop *L, enum loop_end end, enum loop_cause cause,
	       const struct loop_where *w)
{
	uint32_t i;

	for (i = 0; i < L->rig->naxes; i++) {
		hal_axis_disable(L->rig->axes[i]);
		L->safety.dev_off[i] = true;
	}
	loop_triggers_off(L);
	loop_fail(L, end, cause, w);
	L->seq.state = LOOP_ENDED;
}

void STRAND_RT loop_stop(struct loop *L, enum loop_end end, enum loop_cause cause,
	       const struct loop_where *w)
{
	uint32_t i;

	loop_fail(L, end, cause, w);
	if (L->seq.state == LOOP_ENDED)
		return;
	for (i = 0; i < L->rig->ntrig; i++)
		L->trig.pulse[i].pending = false;
	L->seq.state = LOOP_STOPPING;
	L->seq.seg_j = 0;
}

struct loop_where STRAND_RT loop_where_fault(const char *device, const struct hal_fault *f)
{
	return (struct loop_where){ .device = device, .channel = f->channel, .out = -1,
				    .what = f->cause, .code = f->code, .detail = f->detail };
}

struct loop_where STRAND_RT loop_where_out(const struct loop *L, uint32_t i, double value, double bound)
{
	const struct rig_out *o = &L->rig->out[i];

	return (struct loop_where){ .device = L->rig->axes[o->dev]->name,
				    .channel = (int32_t)o->ch, .out = (int32_t)i,
				    .value = value, .bound = bound };
}

void STRAND_RT loop_fault_device(struct loop *L, uint32_t dev, const struct hal_fault *f)
{
	struct loop_where w = loop_where_fault(L->rig->axes[dev]->name, f);
	uint32_t i;

	hal_axis_disable(L->rig->axes[dev]);
	L->safety.dev_off[dev] = true;
	for (i = 0; i < L->n; i++)
		if (L->rig->out[i].dev == dev && (int32_t)L->rig->out[i].ch == f->channel)
			w.out = (int32_t)i;
	loop_stop(L, LOOP_END_FAULT, LOOP_CAUSE_DEVICE, &w);
}

/* ---- inputs ---- */

/* Line `line` of input device d: its input's index in rig->in, or -1. */
static int32_t STRAND_RT input_of(const struct loop *L, uint32_t d, uint32_t line)
{
	const struct loop_safety *s = &L->safety;
	uint32_t first = s->in_first[d];

	return line < s->in_first[d + 1] - first ? s->in_of[first + line] : -1;
}

/* One edge of input device d, to what its line is for. An asserted e-stop
 * edge is kept (the first of the tick) for loop_inputs to act on. */
static void STRAND_RT input_edge(struct loop *L, uint32_t d, const struct hal_edge *e)
{
	int32_t i = input_of(L, d, e->line);

	if (i < 0)
		return;
	switch (L->rig->in[i].role) {
	case RIG_INPUT_CAMERA_READY:
		L->step.ready = e->asserted;
		if (e->asserted)
			L->step.ready_since_fire = true;
		break;
	case RIG_INPUT_ESTOP:
		/* (a simulated edge "before the run" is dated INT64_MIN: not
		 * one; its level stops the run) */
		if (e->asserted && e->ts_ns >= 0 && L->safety.estop_in < 0) {
			L->safety.estop_in = i;
			L->safety.estop_edge_ns = e->ts_ns;
		}
		break;
	case RIG_INPUT_STOP:
		if (e->asserted)
			loop_request_stop(L, 1, LOOP_CAUSE_STOP_INPUT);
		break;
	}
}

/* Input device d's edges, oldest first, LOOP_EDGES_MAX a poll and at most
 * LOOP_EDGES_PER_TICK in this tick (loop.h): the rest stay queued in the
 * device for the next tick. */
static void STRAND_RT input_drain(struct loop *L, uint32_t d, int64_t now)
{
	struct hal_edge *ev = L->safety.edges;
	struct loop_result *res = L->res;
	uint32_t e, n, got = 0;

	do {
		n = hal_din_poll(L->rig->dins[d], now, ev, LOOP_EDGES_MAX);
		for (e = 0; e < n; e++)
			input_edge(L, d, &ev[e]);
		got += n;
	} while (n == LOOP_EDGES_MAX && got < LOOP_EDGES_PER_TICK);
	res->edges += got;
	if (got > res->edges_tick_max)
		res->edges_tick_max = got;
	if (got == LOOP_EDGES_PER_TICK)
		res->edges_bound_ticks++;
}

void STRAND_RT loop_inputs(struct loop *L, int64_t now)
{
	const struct rig *r = L->rig;
	struct hal_fault f;
	struct loop_where w;
	int32_t hit;
	uint32_t d, i;

	L->safety.estop_in = -1;
	for (d = 0; d < r->ndins; d++) {
		input_drain(L, d, now);
		if (hal_din_fault(r->dins[d], &f)) {
			w = loop_where_fault(r->dins[d]->name, &f);
			loop_halt(L, LOOP_END_FAULT, LOOP_CAUSE_DEVICE, &w);
			return;
		}
	}
	/*
	 * The e-stop by its edge, or by its level. An asserted edge stops
	 * the run even when the level is deasserted again by now (a contact
	 * that opened for less than a tick). The level stops it when the
	 * input was asserted before the run or an edge was lost; and since a
	 * level is the newest the device knows, edges still queued behind
	 * the drain's bound included (din.h), an edge storm ahead of the
	 * e-stop's own edge cannot delay it past this tick.
	 */
	hit = L->safety.estop_in;
	for (i = 0; hit < 0 && i < r->nin; i++)
		if (r->in[i].role == RIG_INPUT_ESTOP &&
		    hal_din_level(r->dins[r->in[i].dev], r->in[i].line))
			hit = (int32_t)i;
	if (hit < 0)
		return;
	w = (struct loop_where){
		.device = r->in[hit].name, .channel = (int32_t)r->in[hit].line, .out = -1,
		.has_edge = L->safety.estop_in >= 0, .edge_ns = L->safety.estop_edge_ns,
		.acted_ns = now,
	};
	loop_halt(L, LOOP_END_ESTOP, LOOP_CAUSE_ESTOP, &w);
}

/* ---- feedback ---- */

/* Feedback, device faults and following errors; this tick's worst
 * |following error| (core units) into *worst, and its output. */
void STRAND_RT loop_feedback(struct loop *L, double *worst, int32_t *worst_out)
{
	const struct rig *r = L->rig;
	struct hal_fault f;
	uint32_t d, i;

	*worst = 0;
	*worst_out = -1;
	for (d = 0; d < r->naxes; d++) {
		if (L->safety.dev_off[d])
			continue;
		if (hal_axis_input(r->axes[d], L->tick) && hal_axis_fault(r->axes[d], &f))
			loop_fault_device(L, d, &f);
	}
	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &r->out[i];
		struct loop_out *lo = &L->out[i];
		double fe, bound;

		lo->has_fb = !o->vel_mode && !L->safety.dev_off[o->dev] &&
			     hal_axis_actual(r->axes[o->dev], o->ch, &lo->act);
		if (!lo->has_fb)
			continue;
		fe = lo->fe = hal_scale_delta_units(&o->scale, lo->sent - lo->act);
		if (fabs(fe) > *worst) {
			*worst = fabs(fe);
			*worst_out = (int32_t)i;
		}
		if (o->ferror <= 0)
			continue;
		/* LinuxCNC's speed scaling: tight at rest, looser at speed */
		bound = fmax(o->min_ferror, o->ferror * fabs(L->out[i].vel) / o->vmax);
		if (fabs(fe) > bound) {
			struct loop_where w = loop_where_out(L, i, fe, bound);

			loop_stop(L, LOOP_END_FAULT, LOOP_CAUSE_FERROR, &w);
		}
	}
}

/* ---- limits ---- */

/* The run's cause for a limit the predicate finds broken. */
static enum loop_cause STRAND_RT limit_cause(enum lim_kind k)
{
	return k == LIM_VEL ? LOOP_CAUSE_LIMIT_VEL :
	       k == LIM_ACC ? LOOP_CAUSE_LIMIT_ACC : LOOP_CAUSE_LIMIT_POS;
}

/*
 * A live loop may find the rig outside a position limit (a drive moved by
 * hand, limits made tighter): it holds there and may move back, never
 * further out (loop_live.h). Any other loop refused to start there.
 */
static bool STRAND_RT outside_ok(const struct loop *L, uint32_t i, enum lim_kind k)
{
	double x = move_q2d(L->val[i]), p = move_q2d(L->prev[i]);

	if (!L->live)
		return false;
	return (k == LIM_MIN && x >= p) || (k == LIM_MAX && x <= p);
}

/*
 * This tick's setpoints against the outputs' limits, with the predicate
 * strand check verified the timeline with (plan/limit.h), over the
 * setpoints the outputs were really sent: the pre-roll, bridges and stops
 * included. A stopping point beyond a limit is not a fault here: the
 * check before the first tick verified that of the scene, and a planned
 * move that ends on a limit approaches it braking.
 */
void STRAND_RT loop_limits(struct loop *L)
{
	const double hz = L->tm->tick_hz;
	uint32_t i, h, nh;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		struct loop_out *lo = &L->out[i];
		struct lim_hit hit[LIM_NKINDS];
		struct lim_measure me;
		struct loop_where w;

		if (L->safety.dev_off[o->dev])
			continue;
		lim_measure(&lo->meter, &L->stencil, L->val[i], &me);
		nh = lim_test(&L->stencil, &lo->lim, &me, hit);
		for (h = 0; h < nh && (hit[h].kind == LIM_STOP || outside_ok(L, i, hit[h].kind));
		     h++)
			;
		if (h == nh || hit[h].kind == LIM_STOP)
			continue;
		if (L->cfg.force) {
			/* clamp as LinuxCNC's limit3 does, without look-ahead */
			double v1 = lo->vel, dv = o->amax / hz;
			double p1 = move_q2d(L->prev[i]), v = loop_speed(L, i);

			v = fmax(-o->vmax, fmin(o->vmax, fmax(v1 - dv, fmin(v1 + dv, v))));
			L->val[i] = move_d2q(fmax(o->min, fmin(o->max, p1 + v / hz)));
			L->limited[i]++;
			continue;
		}
		w = loop_where_out(L, i, hit[h].value,
				   hit[h].kind == LIM_MIN || hit[h].kind == LIM_MAX ? hit[h].limit :
										      fabs(hit[h].limit));
		loop_stop(L, LOOP_END_FAULT, limit_cause(hit[h].kind), &w);
		/* the offending setpoints are not sent: this tick is the stop's
		 * first */
		loop_rest_step(L);
		return;
	}
}

/* ---- stop requests ---- */

void STRAND_RT loop_request_end(struct loop *L, int level, enum loop_end end,
				enum loop_cause cause)
{
	int old = atomic_load(&L->safety.stop_req);

	/* never downgrade: an immediate request stays immediate */
	while ((old & 3) < level &&
	       !atomic_compare_exchange_weak(&L->safety.stop_req, &old,
					     level | (int)cause << 2 | (int)end << 10))
		;
}

void STRAND_RT loop_request_stop(struct loop *L, int level, enum loop_cause cause)
{
	loop_request_end(L, level, LOOP_END_STOPPED, cause);
}

bool loop_report_now(const struct loop *L, struct loop_report *out)
{
	const struct loop_safety *s = &L->safety;
	uint32_t a, b;

	do {
		a = atomic_load_explicit(&s->rep_seq, memory_order_acquire);
		memcpy(out, &s->rep_pub, sizeof(*out));
		atomic_thread_fence(memory_order_acquire);
		b = atomic_load_explicit(&s->rep_seq, memory_order_relaxed);
	} while ((a & 1) || a != b);
	return out->end != LOOP_END_NONE;
}

int STRAND_RT loop_stop_requested(const struct loop *L)
{
	return atomic_load(&L->safety.stop_req) & 3;
}
