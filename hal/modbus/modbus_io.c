/* SPDX-License-Identifier: MIT */
/*
 * modbus_io.c - a Modbus device's I/O thread and every libmodbus call it
 * makes (see modbus_dev.h). Nothing here runs on the loop's thread: the
 * calls block for as long as the drive takes to answer, up to the response
 * timeout.
 */
#define _GNU_SOURCE
#include "hal/clock.h"
#include "modbus_priv.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

/* Between two attempts to connect again at rest. */
#define MB_RECONNECT_NS 100000000LL
/* The I/O thread wakes this often without an update (a disable, the quit). */
#define MB_IDLE_NS 100000000LL

static bool is_exception(int err)
{
	return (err >= EMBXILFUN && err <= EMBXGTAR) || err == EMBUNKEXC;
}

static bool is_drop(int err)
{
	return err == ECONNRESET || err == EPIPE || err == ENOTCONN || err == EBADF ||
	       err == ECONNREFUSED || err == ECONNABORTED;
}

/*
 * A failed call: counted by kind, the connection closed when it is gone,
 * stale bytes flushed, and m->msg says what failed ("<where>: <what>:
 * <why>"). Returns the negative errno the fault carries.
 */
static int failed(struct modbus_drv *m, const char *what, int err)
{
	char why[96];
	int code;

	if (err == ETIMEDOUT) {
		m->st.timeouts++;
		snprintf(why, sizeof(why), "no answer within %g ms", m->d->response_timeout_ms);
		code = -ETIMEDOUT;
	} else if (is_exception(err)) {
		m->st.exceptions++;
		snprintf(why, sizeof(why), "exception %d (%s)", err - MODBUS_ENOBASE,
			 modbus_strerror(err));
		code = -EPROTO;
	} else if (is_drop(err)) {
		m->st.drops++;
		snprintf(why, sizeof(why), "connection lost");
		code = -ECONNRESET;
	} else {
		m->st.other++;
		snprintf(why, sizeof(why), "%s", modbus_strerror(err));
		code = err > 0 && err < MODBUS_ENOBASE ? -err : -EIO;
	}
	snprintf(m->msg, sizeof(m->msg), "%s: %s: %s", m->where, what, why);
	if (code == -ECONNRESET) {
		mb_io_close(m);
	} else if (m->connected && m->d->transport == MODBUS_TCP &&
		   (err == ETIMEDOUT || err == EMBBADDATA)) {
		/* a TCP drive answers in order: the answer still owed (to this
		 * request, or the late one to an earlier) is awaited here, one
		 * more timeout at most, else the next request would take it
		 * for its own and fail too, and the next, ... */
		uint8_t rsp[MODBUS_TCP_MAX_ADU_LENGTH];

		modbus_receive_confirmation(m->mb, rsp);
	} else if (m->connected) {
		/* RTU: a late answer's bytes must not start the next one's */
		modbus_flush(m->mb);
	}
	return code;
}

int mb_io_connect(struct modbus_drv *m)
{
	const struct modbus_desc *d = m->d;
	double rto = d->response_timeout_ms / 1000, bto = d->byte_timeout_ms / 1000;
	char port[8];

	if (!m->mb) {
		if (d->transport == MODBUS_TCP) {
			snprintf(port, sizeof(port), "%u", d->port);
			m->mb = modbus_new_tcp_pi(d->host, port);
		} else {
			m->mb = modbus_new_rtu(d->serial, (int)d->baud, d->parity, 8,
					       (int)d->stop_bits);
		}
		if (!m->mb) {
			snprintf(m->msg, sizeof(m->msg), "%s: %s", m->where, strerror(errno));
			return -errno;
		}
		modbus_set_slave(m->mb, (int)d->unit);
		modbus_set_response_timeout(m->mb, (uint32_t)rto,
					    (uint32_t)((rto - (uint32_t)rto) * 1e6 + 0.5));
		modbus_set_byte_timeout(m->mb, (uint32_t)bto,
					(uint32_t)((bto - (uint32_t)bto) * 1e6 + 0.5));
	}
	if (modbus_connect(m->mb)) {
		int err = errno;

		snprintf(m->msg, sizeof(m->msg), "%s: cannot connect: %s", m->where,
			 modbus_strerror(err));
		return err > 0 && err < MODBUS_ENOBASE ? -err : -EIO;
	}
	m->connected = true;
	return 0;
}

void mb_io_close(struct modbus_drv *m)
{
	if (m->mb && m->connected)
		modbus_close(m->mb);
	m->connected = false;
}

static const char *span(char *buf, size_t size, const struct modbus_block *b)
{
	if (b->count == 1)
		snprintf(buf, size, "holding register %u", b->addr);
	else
		snprintf(buf, size, "holding registers %u-%u", b->addr, b->addr + b->count - 1);
	return buf;
}

int mb_io_write(struct modbus_drv *m, const int64_t *vals, int64_t tick)
{
	uint32_t nch = m->c.nch, i;
	char what[64], regs[48];

	for (i = 0; i < nch; i++)
		modbus_reg_encode(&m->wreg[i], vals[i], m->wimg + m->wplan.off[i]);
	if (m->d->has_heartbeat) {
		/* the tick modulo the register's width: -1 (all ones) before
		 * the first tick */
		uint32_t w = modbus_type_nregs(m->d->heartbeat.type) == 2 ? (uint32_t)tick :
			     (uint16_t)tick;

		modbus_reg_encode(&m->wreg[nch], w, m->wimg + m->wplan.off[nch]);
	}
	for (i = 0; i < m->wplan.nblocks; i++) {
		const struct modbus_block *b = &m->wplan.block[i];

		if (modbus_write_registers(m->mb, b->addr, b->count, m->wimg + b->off) != b->count) {
			int err = errno;

			m->pending->detail = b->addr;
			snprintf(what, sizeof(what), "write of %s", span(regs, sizeof(regs), b));
			return failed(m, what, err);
		}
	}
	return 0;
}

int mb_io_read(struct modbus_drv *m, int64_t tick)
{
	uint32_t i;
	char what[64], regs[48];

	for (i = 0; i < m->rplan.nblocks; i++) {
		const struct modbus_block *b = &m->rplan.block[i];

		if (modbus_read_registers(m->mb, b->addr, b->count, m->rimg + b->off) != b->count) {
			int err = errno;

			m->pending->detail = b->addr;
			snprintf(what, sizeof(what), "read of %s", span(regs, sizeof(regs), b));
			return failed(m, what, err);
		}
	}
	for (i = 0; i < m->c.nch; i++) {
		int32_t f = m->rfield[i];

		if (f < 0)
			continue;
		m->pending->pair[2 * i] = modbus_reg_decode(&m->rreg[f], m->rimg + m->rplan.off[f]);
		m->pending->pair[2 * i + 1] = m->written[i];
	}
	if (m->rstatus >= 0)
		m->pending->status = m->rimg[m->rplan.off[m->rstatus]];
	m->last_read_tick = tick;
	m->have_read = true;
	m->st.reads++;
	return 0;
}

int mb_io_enable(struct modbus_drv *m, bool on)
{
	const struct modbus_desc *d = m->d;
	char what[64];
	int rc;

	if (d->enable_coil)
		rc = modbus_write_bit(m->mb, d->enable_addr, on);
	else
		rc = modbus_write_register(m->mb, d->enable_addr, on ? d->enable_on : d->enable_off);
	if (rc == 1)
		return 0;
	rc = errno;
	m->pending->detail = d->enable_addr;
	snprintf(what, sizeof(what), "%s of the enable %s %u", on ? "setting" : "clearing",
		 d->enable_coil ? "coil" : "holding register", d->enable_addr);
	return failed(m, what, rc);
}

/* The device faults: the message is fixed from now on, the loop's side
 * reads it once the completion is out. */
static void latch(struct modbus_drv *m, struct mb_done *done, int code, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));
static void latch(struct modbus_drv *m, struct mb_done *done, int code, const char *fmt, ...)
{
	va_list ap;

	if (m->fault_sent)
		return;
	va_start(ap, fmt);
	vsnprintf(m->fault_text, sizeof(m->fault_text), fmt, ap);
	va_end(ap);
	m->fault_sent = true;
	done->flags |= MB_DONE_FAULT;
	done->code = code;
}

/* Connected again at rest: the drive may have dropped its enable with the
 * connection, so it is set again before the setpoints. */
static bool reconnect(struct modbus_drv *m)
{
	int64_t now = hal_mono_ns();

	if (now - m->last_try_ns < MB_RECONNECT_NS)
		return false;
	m->last_try_ns = now;
	if (mb_io_connect(m))
		return false;
	if (m->d->has_enable && mb_io_enable(m, true))
		return false;
	m->st.reconnects++;
	return true;
}

static bool read_due(const struct modbus_drv *m, int64_t tick)
{
	if (!m->rplan.nblocks || !m->d->read_every)
		return false;
	return !m->have_read || tick - m->last_read_tick >= (int64_t)m->d->read_every;
}

static void update(struct modbus_drv *m, const struct mb_update *u)
{
	struct mb_done *done = m->pending;
	uint32_t nch = m->c.nch;
	bool rest = m->have_written && !memcmp(u->val, m->written, nch * sizeof(int64_t));
	int64_t t0 = hal_mono_ns(), dt;
	int rc = 0;

	memset(done, 0, m->done_size);
	done->tick = u->tick;
	if (!m->connected && !(rest && reconnect(m))) {
		if (rest) {
			m->st.held++;
			done->flags = MB_DONE_HELD;
			goto out;
		}
		m->st.unsent++;
		snprintf(m->msg, sizeof(m->msg),
			 "%s: not connected (the connection was lost) while the axes move",
			 m->where);
		rc = -ENOTCONN;
	}
	if (!rc)
		rc = mb_io_write(m, u->val, u->tick);
	if (!rc) {
		memcpy(m->written, u->val, nch * sizeof(int64_t));
		m->have_written = true;
		m->st.written++;
		done->flags |= MB_DONE_WRITTEN;
		if (read_due(m, u->tick)) {
			rc = mb_io_read(m, u->tick);
			if (!rc)
				done->flags |= MB_DONE_READ;
		}
		dt = hal_mono_ns() - t0;
		if (!m->st.rtt_n || dt < m->st.rtt_min_ns)
			m->st.rtt_min_ns = dt;
		if (dt > m->st.rtt_max_ns)
			m->st.rtt_max_ns = dt;
		m->st.rtt_sum_ns += dt;
		m->st.rtt_n++;
	}
	if (rc) {
		if (++m->in_a_row >= m->d->max_faults)
			latch(m, done, rc, "%s, %u time%s in a row", m->msg, m->in_a_row,
			      m->in_a_row == 1 ? "" : "s");
	} else {
		m->in_a_row = 0;
		if ((done->flags & MB_DONE_READ) && m->rstatus >= 0 &&
		    (done->status & m->d->status_fault_mask)) {
			done->detail = m->d->status_addr;
			latch(m, done, -EIO,
			      "%s: the drive reports a fault: status register %u reads 0x%04x "
			      "(fault bits 0x%04x)", m->where, m->d->status_addr, done->status,
			      done->status & m->d->status_fault_mask);
		}
	}
out:
	if (!hal_ring_push(&m->done, done))
		m->st.lost++;
}

void *mb_io_main(void *arg)
{
	struct modbus_drv *m = arg;
	const struct mb_update *u;
	struct timespec ts;
	uint32_t cmd;
	int64_t t;

	while (!atomic_load(&m->quit)) {
		t = hal_mono_ns() + MB_IDLE_NS;
		ts.tv_sec = t / 1000000000;
		ts.tv_nsec = t % 1000000000;
		sem_clockwait(&m->wake, CLOCK_MONOTONIC, &ts);
		while (hal_ring_pop(&m->cmd, &cmd)) {
			if (cmd != MB_CMD_DISABLE || m->io_disabled)
				continue;
			m->io_disabled = true;
			memset(m->pending, 0, m->done_size);
			if (m->connected && m->d->has_enable)
				mb_io_enable(m, false);
		}
		u = hal_slot_take(&m->slot);
		/* disabled or faulted: nothing more goes to the drive */
		if (u && !m->io_disabled && !m->fault_sent)
			update(m, u);
	}
	atomic_store(&m->thread_done, true);
	return NULL;
}
