/* SPDX-License-Identifier: MIT */
/* co_describe.c - a master's faults in words (see co_master.h). */
#include "co_master_priv.h"

#include <stdio.h>
#include <string.h>

#include "hal/rt.h"

const char STRAND_RT *co_fault_cause(const struct co_fault *f)
{
	switch (f->kind) {
	case CO_FAULT_NONE:
		return "";
	case CO_FAULT_BOOT:
		return "no boot-up";
	case CO_FAULT_SDO:
		return "configuration aborted (SDO)";
	case CO_FAULT_PROFILE:
		return "not a CiA 402 drive";
	case CO_FAULT_ENABLE:
		return "did not reach operation enabled in time";
	case CO_FAULT_HEARTBEAT:
		return "heartbeat lost";
	case CO_FAULT_NMT:
		return f->detail == CO_NMT_BOOTUP ? "drive rebooted" : "left NMT operational";
	case CO_FAULT_EMCY:
		return "emergency";
	case CO_FAULT_STATE:
		return "left operation enabled";
	case CO_FAULT_TPDO:
		return "TPDOs stopped";
	case CO_FAULT_RANGE:
		return "target beyond the drive's 32 bits";
	case CO_FAULT_PASSIVE:
		return "bus error-passive";
	case CO_FAULT_BUS_OFF:
		return "bus-off";
	case CO_FAULT_SEND:
		return "bus refused a frame";
	case CO_FAULT_STOP:
		return "stop not confirmed";
	}
	return "fault";
}

const char *co_bus_state_name(enum co_bus_state s)
{
	switch (s) {
	case CO_BUS_ACTIVE:
		return "error-active";
	case CO_BUS_WARNING:
		return "error warning";
	case CO_BUS_PASSIVE:
		return "error-passive";
	case CO_BUS_OFF:
		return "bus-off";
	}
	return "?";
}

static const char *nmt_name(uint32_t s)
{
	switch (s) {
	case CO_NMT_BOOTUP:
		return "boot-up: it reset";
	case CO_NMT_STOPPED:
		return "stopped";
	case CO_NMT_OPERATIONAL:
		return "operational";
	case CO_NMT_PREOPERATIONAL:
		return "pre-operational";
	}
	return "unknown NMT state";
}

/* "; last emergency 0x2310 (...)" when the node sent one. */
static void last_emcy(const struct co_master *m, uint8_t node, char *buf, size_t size)
{
	int i = co_master_index(m, node);
	const struct co_node *n = i >= 0 ? &m->node[i] : NULL;

	buf[0] = '\0';
	if (n && n->emcy_count)
		snprintf(buf, size, "; last emergency 0x%04X (%s)", n->emcy.code,
			 co_emcy_class(n->emcy.code));
}

void co_master_describe(const struct co_master *m, const struct co_fault *f, char *buf,
			size_t size)
{
	const char *st = co402_state_name((enum co402_state)f->state);
	char node[16] = "", em[112];

	STRAND_ASSERT_NOT_RT();
	if (f->node)
		snprintf(node, sizeof(node), "node %u: ", f->node);
	last_emcy(m, f->node, em, sizeof(em));
	switch (f->kind) {
	case CO_FAULT_BOOT:
		snprintf(buf, size, "%sno boot-up message within %u ms of the NMT reset "
			 "communication (powered, wired, node-ID and bitrate right?)", node,
			 f->detail);
		break;
	case CO_FAULT_SDO:
		snprintf(buf, size, "%sSDO %s of 0x%04X:%02X aborted: %s (0x%08X)", node,
			 f->read ? "read" : "write", f->index, f->sub, co_abort_name(f->detail),
			 f->detail);
		break;
	case CO_FAULT_PROFILE:
		snprintf(buf, size, "%sdevice type 0x%08X: profile %u, not a CiA 402 drive", node,
			 f->detail, f->detail & 0xffff);
		break;
	case CO_FAULT_ENABLE:
		snprintf(buf, size, "%sdid not reach operation enabled within %u ms: statusword "
			 "0x%04X (%s)%s", node, m->cfg.enable_timeout_ms, f->detail, st, em);
		break;
	case CO_FAULT_HEARTBEAT:
		snprintf(buf, size, "%sheartbeat lost: none for %u ms", node, f->detail);
		break;
	case CO_FAULT_NMT:
		snprintf(buf, size, "%sleft NMT operational: %s", node, nmt_name(f->detail));
		break;
	case CO_FAULT_EMCY:
		snprintf(buf, size, "%semergency 0x%04X (%s), error register 0x%02X, drive %s",
			 node, f->detail, co_emcy_class((uint16_t)f->detail), f->reg, st);
		break;
	case CO_FAULT_STATE:
		snprintf(buf, size, "%sleft operation enabled: statusword 0x%04X (%s)%s", node,
			 f->detail, st, em);
		break;
	case CO_FAULT_TPDO:
		snprintf(buf, size, "%sno TPDO for %u ms while its heartbeat goes on", node,
			 f->detail);
		break;
	case CO_FAULT_RANGE:
		snprintf(buf, size, "%sa target beyond the drive's 32-bit range", node);
		break;
	case CO_FAULT_PASSIVE:
		snprintf(buf, size, "bus error-passive: frames are not acknowledged or arrive "
			 "corrupted (wiring, termination, bitrate, powered drives?)");
		break;
	case CO_FAULT_BUS_OFF:
		snprintf(buf, size, "bus-off: the controller left the bus after too many errors; "
			 "nothing queued is sent after it");
		break;
	case CO_FAULT_SEND:
		snprintf(buf, size, "the bus refused a frame: %s; nothing later was sent",
			 strerror(f->code < 0 ? -f->code : f->code));
		break;
	case CO_FAULT_STOP:
		snprintf(buf, size, "%sdid not confirm the stop within %u ms: still %s", node,
			 f->detail, st);
		break;
	default:
		snprintf(buf, size, "no fault");
		break;
	}
}
