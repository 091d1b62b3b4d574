/* SPDX-License-Identifier: MIT */
/*
 * co_master.h - a small CANopen master for CiA 402 drives in cyclic
 * synchronous position (CSP) or velocity (CSV) mode, one SYNC per tick.
 *
 * The master is a pure state machine, as Lely's core and CANopenNode are:
 * the caller pushes in every received frame (co_master_rx) and the time
 * (co_master_poll), and frames leave through the send callback of the
 * configuration. It does no I/O and allocates nothing: the caller owns the
 * master and the array of nodes. So the same code runs against the
 * simulated drives of the tests, on vcan and on a real bus.
 *
 * A run, from the caller's side:
 *
 *   co_master_start()   reset communication of every drive, then for each,
 *                       in parallel: boot-up observed, configured by SDO
 *                       (device type 402, 0x6060 mode, 0x60C2 interpolation
 *                       period, 0x605A/0x6085 quick stop, RPDO1 and TPDO1
 *                       mapped and synchronous, other PDOs off, 0x1017
 *                       heartbeat), NMT start, then taken to "operation
 *                       enabled" through the controlword in RPDO1 while
 *                       SYNCs go out each period holding the position
 *                       actual; co_master_poll() does the timing until
 *                       co_master_phase() says RUNNING (or FAILED).
 *   each tick           co_master_rx() for what arrived, co_master_poll(),
 *                       co_master_stage() per drive, co_master_cycle():
 *                       the RPDOs, then one SYNC.
 *   co_master_disable() quick stop: every drive brakes on its own ramp
 *                       (0x6085) and switches off; nothing cyclic is sent
 *                       any more.
 *   co_master_stop()    shutdown (or the quick stop finished), confirmed by
 *                       the statusword, then NMT pre-operational.
 *
 * Faults are latched, the first one kept, as a struct co_fault with a kind
 * and numbers; co_fault_cause() gives static text for the loop and
 * co_master_describe() a full sentence for the command line.
 *
 * Unless said otherwise, functions are [rt]: bounded time, no allocation, no
 * blocking; the send callback must be the same.
 */
#ifndef CO_MASTER_H
#define CO_MASTER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co_402.h"
#include "co_emcy.h"
#include "co_frame.h"
#include "co_sdo.h"
#include "hal/rt.h" /* STRAND_RT */

/* A drive, as the master is told of it. */
struct co_drive_cfg {
	uint8_t node;            /* node-ID, 1..127 */
	uint8_t mode;            /* CO402_MODE_CSP or CO402_MODE_CSV */
	uint32_t quick_stop_dec; /* 0x6085 in the drive's units per second (CSP:
				  * counts/s^2); 0 leaves the drive's own */
};

struct co_master_cfg {
	uint32_t tick_hz;           /* the SYNC rate, also 0x60C2 */
	uint16_t sync_id;           /* COB-ID of the SYNC (0x80) */
	uint16_t heartbeat_ms;      /* asked of every drive (0x1017) */
	uint32_t heartbeat_timeout_ms; /* a drive silent this long is lost */
	uint32_t boot_timeout_ms;   /* from reset communication to boot-up */
	uint32_t sdo_timeout_ms;    /* per SDO request */
	uint32_t enable_timeout_ms; /* from NMT start to operation enabled */
	uint32_t stop_timeout_ms;   /* for the drives to confirm the stop */
	co_send_fn send;
	void *ctx;
};

enum co_master_phase {
	CO_MASTER_IDLE,
	CO_MASTER_STARTING, /* start-up sequence under way */
	CO_MASTER_RUNNING,  /* every drive enabled: cyclic exchange */
	CO_MASTER_HALTED,   /* disabled: quick stop sent, nothing cyclic */
	CO_MASTER_STOPPING, /* co_master_stop() under way */
	CO_MASTER_STOPPED,  /* drives off, pre-operational */
	CO_MASTER_FAILED,   /* a fault ended the start-up or the stop */
};

/* Where a node is in the master's sequence. */
enum co_node_phase {
	CO_NODE_IDLE,
	CO_NODE_BOOT,     /* reset communication sent, waiting for boot-up */
	CO_NODE_CONFIG,   /* SDO configuration */
	CO_NODE_ENABLING, /* NMT started, 402 sequence */
	CO_NODE_ENABLED,  /* operation enabled */
	CO_NODE_DONE,     /* stopped, or lost */
};

enum co_fault_kind {
	CO_FAULT_NONE,
	CO_FAULT_BOOT,      /* no boot-up after reset communication */
	CO_FAULT_SDO,       /* a configuration transfer was aborted */
	CO_FAULT_PROFILE,   /* the device type is not CiA 402 */
	CO_FAULT_ENABLE,    /* no "operation enabled" in time */
	CO_FAULT_HEARTBEAT, /* heartbeat lost: the drive is gone */
	CO_FAULT_NMT,       /* the drive left operational (reset, stopped) */
	CO_FAULT_EMCY,      /* an emergency message */
	CO_FAULT_STATE,     /* the statusword left "operation enabled" */
	CO_FAULT_TPDO,      /* TPDOs stopped while heartbeats go on */
	CO_FAULT_RANGE,     /* a target beyond the drive's 32 bits */
	CO_FAULT_PASSIVE,   /* the controller went error-passive */
	CO_FAULT_BUS_OFF,   /* the controller went bus-off */
	CO_FAULT_SEND,      /* the bus refused frames */
	CO_FAULT_STOP,      /* a drive did not confirm the stop in time */
};

struct co_fault {
	int code;          /* negative errno */
	uint8_t kind;      /* enum co_fault_kind */
	uint8_t node;      /* node-ID; 0: the bus */
	uint8_t state;     /* the drive's enum co402_state then */
	uint8_t sub;       /* SDO: the object's sub-index */
	bool read;         /* SDO: an upload */
	uint16_t index;    /* SDO: the object */
	uint16_t reg;      /* EMCY: error register */
	uint32_t detail;   /* EMCY code, SDO abort code, statusword, ms */
};

/* Targets kept per node: a TPDO later than this many SYNCs is not matched
 * to its target (co_master_actual). 16 cover 32 ms of a loop at 500 Hz
 * catching up. */
#define CO_SENT_KEPT 16

struct co_node {
	struct co_drive_cfg cfg;
	uint8_t phase;       /* enum co_node_phase */
	uint8_t step;        /* configuration step (co_config.c) */
	uint8_t nmt;         /* NMT state of the last heartbeat */
	bool lost;           /* heartbeat lost */
	bool tpdo_seen;
	bool left;           /* the statusword left "operation enabled" */
	uint16_t cw;         /* controlword of the last RPDO */
	uint16_t sw;         /* statusword of the last TPDO */
	int32_t target;      /* for the next RPDO */
	int32_t actual;      /* position actual of the last TPDO */
	uint64_t tpdo_sync;  /* SYNCs sent when the last TPDO came */
	/* A TPDO carries no SYNC number: the one that came when tpdo_sync
	 * SYNCs were out answers one of SYNCs tpdo_lo..tpdo_sync. tpdo_lo is
	 * the previous TPDO's plus one (each SYNC has one answer, in order),
	 * never above tpdo_sync; they differ only when the drive answered
	 * after the next SYNC had gone (a drive starved of CPU, a loop that
	 * caught up on late ticks). */
	uint64_t tpdo_lo;
	uint32_t tpdo_late;  /* TPDOs that came after the next SYNC */
	int32_t sent[CO_SENT_KEPT]; /* sent[s % CO_SENT_KEPT]: target before SYNC s */
	int64_t hb_last;     /* the last heartbeat; consumer runs when >= 0 */
	int64_t sync_wait;   /* the oldest SYNC not answered yet went out */
	int64_t deadline;    /* of the phase */
	struct co_sdo sdo;
	uint8_t xfer[4];     /* the expedited value under way */
	uint32_t device_type;
	char name[33];       /* 0x1008, when the drive has one */
	struct co_emcy emcy; /* the last emergency with a non-zero code */
	uint32_t emcy_count;
};

struct co_master {
	struct co_master_cfg cfg;
	struct co_node *node;
	uint32_t nnodes;
	int16_t slot[CO_NODE_MAX + 1]; /* node-ID -> index in node[], -1 */
	uint8_t phase;                 /* enum co_master_phase */
	uint8_t bus;                   /* enum co_bus_state */
	bool mute;                     /* nothing more may be sent */
	uint8_t ip_value;              /* 0x60C2:01 */
	int8_t ip_exp;                 /* 0x60C2:02 */
	int64_t period_ns;
	int64_t next_cycle;            /* start and stop: the next SYNC */
	int64_t deadline;              /* stop */
	uint64_t syncs;                /* SYNCs sent */
	/* SYNCs sent when the start-up ended (every drive enabled and
	 * answering the latest SYNC) and when the run ended (the stop or
	 * the quick stop began); 0 until then */
	uint64_t syncs_started, syncs_ran;
	uint64_t send_errors;
	struct co_fault fault;         /* the first; kind NONE while healthy */
	/* frames of one cycle: an RPDO per node and the SYNC */
	struct co_frame *cycle;
};

/*
 * [init] Set up a master for n drives: nodes (n elements) and cycle (n + 1
 * frames) are the caller's. 0, or -EINVAL for a bad node-ID or mode, a node
 * listed twice or a tick rate 0x60C2 cannot express within 0.1%.
 */
int co_master_init(struct co_master *m, const struct co_master_cfg *cfg,
		   const struct co_drive_cfg *drives, struct co_node *nodes,
		   struct co_frame *cycle, uint32_t n);

/* The interpolation period 0x60C2 of a tick rate: value (1..255) times ten
 * to the exp seconds. 0 when exact, 1 when within 0.1%, -EINVAL otherwise. */
int co_interp_period(uint32_t tick_hz, uint8_t *value, int8_t *exp);

/* Begin the start-up sequence. */
void co_master_start(struct co_master *m, int64_t now);

/* A frame received from the bus. */
void co_master_rx(struct co_master *m, const struct co_frame *f, int64_t now);

/* The controller's state changed (from the transport's error frames). */
void co_master_bus(struct co_master *m, enum co_bus_state s);

/* Timers: timeouts, the heartbeat consumer, and during start and stop the
 * SYNC cycle. Returns the time it next needs a call by. */
int64_t co_master_poll(struct co_master *m, int64_t now);

/* Stage drive i's target for the next cycle: position in counts (CSP) or
 * velocity (CSV). A value beyond 32 bits latches CO_FAULT_RANGE. */
void co_master_stage(struct co_master *m, uint32_t i, int64_t target);

/* The cyclic exchange of a running master: every RPDO, then one SYNC, in
 * one call of send. Nothing once halted or faulted on the bus. */
void co_master_cycle(struct co_master *m, int64_t now);

/* Quick stop of every drive, at once; the master halts. Idempotent. */
void co_master_disable(struct co_master *m, int64_t now);

/* Begin the orderly stop; co_master_poll() carries it on until the phase
 * is STOPPED (or FAILED with CO_FAULT_STOP). */
void co_master_stop(struct co_master *m, int64_t now);

static inline enum co_master_phase STRAND_RT co_master_phase(const struct co_master *m)
{
	return (enum co_master_phase)m->phase;
}

/* The first fault: 0 while healthy, else its negative errno and *f. */
int co_master_fault(const struct co_master *m, struct co_fault *f);

/* Drive i's position actual from a TPDO that came since the latest SYNC:
 * false when none has (late, or lost). In cyclic synchronous position the
 * value is moved by as much as the target moved since the SYNC the TPDO
 * answers, so that the latest target minus it is the following error the
 * drive had then, however late its answer. When that SYNC is not certain
 * (struct co_node: tpdo_lo) it is the one of the possible SYNCs whose
 * target the drive was closest to: a late answer never reads as a
 * following error it did not have. False too when the answer may be older
 * than the targets kept (CO_SENT_KEPT SYNCs). */
bool co_master_actual(const struct co_master *m, uint32_t i, int64_t *counts);

/* Index of the drive with this node-ID, or -1. */
int co_master_index(const struct co_master *m, uint8_t node);

/* Drive i's mode of operation as configured (enum co402_mode): which of a
 * setpoint's position and velocity its target is. */
static inline uint8_t co_master_mode(const struct co_master *m, uint32_t i)
{
	return m->node[i].cfg.mode;
}

/* The identifiers the master consumes from these drives (EMCY, TPDO1, SDO
 * response, heartbeat of each: 4 per drive) into ids; how many. For a
 * transport's receive filter. */
uint32_t co_master_rx_ids(const struct co_drive_cfg *drives, uint32_t n, uint16_t *ids);

/* Static text for a fault, for the loop's report. */
const char *co_fault_cause(const struct co_fault *f);

/* [init] The fault as a sentence that names the node and the numbers. */
void co_master_describe(const struct co_master *m, const struct co_fault *f, char *buf,
			size_t size);

const char *co_bus_state_name(enum co_bus_state s);

#endif /* CO_MASTER_H */
