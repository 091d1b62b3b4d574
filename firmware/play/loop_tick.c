/* SPDX-License-Identifier: MIT */
/*
 * loop_tick.c - the loop proper (loop.h): ticks at their due times, and in
 * each the sequence's setpoints, scaled to counts and sent, between the
 * safety checks (loop_safety.c) and the triggers (loop_trig.c). Every
 * function here is [rt].
 */
#include "loop_priv.h"
#include "chase.h"
#include "hal/rt.h"

#include <errno.h>
#include <time.h>

int64_t STRAND_RT loop_due(const struct loop *L, int64_t k)
{
	uint32_t hz = L->tm->tick_hz;

	if (L->chase) /* the source's time (chase.h) */
		return chase_due(L->chase, k);
	/* whole seconds and the rest separately: exact, and no overflow for
	 * any tick count the core accepts */
	return L->t0 + (k / hz) * 1000000000 + (k % hz) * 1000000000 / hz;
}

const struct loop_result *loop_result(const struct loop *L)
{
	return L->res;
}

/* ---- the sequence ---- */

static void STRAND_RT hold(struct loop *L, const mot_q32 *pose)
{
	uint32_t i;

	for (i = 0; i < L->n; i++)
		L->val[i] = pose[i];
}

/* Go-motion: the exposure's first and last tick, its poses there, and
 * what step mode's EXPOSE counts from (the shutter opening). */
static void STRAND_RT gomo_exposure(struct loop *L)
{
	struct loop_seq *s = &L->seq;
	uint32_t i;

	if (s->scene_k == s->gomo_first) {
		for (i = 0; i < L->n; i++)
			s->gomo_open[i] = L->val[i];
		s->gomo_open_tick = L->tick;
		L->step.fired_at = L->tick;
		L->step.ready_since_fire = false;
	}
	if (s->scene_k == s->gomo_last) {
		for (i = 0; i < L->n; i++)
			s->gomo_close[i] = L->val[i];
		s->gomo_close_tick = L->tick;
		loop_gomo_journal(L);
	}
}

int STRAND_RT loop_gomo_go(struct loop *L)
{
	if (L->seq.state != LOOP_GOMO_ARMED)
		return -EAGAIN;
	loop_gomo_start(L, L->tick);
	return 0;
}

/* This tick's setpoints into L->val, moving through the segments. */
static void STRAND_RT sequence(struct loop *L)
{
	struct loop_seq *s = &L->seq;
	int32_t bad;
	uint32_t i;

	for (;;) {
		switch (s->state) {
		case LOOP_PREROLL:
		case LOOP_BRIDGE_MOVE:
		case LOOP_STEP_MOVE:
			/* samples 1..ticks: the last one is the target */
			if (++s->mv_j <= s->mv.ticks) {
				for (i = 0; i < L->n; i++)
					L->val[i] = move_at(&s->mv, i, s->mv_j);
				return;
			}
			if (s->state == LOOP_STEP_MOVE) {
				s->state = LOOP_STEP_SETTLE;
				L->step.settled = 0;
				s->seg_j = 0;
			} else {
				s->state = LOOP_RUNUP;
				s->ru_j = -1;
			}
			continue;
		case LOOP_RUNUP:
			/* samples 0..ru_ticks - 1: sample 0 repeats the move's
			 * target, so the rig is at rest (two equal setpoints)
			 * before the ramp's first step; PLAY's first tick is the
			 * ramp's end, the pass's first pose */
			if (++s->ru_j < s->ru_ticks) {
				for (i = 0; i < L->n; i++)
					L->val[i] = loop_runup_at(L, i, s->ru_j);
				return;
			}
			s->state = LOOP_PLAY;
			s->scene_k = s->scene_begin - s->dir;
			continue;
		case LOOP_PLAY:
			s->scene_k += s->dir;
			if ((s->scene_k - s->scene_end) * s->dir > 0) {
				s->state = loop_more_passes(L) ? LOOP_BRIDGE_STOP : LOOP_POSTROLL;
				continue;
			}
			loop_eval_at(L, s->scene_k, L->val);
			return;
		case LOOP_BRIDGE_STOP:
			if (!loop_rest_step(L))
				return;
			s->pass++;
			loop_pass_setup(L);
			if (loop_entry_plan(L, &bad)) {
				struct loop_where w = loop_where_out(L, (uint32_t)bad,
								     move_q2d(s->target[bad]), 0);

				/* the rig is at rest: the run ends here */
				loop_fail(L, LOOP_END_FAULT, LOOP_CAUSE_LIMIT_POS, &w);
				s->state = LOOP_ENDED;
				return;
			}
			/* from where this tick's stop sample rests */
			loop_move_plan(L, L->val, s->target);
			s->state = LOOP_BRIDGE_MOVE;
			if (s->mv.ticks == 0)
				continue;
			return; /* this tick holds the rest position (the stop's last) */
		case LOOP_POSTROLL:
		case LOOP_STOPPING:
			if (loop_rest_step(L) && !loop_pulses_active(L)) {
				if (s->state == LOOP_POSTROLL)
					loop_fail(L, LOOP_END_DONE, LOOP_CAUSE_FINISHED, NULL);
				s->state = LOOP_ENDED;
			}
			return;
		case LOOP_STEP_NEXT:
			if (!frames_next(L->cfg.frames, &L->step.fit, &L->step.frame)) {
				loop_fail(L, LOOP_END_DONE, LOOP_CAUSE_FINISHED, NULL);
				s->state = LOOP_ENDED;
				hold(L, L->prev);
				return;
			}
			if (!L->cfg.shutter) {
				src_eval(L->src, L->step.frame * MOT_Q32_ONE, s->target, &L->sat);
			} else if (loop_gomo_plan(L, &bad)) {
				struct loop_where w = loop_where_out(L, (uint32_t)bad,
								     move_q2d(s->target[bad]), 0);

				/* strand check refused this: only --force gets here */
				loop_fail(L, LOOP_END_FAULT, LOOP_CAUSE_LIMIT_POS, &w);
				s->state = LOOP_ENDED;
				hold(L, L->prev);
				return;
			}
			/* to the frame's pose, or to where its go-motion runs up */
			loop_move_plan(L, L->prev, s->target);
			s->state = LOOP_STEP_MOVE;
			continue;
		case LOOP_STEP_SETTLE:
		case LOOP_GOMO_ARMED:
			hold(L, s->target);
			return;
		case LOOP_STEP_EXPOSE:
			/* where the frame's pose, or its go-motion's run-out, left it */
			hold(L, L->prev);
			return;
		case LOOP_GOMO_RUNUP:
			/* as a pass's: sample 0 at rest at the ramps' start */
			if (++s->ru_j < s->ru_ticks) {
				for (i = 0; i < L->n; i++)
					L->val[i] = loop_runup_at(L, i, s->ru_j);
				return;
			}
			s->state = LOOP_GOMO_EXPOSE;
			s->scene_k = s->gomo_first - 1;
			continue;
		case LOOP_GOMO_EXPOSE:
			if (++s->scene_k > s->gomo_last) {
				s->state = LOOP_GOMO_RUNOUT;
				continue;
			}
			loop_eval_at(L, s->scene_k, L->val);
			gomo_exposure(L);
			return;
		case LOOP_GOMO_RUNOUT:
			/* to rest, and every edge of the frame out and over */
			if (loop_rest_step(L) && !loop_pulses_pending(L) && !loop_pulses_active(L))
				s->state = LOOP_STEP_EXPOSE;
			return;
		case LOOP_CUE:
			hold(L, L->prev);
			return;
		case LOOP_ENDED:
			hold(L, L->prev);
			return;
		case LOOP_HOLD:
		case LOOP_JOG:
		case LOOP_MOVE:
			loop_live_sequence(L);
			return;
		}
	}
}

/* ---- outputs ---- */

/* This tick's setpoints in device counts, and the speed they make; false
 * when a scaling saturated (nothing is sent then). */
static bool STRAND_RT scale_outputs(struct loop *L)
{
	const struct rig *r = L->rig;
	uint32_t i, sat = 0;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &r->out[i];
		struct loop_out *lo = &L->out[i];

		lo->vel_now = loop_speed(L, i);
		if (o->vel_mode) {
			lo->sp.pos = 0;
			lo->sp.vel = hal_scale_counts(&o->scale, L->val[i], &sat);
		} else {
			lo->sp.pos = hal_scale_counts(&o->scale, L->val[i], &sat);
			lo->sp.vel = hal_scale_rate(&o->scale, lo->vel_now, &sat);
		}
	}
	L->sat |= sat;
	return !sat;
}

static void STRAND_RT outputs(struct loop *L)
{
	const struct rig *r = L->rig;
	uint32_t i, d;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &r->out[i];

		if (L->safety.dev_off[o->dev])
			continue;
		hal_axis_set(r->axes[o->dev], o->ch, &L->out[i].sp);
		L->out[i].sent = L->out[i].sp.pos;
	}
	for (d = 0; d < r->naxes; d++) {
		struct hal_fault f;

		if (!L->safety.dev_off[d] && hal_axis_commit(r->axes[d], L->tick) &&
		    hal_axis_fault(r->axes[d], &f))
			loop_fault_device(L, d, &f);
	}
}

/* ---- the tick ---- */

void STRAND_RT loop_status_fill(const struct loop *L, struct loop_status *s)
{
	const struct loop_result *res = L->res;

	s->tick = L->tick;
	s->frame = res->last_frame;
	s->fired = res->frames_fired;
	s->total = res->total_frames;
	s->lat_max_ns = res->lat.n ? res->lat.max_ns : 0;
	s->overruns = res->lat.overruns;
	s->ferr = res->ferr_worst;
	s->ferr_out = res->ferr_worst_out;
	s->state = (uint8_t)L->seq.state;
	s->end = (uint8_t)res->rep.end;
}

static void STRAND_RT status(struct loop *L)
{
	struct loop_status s;

	if (!L->status)
		return;
	if (L->live) {
		loop_live_status(L);
		return;
	}
	if (L->seq.state != LOOP_ENDED && L->tick % L->cfg.status_every)
		return;
	loop_status_fill(L, &s);
	if (!hal_ring_push(L->status, &s))
		L->res->status_dropped++;
}

bool STRAND_RT loop_tick(struct loop *L, int64_t k, int64_t due_ns, int64_t now_ns)
{
	struct loop_result *res = L->res;
	double fe = 0;
	int32_t fe_out = -1;
	int req;
	uint32_t i;

	L->tick = k;
	if (L->seq.state == LOOP_ENDED)
		return false;
	loop_inputs(L, now_ns);
	if (L->seq.state == LOOP_ENDED)
		goto out;
	if (L->live)
		loop_live_commands(L);
	loop_chase_tick(L, now_ns);
	req = atomic_load_explicit(&L->safety.stop_req, memory_order_relaxed);
	if ((req & 3) == 2) {
		loop_halt(L, (enum loop_end)(req >> 10), (enum loop_cause)(req >> 2 & 0xff), NULL);
		goto out;
	}
	/* a stop already under way needs no second one */
	if ((req & 3) == 1 && res->rep.end == LOOP_END_NONE)
		loop_stop(L, (enum loop_end)(req >> 10), (enum loop_cause)(req >> 2 & 0xff), NULL);
	if (L->cfg.max_ticks && k >= L->cfg.max_ticks && res->rep.end == LOOP_END_NONE)
		loop_stop(L, LOOP_END_DONE, LOOP_CAUSE_DURATION, NULL);
	loop_feedback(L, &fe, &fe_out);
	if (fe > res->ferr_worst) {
		res->ferr_worst = fe;
		res->ferr_worst_out = fe_out;
	}
	if (L->trig.cur_rec && fe > L->trig.cur_rec->ferr) {
		L->trig.cur_rec->ferr = fe;
		L->trig.cur_rec->ferr_out = fe_out;
	}
	sequence(L);
	loop_limits(L);
	if (!scale_outputs(L) || L->sat) {
		loop_halt(L, LOOP_END_INTERNAL, LOOP_CAUSE_SATURATION, NULL);
		goto out;
	}
	outputs(L);
	loop_triggers(L, due_ns);
	/* this tick's setpoints become the last ones */
	for (i = 0; i < L->n; i++) {
		L->out[i].vel = L->out[i].vel_now;
		if (!L->seq.braked)
			L->out[i].stop_v = L->out[i].vel_now;
		L->prev[i] = L->val[i];
		lim_meter_push(&L->out[i].meter, L->val[i]);
	}
	L->seq.braked = false;
out:
	if (L->live)
		loop_live_tick_end(L);
	loop_chase_after(L);
	res->ticks_run = k + 1;
	status(L);
	return L->seq.state != LOOP_ENDED;
}

void STRAND_RT loop_run(struct loop *L, int64_t t0)
{
	struct lat_stats *lat = &L->res->lat;
	struct timespec c0, c1;
	int64_t k, due, now, end = INT64_MIN;

	L->t0 = t0;
	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
	for (k = 0;; k++) {
		due = loop_due(L, k);
		if (end >= due) {
			/* late already: run this tick now, no sleep, no wake-up */
			now = end;
			lat->catchup++;
		} else {
			hal_clock_sleep_until(L->clk, due);
			now = hal_clock_now(L->clk);
			lat_add(lat, k, now - due);
		}
		if (now - due > lat->late_max_ns)
			lat->late_max_ns = now - due;
		if (!loop_tick(L, k, due, now))
			break;
		/* virtual time stands still during a tick, unless a test makes
		 * it jump (a stall): the same catch-up runs on either clock */
		end = hal_clock_now(L->clk);
		if (end - now > lat->work_max_ns)
			lat->work_max_ns = end - now;
		if (end > loop_due(L, k + 1))
			lat->overruns++;
	}
	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
	L->res->cpu_ns = (c1.tv_sec - c0.tv_sec) * 1000000000LL + (c1.tv_nsec - c0.tv_nsec);
}
