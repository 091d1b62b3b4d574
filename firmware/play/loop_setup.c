/* SPDX-License-Identifier: MIT */
/*
 * loop_setup.c - a run put together before it starts: the loop's one
 * block (measured, allocated, carved, sealed), where the rig stands, and
 * the plan into the first pass. Every function here is [init], but for
 * the two name tables, which any thread may read.
 */
#include "loop_live.h"
#include "loop_priv.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "motion/arena.h"
#include "plan/gomo.h"
#include "hal/rt.h"

static const char *const state_names[] = {
	[LOOP_PREROLL] = "pre-roll",	 [LOOP_RUNUP] = "run-up",
	[LOOP_PLAY] = "play",
	[LOOP_BRIDGE_STOP] = "bridge",	 [LOOP_BRIDGE_MOVE] = "bridge",
	[LOOP_POSTROLL] = "post-roll",	 [LOOP_STEP_NEXT] = "step",
	[LOOP_STEP_MOVE] = "move",	 [LOOP_STEP_SETTLE] = "settle",
	[LOOP_STEP_EXPOSE] = "expose",	 [LOOP_STOPPING] = "stopping",
	[LOOP_ENDED] = "ended",		 [LOOP_CUE] = "cue",
	[LOOP_HOLD] = "hold",		 [LOOP_JOG] = "jog",
	[LOOP_MOVE] = "move",
	[LOOP_GOMO_ARMED] = "armed",	 [LOOP_GOMO_RUNUP] = "go-motion run-up",
	[LOOP_GOMO_EXPOSE] = "go-motion exposure", [LOOP_GOMO_RUNOUT] = "go-motion run-out",
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
	[LOOP_CAUSE_CHASE] = "chase",
	[LOOP_CAUSE_BOARD] = "another board",
	[LOOP_CAUSE_DISABLE] = "drives disabled",
};

const char *loop_state_name(enum loop_state s)
{
	return s <= LOOP_GOMO_RUNOUT ? state_names[s] : "?";
}

const char *loop_cause_name(enum loop_cause c)
{
	return c <= LOOP_CAUSE_DISABLE ? cause_names[c] : "?";
}

/* ---- the block ---- */

/* n elements of `size` bytes, or a failed arena when n * size overflows. */
static void *carve_array(struct mot_arena *a, size_t n, size_t size, size_t align)
{
	if (size && n > SIZE_MAX / size) {
		a->failed = true;
		return NULL;
	}
	return mot_arena_alloc(a, n * size, align);
}

#define CARVE(a, type, n) ((type *)carve_array((a), (n), sizeof(type), _Alignof(type)))

/* The lines of input device d that the line table covers: up to its
 * inputs' highest line (rig_build numbers a device's lines from 0). */
static uint32_t input_lines(const struct rig *rig, uint32_t d)
{
	uint32_t i, n = 0;

	for (i = 0; i < rig->nin; i++)
		if (rig->in[i].dev == d && rig->in[i].line >= n)
			n = rig->in[i].line + 1;
	return n;
}

/* What each input line is for (struct loop_safety), filled in the block
 * carved for it. */
static void input_table(struct loop *L)
{
	const struct rig *rig = L->rig;
	struct loop_safety *s = &L->safety;
	uint32_t d, i;

	s->in_first[0] = 0;
	for (d = 0; d < rig->ndins; d++)
		s->in_first[d + 1] = s->in_first[d] + input_lines(rig, d);
	for (i = 0; i < s->in_first[rig->ndins]; i++)
		s->in_of[i] = -1;
	for (i = 0; i < rig->nin; i++)
		s->in_of[s->in_first[rig->in[i].dev] + rig->in[i].line] = (int32_t)i;
	s->estop_in = -1;
}

/*
 * The loop's block, laid out in the order a tick touches it: struct loop,
 * the per-output state and poses, the per-device and per-trigger flags,
 * and last the result, whose latency histogram is most of the block. On
 * an arena without memory this only measures (and returns NULL); the same
 * code then carves, so the two cannot disagree.
 */
static struct loop *carve(struct mot_arena *a, const struct rig *rig, uint32_t tick_hz)
{
	uint32_t d, n = rig->nout, nlines = 0;
	struct lim_stencil st;
	struct loop *L;

	for (d = 0; d < rig->ndins; d++)
		nlines += input_lines(rig, d);
	lim_stencil_init(&st, tick_hz);
	L = CARVE(a, struct loop, 1);
	struct loop_out *out = CARVE(a, struct loop_out, n);
	mot_q32 *val = CARVE(a, mot_q32, n);
	mot_q32 *prev = CARVE(a, mot_q32, n);
	mot_q32 *target = CARVE(a, mot_q32, n);
	mot_q32 *ru_end = CARVE(a, mot_q32, n);
	mot_q32 *gomo_open = CARVE(a, mot_q32, n);
	mot_q32 *gomo_close = CARVE(a, mot_q32, n);
	mot_q32 *tl_mem = CARVE(a, mot_q32, TIMELINE_WORDS(n));
	mot_q32 *rings = CARVE(a, mot_q32, (size_t)n * LIM_METER_LEN(st.h));
	bool *extend = CARVE(a, bool, n);
	struct move_ch *mv_ch = CARVE(a, struct move_ch, n);
	double *vmax = CARVE(a, double, n);
	double *amax = CARVE(a, double, n);
	bool *dev_off = CARVE(a, bool, rig->naxes);
	struct loop_pulse *pulse = CARVE(a, struct loop_pulse, rig->ntrig);
	bool *dout_dirty = CARVE(a, bool, rig->ndouts);
	int64_t *limited = CARVE(a, int64_t, n);
	uint32_t *in_first = CARVE(a, uint32_t, rig->ndins + 1);
	int32_t *in_of = CARVE(a, int32_t, nlines);
	struct loop_result *res = carve_array(a, 1, sizeof(*res), 64);

	if (!L || a->failed)
		return NULL;
	L->n = n;
	L->stencil = st;
	L->seq.tl_mem = tl_mem;
	L->seq.extend = extend;
	for (d = 0; d < n; d++)
		out[d].meter.ring = rings + (size_t)d * LIM_METER_LEN(st.h);
	L->out = out;
	L->val = val;
	L->prev = prev;
	L->seq.target = target;
	L->seq.ru_end = ru_end;
	L->seq.gomo_open = gomo_open;
	L->seq.gomo_close = gomo_close;
	L->seq.mv.ch = mv_ch;
	L->seq.vmax = vmax;
	L->seq.amax = amax;
	L->safety.dev_off = dev_off;
	L->safety.in_first = in_first;
	L->safety.in_of = in_of;
	L->trig.pulse = pulse;
	L->trig.dout_dirty = dout_dirty;
	L->limited = limited;
	L->res = res;
	res->limited = limited;
	return L;
}

/* The block: measured, allocated once (64-byte aligned, as the arena
 * wants its base), carved, sealed. NULL when out of memory. */
static struct loop *block_new(const struct rig *rig, uint32_t tick_hz)
{
	struct mot_arena a;
	struct loop *L;
	size_t size;
	void *block;

	mot_arena_init(&a, NULL, 0);
	carve(&a, rig, tick_hz);
	if (a.failed)
		return NULL;
	size = (a.used + 63) & ~(size_t)63;
	block = aligned_alloc(64, size);
	if (!block)
		return NULL;
	mot_arena_init(&a, block, size);
	L = carve(&a, rig, tick_hz);
	mot_arena_seal(&a);
	if (!L) { /* cannot happen: the same carving measured it */
		free(block);
		return NULL;
	}
	return L; /* carved first: the block's own address */
}

/* ---- the plan ---- */

/* Output o's limits as the predicate takes them. */
static struct lim_bounds out_bounds(const struct rig_out *o)
{
	return (struct lim_bounds){ .min = o->min, .max = o->max, .vel = o->vmax,
				    .acc = o->amax, .vel_ch = o->vel_mode };
}

/* Where the rig stands: feedback where there is some, else home; each
 * output's limits and its meter, standing there. */
static void read_rig(struct loop *L)
{
	const struct rig *rig = L->rig;
	uint32_t i;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &rig->out[i];
		int64_t act;

		L->seq.vmax[i] = o->vmax;
		L->seq.amax[i] = o->amax;
		L->prev[i] = o->vel_mode ? 0 : o->home;
		if (!o->vel_mode && hal_axis_input(rig->axes[o->dev], -1) == 0 &&
		    hal_axis_actual(rig->axes[o->dev], o->ch, &act))
			L->prev[i] = move_d2q((double)(act - o->scale.offset) /
					      o->scale.per_unit_d);
		L->val[i] = L->prev[i];
		L->out[i].sent = o->vel_mode ? 0 : hal_scale_counts(&o->scale, L->prev[i], NULL);
		L->out[i].lim = out_bounds(o);
		L->out[i].has_fb = false; /* until loop_feedback reads some */
		/* the run starts from rest where the rig stands */
		lim_meter_reset(&L->out[i].meter, &L->stencil, L->out[i].meter.ring, L->prev[i],
				true);
		L->seq.extend[i] = timeline_extends(o->unit);
	}
}

/* Every output stands inside its position limits: a move from outside
 * would break them at its first tick. -EDOM, naming it, otherwise. */
static int standing(struct loop *L, char *err, size_t errsize)
{
	uint32_t i;

	for (i = 0; i < L->n; i++) {
		const struct rig_out *o = &L->rig->out[i];
		double x = move_q2d(L->prev[i]);

		if (o->vel_mode || (x >= o->min - 1e-9 && x <= o->max + 1e-9))
			continue;
		snprintf(err, errsize, "%s (device '%s' axis %u) stands at %.7g %s, outside its "
			 "limits %.7g to %.7g %s: bring it inside them before playing",
			 o->channel, L->rig->axes[o->dev]->name, o->ch,
			 rig_file_units(o->unit, x), rig_unit_name(o->unit),
			 rig_file_units(o->unit, o->min), rig_file_units(o->unit, o->max),
			 rig_unit_name(o->unit));
		return -EDOM;
	}
	return 0;
}

static int plan_step(struct loop *L, char *err, size_t errsize)
{
	const struct loop_cfg *cfg = &L->cfg;

	if (!cfg->frames || !cfg->frames->n) {
		snprintf(err, errsize, "step mode: no frames to shoot");
		return -EINVAL;
	}
	if (__builtin_mul_overflow(frames_count(cfg->frames), (int64_t)L->rig->ntrig,
				   &L->res->total_frames)) {
		snprintf(err, errsize, "--frames: more shots times %u triggers than a run counts",
			 L->rig->ntrig);
		return -EINVAL;
	}
	if (cfg->shutter) {
		const struct play_source *g = cfg->gomo_src ? cfg->gomo_src : L->src;

		if (g->timing.tick_hz != L->tm->tick_hz ||
		    gomo_shutter_check(&g->timing, cfg->shutter)) {
			snprintf(err, errsize, "go-motion: the shutter opens for less than two ticks, "
				 "or its motion has another tick rate than the run");
			return -EINVAL;
		}
		loop_gomo_setup(L);
	}
	L->seq.state = LOOP_STEP_NEXT;
	return 0;
}

static int plan_continuous(struct loop *L, char *err, size_t errsize)
{
	const struct loop_cfg *cfg = &L->cfg;
	const struct rig *rig = L->rig;
	int32_t bad;

	if (cfg->to < cfg->from) {
		snprintf(err, errsize, "--from %lld is after --to %lld", (long long)cfg->from,
			 (long long)cfg->to);
		return -EINVAL;
	}
	if (cfg->ping_pong && cfg->to == cfg->from) {
		snprintf(err, errsize, "--ping-pong needs at least two frames");
		return -EINVAL;
	}
	if ((cfg->loop || cfg->ping_pong) && cfg->passes == 0) {
		L->res->total_frames = -1;
	} else {
		int64_t per = cfg->to - cfg->from + 1, p = (cfg->loop || cfg->ping_pong) ?
							   cfg->passes : 1;
		int64_t f;
		bool over;

		/* --from, --to and --passes are below 2^31, so from the command
		 * line only the triggers can make this overflow */
		if (cfg->ping_pong)
			over = __builtin_mul_overflow(p - 1, per - 1, &f) ||
			       __builtin_add_overflow(f, per, &f);
		else
			over = __builtin_mul_overflow(per, p, &f);
		if (over || __builtin_mul_overflow(f, (int64_t)rig->ntrig, &L->res->total_frames)) {
			snprintf(err, errsize, "--passes %lld: that many passes of %lld frames, "
				 "%u triggers each, are more frames than a run counts (2^63)",
				 (long long)p, (long long)per, rig->ntrig);
			return -EINVAL;
		}
	}
	L->seq.pass = 0;
	loop_pass_setup(L);
	if (loop_entry_plan(L, &bad)) {
		const struct rig_out *o = &rig->out[bad];

		snprintf(err, errsize,
			 "%s moves at %.6g %s/s at frame %lld: coming up to that speed within "
			 "its acceleration limit needs a run-up from %.6g %s, outside its limits; "
			 "start from a frame where it moves slower",
			 o->channel, rig_file_units(o->unit, L->out[bad].ru.v),
			 rig_unit_name(o->unit), (long long)L->seq.pass_first,
			 rig_file_units(o->unit, move_q2d(L->seq.target[bad])),
			 rig_unit_name(o->unit));
		return -ERANGE;
	}
	loop_move_plan(L, L->prev, L->seq.target);
	if (L->seq.mv.ticks >= NUM_TICKS_MAX) {
		snprintf(err, errsize, "the pre-roll to frame %lld would take more than 2^53 ticks "
			 "(%.3g years) at the outputs' velocity and acceleration limits",
			 (long long)L->seq.pass_first, (double)NUM_TICKS_MAX / L->tm->tick_hz /
			 (365.25 * 86400));
		return -ERANGE;
	}
	L->seq.state = LOOP_PREROLL;
	return 0;
}

int loop_init(struct loop **out, const struct loop_cfg *cfg, struct rig *rig,
	      struct play_source *src, struct hal_clock *clk, struct hal_ring *status_ring,
	      char *err, size_t errsize)
{
	int64_t min_off = 0, max_off = 0;
	struct loop *L;
	uint32_t i;
	int rc;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	L = block_new(rig, src->timing.tick_hz);
	if (!L) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	L->cfg = *cfg;
	if (L->cfg.status_every < 1)
		L->cfg.status_every = 1;
	L->rig = rig;
	L->src = src;
	L->clk = clk;
	L->status = status_ring;
	L->tm = &src->timing;
	lat_reset(&L->res->lat);
	L->res->last_frame = -1;
	L->res->ferr_worst_out = -1;
	L->res->rep.channel = -1;
	L->res->rep.out = -1;
	input_table(L);
	for (i = 0; i < rig->nin; i++)
		L->step.has_ready_input |= rig->in[i].role == RIG_INPUT_CAMERA_READY;
	for (i = 0; i < rig->ntrig; i++) {
		if (rig->trig[i].offset < min_off)
			min_off = rig->trig[i].offset;
		if (rig->trig[i].offset > max_off)
			max_off = rig->trig[i].offset;
	}
	L->seq.lead = -min_off;
	L->seq.tail = max_off;
	read_rig(L);
	/* a live loop plans each segment when a command asks for it, and
	 * may start outside the limits: a jog brings it back (loop_live.h) */
	rc = cfg->live ? 0 : standing(L, err, errsize);
	if (!rc && !cfg->live)
		rc = cfg->mode == LOOP_MODE_STEP ? plan_step(L, err, errsize) :
						   plan_continuous(L, err, errsize);
	if (rc) {
		loop_free(L);
		return rc;
	}
	*out = L;
	return 0;
}

void loop_set_journal(struct loop *L, struct journal *jr)
{
	L->trig.jr = jr;
}

void loop_free(struct loop *L)
{
	STRAND_ASSERT_NOT_RT();

	loop_live_free(L);
	free(L); /* the block */
}

int64_t loop_play_tick(const struct loop *L)
{
	return L->seq.mv.ticks + L->seq.ru_ticks;
}
