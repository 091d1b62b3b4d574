/* SPDX-License-Identifier: MIT */
/*
 * loop_plan.c - the motion between the scene's own: the frames and scene
 * ticks of a pass, the run-up into it (loop.h, "run-up"), moves from pose
 * to pose and stops. loop_init plans the first pass with these; the
 * sequence plans each later one when it gets there, so every function here
 * is [rt].
 */
#include "loop_priv.h"
#include "hal/rt.h"
#include "plan/gomo.h"

#include <math.h>

void STRAND_RT loop_eval_at(struct loop *L, int64_t scene_tick, mot_q32 *out)
{
	timeline_eval(&L->seq.tl, scene_tick, out, &L->sat);
}

void STRAND_RT loop_move_plan(struct loop *L, const mot_q32 *from, const mot_q32 *to)
{
	/* limits were checked positive and finite when the rig was built; a
	 * move longer than NUM_TICKS_MAX is not played: the run ends as one
	 * whose arithmetic saturated (loop_init refuses such a pre-roll) */
	if (move_plan(&L->seq.mv, L->seq.mv.ch, L->n, from, to, L->seq.vmax, L->seq.amax,
		      L->tm->tick_hz))
		L->sat |= MOT_SAT_OVERFLOW;
	L->seq.mv_j = 0;
}

void STRAND_RT loop_pass_setup(struct loop *L)
{
	const struct loop_cfg *c = &L->cfg;
	struct loop_seq *s = &L->seq;
	uint32_t i;

	pass_span(&s->span, L->tm, c->from, c->to, c->ping_pong, s->pass, s->lead, s->tail);
	s->dir = s->span.dir;
	s->pass_first = s->span.first;
	s->pass_last = s->span.last;
	s->scene_begin = s->span.begin;
	s->scene_end = s->span.end;
	timeline_init(&s->tl, L->src, L->n, s->extend, s->span.lo, s->span.hi, s->tl_mem, &L->sat);
	for (i = 0; i < L->rig->ntrig; i++) {
		struct loop_pulse *t = &L->trig.pulse[i];

		t->next_frame = s->pass_first;
		t->pending = true;
		t->edge_k = mot_timing_trigger_tick(L->tm, t->next_frame) +
			    s->dir * L->rig->trig[i].offset;
	}
}

/*
 * The first pose and speed of the pass, each output's ramp (runup.h), and
 * in seq.target where the ramps start (the pre-roll's or bridge's
 * destination).
 */
int STRAND_RT loop_entry_plan(struct loop *L, int32_t *bad)
{
	struct loop_seq *s = &L->seq;
	uint32_t i;

	loop_eval_at(L, s->scene_begin, s->ru_end);
	loop_eval_at(L, s->scene_begin + s->dir, s->target);
	s->ru_ticks = 0;
	s->ru_j = 0;
	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		struct loop_out *lo = &L->out[i];
		int rc = runup_plan(&lo->ru, s->ru_end[i], s->target[i], L->tm->tick_hz, o->amax,
				    &s->target[i]);
		double start = move_q2d(s->target[i]);

		if (lo->ru.n > s->ru_ticks)
			s->ru_ticks = lo->ru.n;
		if (rc || start < o->min - 1e-9 || start > o->max + 1e-9) {
			*bad = (int32_t)i;
			return -1;
		}
	}
	return 0;
}

/* j = 0: at rest at the ramp's start; j = ru_ticks: the pass's first pose. */
mot_q32 STRAND_RT loop_runup_at(const struct loop *L, uint32_t i, int64_t j)
{
	return runup_at(&L->out[i].ru, L->seq.ru_end[i], L->seq.ru_ticks, j, L->tm->tick_hz);
}

bool STRAND_RT loop_more_passes(const struct loop *L)
{
	const struct loop_cfg *c = &L->cfg;

	if (!c->loop && !c->ping_pong)
		return false;
	return c->passes == 0 || L->seq.pass + 1 < c->passes;
}

bool STRAND_RT loop_rest_step(struct loop *L)
{
	bool rest = true;
	uint32_t i;

	L->seq.braked = true;
	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];

		L->val[i] = L->prev[i];
		if (L->safety.dev_off[o->dev])
			continue;
		rest &= move_stop_step(&L->val[i], &L->out[i].stop_v, o->vel_mode, o->vmax,
				       o->amax, L->tm->tick_hz);
	}
	return rest;
}

/* ---- go-motion (plan/gomo.h) ---- */

void STRAND_RT loop_gomo_setup(struct loop *L)
{
	const struct loop_cfg *c = &L->cfg;
	struct play_source *src = c->gomo_src ? c->gomo_src : L->src;
	int64_t lo = c->from < c->to ? c->from : c->to, hi = c->from ^ c->to ^ lo;

	timeline_init(&L->seq.tl, src, L->n, L->seq.extend, lo, hi, L->seq.tl_mem, &L->sat);
}

int STRAND_RT loop_gomo_plan(struct loop *L, int32_t *bad)
{
	struct loop_seq *s = &L->seq;
	uint32_t i;

	/* the shutter was checked against the timing before the run: the
	 * window holds two ticks (a failure here is arithmetic gone wrong) */
	if (gomo_window(&s->tl.src->timing, L->step.frame, L->cfg.shutter, &s->gomo_first,
			&s->gomo_last))
		L->sat |= MOT_SAT_OVERFLOW;
	s->gomo_open_tick = s->gomo_close_tick = -1;
	for (i = 0; i < L->rig->ntrig; i++) {
		L->trig.pulse[i].rec = NULL;
		L->trig.pulse[i].pending = false;
	}
	/* a pass over the exposure's ticks: the run-up into its first */
	s->dir = 1;
	s->scene_begin = s->gomo_first;
	if (loop_entry_plan(L, bad))
		return -1;
	/* the ramps may end later: a trigger that fires early (a negative
	 * offset) rises during the run-up, never before it */
	if (s->ru_ticks < s->lead)
		s->ru_ticks = s->lead;
	if (s->ru_ticks < L->cfg.gomo_runup_ticks)
		s->ru_ticks = L->cfg.gomo_runup_ticks;
	return 0;
}

void STRAND_RT loop_gomo_start(struct loop *L, int64_t t0)
{
	struct loop_seq *s = &L->seq;
	uint32_t i;

	s->state = LOOP_GOMO_RUNUP;
	s->ru_j = -1;
	/* the exposure's first tick is t0 + ru_ticks; each edge is moved by
	 * its trigger's offset from there, as in a pass */
	for (i = 0; i < L->rig->ntrig; i++) {
		struct loop_pulse *t = &L->trig.pulse[i];

		t->next_frame = L->step.frame;
		t->pending = true;
		t->edge_k = t0 + s->ru_ticks + L->rig->trig[i].offset;
	}
}
