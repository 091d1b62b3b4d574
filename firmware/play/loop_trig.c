/* SPDX-License-Identifier: MIT */
/*
 * loop_trig.c - the trigger lines: pulses rising when their frame is due
 * (PLAY), or when step mode's drives have settled, and falling `width`
 * ticks later; each rising edge bracketed by its journal record (ARMED
 * before the edge goes out, FIRED after: journal.h). Step mode's gates,
 * "every drive in position" and "exposed", live here because they decide
 * when its trigger fires. Every function here is [rt].
 */
#include "loop_priv.h"
#include "hal/rt.h"

#include <math.h>
#include <sched.h>

void STRAND_RT loop_triggers_off(struct loop *L)
{
	uint32_t i;

	for (i = 0; i < L->rig->ntrig; i++) {
		const struct rig_trig *t = &L->rig->trig[i];

		hal_dout_set(L->rig->douts[t->dev], t->line, false);
		L->trig.pulse[i].active = false;
		L->trig.pulse[i].pending = false;
	}
	for (i = 0; i < L->rig->ndouts; i++)
		hal_dout_commit(L->rig->douts[i], L->tick);
}

bool STRAND_RT loop_pulses_pending(const struct loop *L)
{
	uint32_t i;

	for (i = 0; i < L->rig->ntrig; i++)
		if (L->trig.pulse[i].pending)
			return true;
	return false;
}

bool STRAND_RT loop_pulses_active(const struct loop *L)
{
	uint32_t i;

	for (i = 0; i < L->rig->ntrig; i++)
		if (L->trig.pulse[i].active)
			return true;
	return false;
}

/* The journal record of trigger i firing frame f, filled and ARMED; NULL
 * when the journal cannot take it. */
static struct journal_rec STRAND_RT *journal_take(struct loop *L, uint32_t i, int64_t f, int64_t due)
{
	struct journal *jr = L->trig.jr;
	struct journal_rec *rec;
	uint32_t k;

	while (!(rec = journal_next(jr))) {
		/* on the virtual clock time waits for the journal's service; on
		 * the wall clock a frame that cannot be recorded is not fired */
		if (!L->cfg.wait_for_journal || journal_refused(jr))
			return NULL;
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
	rec->src_frame = loop_chase_frame(L, due);
	if (jr->mode & JOURNAL_MODE_GOMO) {
		struct journal_gomo *g = journal_gomo_of(rec, L->n);

		g->open_tick = g->close_tick = -1;
	}
	for (k = 0; k < L->n; k++)
		rec->sp[k] = L->val[k];
	journal_arm(jr, rec);
	return rec;
}

/* Raise trigger i for frame f in this tick; false when the journal
 * refused it (the run is stopping then). */
static bool STRAND_RT rise(struct loop *L, uint32_t i, int64_t f, int64_t due)
{
	const struct rig_trig *t = &L->rig->trig[i];
	struct loop_pulse *pl = &L->trig.pulse[i];

	if (L->trig.jr) {
		pl->armed = journal_take(L, i, f, due);
		if (!pl->armed) {
			struct loop_where w = { .channel = -1, .out = -1, .code = journal_error(L->trig.jr) };

			loop_stop(L, LOOP_END_FAULT, LOOP_CAUSE_JOURNAL, &w);
			return false;
		}
	}
	if (L->cfg.shutter && L->trig.jr && (L->trig.jr->mode & JOURNAL_MODE_GOMO)) {
		/* its exposure, when that has ended already (a late edge) */
		pl->rec = pl->armed;
		loop_gomo_journal(L);
	}
	hal_dout_set(L->rig->douts[t->dev], t->line, true);
	L->trig.dout_dirty[t->dev] = true;
	pl->active = true;
	pl->fall_tick = L->tick + t->width;
	L->res->last_frame = f;
	L->res->frames_fired++;
	return true;
}

/* PLAY: the edges due at this scene tick; true when one rose. */
static bool STRAND_RT play_edges(struct loop *L, int64_t due)
{
	const struct rig *r = L->rig;
	bool any = false;
	uint32_t i;

	for (i = 0; i < r->ntrig; i++) {
		struct loop_pulse *t = &L->trig.pulse[i];

		if (!t->pending || L->seq.scene_k != t->edge_k)
			continue;
		if (!rise(L, i, t->next_frame, due))
			break;
		any = true;
		if (t->next_frame == L->seq.pass_last) {
			t->pending = false;
		} else {
			t->next_frame += L->seq.dir;
			t->edge_k = mot_timing_trigger_tick(L->tm, t->next_frame) +
				    L->seq.dir * r->trig[i].offset;
		}
	}
	return any;
}

void STRAND_RT loop_gomo_journal(struct loop *L)
{
	const struct loop_seq *s = &L->seq;
	uint32_t i, k, n = L->n;

	if (s->gomo_close_tick < 0)
		return;
	for (i = 0; i < L->rig->ntrig; i++) {
		struct journal_rec *r = L->trig.pulse[i].rec;
		struct journal_gomo *g;

		if (!r)
			continue;
		g = journal_gomo_of(r, n);
		for (k = 0; k < n; k++) {
			g->sp[k] = s->gomo_open[k];
			g->sp[n + k] = s->gomo_close[k];
		}
		g->open_tick = s->gomo_open_tick;
		g->close_tick = s->gomo_close_tick;
		L->trig.pulse[i].rec = NULL;
	}
}

/* Go-motion: the edges due at this run tick (loop_gomo_start set them);
 * true when one rose. */
static bool STRAND_RT gomo_edges(struct loop *L, int64_t due)
{
	bool any = false;
	uint32_t i;

	for (i = 0; i < L->rig->ntrig; i++) {
		struct loop_pulse *t = &L->trig.pulse[i];

		if (!t->pending || L->tick != t->edge_k)
			continue;
		t->pending = false;
		if (!rise(L, i, t->next_frame, due))
			break;
		any = true;
	}
	return any;
}

/* STEP_SETTLE, settled, go-motion: armed to wait for the word, or the
 * run-up from the next tick on. */
static void STRAND_RT gomo_settled(struct loop *L)
{
	if (L->cfg.gomo_wait)
		L->seq.state = LOOP_GOMO_ARMED;
	else
		loop_gomo_start(L, L->tick + 1);
}

/* STEP_SETTLE: true when the frame may be shot (every drive in position
 * for the settle time, no pulse under way, the camera ready); stops the
 * run when that takes longer than the timeout. */
static bool STRAND_RT step_settled(struct loop *L)
{
	const struct rig *r = L->rig;
	struct loop_step *st = &L->step;
	bool in_pos = true;
	uint32_t i;
	double fe;

	for (i = 0; i < L->n && in_pos; i++)
		if (loop_ferror(L, i, &fe))
			in_pos = fabs(fe) <= r->out[i].in_position;
	st->settled = in_pos ? st->settled + 1 : 0;
	if (st->settled > L->cfg.settle_ticks && !loop_pulses_active(L) &&
	    (!st->has_ready_input || st->ready))
		return true;
	if (++L->seq.seg_j > L->cfg.in_position_timeout_ticks) {
		enum loop_cause why = in_pos ? LOOP_CAUSE_READY : LOOP_CAUSE_IN_POSITION;
		struct loop_where w = { .channel = -1, .out = -1 };

		/* name the first output out of position, if one is */
		for (i = 0; i < L->n; i++) {
			if (loop_ferror(L, i, &fe) && fabs(fe) > r->out[i].in_position) {
				w = loop_where_out(L, i, fe, r->out[i].in_position);
				break;
			}
		}
		loop_stop(L, LOOP_END_FAULT, why, &w);
	}
	return false;
}

/* STEP_SETTLE, settled: the frame's trigger on every line; true when it
 * rose (the run may be stopping instead, when the journal refused). */
static bool STRAND_RT step_fire(struct loop *L, int64_t due)
{
	uint32_t i;

	for (i = 0; i < L->rig->ntrig; i++)
		if (!rise(L, i, L->step.frame, due))
			break;
	if (L->seq.state != LOOP_STEP_SETTLE)
		return false;
	L->seq.state = LOOP_STEP_EXPOSE;
	L->step.fired_at = L->tick;
	L->step.ready_since_fire = false;
	return true;
}

/* STEP_EXPOSE: on to the next frame once exposed (the exposure time, or
 * the camera-ready edge) and the pulse is over. */
static void STRAND_RT step_exposed(struct loop *L)
{
	const struct loop_step *st = &L->step;
	int64_t since = L->tick - st->fired_at;
	bool done = st->has_ready_input ? st->ready_since_fire && st->ready :
					  since >= L->cfg.exposure_ticks;

	if (done && !loop_pulses_active(L))
		L->seq.state = LOOP_STEP_NEXT;
	else if (since > L->cfg.ready_timeout_ticks)
		loop_stop(L, LOOP_END_FAULT, LOOP_CAUSE_READY, NULL);
}

void STRAND_RT loop_triggers(struct loop *L, int64_t due)
{
	const struct rig *r = L->rig;
	bool any = false;
	uint32_t i, d;

	for (i = 0; i < r->ntrig; i++) {
		struct loop_pulse *t = &L->trig.pulse[i];

		t->armed = NULL;
		if (t->active && L->tick >= t->fall_tick) {
			hal_dout_set(r->douts[r->trig[i].dev], r->trig[i].line, false);
			L->trig.dout_dirty[r->trig[i].dev] = true;
			t->active = false;
		}
	}
	if (L->seq.state == LOOP_PLAY)
		any = play_edges(L, due);
	else if (L->seq.state == LOOP_STEP_SETTLE && L->cfg.shutter && step_settled(L))
		gomo_settled(L);
	else if (L->seq.state == LOOP_STEP_SETTLE && !L->cfg.shutter)
		any = step_settled(L) && step_fire(L, due);
	else if (L->seq.state == LOOP_GOMO_RUNUP || L->seq.state == LOOP_GOMO_EXPOSE ||
		 L->seq.state == LOOP_GOMO_RUNOUT)
		any = gomo_edges(L, due);
	else if (L->seq.state == LOOP_STEP_EXPOSE)
		step_exposed(L);
	for (d = 0; d < r->ndouts; d++) {
		struct hal_fault f;

		if (!L->trig.dout_dirty[d])
			continue;
		L->trig.dout_dirty[d] = false;
		if (hal_dout_commit(r->douts[d], L->tick) && hal_dout_fault(r->douts[d], &f)) {
			struct loop_where w = loop_where_fault(r->douts[d]->name, &f);

			loop_stop(L, LOOP_END_FAULT, LOOP_CAUSE_DEVICE, &w);
		}
	}
	if (any && L->trig.jr) {
		/* the edges are out: their time, then FIRED */
		int64_t mono = hal_clock_now(L->clk), wall = hal_clock_wall(L->clk);

		for (i = 0; i < r->ntrig; i++)
			if (L->trig.pulse[i].armed) {
				journal_fire(L->trig.pulse[i].armed, mono, wall);
				L->trig.cur_rec = L->trig.pulse[i].armed;
			}
	}
}
