/* SPDX-License-Identifier: MIT */
/*
 * live_run.c - a run of the loop while the drives are enabled: the drives
 * started, the loop prepared in live mode on its strand-rt thread, and at
 * its end (an e-stop, a fault, a disable, a signal) the drives stopped and
 * the machine state it leaves. Every function here is [init], called with
 * the session's lock held.
 */
#define _GNU_SOURCE
#include "live_priv.h"

#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "hal/rt.h"
#include "play/latency.h"
#include "play/play.h"

static void *rt_main(void *arg)
{
	struct live *lv = arg;
	sigset_t all;
	int64_t t0;

	sigfillset(&all);
	pthread_sigmask(SIG_BLOCK, &all, NULL);
	rt_thread_setup(&lv->o.rt, &lv->rt);
	if (!lv->clk.is_virtual)
		t0 = (hal_clock_now(&lv->clk) / 1000000 + 2) * 1000000;
	else
		t0 = (hal_clock_now(&lv->clk) + 999999) / 1000000 * 1000000;
	strand_rt_enter();
	loop_run(lv->L, t0);
	strand_rt_leave();
	atomic_store(&lv->done, true);
	return NULL;
}

/* Edges the inputs queued while no loop read them: an e-stop pressed and
 * released before must not stop the next run (its level does, if held);
 * and a level read after them is the input's now (a simulated input's
 * level moves only as its edges are taken). */
void live_drain_inputs(struct live *lv)
{
	struct hal_edge ev[32];
	int64_t now = hal_clock_now(&lv->clk);
	uint32_t d;

	for (d = 0; d < lv->rig.ndins; d++)
		while (hal_din_poll(lv->rig.dins[d], now, ev, 32) == 32)
			;
}

bool live_estop_input(struct live *lv, char *msg, size_t size)
{
	uint32_t i;

	for (i = 0; i < lv->rig.nin; i++) {
		const struct rig_in *in = &lv->rig.in[i];

		if (in->role == RIG_INPUT_ESTOP && hal_din_level(lv->rig.dins[in->dev], in->line)) {
			snprintf(msg, size, "the e-stop input '%s' is asserted: release it first",
				 in->name);
			return true;
		}
	}
	return false;
}

int live_run_start(struct live *lv, char *msg, size_t size)
{
	struct loop_live_cfg lc;
	struct loop_cfg cfg;
	uint32_t i;
	int rc;

	live_drain_inputs(lv);
	if (live_estop_input(lv, msg, size))
		return -EPERM;
	for (i = 0; i < lv->rig.naxes; i++) {
		rc = hal_axis_start(lv->rig.axes[i]);
		if (rc) {
			snprintf(msg, size, "device '%s': enable: %s", lv->rig.axes[i]->name,
				 strerror(-rc));
			while (i--)
				hal_axis_stop(lv->rig.axes[i]);
			return rc;
		}
	}
	memset(&cfg, 0, sizeof(cfg));
	cfg.live = true;
	cfg.force = lv->o.force;
	/* on the virtual clock time waits for the journal's service */
	cfg.wait_for_journal = lv->clk.is_virtual;
	cfg.status_every = lv->sc->src.s.timing.tick_hz / lv->o.status_hz;
	if (cfg.status_every < 1)
		cfg.status_every = 1;
	loop_free(lv->L);
	lv->L = NULL;
	rc = loop_init(&lv->L, &cfg, &lv->rig, &lv->sc->src.s, &lv->clk, &lv->status, msg, size);
	if (!rc) {
		memset(&lc, 0, sizeof(lc));
		lc.cmds = &lv->cmds;
		lc.acks = &lv->acks;
		lc.deadman_ticks = (int64_t)(lv->o.deadman_ms * 1e-3 *
					     lv->sc->src.s.timing.tick_hz + 0.5);
		lc.pace = lv->clk.is_virtual;
		lc.pace_all = lv->o.pace_all;
		lc.estop = &lv->estop_req;
		lc.signal = &lv->signal_req;
		rc = loop_live_init(lv->L, &lc, msg, size);
	}
	if (rc)
		goto stop;
	hal_ring_init(&lv->status, lv->st_buf, LIVE_STATUS_RING, lv->st_size);
	hal_ring_init(&lv->cmds, lv->cmd_buf, LIVE_CMD_RING, sizeof(struct loop_cmd));
	hal_ring_init(&lv->acks, lv->ack_buf, LIVE_CMD_RING, sizeof(struct loop_ack));
	atomic_store(&lv->done, false);
	rt_lock_memory(&lv->o.rt, &lv->rt);
	rc = rt_thread_start(&lv->thread, &lv->o.rt, &lv->plan, &lv->rt, rt_main, lv);
	if (rc) {
		rt_release(&lv->rt);
		snprintf(msg, size, "cannot start the loop thread: %s", strerror(-rc));
		goto stop;
	}
	lv->seq_run = lv->seq;
	lv->state = LIVE_ENABLED;
	lv->reason[0] = 0;
	pthread_mutex_lock(&lv->snap_mu);
	lv->snap.reason[0] = 0; /* the last run's end is the past */
	pthread_mutex_unlock(&lv->snap_mu);
	lv->running = true;
	return 0;
stop:
	for (i = 0; i < lv->rig.naxes; i++)
		hal_axis_stop(lv->rig.axes[i]);
	return rc;
}

void live_run_end(struct live *lv)
{
	const struct loop_report *r;
	uint32_t i;

	hal_thread_join(&lv->thread);
	rt_release(&lv->rt);
	lv->running = false;
	for (i = 0; i < lv->rig.naxes; i++)
		hal_axis_stop(lv->rig.axes[i]);
	live_journal_close(lv);
	r = &loop_result(lv->L)->rep;
	if (lv->o.lat_hist && lat_write_hist(lv->o.lat_hist, &loop_result(lv->L)->lat))
		fprintf(stderr, "strand serve: %s: %s\n", lv->o.lat_hist, strerror(errno));
	play_report_describe(&lv->rig, &lv->sc->src.s.timing, loop_result(lv->L), r, NULL,
			     lv->reason, sizeof(lv->reason));
	if (r->cause == LOOP_CAUSE_ESTOP || atomic_load(&lv->estop_req))
		lv->state = LIVE_ESTOPPED;
	else if (r->end == LOOP_END_FAULT || r->end == LOOP_END_INTERNAL)
		lv->state = LIVE_FAULTED;
	else
		lv->state = LIVE_DISABLED;
	if (r->cause == LOOP_CAUSE_ESTOP && !atomic_load(&lv->estop_req))
		atomic_store(&lv->estop_req, true); /* the input's: latched as the command's */
	if (r->cause == LOOP_CAUSE_DISABLE || r->end == LOOP_END_NONE)
		lv->reason[0] = 0;
	if (atomic_load(&lv->signal_req))
		atomic_store(&lv->finished, true);
	lv->goto_frame = -1;
}

int live_send(struct live *lv, struct loop_cmd *c, struct loop_ack *a, char *msg, size_t size)
{
	struct timespec nap = { .tv_nsec = 50000 };
	int64_t deadline;

	if (!lv->running || atomic_load(&lv->done)) {
		snprintf(msg, size, "the drives are %s: %s", live_state_name(lv->state),
			 lv->state == LIVE_DISABLED ? "enable them first" :
			 lv->state == LIVE_ESTOPPED ? "e-stopped, reset first" :
			 lv->state == LIVE_FAULTED ? "faulted, reset first" : "wait");
		return -EPERM;
	}
	/* anything but a jog of the camera or a node moves the rig otherwise */
	if (c->kind != LOOP_CMD_JOG_VEC && c->kind != LOOP_CMD_NOP) {
		lv->space.valid = false;
		lv->space_jog.active = false;
	}
	c->seq = ++lv->seq;
	atomic_store(&lv->cmd_sent, c->seq);
	if (!c->arrival_ns)
		c->arrival_ns = hal_mono_ns();
	if (!hal_ring_push(&lv->cmds, c)) {
		snprintf(msg, size, "the loop's command queue is full");
		return -EBUSY;
	}
	deadline = hal_mono_ns() + 2000000000LL;
	while (hal_mono_ns() < deadline) {
		while (hal_ring_pop(&lv->acks, a))
			if (a->seq == c->seq)
				goto answered;
		if (atomic_load(&lv->done)) {
			snprintf(msg, size, "the run ended before the command was taken");
			return -ECANCELED;
		}
		nanosleep(&nap, NULL);
	}
	snprintf(msg, size, "the loop did not answer within 2 s");
	return -ETIMEDOUT;
answered:
	switch (a->code) {
	case LOOP_CMD_OK:
		return 0;
	case LOOP_CMD_BUSY:
		snprintf(msg, size, "the rig is not at rest (%s): stop first",
			 lv->snap.loop_state ? lv->snap.loop_state : "moving");
		return -EBUSY;
	case LOOP_CMD_LIMIT:
		if (a->out >= 0)
			snprintf(msg, size, "%s: the target is outside its position limits",
				 lv->rig.out[a->out].channel);
		else
			snprintf(msg, size, "the move would take longer than the loop counts");
		return -ERANGE;
	case LOOP_CMD_RUNUP:
		snprintf(msg, size, "%s: the run-up into the first frame would start outside its "
			 "position limits; start from a frame where it moves slower",
			 a->out >= 0 ? lv->rig.out[a->out].channel : "?");
		return -ERANGE;
	case LOOP_CMD_STOPPING:
		snprintf(msg, size, "the drives are being disabled");
		return -EPERM;
	default:
		snprintf(msg, size, "invalid command");
		return -EINVAL;
	}
}

int live_journal_open(struct live *lv, struct loop_cmd *c, char *msg, size_t size)
{
	const struct play_source *src = &lv->sc->src.s;
	char path[PATH_MAX], when[32];
	struct tm tm;
	time_t now;
	int rc;

	if (lv->has_sess_jr) { /* the session's: open for as long as it lasts */
		c->jr = &lv->sess_jr;
		return 0;
	}
	if (lv->has_jr) {
		bool over;

		pthread_mutex_lock(&lv->snap_mu);
		over = lv->seen_seq >= lv->jr_seq && !lv->seg_active;
		pthread_mutex_unlock(&lv->snap_mu);
		if (!over) { /* the loop still writes the last segment's */
			snprintf(msg, size, "the rig is not at rest (a play segment): stop first");
			return -EBUSY;
		}
		live_journal_close(lv);
	}
	if (!lv->o.journal)
		return 0;
	/* named by the wall's date, whatever clock the loop runs on */
	now = time(NULL);
	strftime(when, sizeof(when), "%Y%m%d-%H%M%S", gmtime_r(&now, &tm));
	if ((size_t)snprintf(path, sizeof(path), "%s/%s-%s-%u.journal", lv->o.journal, src->name,
			     when, ++lv->jr_n) >= sizeof(path)) {
		snprintf(msg, size, "--journal %s: the path is too long", lv->o.journal);
		return -ENAMETOOLONG;
	}
	rc = play_journal_open(&lv->jr, path, &lv->rig, src,
			       (c->cfg.mode == LOOP_MODE_STEP ? JOURNAL_MODE_STEP : 0) |
			       (c->cfg.mode == LOOP_MODE_STEP && c->cfg.shutter ?
				JOURNAL_MODE_GOMO : 0), -1, hal_clock_wall(&lv->clk), msg, size);
	if (rc)
		return rc;
	lv->has_jr = true;
	c->jr = &lv->jr;
	return 0;
}

void live_journal_close(struct live *lv)
{
	if (!lv->has_jr)
		return;
	if (journal_close(&lv->jr))
		fprintf(stderr, "strand serve: a journal could not be closed: %s\n",
			strerror(errno));
	lv->has_jr = false;
}
