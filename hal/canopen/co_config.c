/* SPDX-License-Identifier: MIT */
/*
 * co_config.c - the configuration of a drive after its boot-up, by SDO, one
 * transfer at a time (see co_master.h for the whole start-up).
 *
 * PDO mapping follows CiA 301 7.5.2.36-7.5.2.38: a PDO is switched off
 * (bit 31 of its COB-ID) while its mapping changes, the mapping's count is
 * set to 0, the entries written, the count set, and the PDO switched on
 * again. The master maps one PDO each way:
 *
 *   RPDO1 (0x1400/0x1600): controlword 0x6040 (16 bits), then the target
 *         position 0x607A (CSP) or target velocity 0x60FF (CSV), 32 bits;
 *   TPDO1 (0x1800/0x1A00): statusword 0x6041 (16), position actual 0x6064 (32);
 *
 * both of transmission type 1: an RPDO takes effect at the next SYNC, a TPDO
 * is sampled and sent at every SYNC. The other three PDOs each way are
 * switched off, so that nothing else takes the bus's time (co_load.h counts
 * on it); a drive that does not have them says so and that is fine.
 */
#include "co_master_priv.h"

#include <errno.h>
#include <string.h>

#include "hal/rt.h"

enum val {
	V_CONST,      /* value as given */
	V_HEARTBEAT,  /* cfg.heartbeat_ms */
	V_MODE,       /* the drive's mode of operation */
	V_IP_VALUE,   /* 0x60C2:01 */
	V_IP_EXP,     /* 0x60C2:02 */
	V_QS_DEC,     /* quick stop deceleration; the step is skipped when 0 */
	V_TARGET_MAP, /* 0x607A or 0x60FF, 32 bits */
	V_PLUS_NODE,  /* value + node-ID */
	V_SYNC_ID,    /* the SYNC's COB-ID; the step is skipped for the default */
};

enum opt {
	REQUIRED,
	IF_PRESENT, /* "object / sub-index does not exist" skips it */
	ANY_ABORT,  /* any failure skips it (what is only informative) */
};

struct step {
	uint16_t index;
	uint8_t sub;
	uint8_t size;   /* bytes written, or read at most */
	bool read;
	uint8_t opt;    /* enum opt */
	uint8_t val;    /* enum val */
	uint32_t value;
};

#define OFF CO_PDO_COBID_OFF
#define NORTR CO_PDO_COBID_NO_RTR

static const struct step steps[] = {
	{ 0x1000, 0, 4, true, REQUIRED, V_CONST, 0 },   /* device type: CiA 402? */
	{ 0x1008, 0, 32, true, ANY_ABORT, V_CONST, 0 }, /* device name (segmented) */
	{ 0x1005, 0, 4, false, REQUIRED, V_SYNC_ID, 0 },
	{ 0x1017, 0, 2, false, REQUIRED, V_HEARTBEAT, 0 },
	{ 0x6060, 0, 1, false, REQUIRED, V_MODE, 0 },
	{ 0x60c2, 1, 1, false, REQUIRED, V_IP_VALUE, 0 },
	{ 0x60c2, 2, 1, false, REQUIRED, V_IP_EXP, 0 },
	{ 0x605a, 0, 2, false, REQUIRED, V_CONST, CO402_QUICK_STOP_RAMP_THEN_DISABLE },
	{ 0x6085, 0, 4, false, REQUIRED, V_QS_DEC, 0 },
	/* RPDO1 */
	{ 0x1400, 1, 4, false, REQUIRED, V_PLUS_NODE, OFF | CO_ID_RPDO1 },
	{ 0x1600, 0, 1, false, REQUIRED, V_CONST, 0 },
	{ 0x1600, 1, 4, false, REQUIRED, V_CONST, 0x60400010 },
	{ 0x1600, 2, 4, false, REQUIRED, V_TARGET_MAP, 0 },
	{ 0x1600, 0, 1, false, REQUIRED, V_CONST, 2 },
	{ 0x1400, 2, 1, false, REQUIRED, V_CONST, CO_PDO_SYNC_EVERY },
	{ 0x1400, 1, 4, false, REQUIRED, V_PLUS_NODE, CO_ID_RPDO1 },
	{ 0x1401, 1, 4, false, IF_PRESENT, V_PLUS_NODE, OFF | 0x300 },
	{ 0x1402, 1, 4, false, IF_PRESENT, V_PLUS_NODE, OFF | 0x400 },
	{ 0x1403, 1, 4, false, IF_PRESENT, V_PLUS_NODE, OFF | 0x500 },
	/* TPDO1 */
	{ 0x1800, 1, 4, false, REQUIRED, V_PLUS_NODE, OFF | NORTR | CO_ID_TPDO1 },
	{ 0x1a00, 0, 1, false, REQUIRED, V_CONST, 0 },
	{ 0x1a00, 1, 4, false, REQUIRED, V_CONST, 0x60410010 },
	{ 0x1a00, 2, 4, false, REQUIRED, V_CONST, 0x60640020 },
	{ 0x1a00, 0, 1, false, REQUIRED, V_CONST, 2 },
	{ 0x1800, 2, 1, false, REQUIRED, V_CONST, CO_PDO_SYNC_EVERY },
	{ 0x1800, 1, 4, false, REQUIRED, V_PLUS_NODE, NORTR | CO_ID_TPDO1 },
	{ 0x1801, 1, 4, false, IF_PRESENT, V_PLUS_NODE, OFF | NORTR | 0x280 },
	{ 0x1802, 1, 4, false, IF_PRESENT, V_PLUS_NODE, OFF | NORTR | 0x380 },
	{ 0x1803, 1, 4, false, IF_PRESENT, V_PLUS_NODE, OFF | NORTR | 0x480 },
	/* where it stands and what state it is in: the start of the 402 sequence */
	{ 0x6064, 0, 4, true, REQUIRED, V_CONST, 0 },
	{ 0x6041, 0, 2, true, REQUIRED, V_CONST, 0 },
};

#define NSTEPS (sizeof(steps) / sizeof(steps[0]))

/* The value step s writes to node n; false: skip the step. */
static bool STRAND_RT value_of(const struct co_master *m, const struct co_node *n,
			       const struct step *s, uint32_t *v)
{
	switch (s->val) {
	case V_HEARTBEAT:
		*v = m->cfg.heartbeat_ms;
		return true;
	case V_MODE:
		*v = n->cfg.mode;
		return true;
	case V_IP_VALUE:
		*v = m->ip_value;
		return true;
	case V_IP_EXP:
		*v = (uint8_t)m->ip_exp;
		return true;
	case V_QS_DEC:
		*v = n->cfg.quick_stop_dec;
		return *v != 0;
	case V_TARGET_MAP:
		*v = n->cfg.mode == CO402_MODE_CSV ? 0x60ff0020 : 0x607a0020;
		return true;
	case V_PLUS_NODE:
		*v = s->value + n->cfg.node;
		return true;
	case V_SYNC_ID:
		*v = m->cfg.sync_id;
		return *v != CO_ID_SYNC;
	default:
		*v = s->value;
		return true;
	}
}

/* Where a read goes. */
static uint8_t STRAND_RT *read_buf(struct co_node *n, const struct step *s)
{
	return s->index == 0x1008 ? (uint8_t *)n->name : n->xfer;
}

/* Issue step n->step, or the next one not skipped; past the last, NMT
 * start and on to the 402 sequence. */
static void STRAND_RT issue(struct co_master *m, struct co_node *n, int64_t now)
{
	const struct step *s = NULL;
	struct co_frame out;
	uint32_t v = 0;

	for (; n->step < NSTEPS; n->step++) {
		s = &steps[n->step];
		if (s->read || value_of(m, n, s, &v))
			break;
	}
	if (n->step == NSTEPS) {
		co_nmt(m, CO_NMT_START, n->cfg.node);
		n->phase = CO_NODE_ENABLING;
		n->deadline = now + m->cfg.enable_timeout_ms * CO_MS;
		return;
	}
	if (s->read) {
		co_sdo_upload(&n->sdo, s->index, s->sub, read_buf(n, s),
			      s->index == 0x1008 ? sizeof(n->name) - 1 : s->size, now, &out);
	} else {
		co_put(n->xfer, v, s->size);
		co_sdo_download(&n->sdo, s->index, s->sub, n->xfer, s->size, now, &out);
	}
	co_send(m, &out, 1);
}

void STRAND_RT co_config_begin(struct co_master *m, struct co_node *n, int64_t now)
{
	n->phase = CO_NODE_CONFIG;
	n->step = 0;
	n->name[0] = '\0';
	issue(m, n, now);
}

static void STRAND_RT sdo_fault(struct co_master *m, struct co_node *n, const struct step *s,
				uint32_t abort)
{
	struct co_fault f = {
		.code = -EIO, .kind = CO_FAULT_SDO, .node = n->cfg.node, .index = s->index,
		.sub = s->sub, .read = s->read, .detail = abort,
	};

	co_latch(m, &f);
}

/* What a read brought: false when it is not acceptable (fault latched). */
static bool STRAND_RT take(struct co_master *m, struct co_node *n, const struct step *s,
			   int64_t now)
{
	uint32_t got = n->sdo.pos;

	if (s->index == 0x1008) {
		n->name[got] = '\0';
		return true;
	}
	if (got != s->size) {
		sdo_fault(m, n, s, CO_ABORT_TYPE_LEN);
		return false;
	}
	switch (s->index) {
	case 0x1000:
		n->device_type = co_get32(n->xfer);
		if ((n->device_type & 0xffff) != 402) {
			co_fail(m, CO_FAULT_PROFILE, -ENODEV, n, n->device_type);
			return false;
		}
		break;
	case 0x6064:
		n->actual = (int32_t)co_get32(n->xfer);
		n->target = n->cfg.mode == CO402_MODE_CSV ? 0 : n->actual;
		break;
	case 0x6041:
		n->sw = co_get16(n->xfer);
		break;
	}
	return true;
}

void STRAND_RT co_config_next(struct co_master *m, struct co_node *n, int64_t now)
{
	const struct step *s = &steps[n->step];

	if (n->sdo.state == CO_SDO_ABORTED) {
		uint32_t a = n->sdo.abort;

		if (s->opt == ANY_ABORT ||
		    (s->opt == IF_PRESENT && (a == CO_ABORT_NO_OBJECT || a == CO_ABORT_NO_SUB))) {
			if (s->index == 0x1008)
				n->name[0] = '\0';
		} else {
			sdo_fault(m, n, s, a);
			return;
		}
	} else if (s->read && !take(m, n, s, now)) {
		return;
	}
	/* the heartbeat consumer runs from when the drive was told to beat */
	if (s->index == 0x1017)
		n->hb_last = now;
	n->step++;
	issue(m, n, now);
}
