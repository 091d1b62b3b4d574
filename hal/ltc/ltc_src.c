/* SPDX-License-Identifier: MIT */
/*
 * ltc_src.c - LTC as an external clock (ltc.h): the capture thread, the
 * ring and the loop's side.
 *
 * The thread is the ring's only producer, the loop its only consumer. What
 * the thread must tell the loop besides marks (the device failed, the
 * source ended) it latches in one atomic fault code; on the virtual clock
 * it also publishes how far it has read (horizon), so that the loop can
 * wait for it (extclk.h).
 */
#define _GNU_SOURCE
#include "ltc.h"

#include <errno.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hal/ring.h"
#include "hal/rt.h"
#include "ltc_dec.h"

struct ltc_src {
	struct hal_extclk base; /* first */
	struct ltc_cap *cap;
	struct ltc_dec dec;
	struct hal_clock *clk;
	struct hal_ring ring;   /* struct hal_mark, thread -> loop */
	struct hal_mark *ring_buf;
	int16_t *buf;           /* a period */
	struct hal_sched sched;
	struct hal_thread thread;
	_Atomic bool quit;
	_Atomic int64_t horizon; /* every mark known by then is in the ring */
	_Atomic int fault;      /* negative errno, 0: healthy */
	const char *cause;      /* static, set before fault is published */
	_Atomic int64_t dropped; /* marks the ring had no room for (real clock) */
	_Atomic int64_t periods;
	_Atomic float level;
	struct hal_mark held;   /* the loop's: popped, not yet known */
	bool has_held;
	char name[];
};

static struct ltc_src STRAND_RT *to_src(struct hal_extclk *c)
{
	return (struct ltc_src *)c;
}

static void latch(struct ltc_src *s, int code, const char *cause)
{
	int none = 0;

	s->cause = cause;
	atomic_compare_exchange_strong(&s->fault, &none, code);
}

/* Hand a mark to the loop. On the virtual clock the loop consumes by its
 * time, so a full ring waits for it; on the wall clock a loop that does not
 * read (not started yet) loses the newest marks, counted. */
static bool send(struct ltc_src *s, const struct hal_mark *m)
{
	const struct timespec nap = { .tv_sec = 0, .tv_nsec = 100000 };

	while (!hal_ring_push(&s->ring, m)) {
		if (!s->clk->is_virtual) {
			atomic_fetch_add(&s->dropped, 1);
			return true;
		}
		if (atomic_load(&s->quit))
			return false;
		nanosleep(&nap, NULL);
	}
	return true;
}

static void *capture_thread(void *arg)
{
	struct ltc_src *s = arg;
	struct hal_mark m[8];
	struct ltc_stamp st;
	uint32_t i, n;
	int rc;

	while (!atomic_load(&s->quit)) {
		rc = ltc_cap_read(s->cap, s->buf, s->cap->period, &st);
		if (rc == -EPIPE) { /* an overrun: samples lost, the position breaks off */
			rc = ltc_dec_resync(&s->dec);
			if (rc) {
				latch(s, rc, "out of memory");
				break;
			}
			continue;
		}
		if (rc <= 0) {
			latch(s, rc ? rc : -ENODATA, rc ? "capture failed" : "the source ended");
			break;
		}
		n = ltc_dec_period(&s->dec, s->buf, (uint32_t)rc, &st, m, 8);
		atomic_fetch_add(&s->periods, 1);
		for (i = 0; i < n; i++) {
			atomic_store(&s->level, m[i].level_dbfs);
			if (!send(s, &m[i]))
				goto out;
		}
		atomic_store_explicit(&s->horizon, st.t_ns, memory_order_release);
	}
out:
	atomic_store_explicit(&s->horizon, INT64_MAX, memory_order_release);
	return NULL;
}

static int src_start(struct hal_extclk *c)
{
	struct ltc_src *s = to_src(c);

	STRAND_ASSERT_NOT_RT();
	return hal_thread_start(&s->thread, "strand-ltc", &s->sched, 0, capture_thread, s);
}

static uint32_t STRAND_RT src_poll(struct hal_extclk *c, int64_t now, struct hal_mark *m,
				   uint32_t max)
{
	struct ltc_src *s = to_src(c);
	uint32_t k = 0;

	/* on the virtual clock, until the thread has read as far as now */
	while (s->clk->is_virtual &&
	       atomic_load_explicit(&s->horizon, memory_order_acquire) < now)
		sched_yield();
	while (k < max) {
		if (!s->has_held) {
			if (!hal_ring_pop(&s->ring, &s->held))
				break;
			s->has_held = true;
		}
		if (s->held.avail_ns > now)
			break;
		m[k++] = s->held;
		s->has_held = false;
	}
	return k;
}

static int STRAND_RT src_fault(struct hal_extclk *c, struct hal_fault *f)
{
	struct ltc_src *s = to_src(c);
	int code = atomic_load_explicit(&s->fault, memory_order_acquire);

	if (!code)
		return 0;
	/* a source that ended is a fault once its last marks are taken */
	if (code == -ENODATA && (s->has_held || hal_ring_count(&s->ring)))
		return 0;
	f->code = code;
	f->channel = -1;
	f->cause = s->cause;
	f->detail = 0;
	return code;
}

static int src_stop(struct hal_extclk *c)
{
	struct ltc_src *s = to_src(c);

	STRAND_ASSERT_NOT_RT();
	atomic_store(&s->quit, true);
	hal_thread_join(&s->thread);
	return 0;
}

static void src_close(struct hal_extclk *c)
{
	struct ltc_src *s = to_src(c);

	STRAND_ASSERT_NOT_RT();
	if (s->thread.running)
		src_stop(c);
	ltc_dec_free(&s->dec);
	ltc_cap_close(s->cap);
	free(s->ring_buf);
	free(s->buf);
	free(s);
}

static const struct hal_extclk_ops ltc_ops = {
	.start = src_start,
	.poll = src_poll,
	.fault = src_fault,
	.stop = src_stop,
	.close = src_close,
};

int hal_ltc_open(struct hal_extclk **out, const struct hal_ltc_cfg *cfg, char *err,
		 size_t errsize)
{
	size_t len = strlen(cfg->name);
	struct ltc_src *s;
	int rc;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	s = calloc(1, sizeof(*s) + len + 1);
	if (!s) {
		ltc_cap_close(cfg->cap);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	memcpy(s->name, cfg->name, len + 1);
	s->base.ops = &ltc_ops;
	s->base.name = s->name;
	s->base.labelled = true;
	s->cap = cfg->cap;
	s->clk = cfg->clk;
	s->sched = cfg->sched;
	atomic_init(&s->horizon, INT64_MIN);
	s->ring_buf = calloc(HAL_LTC_RING, sizeof(*s->ring_buf));
	s->buf = calloc(s->cap->period, sizeof(*s->buf));
	if (!s->ring_buf || !s->buf) {
		src_close(&s->base);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	hal_ring_init(&s->ring, s->ring_buf, HAL_LTC_RING, sizeof(*s->ring_buf));
	rc = ltc_dec_init(&s->dec, s->cap->rate, s->cap->period, cfg->fps, err, errsize);
	if (rc) {
		src_close(&s->base);
		return rc;
	}
	*out = &s->base;
	return 0;
}

void hal_ltc_stats(struct hal_extclk *c, struct hal_ltc_stats *st)
{
	struct ltc_src *s = to_src(c);

	st->periods = atomic_load(&s->periods);
	st->frames = s->dec.frames;
	st->dropped = atomic_load(&s->dropped);
	st->resyncs = s->dec.resyncs;
	st->rate_hz = s->dec.clk.per > 0 ? 1e9 / s->dec.clk.per : 0;
	st->level_dbfs = atomic_load(&s->level);
}
