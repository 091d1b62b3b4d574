/* SPDX-License-Identifier: MIT */
/* loop.c - the real-time loop (see loop.h). */
#include "loop.h"

#include <errno.h>
#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Slack on a limit for the rounding of Q32.32 setpoints computed in double:
 * relative, and absolute a few units of 2^-32 per tick. */
#define LIMIT_REL 1e-6

static const char *const state_names[] = {
	[LOOP_PREROLL] = "pre-roll",	 [LOOP_RUNUP] = "run-up",
	[LOOP_PLAY] = "play",
	[LOOP_BRIDGE_STOP] = "bridge",	 [LOOP_BRIDGE_MOVE] = "bridge",
	[LOOP_POSTROLL] = "post-roll",	 [LOOP_STEP_NEXT] = "step",
	[LOOP_STEP_MOVE] = "move",	 [LOOP_STEP_SETTLE] = "settle",
	[LOOP_STEP_EXPOSE] = "expose",	 [LOOP_STOPPING] = "stopping",
	[LOOP_ENDED] = "ended",
};

static const char *const cause_names[] = {
	[LOOP_CAUSE_NONE] = "",
	[LOOP_CAUSE_FINISHED] = "finished",
	[LOOP_CAUSE_DURATION] = "duration reached",
	[LOOP_CAUSE_SIGNAL] = "stop requested (signal)",
	[LOOP_CAUSE_IMMEDIATE] = "immediate stop (second signal)",
	[LOOP_CAUSE_STOP_INPUT] = "stop input",
	[LOOP_CAUSE_ESTOP] = "e-stop",
	[LOOP_CAUSE_DEVICE] = "device fault",
	[LOOP_CAUSE_FERROR] = "following error",
	[LOOP_CAUSE_LIMIT_POS] = "position limit",
	[LOOP_CAUSE_LIMIT_VEL] = "velocity limit",
	[LOOP_CAUSE_LIMIT_ACC] = "acceleration limit",
	[LOOP_CAUSE_IN_POSITION] = "not in position",
	[LOOP_CAUSE_READY] = "camera not ready",
	[LOOP_CAUSE_JOURNAL] = "journal cannot record the frame",
	[LOOP_CAUSE_SATURATION] = "arithmetic saturated",
};

const char *loop_state_name(enum loop_state s)
{
	return s <= LOOP_ENDED ? state_names[s] : "?";
}

const char *loop_cause_name(enum loop_cause c)
{
	return c <= LOOP_CAUSE_SATURATION ? cause_names[c] : "?";
}

int64_t loop_due(const struct loop *L, int64_t k)
{
	uint32_t hz = L->tm->tick_hz;

	/* whole seconds and the rest separately: exact, and no overflow for
	 * any tick count the core accepts */
	return L->t0 + (k / hz) * 1000000000 + (k % hz) * 1000000000 / hz;
}

void loop_request_stop(struct loop *L, int level, enum loop_cause cause)
{
	int old = atomic_load(&L->stop_req);

	/* never downgrade: an immediate request stays immediate */
	while ((old & 3) < level &&
	       !atomic_compare_exchange_weak(&L->stop_req, &old, level | (int)cause << 2))
		;
}

/* ---- the end of a run ---- */

static void report(struct loop *L, enum loop_end end, enum loop_cause cause)
{
	/* the first reason stands, but an e-stop outranks them all */
	if (L->rep.end != LOOP_END_NONE && end != LOOP_END_ESTOP)
		return;
	L->rep.end = end;
	L->rep.cause = cause;
	L->rep.tick = L->tick;
	L->rep.frame = L->last_frame;
}

/* Where the trouble is, unless an earlier reason is already recorded. */
static void where(struct loop *L, bool force, const char *device, int32_t channel,
		  const char *what, int code)
{
	if (L->rep.end != LOOP_END_NONE && !force)
		return;
	L->rep.device = device;
	L->rep.channel = channel;
	L->rep.out = -1;
	L->rep.what = what;
	L->rep.code = code;
}

/* Triggers off now, in this tick. */
static void triggers_off(struct loop *L)
{
	uint32_t i;

	for (i = 0; i < L->rig->ntrig; i++) {
		const struct rig_trig *t = &L->rig->trig[i];

		hal_dout_set(L->rig->douts[t->dev], t->line, false);
		L->ts[i].active = false;
		L->ts[i].pending = false;
	}
	for (i = 0; i < L->rig->ndouts; i++)
		hal_dout_commit(L->rig->douts[i], L->tick);
}

/* E-stop and the immediate stop: drives off, triggers off, the run ends. */
static void halt(struct loop *L, enum loop_end end, enum loop_cause cause)
{
	uint32_t i;

	for (i = 0; i < L->rig->naxes; i++) {
		hal_axis_disable(L->rig->axes[i]);
		L->dev_off[i] = true;
	}
	triggers_off(L);
	report(L, end, cause);
	L->state = LOOP_ENDED;
}

/* Begin a controlled stop: no new triggers, every output to rest. */
static void begin_stop(struct loop *L, enum loop_end end, enum loop_cause cause)
{
	uint32_t i;

	report(L, end, cause);
	if (L->state == LOOP_ENDED)
		return;
	for (i = 0; i < L->rig->ntrig; i++)
		L->ts[i].pending = false;
	L->state = LOOP_STOPPING;
	L->seg_j = 0;
}

static void fault_device(struct loop *L, uint32_t dev, const struct hal_fault *f)
{
	hal_axis_disable(L->rig->axes[dev]);
	L->dev_off[dev] = true;
	if (L->rep.end == LOOP_END_NONE) {
		where(L, false, L->rig->axes[dev]->name, f->channel, f->cause, f->code);
		L->rep.detail = f->detail;
		for (uint32_t i = 0; i < L->n; i++)
			if (L->rig->out[i].dev == dev && (int32_t)L->rig->out[i].ch == f->channel)
				L->rep.out = (int32_t)i;
	}
	begin_stop(L, LOOP_END_FAULT, LOOP_CAUSE_DEVICE);
}

static void fault_out(struct loop *L, uint32_t i, enum loop_cause cause, double value,
		      double bound)
{
	const struct rig_out *o = &L->rig->out[i];

	if (L->rep.end == LOOP_END_NONE) {
		L->rep.device = L->rig->axes[o->dev]->name;
		L->rep.channel = (int32_t)o->ch;
		L->rep.out = (int32_t)i;
		L->rep.value = value;
		L->rep.bound = bound;
	}
	begin_stop(L, LOOP_END_FAULT, cause);
}

/* ---- inputs ---- */

static void inputs(struct loop *L, int64_t now)
{
	const struct rig *r = L->rig;
	uint32_t d, e, i, n;
	struct hal_fault f;

	for (d = 0; d < r->ndins; d++) {
		while ((n = hal_din_poll(r->dins[d], now, L->edges, LOOP_EDGES_MAX)) > 0) {
			for (e = 0; e < n; e++) {
				for (i = 0; i < r->nin; i++) {
					const struct rig_in *in = &r->in[i];

					if (in->dev != d || in->line != L->edges[e].line)
						continue;
					if (in->role == RIG_INPUT_CAMERA_READY) {
						L->ready = L->edges[e].asserted;
						if (L->ready)
							L->ready_since_fire = true;
					} else if (in->role == RIG_INPUT_ESTOP &&
						   L->edges[e].asserted && L->edges[e].ts_ns >= 0) {
						/* (a simulated edge "before the run" is
						 * dated INT64_MIN: not one) */
						L->estop_edge_ns = L->edges[e].ts_ns;
						L->estop_edge = true;
					} else if (in->role == RIG_INPUT_STOP && L->edges[e].asserted) {
						loop_request_stop(L, 1, LOOP_CAUSE_STOP_INPUT);
					}
				}
			}
			if (n < LOOP_EDGES_MAX)
				break;
		}
		if (hal_din_fault(r->dins[d], &f)) {
			where(L, false, r->dins[d]->name, f.channel, f.cause, f.code);
			halt(L, LOOP_END_FAULT, LOOP_CAUSE_DEVICE);
			return;
		}
	}
	/* the e-stop by level, not only by edge: an input asserted before the
	 * run, or an edge lost, still stops it */
	for (i = 0; i < r->nin; i++) {
		const struct rig_in *in = &r->in[i];

		if (in->role == RIG_INPUT_ESTOP && hal_din_level(r->dins[in->dev], in->line)) {
			where(L, true, in->name, (int32_t)in->line, NULL, 0);
			L->rep.has_edge = L->estop_edge;
			L->rep.edge_ns = L->estop_edge_ns;
			L->rep.acted_ns = now;
			halt(L, LOOP_END_ESTOP, LOOP_CAUSE_ESTOP);
			return;
		}
	}
}

/* Feedback, device faults and following errors; returns this tick's
 * worst |following error| (core units) in *worst and its output. */
static void feedback(struct loop *L, double *worst, int32_t *worst_out)
{
	const struct rig *r = L->rig;
	struct hal_fault f;
	uint32_t d, i;

	*worst = 0;
	*worst_out = -1;
	for (d = 0; d < r->naxes; d++) {
		if (L->dev_off[d])
			continue;
		if (hal_axis_input(r->axes[d], L->tick) && hal_axis_fault(r->axes[d], &f))
			fault_device(L, d, &f);
	}
	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &r->out[i];
		int64_t act;
		double fe, bound;

		if (o->vel_mode || L->dev_off[o->dev] || !hal_axis_actual(r->axes[o->dev], o->ch, &act))
			continue;
		fe = hal_scale_delta_units(&o->scale, L->sent[i] - act);
		if (fabs(fe) > *worst) {
			*worst = fabs(fe);
			*worst_out = (int32_t)i;
		}
		if (o->ferror <= 0)
			continue;
		bound = fmax(o->min_ferror, o->ferror * fabs(L->vel[i]) / o->vmax);
		if (fabs(fe) > bound)
			fault_out(L, i, LOOP_CAUSE_FERROR, fe, bound);
	}
}

/* ---- the sequence ---- */

static void eval_at_tick(struct loop *L, int64_t scene_tick, mot_q32 *out)
{
	src_eval(L->src, mot_timing_tick_frame(L->tm, scene_tick), out, &L->sat);
}

/* A move from `from` (at rest) to `to`; its sample 0 is `from`, and the
 * following ticks take samples 1, 2, ... up to the target. */
static void plan_move(struct loop *L, const mot_q32 *from, const mot_q32 *to)
{
	/* limits were checked positive and finite when the rig was built */
	move_plan(&L->mv, L->mv_ch, L->n, from, to, L->vmax, L->amax, L->tm->tick_hz);
	L->mv_j = 0;
}

/* The frames of pass p, in firing order, and the scene ticks it covers. */
static void setup_pass(struct loop *L)
{
	const struct loop_cfg *c = &L->cfg;
	int64_t p = L->pass;
	uint32_t i;

	L->dir = 1;
	L->pass_first = c->from;
	L->pass_last = c->to;
	if (c->ping_pong && c->to > c->from) {
		if (p % 2) {
			L->dir = -1;
			L->pass_first = c->to - 1;
			L->pass_last = c->from;
		} else if (p > 0) {
			L->pass_first = c->from + 1;
		}
	}
	L->scene_begin = mot_timing_trigger_tick(L->tm, L->pass_first) - L->dir * L->lead;
	L->scene_end = mot_timing_trigger_tick(L->tm, L->pass_last) + L->dir * L->tail;
	for (i = 0; i < L->rig->ntrig; i++) {
		struct trig_state *t = &L->ts[i];

		t->next_frame = L->pass_first;
		t->pending = true;
		t->edge_k = mot_timing_trigger_tick(L->tm, t->next_frame) +
			    L->dir * L->rig->trig[i].offset;
	}
}

/*
 * The way into a pass (loop.h, "run-up"): the first pose and speed of the
 * pass, each channel's ramp, and in L->target where the ramps start (the
 * pre-roll's or bridge's destination). -1 and the channel's index in *bad
 * when a ramp would start outside its position limits.
 */
static int plan_entry(struct loop *L, int32_t *bad)
{
	const double hz = L->tm->tick_hz, dt = 1.0 / hz;
	uint32_t i;

	eval_at_tick(L, L->scene_begin, L->ru_end);
	eval_at_tick(L, L->scene_begin + L->dir, L->target);
	L->ru_ticks = 0;
	L->ru_j = 0;
	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		double v = (move_q2d(L->target[i]) - move_q2d(L->ru_end[i])) * hz;
		double back;
		int64_t n = (int64_t)ceil(fabs(v) * hz / o->amax * (1 + 1e-9));

		L->ru_v[i] = v;
		L->ru_n[i] = n;
		if (n > L->ru_ticks)
			L->ru_ticks = n;
		/* speeds v k / n for k = 1..n cover v dt (n + 1) / 2 */
		back = v * dt * (double)(n + 1) / 2;
		L->target[i] = n ? L->ru_end[i] - move_d2q(back) : L->ru_end[i];
		if (move_q2d(L->target[i]) < o->min - 1e-9 || move_q2d(L->target[i]) > o->max + 1e-9) {
			*bad = (int32_t)i;
			return -1;
		}
	}
	return 0;
}

/* Channel i at step j of the run-up (0: at rest at its start, ru_ticks:
 * the first pose). */
static mot_q32 runup_at(const struct loop *L, uint32_t i, int64_t j)
{
	int64_t n = L->ru_n[i], m = j - (L->ru_ticks - n); /* the ramps end together */
	double left;

	if (n == 0 || m >= n)
		return L->ru_end[i];
	if (m < 0)
		m = 0;
	/* the distance still to go after step m: sum of v k / n dt, k = m+1..n */
	left = L->ru_v[i] / n / L->tm->tick_hz * (double)(n * (n + 1) - m * (m + 1)) / 2;
	return L->ru_end[i] - move_d2q(left);
}

static bool more_passes(const struct loop *L)
{
	const struct loop_cfg *c = &L->cfg;

	if (!c->loop && !c->ping_pong)
		return false;
	return c->passes == 0 || L->pass + 1 < c->passes;
}

/* Every output to rest for one tick; true when all are. */
static bool stop_step(struct loop *L)
{
	bool rest = true;
	uint32_t i;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		double v = L->vel[i];

		L->val[i] = L->prev[i];
		if (L->dev_off[o->dev])
			continue;
		rest &= move_stop_step(&L->val[i], &v, o->vel_mode, o->vmax, o->amax,
				       L->tm->tick_hz);
	}
	return rest;
}

static bool pulses_active(const struct loop *L)
{
	uint32_t i;

	for (i = 0; i < L->rig->ntrig; i++)
		if (L->ts[i].active)
			return true;
	return false;
}

/* This tick's setpoints into L->val, moving through the segments. */
static void sequence(struct loop *L)
{
	int32_t bad;
	uint32_t i;

	for (;;) {
		switch (L->state) {
		case LOOP_PREROLL:
		case LOOP_BRIDGE_MOVE:
		case LOOP_STEP_MOVE:
			/* samples 1..ticks: the last one is the target */
			if (++L->mv_j <= L->mv.ticks) {
				for (i = 0; i < L->n; i++)
					L->val[i] = move_at(&L->mv, i, L->mv_j);
				return;
			}
			if (L->state == LOOP_STEP_MOVE) {
				L->state = LOOP_STEP_SETTLE;
				L->settled = 0;
				L->seg_j = 0;
			} else {
				L->state = LOOP_RUNUP;
				L->ru_j = -1;
			}
			continue;
		case LOOP_RUNUP:
			/* samples 0..ru_ticks - 1: sample 0 repeats the move's
			 * target, so the rig is at rest (two equal setpoints)
			 * before the ramp's first step; PLAY's first tick is the
			 * ramp's end, the pass's first pose */
			if (++L->ru_j < L->ru_ticks) {
				for (i = 0; i < L->n; i++)
					L->val[i] = runup_at(L, i, L->ru_j);
				return;
			}
			L->state = LOOP_PLAY;
			L->scene_k = L->scene_begin - L->dir;
			continue;
		case LOOP_PLAY:
			L->scene_k += L->dir;
			if ((L->scene_k - L->scene_end) * L->dir > 0) {
				L->state = more_passes(L) ? LOOP_BRIDGE_STOP : LOOP_POSTROLL;
				continue;
			}
			eval_at_tick(L, L->scene_k, L->val);
			return;
		case LOOP_BRIDGE_STOP:
			if (!stop_step(L))
				return;
			L->pass++;
			setup_pass(L);
			if (plan_entry(L, &bad)) {
				fault_out(L, (uint32_t)bad, LOOP_CAUSE_LIMIT_POS,
					  move_q2d(L->target[bad]), 0);
				L->state = LOOP_ENDED;
				report(L, LOOP_END_FAULT, LOOP_CAUSE_LIMIT_POS);
				return;
			}
			/* from where this tick's stop sample rests */
			plan_move(L, L->val, L->target);
			L->state = LOOP_BRIDGE_MOVE;
			if (L->mv.ticks == 0)
				continue;
			return; /* this tick holds the rest position (the stop's last) */
		case LOOP_POSTROLL:
		case LOOP_STOPPING:
			if (stop_step(L) && !pulses_active(L)) {
				if (L->state == LOOP_POSTROLL)
					report(L, LOOP_END_DONE, LOOP_CAUSE_FINISHED);
				L->state = LOOP_ENDED;
			}
			return;
		case LOOP_STEP_NEXT:
			if (!frames_next(L->cfg.frames, &L->fit, &L->step_frame)) {
				report(L, LOOP_END_DONE, LOOP_CAUSE_FINISHED);
				L->state = LOOP_ENDED;
				for (i = 0; i < L->n; i++)
					L->val[i] = L->prev[i];
				return;
			}
			src_eval(L->src, L->step_frame * MOT_Q32_ONE, L->target, &L->sat);
			plan_move(L, L->prev, L->target);
			L->state = LOOP_STEP_MOVE;
			continue;
		case LOOP_STEP_SETTLE:
		case LOOP_STEP_EXPOSE:
			for (i = 0; i < L->n; i++)
				L->val[i] = L->target[i];
			return;
		case LOOP_ENDED:
			for (i = 0; i < L->n; i++)
				L->val[i] = L->prev[i];
			return;
		}
	}
}

/* ---- limits ---- */

static void limits(struct loop *L)
{
	const double hz = L->tm->tick_hz;
	uint32_t i;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		double p = move_q2d(L->val[i]), p1 = move_q2d(L->prev[i]);
		double v = (p - p1) * hz, a = (v - L->vel[i]) * hz;
		double eps_v = o->vmax * LIMIT_REL + 4 * hz / 4294967296.0;
		double eps_a = o->amax * LIMIT_REL + 8 * hz * hz / 4294967296.0;
		enum loop_cause why = LOOP_CAUSE_NONE;
		double val = 0, bound = 0;

		if (L->dev_off[o->dev])
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
			double v1 = L->vel[i], dv = o->amax / hz;

			v = fmax(-o->vmax, fmin(o->vmax, fmax(v1 - dv, fmin(v1 + dv, v))));
			p = fmax(o->min, fmin(o->max, p1 + v / hz));
			L->val[i] = move_d2q(p);
			L->limited[i]++;
			continue;
		}
		fault_out(L, i, why, val, bound);
		/* the offending setpoints are not sent: this tick is the stop's
		 * first */
		stop_step(L);
		return;
	}
}

/* ---- outputs and triggers ---- */

/* This tick's setpoints in device counts; false when a scaling saturated
 * (nothing is sent then). */
static bool scale_outputs(struct loop *L)
{
	const struct rig *r = L->rig;
	uint32_t i, sat = 0;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &r->out[i];
		struct hal_setpoint *sp = &L->sp[i];
		double v = (move_q2d(L->val[i]) - move_q2d(L->prev[i])) * L->tm->tick_hz;

		if (o->vel_mode) {
			sp->pos = 0;
			sp->vel = hal_scale_counts(&o->scale, L->val[i], &sat);
		} else {
			sp->pos = hal_scale_counts(&o->scale, L->val[i], &sat);
			sp->vel = hal_scale_rate(&o->scale, v);
		}
	}
	L->sat |= sat;
	return !sat;
}

static void outputs(struct loop *L)
{
	const struct rig *r = L->rig;
	uint32_t i, d;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &r->out[i];

		if (L->dev_off[o->dev])
			continue;
		hal_axis_set(r->axes[o->dev], o->ch, &L->sp[i]);
		L->sent[i] = L->sp[i].pos;
	}
	for (d = 0; d < r->naxes; d++) {
		struct hal_fault f;

		if (!L->dev_off[d] && hal_axis_commit(r->axes[d], L->tick) &&
		    hal_axis_fault(r->axes[d], &f))
			fault_device(L, d, &f);
	}
}

/* Fill the journal record of trigger i firing frame f; NULL: refused. */
static struct journal_rec *journal_take(struct loop *L, uint32_t i, int64_t f, int64_t due)
{
	struct journal_rec *rec;
	uint32_t k;

	if (!L->jr)
		return NULL;
	while (!(rec = journal_next(L->jr))) {
		/* on the virtual clock time waits for the journal's service; on
		 * the wall clock a frame that cannot be recorded is not fired */
		if (!L->cfg.wait_for_journal || L->jr->err || L->jr->next >= L->jr->capacity)
			return NULL;
		L->journal_waits++;
		sched_yield();
	}
	rec->trigger = i;
	rec->frame = f;
	rec->tick = L->tick;
	rec->due_ns = due;
	rec->mono_ns = 0;
	rec->wall_ns = 0;
	rec->ferr = 0;
	rec->ferr_out = -1;
	for (k = 0; k < L->n; k++)
		rec->sp[k] = L->val[k];
	journal_arm(L->jr, rec);
	return rec;
}

/* Raise trigger i for frame f in this tick; false when the journal
 * refused it (the run is stopping then). */
static bool rise(struct loop *L, uint32_t i, int64_t f, int64_t due)
{
	const struct rig_trig *t = &L->rig->trig[i];

	if (L->jr) {
		L->armed[i] = journal_take(L, i, f, due);
		if (!L->armed[i]) {
			L->rep.code = L->jr->err;
			begin_stop(L, LOOP_END_FAULT, LOOP_CAUSE_JOURNAL);
			return false;
		}
	}
	hal_dout_set(L->rig->douts[t->dev], t->line, true);
	L->dout_dirty[t->dev] = true;
	L->ts[i].active = true;
	L->ts[i].fall_tick = L->tick + t->width;
	L->last_frame = f;
	L->frames_fired++;
	return true;
}

static void triggers(struct loop *L, int64_t due)
{
	const struct rig *r = L->rig;
	bool any = false, fire_step = false;
	uint32_t i, d;

	for (i = 0; i < r->ntrig; i++) {
		struct trig_state *t = &L->ts[i];

		L->armed[i] = NULL;
		if (t->active && L->tick >= t->fall_tick) {
			hal_dout_set(r->douts[r->trig[i].dev], r->trig[i].line, false);
			L->dout_dirty[r->trig[i].dev] = true;
			t->active = false;
		}
	}
	if (L->state == LOOP_PLAY) {
		for (i = 0; i < r->ntrig; i++) {
			struct trig_state *t = &L->ts[i];

			if (!t->pending || L->scene_k != t->edge_k)
				continue;
			if (!rise(L, i, t->next_frame, due))
				break;
			any = true;
			if (t->next_frame == L->pass_last) {
				t->pending = false;
			} else {
				t->next_frame += L->dir;
				t->edge_k = mot_timing_trigger_tick(L->tm, t->next_frame) +
					    L->dir * r->trig[i].offset;
			}
		}
	} else if (L->state == LOOP_STEP_SETTLE) {
		const struct rig_out *o;
		bool in_pos = true;
		double fe;
		int64_t act;

		for (i = 0; i < L->n && in_pos; i++) {
			o = &r->out[i];
			if (o->vel_mode || L->dev_off[o->dev] ||
			    !hal_axis_actual(r->axes[o->dev], o->ch, &act))
				continue;
			fe = hal_scale_delta_units(&o->scale, L->sent[i] - act);
			in_pos = fabs(fe) <= o->in_position;
		}
		L->settled = in_pos ? L->settled + 1 : 0;
		if (L->settled > L->cfg.settle_ticks && !pulses_active(L) &&
		    (!L->has_ready_input || L->ready)) {
			fire_step = true;
		} else if (++L->seg_j > L->cfg.in_position_timeout_ticks) {
			enum loop_cause why = in_pos ? LOOP_CAUSE_READY : LOOP_CAUSE_IN_POSITION;

			/* name the output furthest from its target */
			for (i = 0; i < L->n; i++) {
				o = &r->out[i];
				if (o->vel_mode || !hal_axis_actual(r->axes[o->dev], o->ch, &act))
					continue;
				fe = hal_scale_delta_units(&o->scale, L->sent[i] - act);
				if (fabs(fe) > o->in_position) {
					fault_out(L, i, why, fe, o->in_position);
					break;
				}
			}
			begin_stop(L, LOOP_END_FAULT, why);
		}
	} else if (L->state == LOOP_STEP_EXPOSE) {
		int64_t since = L->tick - L->fired_at;
		bool done = L->has_ready_input ? L->ready_since_fire && L->ready :
						 since >= L->cfg.exposure_ticks;

		if (done && !pulses_active(L)) {
			L->state = LOOP_STEP_NEXT;
		} else if (since > L->cfg.ready_timeout_ticks) {
			begin_stop(L, LOOP_END_FAULT, LOOP_CAUSE_READY);
		}
	}
	if (fire_step) {
		for (i = 0; i < r->ntrig; i++)
			if (!rise(L, i, L->step_frame, due))
				break;
		if (L->state == LOOP_STEP_SETTLE) {
			any = true;
			L->state = LOOP_STEP_EXPOSE;
			L->fired_at = L->tick;
			L->ready_since_fire = false;
		}
	}
	for (d = 0; d < r->ndouts; d++) {
		struct hal_fault f;

		if (!L->dout_dirty[d])
			continue;
		L->dout_dirty[d] = false;
		if (hal_dout_commit(r->douts[d], L->tick) && hal_dout_fault(r->douts[d], &f)) {
			where(L, false, r->douts[d]->name, f.channel, f.cause, f.code);
			begin_stop(L, LOOP_END_FAULT, LOOP_CAUSE_DEVICE);
		}
	}
	if (any && L->jr) {
		/* the edges are out: their time, then FIRED */
		int64_t mono = hal_clock_now(L->clk), wall = hal_clock_wall(L->clk);

		for (i = 0; i < r->ntrig; i++)
			if (L->armed[i]) {
				journal_fire(L->armed[i], mono, wall);
				L->cur_rec = L->armed[i];
			}
	}
}

static void status(struct loop *L)
{
	struct loop_status s;

	if (!L->status)
		return;
	if (L->state != LOOP_ENDED && L->tick % L->cfg.status_every)
		return;
	s.tick = L->tick;
	s.frame = L->last_frame;
	s.fired = L->frames_fired;
	s.total = L->total_frames;
	s.lat_max_ns = L->lat.n ? L->lat.max_ns : 0;
	s.overruns = L->lat.overruns;
	s.ferr = L->ferr_worst;
	s.ferr_out = L->ferr_worst_out;
	s.state = (uint8_t)L->state;
	s.end = (uint8_t)L->rep.end;
	if (!hal_ring_push(L->status, &s))
		L->status_dropped++;
}

bool loop_tick(struct loop *L, int64_t k, int64_t due_ns, int64_t now_ns)
{
	double fe = 0;
	int32_t fe_out = -1;
	int req;
	uint32_t i;

	L->tick = k;
	if (L->state == LOOP_ENDED)
		return false;
	inputs(L, now_ns);
	if (L->state == LOOP_ENDED)
		goto out;
	req = atomic_load_explicit(&L->stop_req, memory_order_relaxed);
	if ((req & 3) == 2) {
		halt(L, LOOP_END_STOPPED, (enum loop_cause)(req >> 2));
		goto out;
	}
	if ((req & 3) == 1 && L->rep.end == LOOP_END_NONE)
		begin_stop(L, LOOP_END_STOPPED, (enum loop_cause)(req >> 2));
	if (L->cfg.max_ticks && k >= L->cfg.max_ticks && L->rep.end == LOOP_END_NONE)
		begin_stop(L, LOOP_END_DONE, LOOP_CAUSE_DURATION);
	feedback(L, &fe, &fe_out);
	if (fe > L->ferr_worst) {
		L->ferr_worst = fe;
		L->ferr_worst_out = fe_out;
	}
	if (L->cur_rec && fe > L->cur_rec->ferr) {
		L->cur_rec->ferr = fe;
		L->cur_rec->ferr_out = fe_out;
	}
	sequence(L);
	limits(L);
	if (!scale_outputs(L) || L->sat) {
		halt(L, LOOP_END_INTERNAL, LOOP_CAUSE_SATURATION);
		goto out;
	}
	outputs(L);
	triggers(L, due_ns);
	for (i = 0; i < L->n; i++) {
		L->vel[i] = (move_q2d(L->val[i]) - move_q2d(L->prev[i])) * L->tm->tick_hz;
		L->prev[i] = L->val[i];
	}
out:
	L->ticks_run = k + 1;
	status(L);
	return L->state != LOOP_ENDED;
}

void loop_run(struct loop *L, int64_t t0)
{
	struct timespec c0, c1;
	int64_t k, due, now, end = INT64_MIN;

	L->t0 = t0;
	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
	for (k = 0;; k++) {
		due = loop_due(L, k);
		if (end >= due) {
			/* late already: run this tick now, no sleep, no wake-up */
			now = end;
			L->lat.catchup++;
		} else {
			hal_clock_sleep_until(L->clk, due);
			now = hal_clock_now(L->clk);
			lat_add(&L->lat, k, now - due);
		}
		if (now - due > L->lat.late_max_ns)
			L->lat.late_max_ns = now - due;
		if (!loop_tick(L, k, due, now))
			break;
		/* virtual time stands still during a tick, unless a test makes
		 * it jump (a stall): the same catch-up runs on either clock */
		end = hal_clock_now(L->clk);
		if (end - now > L->lat.work_max_ns)
			L->lat.work_max_ns = end - now;
		if (end > loop_due(L, k + 1))
			L->lat.overruns++;
	}
	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
	L->cpu_ns = (c1.tv_sec - c0.tv_sec) * 1000000000LL + (c1.tv_nsec - c0.tv_nsec);
}

/* ---- set-up ---- */

static void *zalloc(size_t n, size_t size, bool *ok)
{
	void *p = calloc(n ? n : 1, size);

	*ok &= p != NULL;
	return p;
}

int loop_init(struct loop *L, const struct loop_cfg *cfg, struct rig *rig,
	      struct play_source *src, struct hal_clock *clk, struct journal *jr,
	      struct hal_ring *status_ring, char *err, size_t errsize)
{
	uint32_t i, n = rig->nout;
	int64_t min_off = 0, max_off = 0;
	int32_t bad;
	bool ok = true;

	memset(L, 0, sizeof(*L));
	L->cfg = *cfg;
	if (L->cfg.status_every < 1)
		L->cfg.status_every = 1;
	L->rig = rig;
	L->src = src;
	L->clk = clk;
	L->jr = jr;
	L->status = status_ring;
	L->tm = &src->timing;
	L->n = n;
	L->val = zalloc(n, sizeof(mot_q32), &ok);
	L->prev = zalloc(n, sizeof(mot_q32), &ok);
	L->target = zalloc(n, sizeof(mot_q32), &ok);
	L->vel = zalloc(n, sizeof(double), &ok);
	L->sent = zalloc(n, sizeof(int64_t), &ok);
	L->sp = zalloc(n, sizeof(struct hal_setpoint), &ok);
	L->vmax = zalloc(n, sizeof(double), &ok);
	L->amax = zalloc(n, sizeof(double), &ok);
	L->limited = zalloc(n, sizeof(int64_t), &ok);
	L->mv_ch = zalloc(n, sizeof(struct move_ch), &ok);
	L->ru_end = zalloc(n, sizeof(mot_q32), &ok);
	L->ru_v = zalloc(n, sizeof(double), &ok);
	L->ru_n = zalloc(n, sizeof(int64_t), &ok);
	L->dev_off = zalloc(rig->naxes, sizeof(bool), &ok);
	L->dout_dirty = zalloc(rig->ndouts, sizeof(bool), &ok);
	L->ts = zalloc(rig->ntrig, sizeof(struct trig_state), &ok);
	L->armed = zalloc(rig->ntrig, sizeof(struct journal_rec *), &ok);
	if (!ok) {
		loop_free(L);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	lat_reset(&L->lat);
	L->last_frame = -1;
	L->ferr_worst_out = -1;
	L->rep.channel = -1;
	L->rep.out = -1;
	for (i = 0; i < rig->nin; i++)
		L->has_ready_input |= rig->in[i].role == RIG_INPUT_CAMERA_READY;
	for (i = 0; i < rig->ntrig; i++) {
		if (rig->trig[i].offset < min_off)
			min_off = rig->trig[i].offset;
		if (rig->trig[i].offset > max_off)
			max_off = rig->trig[i].offset;
	}
	L->lead = -min_off;
	L->tail = max_off;

	/* where the rig stands: feedback where there is some, else home */
	for (i = 0; i < n; i++) {
		const struct rig_out *o = &rig->out[i];
		int64_t act;

		L->vmax[i] = o->vmax;
		L->amax[i] = o->amax;
		L->prev[i] = o->vel_mode ? 0 : o->home;
		if (!o->vel_mode && hal_axis_input(rig->axes[o->dev], -1) == 0 &&
		    hal_axis_actual(rig->axes[o->dev], o->ch, &act))
			L->prev[i] = move_d2q((double)(act - o->scale.offset) / o->scale.per_unit_d);
		L->val[i] = L->prev[i];
		L->sent[i] = o->vel_mode ? 0 : hal_scale_counts(&o->scale, L->prev[i], NULL);
	}

	if (cfg->mode == LOOP_MODE_STEP) {
		if (!cfg->frames || !cfg->frames->n) {
			snprintf(err, errsize, "step mode: no frames to shoot");
			loop_free(L);
			return -EINVAL;
		}
		L->total_frames = frames_count(cfg->frames) * rig->ntrig;
		L->state = LOOP_STEP_NEXT;
		return 0;
	}
	if (cfg->to < cfg->from) {
		snprintf(err, errsize, "--from %lld is after --to %lld", (long long)cfg->from,
			 (long long)cfg->to);
		loop_free(L);
		return -EINVAL;
	}
	if (cfg->ping_pong && cfg->to == cfg->from) {
		snprintf(err, errsize, "--ping-pong needs at least two frames");
		loop_free(L);
		return -EINVAL;
	}
	if ((cfg->loop || cfg->ping_pong) && cfg->passes == 0) {
		L->total_frames = -1;
	} else {
		int64_t per = cfg->to - cfg->from + 1, p = (cfg->loop || cfg->ping_pong) ?
							   cfg->passes : 1;

		L->total_frames = (cfg->ping_pong ? per + (p - 1) * (per - 1) : per * p) *
				  rig->ntrig;
	}
	L->pass = 0;
	setup_pass(L);
	if (plan_entry(L, &bad)) {
		const struct rig_out *o = &rig->out[bad];

		snprintf(err, errsize,
			 "%s moves at %.6g %s/s at frame %lld: coming up to that speed within "
			 "its acceleration limit needs a run-up from %.6g %s, outside its limits; "
			 "start from a frame where it moves slower",
			 o->channel, rig_file_units(o->unit, L->ru_v[bad]), rig_unit_name(o->unit),
			 (long long)L->pass_first, rig_file_units(o->unit, move_q2d(L->target[bad])),
			 rig_unit_name(o->unit));
		loop_free(L);
		return -ERANGE;
	}
	plan_move(L, L->prev, L->target);
	L->state = LOOP_PREROLL;
	return 0;
}

void loop_free(struct loop *L)
{
	free(L->val);
	free(L->prev);
	free(L->target);
	free(L->vel);
	free(L->sent);
	free(L->sp);
	free(L->vmax);
	free(L->amax);
	free(L->limited);
	free(L->mv_ch);
	free(L->ru_end);
	free(L->ru_v);
	free(L->ru_n);
	free(L->dev_off);
	free(L->dout_dirty);
	free(L->ts);
	free(L->armed);
	L->val = NULL;
}
