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

/* Slack on a limit for the rounding of Q32.32 setpoints computed in double:
 * relative, and absolute a few units of 2^-32 per tick. */
#define LIMIT_REL 1e-6

static const struct loop_where nowhere = { .channel = -1, .out = -1 };

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

/* The edges of device d's lines, each to what its line is for. */
static void STRAND_RT input_edges(struct loop *L, uint32_t d, const struct hal_edge *ev, uint32_t n)
{
	const struct rig *r = L->rig;
	uint32_t e, i;

	for (e = 0; e < n; e++) {
		for (i = 0; i < r->nin; i++) {
			const struct rig_in *in = &r->in[i];

			if (in->dev != d || in->line != ev[e].line)
				continue;
			if (in->role == RIG_INPUT_CAMERA_READY) {
				L->step.ready = ev[e].asserted;
				if (L->step.ready)
					L->step.ready_since_fire = true;
			} else if (in->role == RIG_INPUT_ESTOP && ev[e].asserted &&
				   ev[e].ts_ns >= 0) {
				/* (a simulated edge "before the run" is dated
				 * INT64_MIN: not one) */
				L->safety.estop_edge_ns = ev[e].ts_ns;
				L->safety.estop_edge = true;
			} else if (in->role == RIG_INPUT_STOP && ev[e].asserted) {
				loop_request_stop(L, 1, LOOP_CAUSE_STOP_INPUT);
			}
		}
	}
}

void STRAND_RT loop_inputs(struct loop *L, int64_t now)
{
	const struct rig *r = L->rig;
	struct hal_edge *ev = L->safety.edges;
	struct hal_fault f;
	uint32_t d, i, n;

	for (d = 0; d < r->ndins; d++) {
		while ((n = hal_din_poll(r->dins[d], now, ev, LOOP_EDGES_MAX)) > 0) {
			input_edges(L, d, ev, n);
			if (n < LOOP_EDGES_MAX)
				break;
		}
		if (hal_din_fault(r->dins[d], &f)) {
			struct loop_where w = loop_where_fault(r->dins[d]->name, &f);

			loop_halt(L, LOOP_END_FAULT, LOOP_CAUSE_DEVICE, &w);
			return;
		}
	}
	/* the e-stop by level, not only by edge: an input asserted before the
	 * run, or an edge lost, still stops it */
	for (i = 0; i < r->nin; i++) {
		const struct rig_in *in = &r->in[i];

		if (in->role == RIG_INPUT_ESTOP && hal_din_level(r->dins[in->dev], in->line)) {
			struct loop_where w = {
				.device = in->name, .channel = (int32_t)in->line, .out = -1,
				.has_edge = L->safety.estop_edge,
				.edge_ns = L->safety.estop_edge_ns, .acted_ns = now,
			};

			loop_halt(L, LOOP_END_ESTOP, LOOP_CAUSE_ESTOP, &w);
			return;
		}
	}
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
		double fe, bound;

		if (!loop_ferror(L, i, &fe))
			continue;
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

void STRAND_RT loop_limits(struct loop *L)
{
	const double hz = L->tm->tick_hz;
	uint32_t i;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		double p = move_q2d(L->val[i]), p1 = move_q2d(L->prev[i]);
		double v = loop_speed(L, i), a = (v - L->out[i].vel) * hz;
		double eps_v = o->vmax * LIMIT_REL + 4 * hz / 4294967296.0;
		double eps_a = o->amax * LIMIT_REL + 8 * hz * hz / 4294967296.0;
		enum loop_cause why = LOOP_CAUSE_NONE;
		double val = 0, bound = 0;
		struct loop_where w;

		if (L->safety.dev_off[o->dev])
			continue;
		if (p < o->min - 1e-9 || p > o->max + 1e-9) {
			why = LOOP_CAUSE_LIMIT_POS;
			val = p;
			bound = p < o->min ? o->min : o->max;
		} else if (fabs(v) > o->vmax + eps_v) {
			why = LOOP_CAUSE_LIMIT_VEL;
			val = v;
			bound = o->vmax;
		} else if (fabs(a) > o->amax + eps_a) {
			why = LOOP_CAUSE_LIMIT_ACC;
			val = a;
			bound = o->amax;
		}
		if (why == LOOP_CAUSE_NONE)
			continue;
		if (L->cfg.force) {
			/* clamp as LinuxCNC's limit3 does, without look-ahead */
			double v1 = L->out[i].vel, dv = o->amax / hz;

			v = fmax(-o->vmax, fmin(o->vmax, fmax(v1 - dv, fmin(v1 + dv, v))));
			p = fmax(o->min, fmin(o->max, p1 + v / hz));
			L->val[i] = move_d2q(p);
			L->limited[i]++;
			continue;
		}
		w = loop_where_out(L, i, val, bound);
		loop_stop(L, LOOP_END_FAULT, why, &w);
		/* the offending setpoints are not sent: this tick is the stop's
		 * first */
		loop_rest_step(L);
		return;
	}
}

/* ---- stop requests ---- */

void STRAND_RT loop_request_stop(struct loop *L, int level, enum loop_cause cause)
{
	int old = atomic_load(&L->safety.stop_req);

	/* never downgrade: an immediate request stays immediate */
	while ((old & 3) < level &&
	       !atomic_compare_exchange_weak(&L->safety.stop_req, &old, level | (int)cause << 2))
		;
}

int STRAND_RT loop_stop_requested(const struct loop *L)
{
	return atomic_load(&L->safety.stop_req) & 3;
}
