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

#include <math.h>

/* Ramps shorter than this (2^31 ticks) sum their steps in int64_t, exactly. */
#define LOOP_RUNUP_EXACT (INT64_C(1) << 31)

void STRAND_RT loop_eval_at(struct loop *L, int64_t scene_tick, mot_q32 *out)
{
	src_eval(L->src, mot_timing_tick_frame(L->tm, scene_tick), out, &L->sat);
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
	int64_t p = s->pass;
	uint32_t i;

	s->dir = 1;
	s->pass_first = c->from;
	s->pass_last = c->to;
	if (c->ping_pong && c->to > c->from) {
		if (p % 2) {
			s->dir = -1;
			s->pass_first = c->to - 1;
			s->pass_last = c->from;
		} else if (p > 0) {
			s->pass_first = c->from + 1;
		}
	}
	s->scene_begin = mot_timing_trigger_tick(L->tm, s->pass_first) - s->dir * s->lead;
	s->scene_end = mot_timing_trigger_tick(L->tm, s->pass_last) + s->dir * s->tail;
	for (i = 0; i < L->rig->ntrig; i++) {
		struct loop_pulse *t = &L->trig.pulse[i];

		t->next_frame = s->pass_first;
		t->pending = true;
		t->edge_k = mot_timing_trigger_tick(L->tm, t->next_frame) +
			    s->dir * L->rig->trig[i].offset;
	}
}

/*
 * The first pose and speed of the pass, each output's ramp, and in
 * seq.target where the ramps start (the pre-roll's or bridge's
 * destination).
 */
int STRAND_RT loop_entry_plan(struct loop *L, int32_t *bad)
{
	const double hz = L->tm->tick_hz, dt = 1.0 / hz;
	struct loop_seq *s = &L->seq;
	uint32_t i;

	loop_eval_at(L, s->scene_begin, s->ru_end);
	loop_eval_at(L, s->scene_begin + s->dir, s->target);
	s->ru_ticks = 0;
	s->ru_j = 0;
	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		struct loop_out *lo = &L->out[i];
		double v = (move_q2d(s->target[i]) - move_q2d(s->ru_end[i])) * hz;
		double back, start, nd = ceil(fabs(v) * hz / o->amax * (1 + 1e-9));
		int64_t n;

		/* a ramp longer than NUM_TICKS_MAX (a crawl of an acceleration
		 * limit) starts beyond the core's range: refused below */
		if (!(nd < (double)NUM_TICKS_MAX))
			nd = (double)NUM_TICKS_MAX;
		n = (int64_t)nd;
		lo->ru_v = v;
		lo->ru_n = n;
		if (n > s->ru_ticks)
			s->ru_ticks = n;
		/* speeds v k / n for k = 1..n cover v dt (n + 1) / 2 */
		back = v * dt * (double)(n + 1) / 2;
		s->target[i] = n ? s->ru_end[i] - move_d2q(back) : s->ru_end[i];
		start = move_q2d(s->target[i]);
		if (start < o->min - 1e-9 || start > o->max + 1e-9 || n >= NUM_TICKS_MAX) {
			*bad = (int32_t)i;
			return -1;
		}
	}
	return 0;
}

/* j = 0: at rest at the ramp's start; j = ru_ticks: the pass's first pose. */
mot_q32 STRAND_RT loop_runup_at(const struct loop *L, uint32_t i, int64_t j)
{
	const struct loop_out *lo = &L->out[i];
	int64_t n = lo->ru_n, m = j - (L->seq.ru_ticks - n); /* the ramps end together */
	double left;

	if (n == 0 || m >= n)
		return L->seq.ru_end[i];
	if (m < 0)
		m = 0;
	/* the distance still to go after step m: sum of v k / n dt, k = m+1..n;
	 * n (n + 1) overflows int64_t from n = 3e9 on: such ramps in doubles */
	if (n < LOOP_RUNUP_EXACT)
		left = lo->ru_v / n / L->tm->tick_hz * (double)(n * (n + 1) - m * (m + 1)) / 2;
	else
		left = lo->ru_v / n / L->tm->tick_hz *
		       ((double)n * (double)(n + 1) - (double)m * (double)(m + 1)) / 2;
	return L->seq.ru_end[i] - move_d2q(left);
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

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		double v = L->out[i].vel;

		L->val[i] = L->prev[i];
		if (L->safety.dev_off[o->dev])
			continue;
		rest &= move_stop_step(&L->val[i], &v, o->vel_mode, o->vmax, o->amax,
				       L->tm->tick_hz);
	}
	return rest;
}
