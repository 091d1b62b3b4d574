/* SPDX-License-Identifier: MIT */
/*
 * dmx_axis.c - a DMX device's HAL operations, the loop's side (see dmx.h):
 * setpoints into the universes' images, a frame every `every` ticks into
 * the slot, never a socket call while the loop runs. start() and stop()
 * send themselves, before the thread starts and after it ended.
 */
#define _GNU_SOURCE
#include "dmx_priv.h"

#include <errno.h>
#include <math.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>

uint32_t dmx_every(const struct dmx_desc *d, uint32_t tick_hz)
{
	double hz = d->refresh_hz > 0 ? d->refresh_hz : DMX_REFRESH_DEFAULT;
	double every = ceil(tick_hz / hz - 1e-9);

	return every < 1 ? 1 : every > 1e9 ? 1000000000u : (uint32_t)every;
}

static int STRAND_RT latch_here(struct dmx_drv *m, int code, int32_t ch, const char *text)
{
	if (m->fault.code)
		return m->fault.code;
	m->fault.code = code;
	m->fault.channel = ch;
	m->fault.cause = text;
	m->fault.detail = ch >= 0 ? (uint32_t)ch % DMX_SLOTS + 1 : 0;
	return code;
}

/* The staged values into a frame's images: false (and the channel) when
 * one does not fit its slots. */
static bool STRAND_RT fill(struct dmx_drv *m, struct dmx_frame *f, int64_t tick, uint32_t *bad)
{
	uint32_t ch;

	for (ch = 0; ch < m->ax.nch; ch++) {
		const struct dmx_chan *c = &m->chan[ch];
		uint8_t *p = &f->img[ch / DMX_SLOTS][ch % DMX_SLOTS];
		int64_t v = m->staged[ch];

		if (!c->used)
			continue;
		if (v < 0 || v > (c->bits == 16 ? 65535 : 255)) {
			*bad = ch;
			return false;
		}
		if (c->bits == 16) {
			p[0] = (uint8_t)(v >> 8); /* coarse, then fine */
			p[1] = (uint8_t)v;
		} else {
			p[0] = (uint8_t)v;
		}
	}
	if (m->d->has_tick_slot) {
		uint32_t s = m->d->tick_slot, k;

		for (k = 0; k < 4; k++)
			f->img[(s + k) / DMX_SLOTS][(s + k) % DMX_SLOTS] =
				(uint8_t)((uint64_t)tick >> (24 - 8 * k));
	}
	f->tick = tick;
	return true;
}

static int start_thread(struct dmx_drv *m)
{
	char name[HAL_THREAD_NAME_MAX + 1];

	hal_thread_name(name, "strand-dmx-", m->ax.name);
	return hal_thread_start(&m->thread, name, &m->c.sched, 0, dmx_io_main, m);
}

static int dmx_start(struct hal_axis *ax)
{
	struct dmx_drv *m = dmx_of(ax);
	uint32_t bad = 0;
	int rc;

	STRAND_ASSERT_NOT_RT();
	rc = dmx_io_open(m);
	if (rc)
		goto fail;
	/* the first frame, with the channels where they stand (home) */
	memset(m->last, 0, m->frame_size);
	if (!fill(m, m->last, 0, &bad)) {
		snprintf(m->io_text, sizeof(m->io_text), "%s", m->chan_text[bad]);
		rc = -ERANGE;
		goto fail;
	}
	rc = dmx_io_send(m, m->last, 0);
	if (rc) {
		snprintf(m->io_text, sizeof(m->io_text), "%s: send failed: %s", m->where,
			 strerror(-rc));
		goto fail;
	}
	m->have_last = true;
	m->published = -1;
	atomic_store(&m->sent_tick, -1);
	atomic_store(&m->quit, false);
	atomic_store(&m->terminate, false);
	rc = start_thread(m);
	if (rc) {
		snprintf(m->io_text, sizeof(m->io_text), "%s: cannot start its I/O thread", m->where);
		goto fail;
	}
	return 0;
fail:
	latch_here(m, rc, -1, m->io_text);
	dmx_io_close(m);
	return rc;
}

static int STRAND_RT dmx_input(struct hal_axis *ax, int64_t tick)
{
	struct dmx_drv *m = dmx_of(ax);
	int e;

	/* lockstep (virtual clock): the frame published is sent before the
	 * next tick, so that every run sends the same frames */
	while (m->c.lockstep && m->thread.running && !m->fault.code &&
	       atomic_load_explicit(&m->sent_tick, memory_order_acquire) < m->published)
		sched_yield();
	e = atomic_load_explicit(&m->io_error, memory_order_acquire);
	if (e)
		latch_here(m, e, -1, m->io_text);
	return m->fault.code;
}

static bool STRAND_RT dmx_actual(struct hal_axis *ax, uint32_t ch, int64_t *counts)
{
	return false; /* lights say nothing back */
}

static void STRAND_RT dmx_set(struct hal_axis *ax, uint32_t ch, const struct hal_setpoint *sp)
{
	dmx_of(ax)->staged[ch] = sp->pos;
}

static int STRAND_RT dmx_commit(struct hal_axis *ax, int64_t tick)
{
	struct dmx_drv *m = dmx_of(ax);
	struct dmx_frame *f;
	uint32_t bad = 0;

	if (m->fault.code)
		return m->fault.code;
	if (m->disabled || tick < 0 || tick % m->every)
		return 0;
	f = hal_slot_back(&m->slot);
	/* a value that does not fit its slots never goes out clipped */
	if (!fill(m, f, tick, &bad))
		return latch_here(m, -ERANGE, (int32_t)bad, m->chan_text[bad]);
	if (hal_slot_publish(&m->slot))
		m->replaced++;
	m->frames++;
	m->published = tick;
	sem_post(&m->wake);
	return 0;
}

static int STRAND_RT dmx_fault(struct hal_axis *ax, struct hal_fault *f)
{
	struct dmx_drv *m = dmx_of(ax);

	if (m->fault.code)
		*f = m->fault;
	return m->fault.code;
}

/* The lights' stream ends (sACN: terminated); what they do then is their
 * own setting for a lost source. */
static void STRAND_RT dmx_disable(struct hal_axis *ax)
{
	struct dmx_drv *m = dmx_of(ax);

	if (m->disabled)
		return;
	m->disabled = true;
	atomic_store(&m->terminate, true);
	sem_post(&m->wake);
}

static int dmx_stop(struct hal_axis *ax)
{
	struct dmx_drv *m = dmx_of(ax);

	STRAND_ASSERT_NOT_RT();
	if (m->thread.running) {
		dmx_disable(ax);
		hal_thread_join(&m->thread);
	}
	dmx_io_close(m);
	return 0;
}

static void dmx_close(struct hal_axis *ax)
{
	struct dmx_drv *m = dmx_of(ax);
	uint32_t i;

	STRAND_ASSERT_NOT_RT();
	if (m->thread.running) {
		atomic_store(&m->quit, true);
		sem_post(&m->wake);
		hal_thread_join(&m->thread);
	}
	dmx_io_close(m);
	if (m->wake_ready)
		sem_destroy(&m->wake);
	for (i = 0; m->chan_text && i < ax->nch; i++)
		free(m->chan_text[i]);
	free(m->chan_text);
	free(m->chan);
	free(m->staged);
	free(m->slot_buf);
	free(m->last);
	free(m);
}

static const struct hal_axis_ops dmx_ops = {
	.start = dmx_start,
	.input = dmx_input,
	.actual = dmx_actual,
	.set = dmx_set,
	.commit = dmx_commit,
	.fault = dmx_fault,
	.disable = dmx_disable,
	.stop = dmx_stop,
	.close = dmx_close,
};

int hal_dmx_open(struct hal_axis **out, const struct dmx_cfg *c, char *err, size_t errsize)
{
	const struct dmx_desc *d = c->d;
	struct dmx_drv *m;
	uint32_t i;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (!d->nuniverses || d->nuniverses > DMX_UNIVERSES_MAX || !c->nch ||
	    c->nch > d->nuniverses * DMX_SLOTS || !c->tick_hz || !d->destination) {
		snprintf(err, errsize, "device '%s': %u channels over %u universes", c->name, c->nch,
			 d->nuniverses);
		return -EINVAL;
	}
	m = calloc(1, sizeof(*m));
	if (!m)
		goto nomem;
	m->ax.ops = &dmx_ops;
	m->ax.name = c->name;
	m->ax.nch = c->nch;
	m->c = *c;
	m->d = d;
	m->fd = -1;
	m->nu = d->nuniverses;
	m->every = dmx_every(d, c->tick_hz);
	snprintf(m->where, sizeof(m->where), "%s to %s", d->protocol == DMX_E131 ? "sACN" : "Art-Net",
		 d->destination);
	m->frame_size = (uint32_t)(sizeof(struct dmx_frame) + (size_t)m->nu * DMX_SLOTS + 7) & ~7u;
	m->chan = calloc(c->nch, sizeof(*m->chan));
	m->staged = calloc(c->nch, sizeof(*m->staged));
	m->chan_text = calloc(c->nch, sizeof(*m->chan_text));
	m->slot_buf = calloc(3, m->frame_size);
	m->last = calloc(1, m->frame_size);
	if (!m->chan || !m->staged || !m->chan_text || !m->slot_buf || !m->last)
		goto nomem;
	memcpy(m->chan, c->chan, c->nch * sizeof(*m->chan));
	if (c->initial)
		memcpy(m->staged, c->initial, c->nch * sizeof(*m->staged));
	for (i = 0; i < c->nch; i++) {
		char buf[DMX_TEXT];

		if (!m->chan[i].used)
			continue;
		snprintf(buf, sizeof(buf), "%s: the value of slot %u of universe %u does not fit "
			 "%u bits (0 to %u)", m->where, i % DMX_SLOTS + 1, d->universes[i / DMX_SLOTS],
			 m->chan[i].bits, m->chan[i].bits == 16 ? 65535 : 255);
		m->chan_text[i] = strdup(buf);
		if (!m->chan_text[i])
			goto nomem;
	}
	dmx_cid(m->cid, c->name);
	hal_slot_init(&m->slot, m->slot_buf, m->frame_size);
	if (sem_init(&m->wake, 0, 0))
		goto nomem;
	m->wake_ready = true;
	*out = &m->ax;
	return 0;
nomem:
	snprintf(err, errsize, "device '%s': out of memory", c->name);
	if (m)
		dmx_close(&m->ax);
	return -ENOMEM;
}

void hal_dmx_report(struct hal_axis *ax, FILE *f)
{
	struct dmx_drv *m = dmx_of(ax);

	fprintf(f, "  device '%s': %s, %u universe%s every %u ticks: %lld frames, %lld replaced "
		"by newer, %lld packets sent, %lld send errors, %lld resent after a quiet second\n",
		ax->name, m->where, m->nu, m->nu == 1 ? "" : "s", m->every, (long long)m->frames,
		(long long)m->replaced, (long long)m->packets, (long long)m->errors,
		(long long)m->resends);
}
