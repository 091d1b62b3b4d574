/* SPDX-License-Identifier: MIT */
/* live_cmd.c - the commands of a live session (live.h). */
#define _GNU_SOURCE
#include "live_priv.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check/run_check.h"
#include "plan/gomo.h"
#include "plan/runup.h"
#include "plan/timeline.h"
#include "play/frames.h"
#include "scene/num.h"

/* The command under the session's lock: lock, evaluate, unlock (the
 * argument is evaluated before the call, after the lock). */
static int unlocked(struct live *lv, int rc)
{
	pthread_mutex_unlock(&lv->mu);
	return rc;
}

#define LOCKED(lv, expr) (pthread_mutex_lock(&(lv)->mu), unlocked((lv), (expr)))
/* The same for a command that needs a scene (msg and size are the
 * caller's). */
#define SCENE_LOCKED(lv, expr) LOCKED(lv, (lv)->sc ? (expr) : live_no_scene(msg, size))

static int enable(struct live *lv, char *msg, size_t size)
{
	switch (lv->state) {
	case LIVE_DISABLED:
		break;
	case LIVE_ESTOPPED:
	case LIVE_FAULTED:
		snprintf(msg, size, "%s: reset first (%s)", live_state_name(lv->state), lv->reason);
		return -EPERM;
	default:
		if (lv->running)
			return 0; /* enabled already */
		break;
	}
	if (atomic_load(&lv->estop_req)) {
		snprintf(msg, size, "e-stopped: reset first");
		return -EPERM;
	}
	return live_run_start(lv, msg, size);
}

int live_enable(struct live *lv, char *msg, size_t size)
{
	return SCENE_LOCKED(lv, enable(lv, msg, size));
}

/* A command of no arguments to the loop while it runs (disable, stop):
 * without a loop there is nothing to bring to rest. */
static int to_running(struct live *lv, enum loop_cmd_kind kind, char *msg, size_t size)
{
	struct loop_cmd c = { .kind = kind };
	struct loop_ack a;

	if (!lv->running)
		return 0;
	return live_send(lv, &c, &a, msg, size);
}

int live_disable(struct live *lv, char *msg, size_t size)
{
	return LOCKED(lv, to_running(lv, LOOP_CMD_DISABLE, msg, size));
}

static int jog(struct live *lv, uint64_t client, uint32_t out, double speed, uint64_t seq,
	       char *msg, size_t size)
{
	struct loop_cmd c = { .kind = LOOP_CMD_JOG, .out = out, .speed = speed };
	struct loop_ack a;

	if (out >= lv->rig.nout) {
		snprintf(msg, size, "output %u: the rig has %u", out, lv->rig.nout);
		return -EINVAL;
	}
	if (!(fabs(speed) <= 1)) {
		snprintf(msg, size, "speed %g: a fraction of the velocity limit, -1 to 1", speed);
		return -ERANGE;
	}
	if (lv->rig.out[out].vel_mode) {
		snprintf(msg, size, "%s is a speed (velocity mode): it cannot be jogged",
			 lv->rig.out[out].channel);
		return -EINVAL;
	}
	if (client != lv->jog_client) {
		lv->jog_client = client;
		memset(lv->jog_seq, 0, sizeof(lv->jog_seq));
	}
	if (seq <= lv->jog_seq[out])
		return 0; /* doubled or stale: ignored */
	lv->jog_seq[out] = seq;
	return live_send(lv, &c, &a, msg, size);
}

int live_jog(struct live *lv, uint64_t client, uint32_t out, double speed, uint64_t seq,
	     char *msg, size_t size)
{
	return SCENE_LOCKED(lv, jog(lv, client, out, speed, seq, msg, size));
}

void live_client_gone(struct live *lv, uint64_t client)
{
	struct loop_cmd c = { .kind = LOOP_CMD_JOG };
	struct loop_ack a;
	char msg[LIVE_MSG];
	uint32_t i;

	pthread_mutex_lock(&lv->mu);
	if (client == lv->jog_client && lv->running) {
		for (i = 0; i < lv->rig.nout; i++) {
			if (!lv->jog_seq[i])
				continue;
			c.out = i;
			live_send(lv, &c, &a, msg, sizeof(msg));
		}
		if (lv->space_seq) { /* a jog of the camera or a node: every output at 0 */
			struct loop_cmd v = { .kind = LOOP_CMD_JOG_VEC };

			live_send(lv, &v, &a, msg, sizeof(msg));
		}
		lv->jog_client = 0;
		lv->space_seq = 0;
		memset(lv->jog_seq, 0, sizeof(lv->jog_seq));
	}
	pthread_mutex_unlock(&lv->mu);
}

static int move_pose(struct live *lv, const mot_q32 *pose, int64_t frame, char *msg,
		     size_t size)
{
	struct loop_cmd c = { .kind = LOOP_CMD_MOVE, .frame = frame };
	struct loop_ack a;

	memcpy(c.pose, pose, lv->rig.nout * sizeof(*pose));
	return live_send(lv, &c, &a, msg, size);
}

static int go_to(struct live *lv, int64_t frame, char *msg, size_t size)
{
	const struct play_source *s = &lv->sc->twin.s;
	mot_q32 pose[LOOP_LIVE_OUT_MAX];
	uint32_t sat = 0;
	int rc;

	if (frame < 0 || frame > INT32_MAX) {
		snprintf(msg, size, "frame %lld: 0 to 2147483647", (long long)frame);
		return -ERANGE;
	}
	src_eval(&lv->sc->twin.s, (mot_q32)frame * MOT_Q32_ONE, pose, &sat);
	if (sat) {
		snprintf(msg, size, "frame %lld: the scene's arithmetic saturates there",
			 (long long)frame);
		return -ERANGE;
	}
	(void)s;
	rc = move_pose(lv, pose, frame, msg, size);
	if (!rc)
		lv->goto_frame = frame;
	else if (rc == -ERANGE)
		snprintf(msg + strlen(msg), size - strlen(msg), " at frame %lld",
			 (long long)frame);
	return rc;
}

int live_goto(struct live *lv, int64_t frame, char *msg, size_t size)
{
	return SCENE_LOCKED(lv, go_to(lv, frame, msg, size));
}

static int step(struct live *lv, int dir, char *msg, size_t size)
{
	const struct play_source *s = &lv->sc->twin.s;
	int64_t f = lv->at_frame;

	if (f < 0)
		f = dir > 0 ? s->frame_first - 1 : s->frame_last + 1; /* off any frame */
	f += dir > 0 ? 1 : -1;
	if (f < 0) {
		snprintf(msg, size, "no frame before 0");
		return -ERANGE;
	}
	return go_to(lv, f, msg, size);
}

int live_step(struct live *lv, int dir, char *msg, size_t size)
{
	return SCENE_LOCKED(lv, step(lv, dir, msg, size));
}

static int move(struct live *lv, const double *pose, uint32_t n, char *msg, size_t size)
{
	mot_q32 q[LOOP_LIVE_OUT_MAX];
	uint32_t i;

	if (n != lv->rig.nout) {
		snprintf(msg, size, "%u values for %u outputs", n, lv->rig.nout);
		return -EINVAL;
	}
	for (i = 0; i < n; i++) {
		const struct rig_out *o = &lv->rig.out[i];
		double v = isnan(pose[i]) ? lv->snap.out[i].sp : pose[i];
		double core = o->unit == SRC_UNIT_TURNS ? v / 360.0 : v;

		if (!isfinite(v) || !sd_to_q32(core, &q[i])) {
			snprintf(msg, size, "%s: %g is outside the core's range", o->channel, v);
			return -ERANGE;
		}
	}
	lv->goto_frame = -1;
	return move_pose(lv, q, -1, msg, size);
}

int live_move(struct live *lv, const double *pose, uint32_t n, char *msg, size_t size)
{
	return SCENE_LOCKED(lv, move(lv, pose, n, msg, size));
}

static int ticks(double v, bool ms, uint32_t hz, int64_t min, int64_t *out, const char *name,
		 char *msg, size_t size)
{
	int rc = ms ? num_ms_to_ticks(v, hz, NUM_ROUND_NEAREST, min, NUM_TICKS_MAX, out) :
		      num_s_to_ticks(v, hz, NUM_ROUND_NEAREST, min, NUM_TICKS_MAX, out);

	if (rc)
		snprintf(msg, size, "%s %g: out of range (at least a tick, at most 1e9 s)", name,
			 v);
	return rc;
}

static int play(struct live *lv, const struct live_play *p, char *msg, size_t size)
{
	const struct play_source *s = &lv->sc->twin.s;
	uint32_t hz = s->timing.tick_hz, i;
	struct loop_cmd c = { .kind = LOOP_CMD_PLAY };
	struct frame_list fl = { 0 };
	struct loop_ack a;
	struct loop_cfg *cfg = &c.cfg;
	struct lim_run run;
	int64_t from = p->has_from ? p->from : s->frame_first;
	int64_t to = p->has_to ? p->to : s->frame_last;
	int rc;

	if (from < 0 || to < 0 || from > INT32_MAX || to > INT32_MAX) {
		snprintf(msg, size, "from/to: frame numbers 0 to 2147483647");
		return -ERANGE;
	}
	if (p->frames && !p->step) {
		snprintf(msg, size, "frames is for step mode");
		return -EINVAL;
	}
	if (p->step && (p->loop || p->ping_pong)) {
		snprintf(msg, size, "loop and ping_pong are for continuous mode");
		return -EINVAL;
	}
	if (p->loop && p->ping_pong) {
		snprintf(msg, size, "loop or ping_pong, not both");
		return -EINVAL;
	}
	if (p->passes && !p->loop && !p->ping_pong) {
		snprintf(msg, size, "passes goes with loop or ping_pong");
		return -EINVAL;
	}
	if (p->shutter && !p->step) {
		snprintf(msg, size, "shutter is go-motion, for step mode");
		return -EINVAL;
	}
	if (p->shutter && !gomo_shutter_of_angle(p->shutter, &cfg->shutter)) {
		snprintf(msg, size, "shutter %g: an angle in degrees, above 0 and at most 360",
			 p->shutter);
		return -ERANGE;
	}
	if (run_check_shutter(&s->timing, cfg->shutter, msg, size))
		return -ERANGE;
	if (p->passes < 0 || p->passes > INT32_MAX) {
		snprintf(msg, size, "passes %lld: 1 to 2147483647", (long long)p->passes);
		return -ERANGE;
	}
	if (!p->step && to < from) {
		snprintf(msg, size, "from %lld is after to %lld", (long long)from, (long long)to);
		return -EINVAL;
	}
	if (!p->step && p->ping_pong && to == from) {
		snprintf(msg, size, "ping_pong needs at least two frames");
		return -EINVAL;
	}
	cfg->mode = p->step ? LOOP_MODE_STEP : LOOP_MODE_CONTINUOUS;
	cfg->from = from;
	cfg->to = to;
	cfg->loop = p->loop;
	cfg->ping_pong = p->ping_pong;
	cfg->passes = p->passes;
	if (ticks(p->settle_ms, true, hz, 0, &cfg->settle_ticks, "settle", msg, size) ||
	    ticks(p->exposure_ms, true, hz, 0, &cfg->exposure_ticks, "exposure", msg, size) ||
	    ticks(p->timeout_s, false, hz, 1, &cfg->in_position_timeout_ticks, "timeout", msg,
		  size) ||
	    (p->duration_s > 0 &&
	     ticks(p->duration_s, false, hz, 1, &cfg->max_ticks, "duration", msg, size)))
		return -ERANGE;
	cfg->ready_timeout_ticks = cfg->in_position_timeout_ticks;
	if (p->step) {
		rc = p->frames ? frames_parse(&fl, p->frames, msg, (unsigned)size) :
				 frames_range(&fl, from, to);
		if (rc) {
			if (!p->frames)
				snprintf(msg, size, "out of memory");
			return rc;
		}
		if (fl.n > LOOP_LIVE_FRAME_ITEMS) {
			snprintf(msg, size, "frames: %u items, at most %d", fl.n,
				 LOOP_LIVE_FRAME_ITEMS);
			frames_free(&fl);
			return -E2BIG;
		}
		c.nframes = fl.n;
		for (i = 0; i < fl.n; i++)
			c.frames[i] = fl.items[i];
		from = INT64_MAX;
		to = INT64_MIN;
		for (i = 0; i < fl.n; i++) {
			int64_t lo = fl.items[i].first < fl.items[i].last ? fl.items[i].first :
									    fl.items[i].last;
			int64_t hi = fl.items[i].first ^ fl.items[i].last ^ lo;

			from = lo < from ? lo : from;
			to = hi > to ? hi : to;
		}
		frames_free(&fl);
	}
	/* held to exactly what strand check verifies, as strand play is */
	run = (struct lim_run){ .from = from, .to = to, .loop = p->loop, .ping_pong = p->ping_pong,
				.passes = p->passes, .step = p->step, .shutter = cfg->shutter,
				.expose_first = from, .expose_last = to };
	if (cfg->shutter) {
		/* go-motion runs the scene's own motion over its span and the
		 * frames shot (as strand play does) */
		cfg->from = run.from = from < s->frame_first ? from : s->frame_first;
		cfg->to = run.to = to > s->frame_last ? to : s->frame_last;
	}
	rc = live_scene_check(lv, lv->sc, &run, msg, size);
	if (!rc)
		rc = live_journal_open(lv, &c, msg, size);
	if (rc)
		return rc;
	rc = live_send(lv, &c, &a, msg, size);
	if (!rc) {
		lv->goto_frame = -1;
		lv->jr_seq = c.seq;
	} else {
		live_journal_close(lv); /* not taken: the loop never had it */
	}
	return rc;
}

int live_play(struct live *lv, const struct live_play *p, char *msg, size_t size)
{
	return SCENE_LOCKED(lv, play(lv, p, msg, size));
}

/* ---- go-motion through a front end's poses ---- */

/* The path through g's poses at frames g->frame - 1, g->frame and
 * g->frame + 1, at shutter / exposure_ms frames a second (thousandths per
 * ms): its shutter fraction of a frame then lasts exposure_ms exactly. */
static int gomo_path(struct live *lv, const struct live_gomo *g, char *msg, size_t size)
{
	const struct mot_timing *t = &lv->sc->src.s.timing;
	const int64_t *pose[3] = { g->prev, g->at, g->next };
	uint32_t i, k, n = lv->rig.nout;
	int rc;

	if (g->frame < 1 || g->frame > INT32_MAX - 1) {
		snprintf(msg, size, "frame %lld: 1 to 2147483646", (long long)g->frame);
		return -ERANGE;
	}
	if (g->shutter < 1 || g->shutter > 1000) {
		snprintf(msg, size, "shutter %u: thousandths of a frame, 1 to 1000", g->shutter);
		return -ERANGE;
	}
	if (g->exposure_ms < 1 || g->exposure_ms > 3600000) {
		snprintf(msg, size, "exposure %u ms: 1 ms to an hour", g->exposure_ms);
		return -ERANGE;
	}
	for (i = 0; i < n; i++) {
		lv->path_names[i] = lv->rig.out[i].channel;
		lv->path_units[i] = lv->rig.out[i].unit;
	}
	rc = source_path_init(&lv->path, "go-motion", n, lv->path_names, lv->path_units,
			      g->shutter, g->exposure_ms, t->tick_hz, g->frame - 1, 3);
	if (rc) {
		snprintf(msg, size, "go-motion: an exposure of %u ms with a shutter of %u "
			 "thousandths is faster than a frame a tick", g->exposure_ms, g->shutter);
		return -ERANGE;
	}
	for (i = 0; i < n; i++)
		for (k = 0; k < 3; k++) {
			double v = live_units(lv, i, pose[k][i]);
			double core = lv->rig.out[i].unit == SRC_UNIT_TURNS ? v / 360.0 : v;

			if (lv->rig.out[i].vel_mode) {
				lv->path.keys[k][i] = 0; /* a speed holds still */
				continue;
			}
			if (!isfinite(v) || !sd_to_q32(core, &lv->path.keys[k][i])) {
				snprintf(msg, size, "%s: %lld counts are outside the core's range",
					 lv->rig.out[i].channel, (long long)pose[k][i]);
				return -ERANGE;
			}
		}
	return 0;
}

static void first_violation(void *ctx, const struct lim_violation *v)
{
	struct run_check *c = ctx;

	if (c->res.violations == 1)
		c->first = *v;
}

/* The go-motion's run-up in ticks, as the loop will plan it (its ramps,
 * at least the triggers' lead: loop_gomo_plan), and strand check's walk
 * of the whole frame (run-up, exposure, run-out): 0, or -EDOM with the
 * first violation in msg. */
static int gomo_plan(struct live *lv, const struct live_gomo *g, mot_q32 s, int64_t *ticks,
		     char *msg, size_t size)
{
	const struct mot_timing *t = &lv->path.s.timing;
	uint32_t i, n = lv->rig.nout, sat = 0;
	struct lim_channel ch[LOOP_LIVE_OUT_MAX];
	bool extend[LOOP_LIVE_OUT_MAX];
	mot_q32 mem[TIMELINE_WORDS(LOOP_LIVE_OUT_MAX)], x0[LOOP_LIVE_OUT_MAX], x1[LOOP_LIVE_OUT_MAX];
	struct run_check c = { .ch = ch, .n = n };
	struct lim_run run = { .from = g->frame - 1, .to = g->frame + 1, .step = true,
			       .shutter = s, .expose_first = g->frame, .expose_last = g->frame };
	struct timeline tl;
	int64_t k0, k1, lead = 0;
	char line[LIVE_MSG];
	int rc;

	for (i = 0; i < lv->rig.ntrig; i++)
		if (-lv->rig.trig[i].offset > lead)
			lead = -lv->rig.trig[i].offset;
	for (i = 0; i < n; i++) {
		const struct rig_out *o = &lv->rig.out[i];

		ch[i] = (struct lim_channel){ .name = o->channel, .src = i, .unit = o->unit,
					      .lim = { o->min, o->max, o->vmax, o->amax,
						       o->vel_mode } };
		extend[i] = timeline_extends(o->unit);
	}
	if (gomo_window(t, g->frame, s, &k0, &k1)) {
		snprintf(msg, size, "go-motion: an exposure of %u ms is shorter than two ticks",
			 g->exposure_ms);
		return -ERANGE;
	}
	/* the loop's run-up: the longest ramp into the exposure's first tick */
	timeline_init(&tl, &lv->path.s, n, extend, g->frame - 1, g->frame + 1, mem, &sat);
	timeline_eval(&tl, k0, x0, &sat);
	timeline_eval(&tl, k0 + 1, x1, &sat);
	*ticks = lead;
	for (i = 0; i < n; i++) {
		struct runup_ramp r;
		mot_q32 start;

		if (!runup_plan(&r, x0[i], x1[i], t->tick_hz, lv->rig.out[i].amax, &start) &&
		    r.n > *ticks)
			*ticks = r.n;
	}
	/* the walk, the loop's lead included */
	run.lead = lead;
	rc = lim_check(&lv->path.s, ch, n, &run, first_violation, &c, &c.res);
	if (!rc && (sat || c.res.sat))
		rc = -ERANGE;
	if (rc) {
		snprintf(msg, size, "go-motion: %s", rc == -ERANGE ? "its arithmetic saturates" :
			 strerror(-rc));
		return rc;
	}
	if (!c.res.violations)
		return 0;
	run_check_line(line, sizeof(line), &c, &c.first);
	snprintf(msg, size, "go-motion: %u limit violation%s, the first: %s", c.res.violations,
		 c.res.violations == 1 ? "" : "s", line);
	return -EDOM;
}

static int gomo(struct live *lv, const struct live_gomo *g, int64_t *delay_ms, char *msg,
		size_t size)
{
	const struct mot_timing *t = &lv->sc->src.s.timing;
	struct loop_cmd c = { .kind = LOOP_CMD_PLAY };
	struct loop_cfg *cfg = &c.cfg;
	struct loop_ack a;
	int64_t ticks;
	mot_q32 s;
	int rc;

	if (lv->state != LIVE_ENABLED || !lv->running || lv->snap.state != LIVE_ENABLED ||
	    lv->snap.cmd_seen < lv->path_seq) {
		snprintf(msg, size, "go-motion: the drives are %s: %s",
			 live_state_name(lv->snap.state), lv->running ?
			 "wait until they are at rest" : "enable them first");
		return lv->running ? -EBUSY : -EPERM;
	}
	rc = gomo_path(lv, g, msg, size);
	if (rc)
		return rc;
	/* thousandths of a frame in Q32.32, rounded to nearest */
	s = (mot_q32)(((uint64_t)g->shutter << 32) + 500) / 1000;
	if (gomo_shutter_check(&lv->path.s.timing, s)) {
		snprintf(msg, size, "go-motion: an exposure of %u ms is shorter than two ticks",
			 g->exposure_ms);
		return -ERANGE;
	}
	rc = gomo_plan(lv, g, s, &ticks, msg, size);
	if (rc && !(rc == -EDOM && lv->o.force))
		return rc;
	/* whole milliseconds from the go, and a run-up as long */
	*delay_ms = (ticks * 1000 + t->tick_hz - 1) / t->tick_hz;
	cfg->mode = LOOP_MODE_STEP;
	cfg->from = g->frame - 1;
	cfg->to = g->frame + 1;
	cfg->shutter = s;
	cfg->gomo_src = &lv->path.s;
	cfg->gomo_wait = true;
	cfg->gomo_runup_ticks = (*delay_ms * t->tick_hz + 999) / 1000;
	cfg->in_position_timeout_ticks = 10 * (int64_t)t->tick_hz;
	cfg->ready_timeout_ticks = cfg->in_position_timeout_ticks;
	c.nframes = 1;
	c.frames[0] = (struct frame_item){ g->frame, g->frame, 1 };
	rc = live_journal_open(lv, &c, msg, size);
	if (rc)
		return rc;
	rc = live_send(lv, &c, &a, msg, size);
	lv->path_seq = c.seq;
	if (!rc) {
		lv->goto_frame = -1;
		lv->gomo_armed = true;
		lv->jr_seq = c.seq;
	} else {
		live_journal_close(lv); /* not taken: the loop never had it */
	}
	return rc;
}

int live_gomo(struct live *lv, const struct live_gomo *g, int64_t *delay_ms, char *msg,
	      size_t size)
{
	return SCENE_LOCKED(lv, gomo(lv, g, delay_ms, msg, size));
}

static int gomo_go(struct live *lv, char *msg, size_t size)
{
	struct loop_cmd c = { .kind = LOOP_CMD_GO };
	struct loop_ack a;
	int rc;

	if (!lv->gomo_armed) {
		snprintf(msg, size, "go: no go-motion is armed");
		return -EBUSY;
	}
	rc = live_send(lv, &c, &a, msg, size);
	if (rc == -EBUSY)
		snprintf(msg, size, "go: the go-motion is not armed yet (%s)",
			 lv->snap.loop_state ? lv->snap.loop_state : "moving");
	if (!rc)
		lv->gomo_armed = false;
	return rc;
}

int live_gomo_go(struct live *lv, char *msg, size_t size)
{
	return LOCKED(lv, gomo_go(lv, msg, size));
}

int live_stop(struct live *lv, char *msg, size_t size)
{
	return LOCKED(lv, to_running(lv, LOOP_CMD_STOP, msg, size));
}

void live_estop(struct live *lv)
{
	atomic_store(&lv->estop_req, true);
	/* a start of the drives under way (an enable) gives up */
	hal_cancel_request(&lv->cancel);
}

static int reset(struct live *lv, char *msg, size_t size)
{
	if (lv->running) {
		snprintf(msg, size, "%s: nothing to reset", live_state_name(lv->state));
		return lv->state == LIVE_ENABLED ? 0 : -EBUSY;
	}
	live_drain_inputs(lv);
	if (live_estop_input(lv, msg, size))
		return -EPERM;
	atomic_store(&lv->estop_req, false);
	hal_cancel_init(&lv->cancel);
	lv->state = LIVE_DISABLED;
	lv->reason[0] = 0;
	return 0;
}

int live_reset(struct live *lv, char *msg, size_t size)
{
	return LOCKED(lv, reset(lv, msg, size));
}

static int ping(struct live *lv, int64_t arrival_ns, int64_t *latency_ns, char *msg,
		size_t size)
{
	struct loop_cmd c = { .kind = LOOP_CMD_NOP, .arrival_ns = arrival_ns };
	struct loop_ack a;
	int rc = live_send(lv, &c, &a, msg, size);

	*latency_ns = rc ? 0 : a.latency_ns;
	return rc;
}

int live_ping(struct live *lv, int64_t arrival_ns, int64_t *latency_ns, char *msg,
	      size_t size)
{
	return SCENE_LOCKED(lv, ping(lv, arrival_ns, latency_ns, msg, size));
}
