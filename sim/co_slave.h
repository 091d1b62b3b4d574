/* SPDX-License-Identifier: MIT */
/*
 * co_slave.h - a simulated CiA 402 servo drive on a CAN bus: NMT with its
 * boot-up message, an SDO server (expedited and segmented) for the objects
 * the master configures, RPDO1/TPDO1 with the mappings it writes, the 402
 * state machine (co_402.h), heartbeat producer, emergency messages when a
 * fault is injected, and behind it the same plant as the in-process drive
 * (sim_drive.h), advanced one interpolation period (0x60C2) per SYNC.
 *
 * Like the master it is a pure state machine: frames and time pushed in,
 * frames out through a send callback. The simulated bus runs it in-process
 * on virtual time (co_simbus.h); strand-simdrive runs it on a real SocketCAN
 * interface.
 *
 * Timing of a SYNC: the RPDO data received since the last SYNC takes
 * effect (controlword, then target), the plant integrates the period the
 * SYNC opens, and the TPDO reports the statusword and the position at the
 * end of it. That is the in-process drive's order too (set, commit, then
 * input advancing the plant), so a run shows the same following errors on
 * either.
 *
 * A quick stop (controlword, or leaving NMT operational while enabled)
 * runs on the drive's own clock, one period at a time from co_slave_poll():
 * the target brakes at the quick stop deceleration 0x6085 (at once if 0),
 * then, with option code 2 (0x605A), the drive switches off.
 *
 * Objects beyond CiA 301/402: 0x2000 (u16, write) injects a fault with that
 * emergency code; 0x2001 (a string of up to 64 bytes) is a note that reads
 * back what was written, for segmented transfers.
 *
 * Functions are [init] and not thread-safe: one thread runs a drive.
 */
#ifndef CO_SLAVE_H
#define CO_SLAVE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "hal/canopen/co_402.h"
#include "hal/canopen/co_frame.h"
#include "sim_drive.h"

struct co_slave_cfg {
	uint8_t node;                    /* 1..127 */
	const char *name;                /* 0x1008 (kept, not copied) */
	struct sim_drive_channel model;  /* the plant; velocity_mode comes from 0x6060 */
	int32_t initial;                 /* position actual at power-on */
	co_send_fn send;
	void *ctx;
};

/* One entry of the 402 transitions a drive made. */
struct co_slave_transition {
	uint8_t from, to; /* enum co402_state */
	uint16_t cw;      /* the controlword then (0 for the drive's own) */
};

#define CO_SLAVE_LOG 64

/* What a drive did, for tests and for strand-simdrive's report. */
struct co_slave_watch {
	uint8_t nmt;           /* enum co_nmt_state */
	uint8_t state;         /* enum co402_state */
	uint16_t cw, sw;
	int8_t mode;           /* 0x6060 */
	uint16_t heartbeat_ms; /* 0x1017 */
	uint16_t error_code;   /* 0x603F */
	int32_t target;        /* the target in effect (position or velocity) */
	int32_t actual;        /* 0x6064 */
	uint64_t syncs;        /* SYNCs taken in operational */
	uint64_t rpdos, tpdos, heartbeats, emcys, sdo_requests;
	uint32_t ntransitions; /* all made; the log keeps the first CO_SLAVE_LOG */
	struct co_slave_transition log[CO_SLAVE_LOG];
};

struct co_slave;

/* [init] A drive, powered off, into *out. 0, or a negative errno (-EINVAL
 * a bad parameter, -ENOMEM) with a message in err naming the device and
 * the node; err may be NULL when errsize is 0. */
int co_slave_new(struct co_slave **out, const struct co_slave_cfg *cfg, char *err,
		 size_t errsize);
void co_slave_free(struct co_slave *s);

/* Power on: its boot-up message, then pre-operational. */
void co_slave_power_on(struct co_slave *s, int64_t now);
/* Power gone: silent from now on (a killed process, a cut cable). */
void co_slave_power_off(struct co_slave *s);
bool co_slave_powered(const struct co_slave *s);

/* A frame from the bus (the drive keeps what is addressed to it). */
void co_slave_rx(struct co_slave *s, const struct co_frame *f, int64_t now);
/* Its own timers: heartbeat, quick stop ramp. Returns when it next needs
 * a call. */
int64_t co_slave_poll(struct co_slave *s, int64_t now);

/* A fault: emergency message with this code, fault reaction, fault. */
void co_slave_fault(struct co_slave *s, uint16_t code, int64_t now);

/* At time at_ns (from co_slave_poll on): a fault with this emergency code,
 * or with code 0 a power cut. One pending at a time. */
void co_slave_inject(struct co_slave *s, int64_t at_ns, uint16_t code);

/* Tests: the next SDO access to index:sub is answered with this abort
 * (0: no longer); the drive ignores SDO requests while deaf; its 402 state
 * machine ignores the controlword while stuck. */
void co_slave_refuse(struct co_slave *s, uint16_t index, uint8_t sub, uint32_t abort);
void co_slave_sdo_deaf(struct co_slave *s, bool deaf);
void co_slave_stuck(struct co_slave *s, bool stuck);

/* Every target that took effect at a SYNC while enabled goes into buf, up
 * to cap of them. */
void co_slave_trace(struct co_slave *s, int32_t *buf, uint32_t cap);
uint32_t co_slave_traced(const struct co_slave *s);

/* What it did: a live view, current after every call into the drive. */
const struct co_slave_watch *co_slave_watch(const struct co_slave *s);
uint8_t co_slave_node(const struct co_slave *s);
/* The SYNC's identifier it listens to (0x1005). */
uint16_t co_slave_sync_id(const struct co_slave *s);

#endif /* CO_SLAVE_H */
