/* SPDX-License-Identifier: MIT */
/*
 * co_master.c - the master's core: frames in, timers, the cyclic exchange,
 * the 402 sequences of start and stop, faults (see co_master.h).
 */
#include "co_master_priv.h"

#include <errno.h>
#include <string.h>

#include "hal/rt.h"

int co_interp_period(uint32_t tick_hz, uint8_t *value, int8_t *exp)
{
	uint64_t pow = 1; /* 10^-e */
	double best_err = 1, v;
	int e;

	if (!tick_hz)
		return -EINVAL;
	/* exact: value = 10^-e / tick_hz, an integer 1..255, largest e first */
	for (e = 0; e >= -9; e--, pow *= 10)
		if (pow % tick_hz == 0 && pow / tick_hz >= 1 && pow / tick_hz <= 255) {
			*value = (uint8_t)(pow / tick_hz);
			*exp = (int8_t)e;
			return 0;
		}
	/* else the most digits that fit in 255 */
	for (e = 0, pow = 1; e >= -9; e--, pow *= 10) {
		v = (double)pow / tick_hz;
		if (v + 0.5 >= 1 && v + 0.5 < 256) {
			double r = (double)(uint64_t)(v + 0.5), err = r > v ? (r - v) / v : (v - r) / v;

			if (err < best_err) {
				best_err = err;
				*value = (uint8_t)r;
				*exp = (int8_t)e;
			}
		}
	}
	return best_err <= 1e-3 ? 1 : -EINVAL;
}

int co_master_init(struct co_master *m, const struct co_master_cfg *cfg,
		   const struct co_drive_cfg *drives, struct co_node *nodes,
		   struct co_frame *cycle, uint32_t n)
{
	uint32_t i;

	memset(m, 0, sizeof(*m));
	if (!n || n > CO_NODE_MAX || !cfg->send || cfg->sync_id > 0x7ff ||
	    co_interp_period(cfg->tick_hz, &m->ip_value, &m->ip_exp) < 0)
		return -EINVAL;
	m->cfg = *cfg;
	m->node = nodes;
	m->nnodes = n;
	m->cycle = cycle;
	m->period_ns = 1000000000LL / cfg->tick_hz;
	for (i = 0; i <= CO_NODE_MAX; i++)
		m->slot[i] = -1;
	for (i = 0; i < n; i++) {
		const struct co_drive_cfg *d = &drives[i];
		struct co_node *nd = &nodes[i];

		if (d->node < 1 || d->node > CO_NODE_MAX || m->slot[d->node] >= 0 ||
		    (d->mode != CO402_MODE_CSP && d->mode != CO402_MODE_CSV))
			return -EINVAL;
		memset(nd, 0, sizeof(*nd));
		nd->cfg = *d;
		nd->hb_last = -1;
		co_sdo_init(&nd->sdo, d->node, cfg->sdo_timeout_ms * CO_MS);
		m->slot[d->node] = (int16_t)i;
	}
	return 0;
}

uint32_t co_master_rx_ids(const struct co_drive_cfg *drives, uint32_t n, uint16_t *ids)
{
	uint32_t i, k = 0;

	for (i = 0; i < n; i++) {
		ids[k++] = (uint16_t)(CO_ID_EMCY + drives[i].node);
		ids[k++] = co_tpdo_id(1, drives[i].node);
		ids[k++] = (uint16_t)(CO_ID_SDO_TX + drives[i].node);
		ids[k++] = (uint16_t)(CO_ID_HEARTBEAT + drives[i].node);
	}
	return k;
}

int STRAND_RT co_master_index(const struct co_master *m, uint8_t node)
{
	return node <= CO_NODE_MAX ? m->slot[node] : -1;
}

/* ---- faults and sending ---- */

void STRAND_RT co_latch(struct co_master *m, const struct co_fault *f)
{
	if (m->fault.kind == CO_FAULT_NONE)
		m->fault = *f;
	if (m->phase == CO_MASTER_STARTING)
		m->phase = CO_MASTER_FAILED;
}

void STRAND_RT co_fail(struct co_master *m, enum co_fault_kind kind, int code,
		       const struct co_node *n, uint32_t detail)
{
	struct co_fault f = {
		.code = code, .kind = (uint8_t)kind, .node = n ? n->cfg.node : 0,
		.state = n ? (uint8_t)co402_decode(n->sw) : 0, .detail = detail,
	};

	co_latch(m, &f);
}

void STRAND_RT co_send(struct co_master *m, const struct co_frame *f, uint32_t n)
{
	int rc;

	if (m->mute)
		return;
	rc = m->cfg.send(m->cfg.ctx, f, n);
	if (rc < 0) {
		/* never retried: a frame that did not go now must not go later */
		m->send_errors++;
		m->mute = true;
		co_fail(m, CO_FAULT_SEND, rc, NULL, 0);
	}
}

void STRAND_RT co_nmt(struct co_master *m, enum co_nmt_cmd cmd, uint8_t node)
{
	struct co_frame f;

	co_frame_init(&f, CO_ID_NMT, 2);
	f.data[0] = (uint8_t)cmd;
	f.data[1] = node;
	co_send(m, &f, 1);
}

int STRAND_RT co_master_fault(const struct co_master *m, struct co_fault *f)
{
	if (m->fault.kind == CO_FAULT_NONE)
		return 0;
	if (f)
		*f = m->fault;
	return m->fault.code;
}

void STRAND_RT co_master_bus(struct co_master *m, enum co_bus_state s)
{
	m->bus = (uint8_t)s;
	if (s == CO_BUS_PASSIVE) {
		co_fail(m, CO_FAULT_PASSIVE, -ECOMM, NULL, 0);
	} else if (s == CO_BUS_OFF) {
		/* off the bus: what the master would send now could only go out
		 * after a restart, long after it meant anything */
		m->mute = true;
		co_fail(m, CO_FAULT_BUS_OFF, -ENETDOWN, NULL, 0);
	}
}

/* ---- frames in ---- */

static void STRAND_RT heartbeat(struct co_master *m, struct co_node *n, uint8_t state, int64_t now)
{
	if (n->hb_last >= 0 && !n->lost)
		n->hb_last = now;
	if (state == CO_NMT_BOOTUP) {
		/* a second boot-up while configuring (powered on as we reset it,
		 * say): what was written is gone, so begin again */
		if (n->phase == CO_NODE_BOOT || n->phase == CO_NODE_CONFIG) {
			co_config_begin(m, n, now);
		} else if (n->phase != CO_NODE_IDLE && n->phase != CO_NODE_DONE) {
			/* it reset itself (or someone reset it) */
			co_fail(m, CO_FAULT_NMT, -ECONNRESET, n, CO_NMT_BOOTUP);
		}
		return;
	}
	n->nmt = state;
	/* not while enabling: a heartbeat sent just before the drive took
	 * the NMT start may still say pre-operational */
	if (n->phase == CO_NODE_ENABLED && m->phase == CO_MASTER_RUNNING &&
	    state != CO_NMT_OPERATIONAL)
		co_fail(m, CO_FAULT_NMT, -ECONNRESET, n, state);
}

static void STRAND_RT sdo(struct co_master *m, struct co_node *n, const struct co_frame *f,
			  int64_t now)
{
	struct co_frame out;

	if (n->phase != CO_NODE_CONFIG)
		return;
	if (co_sdo_rx(&n->sdo, f, now, &out))
		co_send(m, &out, 1);
	if (n->sdo.state == CO_SDO_DONE || n->sdo.state == CO_SDO_ABORTED)
		co_config_next(m, n, now);
}

static void STRAND_RT tpdo(struct co_master *m, struct co_node *n, const struct co_frame *f,
			   int64_t now)
{
	enum co402_state s;

	if (f->len < 6)
		return;
	n->sw = co_get16(&f->data[0]);
	n->actual = (int32_t)co_get32(&f->data[2]);
	/* the answer to the SYNC after the previous answer's, unless that
	 * would be one not sent yet (then the previous guess was too late) */
	n->tpdo_lo = n->tpdo_seen && n->tpdo_lo < m->syncs ? n->tpdo_lo + 1 : m->syncs;
	if (n->tpdo_lo < m->syncs)
		n->tpdo_late++;
	n->tpdo_seen = true;
	n->tpdo_sync = m->syncs;
	s = co402_decode(n->sw);
	if (n->phase == CO_NODE_ENABLING) {
		if (n->cfg.mode == CO402_MODE_CSP)
			n->target = n->actual; /* hold it where it stands */
		if (s == CO402_ENABLED)
			n->phase = CO_NODE_ENABLED;
	} else if (n->phase == CO_NODE_ENABLED && s != CO402_ENABLED &&
		   m->phase == CO_MASTER_RUNNING) {
		/* latched in poll(): an EMCY in the same batch names the cause */
		n->left = true;
	} else if (m->phase == CO_MASTER_STOPPING &&
		   (n->phase == CO_NODE_ENABLED || n->phase == CO_NODE_ENABLING) &&
		   (s == CO402_DISABLED || s == CO402_READY || s == CO402_NOT_READY ||
		    s == CO402_FAULT)) {
		n->phase = CO_NODE_DONE;
	}
}

static void STRAND_RT emcy(struct co_master *m, struct co_node *n, const struct co_emcy *e)
{
	if (e->code == CO_EMCY_RESET)
		return;
	n->emcy = *e;
	n->emcy_count++;
	if (m->phase == CO_MASTER_RUNNING && n->phase == CO_NODE_ENABLED) {
		struct co_fault f = {
			.code = -EIO, .kind = CO_FAULT_EMCY, .node = n->cfg.node,
			.state = (uint8_t)co402_decode(n->sw), .reg = e->reg, .detail = e->code,
		};

		co_latch(m, &f);
	}
}

void STRAND_RT co_master_rx(struct co_master *m, const struct co_frame *f, int64_t now)
{
	struct co_emcy e;
	unsigned fn = f->id & 0x780, id = f->id & 0x7f;
	struct co_node *n;

	if (f->id == m->cfg.sync_id || !id || m->slot[id] < 0)
		return;
	n = &m->node[m->slot[id]];
	switch (fn) {
	case CO_ID_HEARTBEAT:
		if (f->len >= 1)
			heartbeat(m, n, f->data[0] & 0x7f, now);
		break;
	case CO_ID_SDO_TX:
		sdo(m, n, f, now);
		break;
	case CO_ID_TPDO1:
		tpdo(m, n, f, now);
		break;
	case CO_ID_EMCY:
		if (co_emcy_parse(f, m->cfg.sync_id, &e))
			emcy(m, n, &e);
		break;
	}
}

/* ---- the cyclic exchange ---- */

/* RPDO1 of every node in the sequence, then the SYNC. A node that had
 * answered every SYNC before this one starts waiting for an answer now:
 * the TPDO watchdog (watch()) counts from the oldest SYNC not answered, so
 * that time without SYNCs (the pause between the start-up and the loop's
 * first tick, however long a loaded machine makes it) is not taken for a
 * drive that went silent. */
static void STRAND_RT send_cycle(struct co_master *m, int64_t now)
{
	uint32_t i, k = 0;

	for (i = 0; i < m->nnodes; i++) {
		const struct co_node *n = &m->node[i];
		struct co_frame *f = &m->cycle[k];

		if (n->phase != CO_NODE_ENABLING && n->phase != CO_NODE_ENABLED)
			continue;
		co_frame_init(f, co_rpdo_id(1, n->cfg.node), 6);
		co_put16(&f->data[0], n->cw);
		co_put32(&f->data[2], (uint32_t)n->target);
		m->node[i].sent[(m->syncs + 1) % CO_SENT_KEPT] = n->target;
		if (n->tpdo_sync == m->syncs)
			m->node[i].sync_wait = now;
		k++;
	}
	co_frame_init(&m->cycle[k++], m->cfg.sync_id, 0);
	co_send(m, m->cycle, k);
	m->syncs++;
}

void STRAND_RT co_master_stage(struct co_master *m, uint32_t i, int64_t target)
{
	struct co_node *n = &m->node[i];

	if (target < INT32_MIN || target > INT32_MAX) {
		co_fail(m, CO_FAULT_RANGE, -ERANGE, n, 0);
		return;
	}
	n->target = (int32_t)target;
}

void STRAND_RT co_master_cycle(struct co_master *m, int64_t now)
{
	/* after any fault the loop disables the device: nothing more of the
	 * motion goes out, not even this tick's */
	if (m->phase != CO_MASTER_RUNNING || m->fault.kind != CO_FAULT_NONE)
		return;
	send_cycle(m, now);
}

void STRAND_RT co_master_disable(struct co_master *m, int64_t now)
{
	uint32_t i;

	if (m->phase != CO_MASTER_RUNNING && m->phase != CO_MASTER_STARTING)
		return;
	if (m->phase == CO_MASTER_RUNNING)
		m->syncs_ran = m->syncs;
	m->phase = CO_MASTER_HALTED;
	for (i = 0; i < m->nnodes; i++)
		m->node[i].cw = CO402_CW_QUICK_STOP;
	/* the RPDOs take effect at a SYNC: one more, and then no more */
	send_cycle(m, now);
}

/* ---- start ---- */

void co_master_start(struct co_master *m, int64_t now)
{
	uint32_t i;

	m->phase = CO_MASTER_STARTING;
	m->next_cycle = now;
	for (i = 0; i < m->nnodes; i++) {
		struct co_node *n = &m->node[i];

		n->phase = CO_NODE_BOOT;
		n->deadline = now + m->cfg.boot_timeout_ms * CO_MS;
		co_nmt(m, CO_NMT_RESET_COMM, n->cfg.node);
	}
}

/* Start-up: timeouts, the 402 commands of the next cycle, and whether
 * every drive is enabled with a TPDO answering the latest SYNC. */
static void STRAND_RT poll_start(struct co_master *m, int64_t now, bool *cycling)
{
	bool all = true;
	uint32_t i;

	for (i = 0; i < m->nnodes && m->phase == CO_MASTER_STARTING; i++) {
		struct co_node *n = &m->node[i];
		struct co_frame out;

		switch (n->phase) {
		case CO_NODE_BOOT:
			if (now >= n->deadline)
				co_fail(m, CO_FAULT_BOOT, -ETIMEDOUT, n, m->cfg.boot_timeout_ms);
			break;
		case CO_NODE_CONFIG:
			if (co_sdo_poll(&n->sdo, now, &out)) {
				co_send(m, &out, 1);
				co_config_next(m, n, now);
			}
			break;
		case CO_NODE_ENABLING:
			*cycling = true;
			if (now >= n->deadline)
				co_fail(m, CO_FAULT_ENABLE, -ETIMEDOUT, n, n->sw);
			n->cw = co402_toward_enabled(co402_decode(n->sw), n->cw);
			break;
		case CO_NODE_ENABLED:
			*cycling = true;
			n->cw = CO402_CW_ENABLE_OPERATION;
			break;
		}
		all &= n->phase == CO_NODE_ENABLED && n->tpdo_seen && n->tpdo_sync == m->syncs;
	}
	if (all && m->phase == CO_MASTER_STARTING) {
		/* the loop's first tick sends the next SYNC: until then the
		 * TPDOs just received stay the answer to the latest one */
		m->phase = CO_MASTER_RUNNING;
		m->syncs_started = m->syncs;
		*cycling = false;
	}
}

/* ---- stop ---- */

void co_master_stop(struct co_master *m, int64_t now)
{
	bool halted = m->phase == CO_MASTER_HALTED;
	uint32_t i;

	if (m->phase == CO_MASTER_IDLE || m->phase == CO_MASTER_STOPPED)
		return;
	if (m->mute) {
		m->phase = CO_MASTER_FAILED;
		return;
	}
	if (m->phase == CO_MASTER_RUNNING)
		m->syncs_ran = m->syncs;
	m->phase = CO_MASTER_STOPPING;
	m->deadline = now + m->cfg.stop_timeout_ms * CO_MS;
	m->next_cycle = now;
	for (i = 0; i < m->nnodes; i++) {
		struct co_node *n = &m->node[i];

		if (n->lost || (n->phase != CO_NODE_ENABLING && n->phase != CO_NODE_ENABLED)) {
			n->phase = CO_NODE_DONE;
			continue;
		}
		/* at rest after a run: shutdown switches the power stage off;
		 * after a quick stop: let it finish its ramp */
		n->cw = halted ? CO402_CW_QUICK_STOP : CO402_CW_SHUTDOWN;
	}
}

static void STRAND_RT poll_stop(struct co_master *m, int64_t now, bool *cycling)
{
	bool all = true;
	uint32_t i;

	for (i = 0; i < m->nnodes; i++) {
		struct co_node *n = &m->node[i];

		if (n->lost)
			n->phase = CO_NODE_DONE;
		all &= n->phase == CO_NODE_DONE;
	}
	if (!all && now < m->deadline) {
		*cycling = true;
		return;
	}
	for (i = 0; i < m->nnodes; i++) {
		struct co_node *n = &m->node[i];

		if (n->phase != CO_NODE_DONE)
			co_fail(m, CO_FAULT_STOP, -ETIMEDOUT, n, m->cfg.stop_timeout_ms);
		if (!n->lost)
			co_nmt(m, CO_NMT_PREOP, n->cfg.node);
		n->phase = CO_NODE_DONE;
	}
	m->phase = all ? CO_MASTER_STOPPED : CO_MASTER_FAILED;
}

/* ---- timers ---- */

static int64_t STRAND_RT earlier(int64_t a, int64_t b)
{
	return a < b ? a : b;
}

/* The heartbeat consumer, and the TPDO watchdog of a running master. */
static int64_t STRAND_RT watch(struct co_master *m, int64_t now)
{
	int64_t limit = m->cfg.heartbeat_timeout_ms * CO_MS, next = INT64_MAX;
	uint32_t i;

	for (i = 0; i < m->nnodes; i++) {
		struct co_node *n = &m->node[i];

		if (n->hb_last >= 0 && !n->lost && n->phase != CO_NODE_DONE) {
			if (now - n->hb_last > limit) {
				n->lost = true;
				co_fail(m, CO_FAULT_HEARTBEAT, -ETIMEDOUT, n,
					m->cfg.heartbeat_timeout_ms);
			} else {
				next = earlier(next, n->hb_last + limit + 1);
			}
		}
		if (m->phase != CO_MASTER_RUNNING || n->phase != CO_NODE_ENABLED)
			continue;
		if (n->left) {
			n->left = false;
			co_fail(m, CO_FAULT_STATE, -EIO, n, n->sw);
		}
		if (!n->lost && n->tpdo_sync < m->syncs && now - n->sync_wait > limit)
			co_fail(m, CO_FAULT_TPDO, -ETIMEDOUT, n, m->cfg.heartbeat_timeout_ms);
	}
	return next;
}

int64_t STRAND_RT co_master_poll(struct co_master *m, int64_t now)
{
	int64_t next = watch(m, now);
	bool cycling = false;
	uint32_t i;

	if (m->phase == CO_MASTER_STARTING)
		poll_start(m, now, &cycling);
	else if (m->phase == CO_MASTER_STOPPING)
		poll_stop(m, now, &cycling);
	if (cycling && !m->mute) {
		if (now >= m->next_cycle) {
			send_cycle(m, now);
			/* on time from the last one, or from now when behind */
			m->next_cycle = m->next_cycle + m->period_ns > now ?
					m->next_cycle + m->period_ns : now + m->period_ns;
		}
		next = earlier(next, m->next_cycle);
	}
	if (m->phase == CO_MASTER_STOPPING)
		next = earlier(next, m->deadline);
	for (i = 0; i < m->nnodes && m->phase == CO_MASTER_STARTING; i++) {
		const struct co_node *n = &m->node[i];

		if (n->phase == CO_NODE_BOOT || n->phase == CO_NODE_ENABLING)
			next = earlier(next, n->deadline);
		else if (n->phase == CO_NODE_CONFIG && n->sdo.state == CO_SDO_BUSY)
			next = earlier(next, n->sdo.deadline);
	}
	return next;
}

bool STRAND_RT co_master_actual(const struct co_master *m, uint32_t i, int64_t *counts)
{
	const struct co_node *n = &m->node[i];
	uint64_t s, best, lo;
	int64_t d, dbest;

	if (!n->tpdo_seen || n->tpdo_sync != m->syncs)
		return false;
	if (n->cfg.mode == CO402_MODE_CSP && n->tpdo_sync - n->tpdo_lo >= CO_SENT_KEPT)
		return false; /* its target is no longer known */
	*counts = n->actual;
	if (n->cfg.mode != CO402_MODE_CSP || n->tpdo_lo == n->tpdo_sync)
		return true;
	lo = n->tpdo_lo;
	best = n->tpdo_sync;
	dbest = INT64_MAX;
	for (s = lo; s <= n->tpdo_sync; s++) {
		d = (int64_t)n->sent[s % CO_SENT_KEPT] - n->actual;
		d = d < 0 ? -d : d;
		if (d < dbest) {
			dbest = d;
			best = s;
		}
	}
	*counts += (int64_t)n->sent[n->tpdo_sync % CO_SENT_KEPT] - n->sent[best % CO_SENT_KEPT];
	return true;
}
