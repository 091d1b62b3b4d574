/* SPDX-License-Identifier: MIT */
/*
 * modbus_dev.h - servo drives on Modbus (TCP or RTU) behind the HAL axis
 * interface, over libmodbus.
 *
 * A device is one Modbus unit: its axes' targets are holding registers
 * written every update (function 16, one request per block of adjacent
 * registers, modbus_map.h), optionally with the loop's tick as a heartbeat
 * in the same write; optionally an enable coil or register set at start and
 * cleared at stop, and a status register and the axes' actual-position
 * registers read every read_every ticks.
 *
 * libmodbus blocks, so it never runs on the loop's thread. Each device has
 * an I/O thread of its own, strand-mb-DEVICE, scheduled as cfg.sched says
 * (a bus: one connection, one serial line):
 *
 *   strand-rt                          modbus I/O thread
 *   set() stages counts
 *   commit() on an update tick --slot(newest wins)--> write blocks, read
 *            and wakes the thread                   every read_every ticks
 *   input() <------------------ring: completions, actual, status, faults--
 *   disable() -----ring: disable------------------> clear the enable
 *
 * A bus that cannot keep up loses the older setpoint to the newer (the slot
 * keeps the newest; each replaced one is counted), and when no write has
 * completed for max_silence_ms while setpoints wait the device faults: the
 * loop never waits for the bus. Failed transactions (no answer within the
 * response timeout, an exception answer, a dropped connection) are counted;
 * max_faults of them in a row fault the device, with a message that names
 * the unit and register, written by the I/O thread before it reports. A TCP
 * connection that drops is made again while the rig is at rest (the drive
 * holds the very setpoint the loop sends); while it moves, each update that
 * cannot go out counts as a failed one.
 *
 * On the virtual clock (lockstep) input() waits for the previous update to
 * complete: a run is then the same on every run, one update per update
 * tick, as fast as the bus answers.
 */
#ifndef HAL_MODBUS_DEV_H
#define HAL_MODBUS_DEV_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hal/axis.h"
#include "hal/cancel.h"
#include "hal/thread.h"
#include "modbus_desc.h"

/* How the backend is opened. */
struct modbus_cfg {
	const char *name;             /* the device's name (kept, not copied) */
	const struct modbus_desc *d;  /* kept: must outlive the backend */
	uint32_t tick_hz;
	uint32_t nch;                 /* channels used, <= d->naxes */
	const int64_t *initial;       /* nch: a channel's target at start without feedback */
	const bool *velocity;         /* nch: the target register takes the velocity */
	bool lockstep;                /* the loop runs on the virtual clock */
	/* kept: looked at between the start's transactions (connect, read,
	 * write, enable); once set, start() sets nothing more, clears an
	 * enable it set, and returns -ECANCELED. NULL: never. */
	const struct hal_cancel *cancel;
	struct hal_sched sched;       /* the I/O thread's (zero: SCHED_OTHER) */
};

/* [init] The backend into *out (not connected yet: start() connects). 0,
 * or a negative errno (-EINVAL a bad map, -ENOMEM) with a message in err
 * naming the device. */
int hal_modbus_open(struct hal_axis **out, const struct modbus_cfg *c, char *err,
		    size_t errsize);

/* What the device's bus did. Read after the loop ended. */
struct modbus_stats {
	int64_t updates;     /* setpoint updates the loop published */
	int64_t replaced;    /* ... replaced by a newer one before the bus took it */
	int64_t written;     /* updates the drive received */
	int64_t held;        /* at rest while the connection was being made again */
	int64_t reads;
	int64_t timeouts;    /* transactions without an answer in time */
	int64_t exceptions;  /* exception answers */
	int64_t drops;       /* connections lost */
	int64_t reconnects;
	int64_t other;       /* other failed transactions (bad CRC, bad data) */
	int64_t unsent;      /* updates lost to a dropped connection while moving */
	int64_t lost;        /* completions the loop's side had no room for */
	int64_t rtt_min_ns, rtt_max_ns, rtt_sum_ns, rtt_n; /* per update */
};

/* The stats of an axis hal_modbus_open() made. */
void hal_modbus_stats(struct hal_axis *ax, struct modbus_stats *s);

/* [init] One or two lines about the bus of an axis hal_modbus_open() made,
 * for the run's summary. */
void hal_modbus_report(struct hal_axis *ax, FILE *f);

#endif /* HAL_MODBUS_DEV_H */
