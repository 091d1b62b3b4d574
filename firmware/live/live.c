/* SPDX-License-Identifier: MIT */
/* live.c - a live session: open, close, the scene's versions, the service
 * round, the snapshot (live.h). */
#define _GNU_SOURCE
#include "live_priv.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check/pools.h"
#include "check/run_check.h"
#include "hal/rt.h"
#include "play/play.h"

/* ---- a version of the scene ---- */

static int scene_err(char *err, size_t size, const char *path, const struct load_err *e)
{
	if (e->line)
		snprintf(err, size, "%s:%u:%u: %s", path, e->line, e->col, e->msg);
	else
		snprintf(err, size, "%s: %s", path, e->msg);
	return e->code ? e->code : -EINVAL;
}

int live_scene_parse(struct live_scene **out, const char *path, const char *text, size_t len,
		     char *err, size_t errsize)
{
	struct live_scene *s = calloc(1, sizeof(*s));
	struct load_err e;
	int rc;

	*out = NULL;
	if (!s || !(s->text = malloc(len + 1))) {
		free(s);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	memcpy(s->text, text, len);
	s->text[len] = 0;
	s->len = len;
	snprintf(s->path, sizeof(s->path), "%s", path);
	rc = scene_file_parse(&s->sf, s->path, s->text, len, &e);
	if (rc) {
		live_scene_free(s);
		return scene_err(err, errsize, path, &e);
	}
	s->loaded = true;
	rc = scene_file_build(&s->sf, &s->b, &e);
	if (rc) {
		live_scene_free(s);
		return scene_err(err, errsize, path, &e);
	}
	s->built = true;
	if (source_scene_init(&s->src, &s->sf.desc, &s->b.sc) ||
	    (s->has_src = true, source_scene_init(&s->twin, &s->sf.desc, &s->b.sc))) {
		live_scene_free(s);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	s->has_twin = true;
	*out = s;
	return 0;
}

int live_scene_open(struct live_scene **out, const char *path, char *err, size_t errsize)
{
	FILE *f = fopen(path, "rb");
	char *buf;
	long n;
	int rc;

	*out = NULL;
	if (!f) {
		rc = -errno;
		snprintf(err, errsize, "%s: %s", path, strerror(errno));
		return rc;
	}
	if (fseek(f, 0, SEEK_END) || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET)) {
		rc = -errno;
		fclose(f);
		snprintf(err, errsize, "%s: %s", path, strerror(-rc));
		return rc;
	}
	if ((unsigned long)n > LOAD_MAX_BYTES) {
		fclose(f);
		snprintf(err, errsize, "%s: larger than %u bytes", path, LOAD_MAX_BYTES);
		return -EFBIG;
	}
	buf = malloc((size_t)n + 1);
	if (!buf || fread(buf, 1, (size_t)n, f) != (size_t)n) {
		rc = buf ? -EIO : -ENOMEM;
		free(buf);
		fclose(f);
		snprintf(err, errsize, "%s: %s", path, strerror(-rc));
		return rc;
	}
	fclose(f);
	rc = live_scene_parse(out, path, buf, (size_t)n, err, errsize);
	free(buf);
	return rc;
}

/* src's channels: the rig's outputs', in their order. */
static int select_rig(struct play_source *src, const struct rig *rig)
{
	uint32_t idx[LOOP_LIVE_OUT_MAX], i;

	for (i = 0; i < rig->nout && i < LOOP_LIVE_OUT_MAX; i++)
		idx[i] = rig->out[i].src;
	return src_select(src, idx, i);
}

int live_scene_bind(struct live_scene *s, const struct rig *rig)
{
	int rc = select_rig(&s->src.s, rig);

	return rc ? rc : select_rig(&s->twin.s, rig);
}

void live_scene_free(struct live_scene *s)
{
	if (!s)
		return;
	if (s->has_twin)
		source_scene_free(&s->twin);
	if (s->has_src)
		source_scene_free(&s->src);
	if (s->built)
		scene_built_free(&s->b);
	if (s->loaded)
		scene_file_free(&s->sf);
	free(s->text);
	free(s);
}

int live_scene_check(struct live *lv, struct live_scene *s, struct lim_run *run, char *msg,
		     size_t size)
{
	struct run_check c = { .out = NULL };
	char line[LIVE_MSG];
	uint32_t pools;
	int rc = run_check_options(run, msg, size);

	if (rc)
		return rc;
	/* on the twin, which the loop never reads; its channels the rig's
	 * again afterwards (run_check selects its own) */
	rc = run_check(&c, &s->twin, lv->rd, run);
	if (lv->rig_built && select_rig(&s->twin.s, &lv->rig) && !rc)
		rc = -ENOMEM;
	if (rc) {
		snprintf(msg, size, "%s: the limit check: %s", s->path, strerror(-rc));
	} else if (c.res.sat) {
		snprintf(msg, size, "%s: the core's arithmetic saturated at frame %.10g: values "
			 "too large for its Q32.32 format", s->path, c.res.sat_frame);
		rc = -ERANGE;
	} else if (!c.res.violations && !lv->o.force &&
		   (pools = lim_pools(NULL, NULL, &s->sf.desc, &s->b.sc, run->to, line,
				      sizeof(line)))) {
		/* a particle pool that runs out, as strand play refuses it */
		snprintf(msg, size, "%s: strand check finds %u violation%s, the first: %s", s->path,
			 pools, pools == 1 ? "" : "s", line);
		rc = -EDOM;
	} else if (c.res.violations && !lv->o.force) {
		run_check_line(line, sizeof(line), &c, &c.first);
		snprintf(msg, size, "%s: strand check finds %u limit violation%s, the first: %s "
			 "(strand check lists them all; --force plays it, clamping every setpoint "
			 "to its limits)", s->path, c.res.violations,
			 c.res.violations == 1 ? "" : "s", line);
		rc = -EDOM;
	}
	run_check_free(&c);
	return rc;
}

/* ---- the journal ---- */

/* The session's journal (o.journal_file), as strand play opens its own,
 * without an end: every run's shots go into it. */
static int journal_up(struct live *lv, char *err, size_t errsize)
{
	int rc = play_journal_open(&lv->sess_jr, lv->o.journal_file, &lv->rig, &lv->sc->src.s,
				   JOURNAL_MODE_STEP |
				   (lv->o.journal_gomo ? JOURNAL_MODE_GOMO : 0), -1,
				   hal_clock_wall(&lv->clk), err, errsize);

	if (!rc)
		lv->has_sess_jr = true;
	return rc;
}

/* ---- open and close ---- */

static int data_dir_of(struct live *lv, const char *scene)
{
	const char *slash;

	if (lv->o.data_dir) {
		snprintf(lv->data_dir, sizeof(lv->data_dir), "%s", lv->o.data_dir);
		return 0;
	}
	slash = scene ? strrchr(scene, '/') : NULL;
	if (!slash)
		snprintf(lv->data_dir, sizeof(lv->data_dir), ".");
	else
		snprintf(lv->data_dir, sizeof(lv->data_dir), "%.*s", (int)(slash - scene), scene);
	return 0;
}

static int rings_new(struct live *lv, char *err, size_t errsize)
{
	free(lv->st_buf);
	free(lv->st);
	lv->st_size = loop_live_status_size(lv->rig.nout);
	lv->st_buf = calloc(LIVE_STATUS_RING, lv->st_size);
	lv->st = calloc(1, lv->st_size);
	if (!lv->st_buf || !lv->st) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	hal_ring_init(&lv->status, lv->st_buf, LIVE_STATUS_RING, lv->st_size);
	hal_ring_init(&lv->cmds, lv->cmd_buf, LIVE_CMD_RING, sizeof(struct loop_cmd));
	hal_ring_init(&lv->acks, lv->ack_buf, LIVE_CMD_RING, sizeof(struct loop_ack));
	return 0;
}

/* Build the rig for the present scene and start its devices, the drives
 * then disabled (an orderly stop of each axis device). */
int live_rig_up(struct live *lv, char *err, size_t errsize)
{
	struct rig_opts ro;
	uint32_t i;
	int rc;

	lv->rig_sc = lv->sc;
	lv->rd = &lv->sc->sf.rig;
	if (!lv->rd->noutputs && !lv->rd->ntriggers) {
		if (!lv->o.sim) {
			snprintf(err, errsize, "%s: the scene describes no rig (devices:, "
				 "outputs:, triggers:); serve it on a simulated one with --sim",
				 lv->sc->path);
			return -EINVAL;
		}
		if (rig_auto_build(&lv->ra, &lv->sc->sf.desc, &lv->sc->src.s,
				   lv->sc->src.s.frame_first)) {
			snprintf(err, errsize, "out of memory");
			return -ENOMEM;
		}
		lv->rd = &lv->ra.d;
	}
	memset(&ro, 0, sizeof(ro));
	ro.sim = lv->o.sim;
	ro.events = lv->plan.events;
	ro.io = lv->plan.io;
	ro.warn = stderr;
	ro.cancel = &lv->cancel;
	rc = rig_build(&lv->rig, lv->rd, &lv->sc->src.s, &lv->clk, &ro, err, errsize);
	if (rc)
		return rc;
	lv->rig_built = true;
	if (lv->rig.nout > LOOP_LIVE_OUT_MAX) {
		snprintf(err, errsize, "%u outputs: live control takes at most %d", lv->rig.nout,
			 LOOP_LIVE_OUT_MAX);
		return -EINVAL;
	}
	rc = live_scene_bind(lv->sc, &lv->rig);
	if (rc) {
		snprintf(err, errsize, "out of memory");
		return rc;
	}
	rc = rig_start(&lv->rig, err, errsize);
	if (rc)
		return rc;
	lv->rig_started = true;
	for (i = 0; i < lv->rig.naxes; i++)
		hal_axis_stop(lv->rig.axes[i]);
	return rings_new(lv, err, errsize);
}

void live_rig_down(struct live *lv)
{
	if (lv->rig_started)
		rig_stop(&lv->rig);
	lv->rig_started = false;
	if (lv->rig_built)
		rig_free(&lv->rig);
	lv->rig_built = false;
	rig_auto_free(&lv->ra);
	memset(&lv->ra, 0, sizeof(lv->ra));
	lv->rd = NULL;
	if (lv->rig_sc != lv->sc)
		live_scene_free(lv->rig_sc);
	lv->rig_sc = NULL;
}

void live_scene_swap(struct live *lv, struct live_scene *s)
{
	if (lv->sc != lv->rig_sc)
		live_scene_free(lv->sc);
	lv->sc = s;
}

int live_open(struct live **out, const char *scene, const struct live_opts *o, char *err,
	      size_t errsize)
{
	struct live *lv = calloc(1, sizeof(*lv));
	int rc;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (!lv || !(lv->cmd_buf = calloc(LIVE_CMD_RING, sizeof(struct loop_cmd))) ||
	    !(lv->ack_buf = calloc(LIVE_CMD_RING, sizeof(struct loop_ack)))) {
		if (lv)
			free(lv->cmd_buf);
		free(lv);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	lv->o = *o;
	if (!(lv->o.deadman_ms > 0))
		lv->o.deadman_ms = 250;
	/* samples at 250 Hz: the clients get at most 50 a second, but a jog
	 * of the camera or a node turns its direction from where the rig is,
	 * and a sample is as old as its period */
	if (!lv->o.status_hz)
		lv->o.status_hz = 250;
	if (lv->o.virtual_clock) {
		lv->o.rt.priority = 0;
		lv->o.rt.pm_qos = false;
	}
	pthread_mutex_init(&lv->mu, NULL);
	pthread_mutex_init(&lv->snap_mu, NULL);
	hal_clock_init(&lv->clk, lv->o.virtual_clock);
	hal_cancel_init(&lv->cancel);
	rt_plan_make(&lv->plan, &lv->o.rt);
	lv->at_frame = -1;
	atomic_init(&lv->last_frame, -1);
	lv->goto_frame = -1;
	lv->state = LIVE_DISABLED;
	data_dir_of(lv, scene);
	/* without a scene the session waits for a load */
	rc = scene ? live_scene_open(&lv->sc, scene, err, errsize) : 0;
	if (!rc && scene)
		rc = live_rig_up(lv, err, errsize);
	if (!rc && lv->o.journal_file && lv->sc)
		rc = journal_up(lv, err, errsize);
	if (rc) {
		live_close(lv);
		return rc;
	}
	lv->snap.state = LIVE_DISABLED;
	lv->snap.loop_state = "disabled";
	lv->snap.frame = -1;
	lv->snap.journal_frames = -1;
	live_publish_scene(lv);
	*out = lv;
	return 0;
}

void live_close(struct live *lv)
{
	if (!lv)
		return;
	STRAND_ASSERT_NOT_RT();
	if (lv->running) {
		live_signal(lv, 1);
		while (!atomic_load(&lv->done))
			nanosleep(&(struct timespec){ .tv_nsec = 1000000 }, NULL);
		live_run_end(lv);
	}
	loop_free(lv->L);
	live_rig_down(lv);
	if (lv->has_sess_jr)
		journal_close(&lv->sess_jr);
	live_scene_free(lv->sc);
	free(lv->st_buf);
	free(lv->st);
	free(lv->cmd_buf);
	free(lv->ack_buf);
	pthread_mutex_destroy(&lv->mu);
	pthread_mutex_destroy(&lv->snap_mu);
	free(lv);
}

/* ---- the service round and the snapshot ---- */

double live_file_units(const struct live *lv, uint32_t i, double v)
{
	return rig_file_units(lv->rig.out[i].unit, v);
}

static enum live_state state_of(const struct loop_live_status *st)
{
	switch ((enum loop_state)st->s.state) {
	case LOOP_HOLD:
		return LIVE_ENABLED;
	case LOOP_STOPPING:
	case LOOP_ENDED:
		return LIVE_STOPPING;
	default:
		return LIVE_MOVING;
	}
}

/* A sample into the snapshot (snap_mu held). */
static void take_sample(struct live *lv, const struct loop_live_status *st)
{
	struct live_snap *s = &lv->snap;
	uint32_t i;

	s->state = state_of(st);
	s->tick = st->s.tick;
	s->t_ns = st->t_ns;
	s->loop_state = loop_state_name((enum loop_state)st->s.state);
	s->fired = st->s.fired;
	s->total = st->s.total;
	s->lat_max_ns = st->s.lat_max_ns;
	s->lat_min_ns = st->lat_min_ns;
	s->lat_n = (uint64_t)st->lat_n;
	s->lat_avg_ns = st->lat_n ? st->lat_sum_ns / st->lat_n : 0;
	s->overruns = st->s.overruns;
	lv->at_frame = st->at_frame;
	if (st->at_frame >= 0)
		atomic_store(&lv->last_frame, st->at_frame);
	s->frame = st->at_frame;
	if (st->rep.end != LOOP_END_NONE)
		play_report_describe(&lv->rig, &lv->sc->src.s.timing,
				     &(struct loop_result){ .frames_fired = st->s.fired }, &st->rep,
				     NULL, s->reason, sizeof(s->reason));
	s->nout = st->n;
	for (i = 0; i < st->n && i < LOOP_LIVE_OUT_MAX; i++) {
		s->out[i] = st->out[i];
		s->out[i].sp = live_file_units(lv, i, st->out[i].sp);
		s->out[i].act = live_file_units(lv, i, st->out[i].act);
		s->out[i].fe = live_file_units(lv, i, st->out[i].fe);
		s->out[i].vel = live_file_units(lv, i, st->out[i].vel);
	}
	/* a run's loop counts from the commands it took itself */
	s->cmd_seen = st->cmd_seq > lv->seq_run ? st->cmd_seq : lv->seq_run;
	if (lv->has_sess_jr)
		s->journal_frames = atomic_load(&lv->sess_jr.written);
	s->taken_ns = hal_mono_ns();
	lv->seg_active = st->seg_first >= 0;
	lv->seen_seq = st->cmd_seq;
	s->serial = ++lv->serial;
}

int live_service(struct live *lv)
{
	bool any = false;

	/* chunks mapped ahead of the loop (journal.h); its error stops the
	 * run at the next shot, which the report then names */
	if (lv->has_sess_jr)
		journal_service(&lv->sess_jr, hal_mono_ns());
	/* the status ring's consumer is this thread alone; a run's start
	 * sets the ring up before it sets running */
	while (lv->running && hal_ring_pop(&lv->status, lv->st)) {
		pthread_mutex_lock(&lv->snap_mu);
		take_sample(lv, lv->st);
		pthread_mutex_unlock(&lv->snap_mu);
		any = true;
	}
	/* what needs the session's lock waits for no command: a command
	 * under way (an enable starting the drives) has it, and the next
	 * round comes in milliseconds */
	if (!lv->running && atomic_load(&lv->estop_req)) {
		/* latched at once, whatever command holds the lock (an enable
		 * that the e-stop gives up) */
		pthread_mutex_lock(&lv->snap_mu);
		if (lv->snap.state != LIVE_ESTOPPED) {
			lv->snap.state = LIVE_ESTOPPED;
			lv->snap.loop_state = live_state_name(LIVE_ESTOPPED);
			snprintf(lv->snap.reason, sizeof(lv->snap.reason),
				 "e-stop (commanded) while the drives were disabled; latched");
			lv->snap.serial = ++lv->serial;
		}
		pthread_mutex_unlock(&lv->snap_mu);
	}
	if (pthread_mutex_trylock(&lv->mu))
		return 2;
	if (lv->running && !atomic_load(&lv->done))
		live_space_follow(lv);
	if (lv->has_jr) {
		bool over;

		journal_service(&lv->jr, hal_mono_ns());
		pthread_mutex_lock(&lv->snap_mu);
		lv->snap.journal_frames = atomic_load(&lv->jr.written);
		/* a sample of a tick that had taken the play and left its
		 * segment: the loop has let the journal go */
		over = lv->seen_seq >= lv->jr_seq && !lv->seg_active;
		pthread_mutex_unlock(&lv->snap_mu);
		if (over)
			live_journal_close(lv);
	}
	if (lv->running && atomic_load(&lv->done)) {
		/* the last samples first */
		while (hal_ring_pop(&lv->status, lv->st)) {
			pthread_mutex_lock(&lv->snap_mu);
			take_sample(lv, lv->st);
			pthread_mutex_unlock(&lv->snap_mu);
		}
		live_run_end(lv);
	}
	if (!lv->running) {
		if (atomic_load(&lv->estop_req) && lv->state != LIVE_ESTOPPED) {
			lv->state = LIVE_ESTOPPED;
			snprintf(lv->reason, sizeof(lv->reason),
				 "e-stop (commanded) while the drives were disabled; latched");
		}
		if (atomic_load(&lv->signal_req))
			atomic_store(&lv->finished, true);
		pthread_mutex_lock(&lv->snap_mu);
		if (lv->snap.state != lv->state || strcmp(lv->snap.reason, lv->reason))
			lv->snap.serial = ++lv->serial; /* news for the clients */
		lv->snap.state = lv->state;
		snprintf(lv->snap.reason, sizeof(lv->snap.reason), "%s", lv->reason);
		lv->snap.loop_state = lv->state == LIVE_DISABLED ? "disabled" :
				      live_state_name(lv->state);
		for (uint32_t i = 0; i < lv->snap.nout; i++)
			lv->snap.out[i].off = 1;
		pthread_mutex_unlock(&lv->snap_mu);
	}
	pthread_mutex_unlock(&lv->mu);
	return any ? 2 : 5;
}

int live_no_scene(char *msg, size_t size)
{
	snprintf(msg, size, "no scene loaded: load one of the data folder (load {file})");
	return -ENOENT;
}

void live_publish_scene(struct live *lv)
{
	pthread_mutex_lock(&lv->snap_mu);
	lv->generation++;
	lv->snap.nout = lv->sc ? lv->rig.nout : 0;
	lv->snap.fps_num = lv->sc ? lv->sc->src.s.timing.num : 0;
	lv->snap.fps_den = lv->sc ? lv->sc->src.s.timing.den : 0;
	pthread_mutex_unlock(&lv->snap_mu);
}

void live_snapshot(struct live *lv, struct live_snap *s)
{
	pthread_mutex_lock(&lv->snap_mu);
	*s = lv->snap;
	s->generation = lv->generation;
	s->cmd_sent = atomic_load(&lv->cmd_sent);
	pthread_mutex_unlock(&lv->snap_mu);
}

int64_t live_counts(struct live *lv, uint32_t i, double v)
{
	const struct rig_out *o = &lv->rig.out[i];
	double core = o->unit == SRC_UNIT_TURNS ? v / 360.0 : v;
	mot_q32 q;

	if (!sd_to_q32(core, &q))
		q = core < 0 ? MOT_Q32_MIN : MOT_Q32_MAX;
	return hal_scale_counts(&o->scale, q, NULL);
}

double live_units(struct live *lv, uint32_t i, int64_t counts)
{
	const struct rig_out *o = &lv->rig.out[i];

	return rig_file_units(o->unit, (double)(counts - o->scale.offset) / o->scale.per_unit_d);
}

uint32_t live_outputs(struct live *lv, struct live_out_info *out, uint32_t max)
{
	uint32_t i;

	for (i = 0; i < lv->rig.nout && i < max; i++) {
		const struct rig_out *o = &lv->rig.out[i];
		const struct chan *c = &lv->sc->src.all.c[o->src];

		out[i].channel = o->channel;
		out[i].unit = rig_unit_name(o->unit);
		out[i].min = rig_file_units(o->unit, o->min);
		out[i].max = rig_file_units(o->unit, o->max);
		out[i].vmax = rig_file_units(o->unit, o->vmax);
		out[i].amax = rig_file_units(o->unit, o->amax);
		out[i].jog = !o->vel_mode;
		out[i].teach = c->kind == CHAN_VALUE;
		out[i].node = c->kind == CHAN_VALUE ? (int32_t)c->index : -1;
	}
	return i;
}

void live_span(struct live *lv, int64_t *first, int64_t *last, uint32_t *num, uint32_t *den,
	       uint32_t *tick_hz, const char **name, const char **path)
{
	const struct play_source *s = lv->sc ? &lv->sc->src.s : NULL;

	if (!s) {
		*first = *last = 0;
		*num = *den = *tick_hz = 0;
		*name = *path = "";
		return;
	}
	*first = s->frame_first;
	*last = s->frame_last;
	*num = s->timing.num;
	*den = s->timing.den;
	*tick_hz = s->timing.tick_hz;
	*name = s->name;
	*path = lv->sc->path;
}

void live_keys(struct live *lv, void (*fn)(void *ctx, const char *channel, double frame),
	       void *ctx)
{
	struct live_out_info info[LOOP_LIVE_OUT_MAX];
	uint32_t n = live_outputs(lv, info, LOOP_LIVE_OUT_MAX), i, k;

	for (i = 0; i < n; i++) {
		const struct sf_strand *st;

		if (info[i].node < 0)
			continue;
		st = &lv->sc->sf.strand[info[i].node];
		for (k = 0; st->present && k < st->nkeys; k++)
			fn(ctx, info[i].channel, st->key_frames[k]);
	}
}

uint32_t live_jog_targets(struct live *lv, const char **names, uint32_t max)
{
	const struct scene_desc *d = lv->sc ? &lv->sc->sf.desc : NULL;
	uint32_t i, n = 0;

	if (d && d->has_camera && n < max)
		names[n++] = "camera";
	for (i = 0; d && i < d->nnodes && n < max; i++)
		if (d->nodes[i].kind == MOT_NODE_FREE)
			names[n++] = d->nodes[i].name;
	return n;
}

const char *live_state_name(enum live_state s)
{
	static const char *const names[] = {
		[LIVE_DISABLED] = "disabled", [LIVE_ENABLED] = "enabled",
		[LIVE_MOVING] = "moving",     [LIVE_STOPPING] = "stopping",
		[LIVE_ESTOPPED] = "e-stopped", [LIVE_FAULTED] = "faulted",
	};

	return s <= LIVE_FAULTED ? names[s] : "?";
}

void live_signal(struct live *lv, int level)
{
	atomic_store(&lv->signal_req, level);
	hal_cancel_request(&lv->cancel);
	if (level >= 2)
		atomic_store(&lv->estop_req, true);
}

bool live_finished(struct live *lv)
{
	return atomic_load(&lv->finished);
}
