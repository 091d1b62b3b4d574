/* SPDX-License-Identifier: MIT */
/*
 * loop_live.c - the loop's live mode (loop_live.h): commands taken in the
 * tick, HOLD, JOG and MOVE, a segment's end back to HOLD, the live status
 * sample. Every function here is [rt] but loop_live_init and
 * loop_live_free.
 */
#include "loop_live.h"
#include "loop_priv.h"
#include "hal/rt.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

struct live_jog {
	double f;        /* commanded fraction of vmax */
	double v;        /* present speed, core units/s */
	int64_t refresh; /* the tick of the last refresh */
};

struct loop_live {
	struct loop_live_cfg cfg;
	struct live_jog *jog;   /* n */
	struct frame_list fl;   /* a step segment's frames: items below */
	struct frame_item items[LOOP_LIVE_FRAME_ITEMS];
	struct loop_cmd cmd;    /* the one being taken */
	struct loop_live_status *st; /* the sample being composed */
	uint32_t st_size;
	uint64_t cmd_seq;
	int64_t seg_first;
	int64_t wake_ns;        /* hal_mono_ns() at the tick's start */
	struct loop_report last;
	int64_t at_frame;       /* the frame the rig is at, -1 off any */
	int64_t move_frame;     /* a MOVE's, -1 for a pose */
	int64_t pace_wall, pace_t; /* pacing: hal_mono_ns() at virtual time pace_t */
	bool paced;             /* the last tick was paced */
	uint8_t st_state;       /* the state of the last sample pushed */
	bool st_pending;        /* a sample the ring had no room for */
	bool quit;
};

int loop_live_init(struct loop *L, const struct loop_live_cfg *lc, char *err, size_t errsize)
{
	struct loop_live *lv;

	STRAND_ASSERT_NOT_RT();
	if (!lc->estop || !lc->signal || !lc->cmds || !lc->acks) {
		snprintf(err, errsize, "live mode: rings and requests not given");
		return -EINVAL;
	}
	if (L->n > LOOP_LIVE_OUT_MAX) {
		snprintf(err, errsize, "%u outputs: live control takes at most %d", L->n,
			 LOOP_LIVE_OUT_MAX);
		return -EINVAL;
	}
	lv = calloc(1, sizeof(*lv));
	if (!lv)
		goto nomem;
	lv->jog = calloc(L->n ? L->n : 1, sizeof(*lv->jog));
	lv->st_size = loop_live_status_size(L->n);
	lv->st = calloc(1, lv->st_size);
	if (!lv->jog || !lv->st) {
		free(lv->jog);
		free(lv->st);
		free(lv);
		goto nomem;
	}
	lv->cfg = *lc;
	lv->fl.items = lv->items;
	lv->seg_first = -1;
	lv->at_frame = -1;
	lv->move_frame = -1;
	lv->last.channel = -1;
	lv->last.out = -1;
	L->live = lv;
	L->seq.state = LOOP_HOLD;
	L->res->total_frames = 0;
	return 0;
nomem:
	snprintf(err, errsize, "out of memory");
	return -ENOMEM;
}

void loop_live_free(struct loop *L)
{
	STRAND_ASSERT_NOT_RT();
	if (!L || !L->live)
		return;
	free(L->live->jog);
	free(L->live->st);
	free(L->live);
	L->live = NULL;
}

/* ---- commands ---- */

static void STRAND_RT ack(struct loop *L, const struct loop_cmd *c, int code, int32_t out)
{
	struct loop_ack a = {
		.seq = c->seq, .code = code, .out = out, .tick = L->tick,
		.latency_ns = L->live->wake_ns - c->arrival_ns,
	};

	L->live->cmd_seq = c->seq;
	/* the owner waits for its answer: a full ring is its own fault, and
	 * it times out */
	hal_ring_push(L->live->cfg.acks, &a);
}

static bool STRAND_RT at_rest(const struct loop *L)
{
	return L->seq.state == LOOP_HOLD && !L->live->quit;
}

static void STRAND_RT jog_clear(struct loop *L)
{
	uint32_t i;

	for (i = 0; i < L->n; i++) {
		L->live->jog[i].f = 0;
		L->live->jog[i].v = 0;
	}
}

/* A controlled stop back to HOLD: a jog lapses, anything else brakes. */
static void STRAND_RT live_stop(struct loop *L)
{
	uint32_t i;

	switch (L->seq.state) {
	case LOOP_HOLD:
	case LOOP_STOPPING:
	case LOOP_ENDED:
		return;
	case LOOP_JOG:
		for (i = 0; i < L->n; i++)
			L->live->jog[i].f = 0;
		return;
	default:
		for (i = 0; i < L->rig->ntrig; i++)
			L->trig.pulse[i].pending = false;
		L->seq.state = LOOP_STOPPING;
		L->seq.seg_j = 0;
		return;
	}
}

/* The first output of pose outside its position limits, or -1. */
static int32_t STRAND_RT outside(const struct loop *L, const mot_q32 *pose)
{
	uint32_t i;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		double p = move_q2d(pose[i]);

		if (!o->vel_mode && (p < o->min - 1e-9 || p > o->max + 1e-9))
			return (int32_t)i;
	}
	return -1;
}

/* A move from where the rig rests to seq.target: false when the limits
 * allow none in the ticks a run counts. */
static bool STRAND_RT plan_to_target(struct loop *L)
{
	struct loop_seq *s = &L->seq;

	if (move_plan(&s->mv, s->mv.ch, L->n, L->prev, s->target, s->vmax, s->amax,
		      L->tm->tick_hz))
		return false;
	s->mv_j = 0;
	return true;
}

/* Frames the segment fires (loop_setup.c's plan_continuous counts the
 * same way), -1 without an end; false when they overflow a count. */
static bool STRAND_RT seg_total(const struct loop *L, int64_t *total)
{
	const struct loop_cfg *c = &L->cfg;
	int64_t per, p, f;
	bool over;

	if (c->mode == LOOP_MODE_STEP) {
		f = frames_count(c->frames);
		return !__builtin_mul_overflow(f, (int64_t)L->rig->ntrig, total);
	}
	if ((c->loop || c->ping_pong) && c->passes == 0) {
		*total = -1;
		return true;
	}
	per = c->to - c->from + 1;
	p = (c->loop || c->ping_pong) ? c->passes : 1;
	if (c->ping_pong)
		over = __builtin_mul_overflow(p - 1, per - 1, &f) ||
		       __builtin_add_overflow(f, per, &f);
	else
		over = __builtin_mul_overflow(per, p, &f);
	return !over && !__builtin_mul_overflow(f, (int64_t)L->rig->ntrig, total);
}

static int STRAND_RT take_play(struct loop *L, const struct loop_cmd *c, int32_t *bad)
{
	struct loop_live *lv = L->live;
	struct loop_cfg *cfg = &L->cfg;
	const struct loop_cfg *in = &c->cfg;
	int64_t total;
	uint32_t i;

	if (in->mode == LOOP_MODE_STEP ? (c->nframes < 1 || c->nframes > LOOP_LIVE_FRAME_ITEMS) :
	    (in->from < 0 || in->to < in->from || (in->ping_pong && in->to == in->from)))
		return LOOP_CMD_INVALID;
	cfg->mode = in->mode;
	cfg->from = in->from;
	cfg->to = in->to;
	cfg->loop = in->loop;
	cfg->ping_pong = in->ping_pong;
	cfg->passes = in->passes;
	cfg->settle_ticks = in->settle_ticks;
	cfg->exposure_ticks = in->exposure_ticks;
	cfg->in_position_timeout_ticks = in->in_position_timeout_ticks;
	cfg->ready_timeout_ticks = in->ready_timeout_ticks;
	cfg->max_ticks = in->max_ticks ? L->tick + in->max_ticks : 0;
	cfg->shutter = in->mode == LOOP_MODE_STEP ? in->shutter : 0;
	cfg->gomo_src = in->gomo_src;
	cfg->gomo_wait = in->gomo_wait;
	cfg->gomo_runup_ticks = in->gomo_runup_ticks;
	for (i = 0; i < c->nframes; i++)
		lv->items[i] = c->frames[i];
	lv->fl.n = c->nframes;
	cfg->frames = &lv->fl;
	if (!seg_total(L, &total))
		return LOOP_CMD_INVALID;
	if (cfg->mode == LOOP_MODE_STEP) {
		/* the owner checked the shutter against the timing (two ticks) */
		if (cfg->shutter) {
			if (cfg->gomo_src && cfg->gomo_src->timing.tick_hz != L->tm->tick_hz)
				return LOOP_CMD_INVALID;
			loop_gomo_setup(L);
		}
		memset(&L->step.fit, 0, sizeof(L->step.fit));
		L->step.frame = -1;
		L->seq.state = LOOP_STEP_NEXT;
		lv->seg_first = lv->items[0].first;
	} else {
		L->seq.pass = 0;
		loop_pass_setup(L);
		if (loop_entry_plan(L, bad))
			return LOOP_CMD_RUNUP;
		if (!plan_to_target(L))
			return LOOP_CMD_LIMIT;
		L->seq.state = LOOP_PREROLL;
		lv->seg_first = cfg->from;
	}
	L->res->total_frames = total;
	L->res->frames_fired = 0;
	L->trig.jr = c->jr;
	return LOOP_CMD_OK;
}

/* Every output's fraction at once. */
static int STRAND_RT take_jog_vec(struct loop *L, const struct loop_cmd *c)
{
	struct loop_live *lv = L->live;
	bool any = false;
	uint32_t i;

	for (i = 0; i < L->n; i++)
		if (!(fabs(c->vec[i]) <= 1) || (c->vec[i] != 0 && L->rig->out[i].vel_mode))
			return LOOP_CMD_INVALID;
	if (lv->quit || L->seq.state == LOOP_ENDED)
		return LOOP_CMD_STOPPING;
	for (i = 0; i < L->n; i++)
		any |= c->vec[i] != 0;
	if (c->keep) {
		bool live = false;

		for (i = 0; i < L->n; i++)
			live |= lv->jog[i].f != 0;
		if (L->seq.state != LOOP_JOG || !live)
			return LOOP_CMD_OK; /* lapsed or stopped meanwhile */
		for (i = 0; i < L->n; i++)
			lv->jog[i].f = c->vec[i];
		return LOOP_CMD_OK;
	}
	if (L->seq.state != LOOP_HOLD && L->seq.state != LOOP_JOG)
		return any ? LOOP_CMD_BUSY : LOOP_CMD_OK;
	for (i = 0; i < L->n; i++) {
		lv->jog[i].f = c->vec[i];
		lv->jog[i].refresh = L->tick;
	}
	if (L->seq.state == LOOP_HOLD && any) {
		L->seq.state = LOOP_JOG;
		lv->seg_first = -1;
		lv->at_frame = -1;
	}
	return LOOP_CMD_OK;
}

static void STRAND_RT take(struct loop *L, const struct loop_cmd *c)
{
	struct loop_live *lv = L->live;
	int32_t bad = -1;
	int code = LOOP_CMD_OK;
	uint32_t i;

	switch (c->kind) {
	case LOOP_CMD_JOG:
		if (c->out >= L->n || !(fabs(c->speed) <= 1) || L->rig->out[c->out].vel_mode) {
			code = LOOP_CMD_INVALID;
		} else if (lv->quit || L->seq.state == LOOP_ENDED) {
			code = LOOP_CMD_STOPPING;
		} else if (L->seq.state != LOOP_HOLD && L->seq.state != LOOP_JOG) {
			/* releasing a key while something else moves is no error */
			code = c->speed == 0 ? LOOP_CMD_OK : LOOP_CMD_BUSY;
		} else {
			lv->jog[c->out].f = c->speed;
			lv->jog[c->out].refresh = L->tick;
			if (L->seq.state == LOOP_HOLD && c->speed != 0) {
				L->seq.state = LOOP_JOG;
				lv->seg_first = -1;
				lv->at_frame = -1;
			}
		}
		break;
	case LOOP_CMD_JOG_VEC:
		code = take_jog_vec(L, c);
		break;
	case LOOP_CMD_MOVE:
		if (!at_rest(L)) {
			code = LOOP_CMD_BUSY;
			break;
		}
		bad = outside(L, c->pose);
		if (bad >= 0) {
			code = LOOP_CMD_LIMIT;
			break;
		}
		for (i = 0; i < L->n; i++)
			L->seq.target[i] = L->rig->out[i].vel_mode ? 0 : c->pose[i];
		if (!plan_to_target(L)) {
			code = LOOP_CMD_LIMIT;
			break;
		}
		L->seq.state = LOOP_MOVE;
		lv->seg_first = -1;
		lv->move_frame = c->frame;
		lv->at_frame = -1;
		break;
	case LOOP_CMD_PLAY:
		code = at_rest(L) ? take_play(L, c, &bad) : LOOP_CMD_BUSY;
		if (code != LOOP_CMD_OK && at_rest(L)) {
			L->seq.state = LOOP_HOLD;
			L->cfg.max_ticks = 0;
		}
		break;
	case LOOP_CMD_STOP:
		live_stop(L);
		break;
	case LOOP_CMD_DISABLE:
		lv->quit = true;
		/* the run's end, whatever it was doing (a stop under way too) */
		loop_fail(L, LOOP_END_STOPPED, LOOP_CAUSE_DISABLE, NULL);
		if (L->seq.state == LOOP_HOLD)
			L->seq.state = LOOP_ENDED;
		else
			live_stop(L);
		break;
	case LOOP_CMD_SOURCE:
		if (!at_rest(L) || !c->src) {
			code = at_rest(L) ? LOOP_CMD_INVALID : LOOP_CMD_BUSY;
			break;
		}
		L->src = c->src;
		L->tm = &c->src->timing;
		break;
	case LOOP_CMD_NOP:
		break;
	case LOOP_CMD_GO:
		code = loop_gomo_go(L) ? LOOP_CMD_BUSY : LOOP_CMD_OK;
		break;
	default:
		code = LOOP_CMD_INVALID;
		break;
	}
	ack(L, c, code, bad);
}

void STRAND_RT loop_live_commands(struct loop *L)
{
	struct loop_live *lv = L->live;
	int i;

	lv->wake_ns = hal_mono_ns();
	if (atomic_load_explicit(lv->cfg.estop, memory_order_acquire))
		loop_request_stop(L, 2, LOOP_CAUSE_ESTOP);
	i = atomic_load_explicit(lv->cfg.signal, memory_order_relaxed);
	if (i)
		loop_request_stop(L, i >= 2 ? 2 : 1,
				  i >= 2 ? LOOP_CAUSE_IMMEDIATE : LOOP_CAUSE_SIGNAL);
	for (i = 0; i < LOOP_LIVE_CMDS_PER_TICK && hal_ring_pop(lv->cfg.cmds, &lv->cmd); i++)
		take(L, &lv->cmd);
}

/* ---- jog ---- */

/*
 * The fastest speed (>= 0) from which an output stops within distance d,
 * losing at most u of speed a tick (u = amax dt): it moves v this tick,
 * then v - u, v - 2u, ... for m more ticks while that stays positive, and
 * covers dt ((m + 1) v - u m (m + 1) / 2). That is at most d for the m
 * with dt u m (m + 1) / 2 <= d < dt u (m + 1) (m + 2) / 2, and v up to
 * d / (dt (m + 1)) + u m / 2. A jog held at this speed every tick brakes
 * by exactly u a tick and its last step lands on the limit.
 */
static double STRAND_RT jog_vmax(double d, double u, double dt)
{
	double m;

	if (!(d > 0))
		return 0;
	if (!isfinite(d))
		return INFINITY;
	m = floor((sqrt(1 + 8 * d / (dt * u)) - 1) / 2);
	if (dt * u * m * (m + 1) / 2 > d) /* rounding of the square root */
		m -= 1;
	return (d / (dt * (m + 1)) + u * m / 2) * (1 - 1e-12);
}

/* An output that takes part in the jog: not a speed, its device on. */
static bool STRAND_RT jogs(const struct loop *L, uint32_t i)
{
	const struct rig_out *o = &L->rig->out[i];

	return !o->vel_mode && !L->safety.dev_off[o->dev];
}

/*
 * The ticks the slowest output needs to reach its commanded speed, each
 * gaining at most amax dt a tick: every output's change is spread over as
 * many, so that their speeds keep their proportions while they ramp (a
 * camera dollied moves along its axis from the first tick), and none
 * changes faster than its own limit allows.
 */
static double STRAND_RT ramp_ticks(struct loop *L, double dt)
{
	struct loop_live *lv = L->live;
	double k = 1;
	uint32_t i;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		struct live_jog *j = &lv->jog[i];

		if (!jogs(L, i))
			continue;
		if (j->f != 0 && L->tick - j->refresh > lv->cfg.deadman_ticks)
			j->f = 0; /* the dead-man: no refresh in time */
		k = fmax(k, ceil(fabs(j->f * o->vmax - j->v) / (o->amax * dt) - 1e-9));
	}
	return k;
}

static void STRAND_RT jog_step(struct loop *L)
{
	struct loop_live *lv = L->live;
	const double hz = L->tm->tick_hz, dt = 1.0 / hz;
	double k = ramp_ticks(L, dt);
	bool moving = false;
	uint32_t i;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		struct live_jog *j = &lv->jog[i];
		double u = o->amax * dt, p = move_q2d(L->prev[i]), v, lim;
		mot_q32 q;

		L->val[i] = L->prev[i];
		if (!jogs(L, i)) {
			j->v = 0;
			continue;
		}
		v = j->v + (j->f * o->vmax - j->v) / k;
		v = fmax(j->v - u, fmin(j->v + u, v));
		if (v > 0) {
			lim = jog_vmax(o->max - p, u, dt);
			v = fmin(v, lim);
		} else if (v < 0) {
			lim = jog_vmax(p - o->min, u, dt);
			v = fmax(v, -lim);
		}
		j->v = v;
		if (v == 0 && j->f == 0)
			continue;
		moving = true;
		q = mot_add_sat(L->prev[i], move_d2q(v * dt), NULL);
		/* on the limit, not a rounding beyond it */
		if (v > 0 && move_q2d(q) > o->max)
			for (q = move_d2q(o->max); move_q2d(q) > o->max; q--)
				;
		if (v < 0 && move_q2d(q) < o->min)
			for (q = move_d2q(o->min); move_q2d(q) < o->min; q++)
				;
		L->val[i] = q;
	}
	if (!moving)
		L->seq.state = LOOP_HOLD;
}

void STRAND_RT loop_live_sequence(struct loop *L)
{
	struct loop_seq *s = &L->seq;
	uint32_t i;

	switch (s->state) {
	case LOOP_JOG:
		jog_step(L);
		return;
	case LOOP_MOVE:
		if (++s->mv_j <= s->mv.ticks) {
			for (i = 0; i < L->n; i++)
				L->val[i] = move_at(&s->mv, i, s->mv_j);
			return;
		}
		s->state = LOOP_HOLD;
		L->live->at_frame = L->live->move_frame;
		/* the last sample was the target */
		__attribute__((fallthrough));
	default:
		for (i = 0; i < L->n; i++)
			L->val[i] = L->prev[i];
		return;
	}
}

/* ---- the end of a tick ---- */

/* Virtual time at the wall clock's pace (loop_live_cfg.pace): the next
 * tick waits for the wall to catch up with it, counted from the first
 * paced tick after an unpaced stretch. */
static void STRAND_RT pace(struct loop *L)
{
	struct loop_live *lv = L->live;
	bool on = lv->cfg.pace && (lv->cfg.pace_all || L->seq.state == LOOP_HOLD ||
				   L->seq.state == LOOP_JOG);
	int64_t due = loop_due(L, L->tick + 1), t;
	struct timespec ts;

	if (!on || L->seq.state == LOOP_ENDED) {
		lv->paced = false;
		return;
	}
	if (!lv->paced) {
		lv->pace_wall = hal_mono_ns();
		lv->pace_t = loop_due(L, L->tick);
		lv->paced = true;
	}
	t = lv->pace_wall + (due - lv->pace_t);
	ts.tv_sec = t / 1000000000;
	ts.tv_nsec = t % 1000000000;
	clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL);
}

void STRAND_RT loop_live_tick_end(struct loop *L)
{
	struct loop_live *lv = L->live;
	struct loop_report *r = &L->res->rep;

	pace(L);
	if (L->seq.state != LOOP_ENDED || lv->quit ||
	    (r->end != LOOP_END_NONE && r->end != LOOP_END_DONE))
		return;
	/* a segment ended (its frames ran out, --duration, a stop command):
	 * its report is kept for the status, and the rig holds */
	if (r->end != LOOP_END_NONE)
		lv->last = *r;
	memset(r, 0, sizeof(*r));
	r->channel = -1;
	r->out = -1;
	L->seq.state = LOOP_HOLD;
	L->cfg.max_ticks = 0;
	L->trig.cur_rec = NULL;
	L->trig.jr = NULL; /* the owner closes it once it sees the segment over */
	lv->seg_first = -1;
	jog_clear(L);
}

void STRAND_RT loop_live_status(struct loop *L)
{
	struct loop_live *lv = L->live;
	struct loop_live_status *st = lv->st;
	const struct lat_stats *lat = &L->res->lat;
	uint32_t i;

	if (lv->seg_first >= 0 && L->res->last_frame >= 0)
		lv->at_frame = L->res->last_frame;
	/* every state a sample of its own (a console must see a move end),
	 * and one the ring had no room for again at the next tick */
	if (L->seq.state != LOOP_ENDED && L->tick % L->cfg.status_every && !lv->st_pending &&
	    lv->st_state == (uint8_t)L->seq.state)
		return;
	loop_status_fill(L, &st->s);
	st->at_frame = lv->at_frame;
	st->cmd_seq = lv->cmd_seq;
	st->seg_first = lv->seg_first;
	st->lat_n = lat->n;
	st->lat_min_ns = lat->n ? lat->min_ns : 0;
	st->lat_sum_ns = lat->sum_ns;
	st->t_ns = loop_due(L, L->tick);
	st->rep = L->res->rep.end != LOOP_END_NONE ? L->res->rep : lv->last;
	st->n = L->n;
	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		struct loop_live_out *so = &st->out[i];
		int64_t act;

		so->sp = move_q2d(L->val[i]);
		so->vel = L->out[i].vel;
		so->off = L->safety.dev_off[o->dev];
		so->jog = L->seq.state == LOOP_JOG && lv->jog[i].v != 0;
		so->has_act = loop_ferror(L, i, &so->fe);
		act = L->out[i].act;
		so->act = so->has_act ? (double)(act - o->scale.offset) / o->scale.per_unit_d : 0;
		if (!so->has_act)
			so->fe = 0;
	}
	lv->st_state = (uint8_t)L->seq.state;
	lv->st_pending = !hal_ring_push(L->status, st);
	if (lv->st_pending)
		L->res->status_dropped++;
}
