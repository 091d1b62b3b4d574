/* SPDX-License-Identifier: MIT */
/*
 * modbus_axis.c - a Modbus device's HAL operations, the loop's side (see
 * modbus_dev.h): setpoints into the slot, completions and faults out of the
 * ring, never a libmodbus call while the loop runs. start() and stop() talk
 * to the drive themselves, before the I/O thread starts and after it ended.
 */
#define _GNU_SOURCE
#include "modbus_priv.h"

#include <errno.h>
#include <math.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>

#include "hal/rt.h"

static const char *const type_names[] = {
	[MODBUS_TYPE_INT16] = "int16", [MODBUS_TYPE_UINT16] = "uint16",
	[MODBUS_TYPE_INT32] = "int32", [MODBUS_TYPE_UINT32] = "uint32",
};

/* A fault found here or at start: the message is m->msg, fixed from now. */
static int STRAND_RT latch_here(struct modbus_drv *m, int code, int32_t ch, const char *text,
				uint32_t reg)
{
	if (m->fault.code)
		return m->fault.code;
	m->fault.code = code;
	m->fault.channel = ch;
	m->fault.cause = text;
	m->fault.detail = reg;
	return code;
}

/*
 * The I/O thread, strand-mb-DEVICE, scheduled as the configuration says
 * (strand's plan: SCHED_FIFO just below the loop, play/rt.h, which says
 * why). Refused SCHED_FIFO, it runs at normal priority, and the summary
 * says so.
 */
static int start_thread(struct modbus_drv *m)
{
	char name[HAL_THREAD_NAME_MAX + 1];

	hal_thread_name(name, "strand-mb-", m->ax.name);
	return hal_thread_start(&m->thread, name, &m->c.sched, 0, mb_io_main, m);
}

/*
 * Between the start's transactions: rc, or -ECANCELED once the run's cancel
 * request came (a signal). libmodbus's waits are its own (a signal does not
 * cut short its wait for an answer, which the response timeout bounds), so
 * the start looks between them; a transaction a signal did cut short (the
 * connect) is given up the same way, whatever it returned.
 */
static int given_up(struct modbus_drv *m, int rc)
{
	if (!hal_cancelled(m->c.cancel))
		return rc;
	snprintf(m->msg, sizeof(m->msg), "%s: start given up (a stop was asked for)", m->where);
	return -ECANCELED;
}

/*
 * A start after a stop (a live session enables the drives again for each
 * run of the loop, whose ticks count from 0 again): nothing of the last
 * run may carry over. Its disable would keep every update from the drive
 * (and the I/O thread's, every write), its latched fault fail the new run
 * at once, its reads' ticks put the next read thousands of ticks off, and
 * an update or a command left in the slot and the rings be taken as the
 * new run's. No thread runs here.
 */
static void forget_run(struct modbus_drv *m)
{
	uint32_t nch = m->ax.nch;

	m->disabled = false;
	memset(&m->fault, 0, sizeof(m->fault));
	m->have_actual = false;
	m->io_disabled = false;
	m->fault_sent = false;
	m->have_read = false;
	m->in_a_row = 0;
	hal_slot_init(&m->slot, m->slot_buf, (uint32_t)(sizeof(struct mb_update) +
							nch * sizeof(int64_t)));
	hal_ring_init(&m->done, m->done_buf, MB_DONE_RING, m->done_size);
	hal_ring_init(&m->cmd, m->cmd_buf, MB_CMD_RING, sizeof(uint32_t));
	while (sem_trywait(&m->wake) == 0)
		;
}

static int mb_start(struct hal_axis *ax)
{
	struct modbus_drv *m = mb_of(ax);
	uint32_t i, nch = ax->nch;
	bool enabled = false;
	int rc;

	STRAND_ASSERT_NOT_RT();
	forget_run(m);
	m->pending = m->popped; /* no thread yet: the loop's buffer serves */
	memset(m->pending, 0, m->done_size);
	rc = given_up(m, 0);
	if (!rc)
		rc = given_up(m, mb_io_connect(m));
	if (rc)
		goto fail;
	/* hold where the drive stands: its actual position where it has one */
	memcpy(m->written, m->initial, nch * sizeof(int64_t));
	if (m->rplan.nblocks) {
		rc = given_up(m, mb_io_read(m, -1));
		if (rc)
			goto fail;
		if (m->rstatus >= 0 && (m->pending->status & m->d->status_fault_mask)) {
			snprintf(m->msg, sizeof(m->msg),
				 "%s: the drive reports a fault: status register %u reads 0x%04x",
				 m->where, m->d->status_addr, m->pending->status);
			m->pending->detail = m->d->status_addr;
			rc = -EIO;
			goto fail;
		}
		for (i = 0; i < nch; i++) {
			if (m->rfield[i] < 0 || m->velocity[i])
				continue;
			m->written[i] = m->pending->pair[2 * i];
			m->actual[i] = m->written[i];
			m->at_read[i] = m->written[i];
			m->have_actual = true;
		}
	}
	for (i = 0; i < nch; i++) {
		if (m->velocity[i])
			m->written[i] = 0;
		if (!modbus_reg_fits(&m->wreg[i], m->written[i])) {
			snprintf(m->msg, sizeof(m->msg), "%s", m->range_text[i]);
			m->pending->detail = m->wreg[i].addr;
			rc = -ERANGE;
			goto fail;
		}
	}
	rc = given_up(m, mb_io_write(m, m->written, -1));
	if (!rc && m->d->has_enable) {
		/* an enable whose answer did not come may have been set too */
		enabled = true;
		rc = mb_io_enable(m, true);
	}
	/* nothing may stay enabled after a stop was asked for */
	rc = given_up(m, rc);
	if (rc)
		goto fail;
	m->have_written = true;
	memcpy(m->staged, m->written, nch * sizeof(int64_t));
	memcpy(m->last_pos, m->written, nch * sizeof(int64_t));
	m->published = m->completed = m->ok_tick = -1;
	m->pending = (struct mb_done *)((char *)m->popped + m->done_size);
	atomic_store(&m->quit, false);
	atomic_store(&m->thread_done, false);
	rc = start_thread(m);
	if (rc) {
		snprintf(m->msg, sizeof(m->msg), "%s: cannot start its I/O thread", m->where);
		goto fail;
	}
	return 0;
fail:
	memcpy(m->fault_text, m->msg, sizeof(m->fault_text));
	m->fault_sent = true;
	latch_here(m, rc, -1, m->fault_text, m->pending->detail);
	/* the power stage off again where this start put it on */
	if (enabled && m->connected)
		mb_io_enable(m, false);
	mb_io_close(m);
	return rc;
}

static void STRAND_RT take(struct modbus_drv *m, const struct mb_done *d)
{
	uint32_t i;

	m->completed = d->tick;
	if (d->flags & (MB_DONE_WRITTEN | MB_DONE_HELD))
		m->ok_tick = d->tick;
	if (d->flags & MB_DONE_READ) {
		for (i = 0; i < m->ax.nch; i++) {
			if (m->rfield[i] < 0)
				continue;
			m->actual[i] = d->pair[2 * i];
			m->at_read[i] = d->pair[2 * i + 1];
			m->have_actual = true;
		}
	}
	/* the I/O thread wrote fault_text before it pushed (ring.h: release) */
	if (d->flags & MB_DONE_FAULT)
		latch_here(m, d->code, -1, m->fault_text, d->detail);
}

static int STRAND_RT mb_input(struct hal_axis *ax, int64_t tick)
{
	struct modbus_drv *m = mb_of(ax);

	for (;;) {
		while (hal_ring_pop(&m->done, m->popped))
			take(m, m->popped);
		/* lockstep (virtual clock): no deadline, so wait for the update
		 * to be answered; yielding, as the loop waits for its journal */
		if (!m->c.lockstep || m->completed >= m->published || m->fault.code ||
		    !m->thread.running || atomic_load(&m->thread_done))
			break;
		sched_yield();
	}
	if (!m->fault.code && !m->disabled && m->published > m->ok_tick &&
	    tick - m->ok_tick > m->silence_ticks)
		latch_here(m, -ETIMEDOUT, -1, m->silence_text, m->wreg[0].addr);
	return m->fault.code;
}

/* The drive's position as read, moved by as much as the setpoint moved
 * since: the loop's setpoint minus this is the following error the drive
 * had when it was read, however old the reading. */
static bool STRAND_RT mb_actual(struct hal_axis *ax, uint32_t ch, int64_t *counts)
{
	struct modbus_drv *m = mb_of(ax);

	if (!m->have_actual || m->rfield[ch] < 0 || m->velocity[ch])
		return false;
	*counts = m->actual[ch] + (m->last_pos[ch] - m->at_read[ch]);
	return true;
}

static void STRAND_RT mb_set(struct hal_axis *ax, uint32_t ch, const struct hal_setpoint *sp)
{
	struct modbus_drv *m = mb_of(ax);

	m->staged[ch] = m->velocity[ch] ? sp->vel : sp->pos;
	m->last_pos[ch] = sp->pos;
}

static int STRAND_RT mb_commit(struct hal_axis *ax, int64_t tick)
{
	struct modbus_drv *m = mb_of(ax);
	struct mb_update *u;
	uint32_t i;

	if (m->fault.code)
		return m->fault.code;
	if (m->disabled || tick < 0 || tick % m->every)
		return 0;
	/* a value that does not fit its register never goes out wrapped */
	for (i = 0; i < ax->nch; i++)
		if (!modbus_reg_fits(&m->wreg[i], m->staged[i]))
			return latch_here(m, -ERANGE, (int32_t)i, m->range_text[i],
					  m->wreg[i].addr);
	u = hal_slot_back(&m->slot);
	u->tick = tick;
	memcpy(u->val, m->staged, ax->nch * sizeof(int64_t));
	if (hal_slot_publish(&m->slot))
		m->replaced++;
	m->updates++;
	m->published = tick;
	/* an atomic add, and a futex wake only when the thread sleeps */
	sem_post(&m->wake);
	return 0;
}

static int STRAND_RT mb_fault(struct hal_axis *ax, struct hal_fault *f)
{
	struct modbus_drv *m = mb_of(ax);

	if (m->fault.code)
		*f = m->fault;
	return m->fault.code;
}

static void STRAND_RT mb_disable(struct hal_axis *ax)
{
	struct modbus_drv *m = mb_of(ax);
	uint32_t cmd = MB_CMD_DISABLE;

	if (m->disabled)
		return;
	m->disabled = true;
	/* a ring of four for one command: it cannot be full */
	hal_ring_push(&m->cmd, &cmd);
	sem_post(&m->wake);
}

static int mb_stop(struct hal_axis *ax)
{
	struct modbus_drv *m = mb_of(ax);
	int rc = 0;

	STRAND_ASSERT_NOT_RT();
	if (m->thread.running) {
		mb_disable(ax);
		atomic_store(&m->quit, true);
		sem_post(&m->wake);
		hal_thread_join(&m->thread);
		m->pending = m->popped;
		/* the thread may have quit before it saw the disable */
		if (m->connected && m->d->has_enable && !m->io_disabled) {
			rc = mb_io_enable(m, false);
			m->io_disabled = !rc;
		}
	}
	mb_io_close(m);
	return rc;
}

static void mb_close(struct hal_axis *ax)
{
	struct modbus_drv *m = mb_of(ax);
	uint32_t i;

	STRAND_ASSERT_NOT_RT();
	mb_stop(ax);
	if (m->mb)
		modbus_free(m->mb);
	sem_destroy(&m->wake);
	modbus_plan_free(&m->wplan);
	modbus_plan_free(&m->rplan);
	for (i = 0; m->range_text && i < ax->nch; i++)
		free(m->range_text[i]);
	free(m->range_text);
	free(m->wreg);
	free(m->rreg);
	free(m->rfield);
	free(m->wimg);
	free(m->rimg);
	free(m->slot_buf);
	free(m->done_buf);
	free(m->popped);
	free(m->velocity);
	free(m->initial);
	free(m->staged);
	free(m->last_pos);
	free(m->actual);
	free(m->at_read);
	free(m->written);
	free(m);
}

static const struct hal_axis_ops modbus_ops = {
	.start = mb_start,
	.input = mb_input,
	.actual = mb_actual,
	.set = mb_set,
	.commit = mb_commit,
	.fault = mb_fault,
	.disable = mb_disable,
	.stop = mb_stop,
	.close = mb_close,
};

static void *zalloc(size_t n, size_t size, bool *ok)
{
	void *p = calloc(n ? n : 1, size);

	*ok &= p != NULL;
	return p;
}

/* The texts of the faults the loop's side finds itself, made now. */
static bool make_texts(struct modbus_drv *m)
{
	uint32_t i, nreq = m->wplan.nblocks + m->rplan.nblocks;
	double period_ms = 1000.0 * m->every / m->c.tick_hz, silence_ms, silence_ticks;

	/* long enough for max_faults timeouts of every request of an update
	 * (those fault with their own message first) and two updates more */
	silence_ms = m->d->max_silence_ms > 0 ? m->d->max_silence_ms :
		     (m->d->max_faults + 1) * m->d->response_timeout_ms * nreq + 2 * period_ms;
	/* the loader holds max_silence_ms and the timeouts to their ranges
	 * (modbus_desc.h); a description made in code saturates here */
	silence_ticks = ceil(silence_ms * m->c.tick_hz / 1000);
	m->silence_ticks = silence_ticks < 9.2e18 ? (int64_t)silence_ticks : INT64_MAX;
	snprintf(m->silence_text, sizeof(m->silence_text),
		 "%s: no update answered for %g ms while setpoints waited (the bus cannot keep up)",
		 m->where, silence_ms);
	for (i = 0; i < m->ax.nch; i++) {
		const struct modbus_reg *r = &m->wreg[i];
		char buf[MB_FAULT_TEXT];

		snprintf(buf, sizeof(buf),
			 "%s: axis %u's %s does not fit holding register %u (%s, %lld to %lld)",
			 m->where, i, m->velocity[i] ? "velocity" : "target", r->addr,
			 type_names[r->type], (long long)modbus_type_min(r->type),
			 (long long)modbus_type_max(r->type));
		m->range_text[i] = strdup(buf);
		if (!m->range_text[i])
			return false;
	}
	return true;
}

int hal_modbus_open(struct hal_axis **out, const struct modbus_cfg *c, char *err,
		    size_t errsize)
{
	const struct modbus_desc *d = c->d;
	uint32_t nch = c->nch, nw, nr, a = 0, b = 0;
	struct modbus_drv *m;
	bool ok = true;
	int rc;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (!nch || nch > d->naxes || !c->tick_hz) {
		snprintf(err, errsize, "device '%s': %u axes used, %u in its register map", c->name,
			 nch, d->naxes);
		return -EINVAL;
	}
	m = calloc(1, sizeof(*m));
	if (!m)
		goto nomem;
	m->ax.ops = &modbus_ops;
	m->ax.name = c->name;
	m->ax.nch = nch;
	m->c = *c;
	m->d = d;
	m->every = modbus_update_every(d, c->tick_hz);
	m->rstatus = -1;
	modbus_where(m->where, sizeof(m->where), d);
	m->velocity = zalloc(nch, sizeof(bool), &ok);
	m->initial = zalloc(nch, sizeof(int64_t), &ok);
	m->staged = zalloc(nch, sizeof(int64_t), &ok);
	m->last_pos = zalloc(nch, sizeof(int64_t), &ok);
	m->actual = zalloc(nch, sizeof(int64_t), &ok);
	m->at_read = zalloc(nch, sizeof(int64_t), &ok);
	m->written = zalloc(nch, sizeof(int64_t), &ok);
	m->wreg = zalloc(nch + 1, sizeof(*m->wreg), &ok);
	m->rreg = zalloc(nch + 1, sizeof(*m->rreg), &ok);
	m->rfield = zalloc(nch, sizeof(int32_t), &ok);
	m->range_text = zalloc(nch, sizeof(char *), &ok);
	/* 8-byte aligned elements: the completions hold int64_t */
	m->done_size = (uint32_t)(sizeof(struct mb_done) + 2 * nch * sizeof(int64_t) + 7) & ~7u;
	m->done_buf = zalloc(MB_DONE_RING, m->done_size, &ok);
	m->popped = zalloc(2, m->done_size, &ok);
	m->slot_buf = zalloc(3, sizeof(struct mb_update) + nch * sizeof(int64_t), &ok);
	if (!ok)
		goto nomem;
	if (c->velocity)
		memcpy(m->velocity, c->velocity, nch * sizeof(bool));
	if (c->initial)
		memcpy(m->initial, c->initial, nch * sizeof(int64_t));
	modbus_desc_regs(d, nch, m->wreg, &nw, m->rreg, &nr, m->rfield, &m->rstatus);
	rc = modbus_plan_make(&m->wplan, m->wreg, nw, MODBUS_MAP_WRITE_MAX, &a, &b);
	if (rc == -ENOMEM)
		goto nomem;
	if (rc) {
		snprintf(err, errsize, "device '%s': registers written every update overlap at %u",
			 c->name, m->wreg[b].addr);
		rc = -EINVAL;
		goto fail;
	}
	rc = modbus_plan_make(&m->rplan, m->rreg, nr, MODBUS_MAP_READ_MAX, &a, &b);
	if (rc == -ENOMEM)
		goto nomem;
	if (rc) {
		snprintf(err, errsize, "device '%s': registers read overlap at %u", c->name,
			 m->rreg[b].addr);
		rc = -EINVAL;
		goto fail;
	}
	m->wimg = zalloc(m->wplan.nregs, sizeof(uint16_t), &ok);
	m->rimg = zalloc(m->rplan.nregs, sizeof(uint16_t), &ok);
	if (!ok || !make_texts(m))
		goto nomem;
	hal_slot_init(&m->slot, m->slot_buf, (uint32_t)(sizeof(struct mb_update) +
							nch * sizeof(int64_t)));
	hal_ring_init(&m->done, m->done_buf, MB_DONE_RING, m->done_size);
	hal_ring_init(&m->cmd, m->cmd_buf, MB_CMD_RING, sizeof(uint32_t));
	if (sem_init(&m->wake, 0, 0))
		goto nomem;
	m->wake_ready = true;
	*out = &m->ax;
	return 0;
nomem:
	rc = -ENOMEM;
	snprintf(err, errsize, "device '%s': out of memory", c->name);
fail:
	if (m && !m->wake_ready)
		sem_init(&m->wake, 0, 0); /* mb_close destroys it */
	if (m)
		mb_close(&m->ax);
	return rc;
}

void hal_modbus_stats(struct hal_axis *ax, struct modbus_stats *s)
{
	struct modbus_drv *m = mb_of(ax);

	*s = m->st;
	s->updates = m->updates;
	s->replaced = m->replaced;
}

void hal_modbus_report(struct hal_axis *ax, FILE *f)
{
	struct modbus_drv *m = mb_of(ax);
	struct modbus_stats s;

	hal_modbus_stats(ax, &s);
	fprintf(f, "  modbus '%s' (%s): %lld updates every %u tick%s, %lld written, %lld replaced "
		"by a newer one, %lld held at rest, %lld reads; I/O thread %s\n", ax->name,
		m->where, (long long)s.updates, m->every, m->every == 1 ? "" : "s",
		(long long)s.written, (long long)s.replaced, (long long)s.held, (long long)s.reads,
		m->thread.fifo ? "SCHED_FIFO" : "SCHED_OTHER");
	if (s.rtt_n)
		fprintf(f, "    update round trip us: min %.0f avg %.0f max %.0f\n",
			s.rtt_min_ns / 1e3, (double)s.rtt_sum_ns / s.rtt_n / 1e3,
			s.rtt_max_ns / 1e3);
	if (s.timeouts || s.exceptions || s.drops || s.reconnects || s.other || s.unsent)
		fprintf(f, "    %lld timeouts, %lld exception answers, %lld connections lost, "
			"%lld made again, %lld updates unsent, %lld other errors\n",
			(long long)s.timeouts, (long long)s.exceptions, (long long)s.drops,
			(long long)s.reconnects, (long long)s.unsent, (long long)s.other);
}
