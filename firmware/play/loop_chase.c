/* SPDX-License-Identifier: MIT */
/*
 * loop_chase.c - the loop chasing an external clock (chase.h): it waits at
 * rest in LOOP_CUE until the source is locked, cues the frame the source
 * names a lead time ahead (the pre-roll and run-up to it must fit before
 * the source gets there: as many frames later as that takes), maps the
 * run's ticks onto the source's time so that the scene's tick of that
 * frame is due when the source plays it, and enters the pre-roll at the
 * tick that makes the run-up end there. A jump, a stop, reverse play, a
 * rate beyond what the limits allow or a source lost past the freewheel
 * time stops the run under control (LOOP_CAUSE_CHASE); once at rest it
 * waits and cues again. A source that failed or ended ends the run.
 *
 * The motion is the loop's own, tick by tick; only when each tick is due
 * follows the source (chase_due), so no axis ever jumps. Every function
 * here is [rt] but loop_set_chase.
 */
#include "loop_priv.h"
#include "chase.h"
#include "hal/rt.h"

#include <math.h>
#include <stdatomic.h>

/* The least lead a cue leaves before the source reaches the cued frame,
 * beyond the pre-roll and run-up: time for the schedule to settle on the
 * source's phase (a tick's worth at CHASE_SLEW takes 250 ms). */
#define CHASE_LEAD_S 0.5
/* The journal's source frame of an edge: the one playing at its due time,
 * or the next when the edge is less than this much of a frame before it
 * (an edge due on a frame's start may land microseconds ahead of it). */
#define CHASE_TC_EARLY 0.05

void loop_set_chase(struct loop *L, struct chase *c)
{
	double rv = 1 + CHASE_RATE_MAX;
	uint32_t i;

	STRAND_ASSERT_NOT_RT();
	L->chase = c;
	L->res->total_frames = -1; /* a chase ends when the scene does, or never */
	/* the source may run CHASE_RATE_MAX fast: the moves the loop plans
	 * (pre-roll, stops) leave that much room in the limits */
	for (i = 0; i < L->n; i++) {
		L->seq.vmax[i] /= rv;
		L->seq.amax[i] /= rv * rv;
	}
	L->seq.state = LOOP_CUE;
}

/* The cue: 0 when made (or to be tried again later), -1 when the run
 * cannot enter the frame (its run-up starts outside a limit). */
static int STRAND_RT cue(struct loop *L, struct chase *ch, int64_t now)
{
	const struct mot_timing *tm = L->tm;
	double fps = (double)tm->num / tm->den, x_now = chase_src_at(ch, (double)now);
	double step = ch->tick_frames * ch->dll.per, t_begin = 0;
	int64_t f, need = 0;
	int32_t bad;
	int it;

	if (ch->cfg.src->labelled) {
		double f_now = (x_now - (double)ch->cfg.offset) * ch->cfg.mult;

		f = (int64_t)ceil(f_now + CHASE_LEAD_S * fps);
		if (f < L->cfg.from)
			f = L->cfg.from;
	} else {
		/* pulses name no frame: the range's first frame is the pulse
		 * a lead time from now */
		f = L->cfg.from;
		ch->cfg.offset = (int64_t)ceil(x_now + CHASE_LEAD_S * fps / ch->cfg.mult) -
				 f / ch->cfg.mult;
	}
	for (it = 0; it < 8; it++) {
		double t_ready, late;

		ch->past_end = f > L->cfg.to;
		if (ch->past_end)
			return 0; /* wait for the source to come back into the range */
		L->cfg.from = f;
		L->seq.pass = 0;
		loop_pass_setup(L);
		if (loop_entry_plan(L, &bad)) {
			struct loop_where w = loop_where_out(L, (uint32_t)bad,
							     move_q2d(L->seq.target[bad]), 0);

			loop_fail(L, LOOP_END_FAULT, LOOP_CAUSE_LIMIT_POS, &w);
			L->seq.state = LOOP_ENDED;
			return -1;
		}
		loop_move_plan(L, L->prev, L->seq.target);
		need = L->seq.mv.ticks + L->seq.ru_ticks;
		t_begin = chase_time_of(ch, chase_src_of_scene_tick(ch, L->seq.scene_begin));
		t_ready = (double)now + (double)(need + 2) * step + CHASE_LEAD_S * 1e9;
		if (t_begin >= t_ready)
			break;
		late = ceil((t_ready - t_begin) / 1e9 * fps) + 1;
		if (ch->cfg.src->labelled)
			f += (int64_t)late;
		else
			ch->cfg.offset += (int64_t)ceil(late / ch->cfg.mult);
	}
	ch->k_play = L->tick + llround((t_begin - (double)chase_due(ch, L->tick)) / step);
	ch->k_start = ch->k_play - need;
	if (ch->k_start <= L->tick) { /* cannot be, but never a tick in the past */
		ch->k_start = L->tick + 1;
		ch->k_play = ch->k_start + need;
	}
	ch->scene_begin = L->seq.scene_begin;
	ch->mapped = true;
	ch->cued = true;
	return 0;
}

void STRAND_RT loop_chase_tick(struct loop *L, int64_t now)
{
	struct chase *ch = L->chase;
	struct hal_fault f;
	enum chase_event ev;

	if (!ch)
		return;
	chase_poll(ch, now);
	if (!ch->ended && hal_extclk_fault(ch->cfg.src, &f)) {
		struct loop_where w = loop_where_fault(ch->cfg.src->name, &f);

		ch->ended = true;
		ch->mapped = ch->cued = false;
		loop_stop(L, LOOP_END_FAULT, LOOP_CAUSE_CHASE, &w);
		return;
	}
	ev = chase_take_event(ch, now);
	if (ev != CHASE_EV_NONE) {
		struct loop_where w = { .device = ch->cfg.src->name, .channel = -1, .out = -1,
					.detail = ev, .value = ch->st.rate };

		if (L->seq.state == LOOP_CUE) {
			ch->mapped = ch->cued = false; /* the cue is off: wait again */
		} else if (L->seq.state != LOOP_STOPPING && L->seq.state != LOOP_ENDED) {
			loop_stop(L, LOOP_END_STOPPED, LOOP_CAUSE_CHASE, &w);
			/* at rest, it cues again (loop_chase_after) */
		}
	}
	if (L->seq.state != LOOP_CUE || ch->ended)
		return;
	if (!ch->cued && ch->locked && cue(L, ch, now))
		return;
	if (ch->cued && L->tick >= ch->k_start)
		L->seq.state = LOOP_PREROLL;
}

void STRAND_RT loop_chase_after(struct loop *L)
{
	struct chase *ch = L->chase;
	struct loop_report *r = &L->res->rep;

	if (!ch || L->seq.state != LOOP_ENDED || r->cause != LOOP_CAUSE_CHASE ||
	    r->end != LOOP_END_STOPPED || ch->ended ||
	    atomic_load_explicit(&L->safety.stop_req, memory_order_relaxed))
		return;
	/* the source stopped the run, and the rig is at rest: wait for it */
	r->end = LOOP_END_NONE;
	r->cause = LOOP_CAUSE_NONE;
	ch->mapped = false;
	ch->cued = false;
	ch->recues++;
	L->seq.state = LOOP_CUE;
}

uint32_t STRAND_RT loop_chase_frame(struct loop *L, int64_t t)
{
	struct chase *ch = L->chase;
	double x;

	if (!ch || !ch->mapped)
		return 0;
	x = floor(chase_src_at(ch, (double)t) + CHASE_TC_EARLY);
	return (uint32_t)(((int64_t)x % ch->day + ch->day) % ch->day + 1);
}
