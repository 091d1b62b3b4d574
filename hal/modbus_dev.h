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
 * an I/O thread of its own (a bus: one connection, one serial line):
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

#include "axis.h"
#include "modbus_map.h"

enum modbus_transport {
	MODBUS_TCP,
	MODBUS_RTU,
};

struct modbus_axis_desc {
	struct modbus_reg target; /* position counts, or counts/s for a velocity channel */
	bool has_actual;
	struct modbus_reg actual; /* the actual position, counts */
};

/* A device as the scene file describes it (rig_desc.h), file units. */
struct modbus_desc {
	enum modbus_transport transport;
	const char *host;           /* TCP: address or name */
	uint16_t port;
	const char *serial;         /* RTU: the serial device */
	uint32_t baud;
	char parity;                /* 'N', 'E' or 'O' */
	uint32_t stop_bits;         /* 1 or 2 */
	uint32_t unit;              /* slave id: 1..247 (TCP: 0..255) */
	double response_timeout_ms; /* for the first byte of an answer */
	double byte_timeout_ms;     /* between two bytes of one answer */
	double update_hz;           /* setpoints sent per second; the tick rate when 0 */
	uint32_t read_every;        /* ticks between reads of actual and status; 0: never */
	uint32_t max_faults;        /* failed transactions in a row that fault the device */
	double max_silence_ms;      /* no write completed this long while setpoints wait */
	double answer_ms;           /* the drive's answer time, for strand check */

	bool has_enable;
	bool enable_coil;           /* a coil, else a holding register */
	uint16_t enable_addr;
	uint16_t enable_on, enable_off; /* register values */

	bool has_status;
	uint16_t status_addr;
	uint16_t status_fault_mask; /* any of these bits set: the drive is in fault */

	bool has_heartbeat;
	struct modbus_reg heartbeat; /* the loop's tick, written with the targets */

	uint32_t naxes;
	const struct modbus_axis_desc *axes;
};

/* Defaults of the optional settings (the loader fills them in). */
#define MODBUS_DEFAULT_RESPONSE_TIMEOUT_MS 20.0
#define MODBUS_DEFAULT_BYTE_TIMEOUT_MS 5.0
#define MODBUS_DEFAULT_MAX_FAULTS 3
#define MODBUS_DEFAULT_ANSWER_MS 1.0

/* [init] Ticks between two updates at tick_hz: tick_hz / update_hz
 * rounded, at least 1. */
uint32_t modbus_update_every(const struct modbus_desc *d, uint32_t tick_hz);

/*
 * [init] What one update takes on the bus, in ns: its writes, and with
 * `read` the reads too. RTU from frame lengths at the line's baud rate with
 * the t3.5 silences and answer_ms per request; TCP answer_ms per request
 * (the frames' time on a LAN is a few us). 0, or a negative errno when the
 * register map is invalid.
 */
int modbus_update_ns(const struct modbus_desc *d, bool read, int64_t *ns);

/*
 * [init] The registers of the first nch axes: w[] gets the nch targets, then
 * the heartbeat (*nw values); r[] the actual registers of the axes that have
 * one, then the status register (*nr values), with rfield[ch] channel ch's
 * index in r[] or -1 and *rstatus the status register's or -1. w and r hold
 * nch + 1 values each.
 */
void modbus_desc_regs(const struct modbus_desc *d, uint32_t nch, struct modbus_reg *w,
		      uint32_t *nw, struct modbus_reg *r, uint32_t *nr, int32_t *rfield,
		      int32_t *rstatus);

/* How the backend is opened. */
struct modbus_cfg {
	const char *name;             /* the device's name (kept, not copied) */
	const struct modbus_desc *d;  /* kept: must outlive the backend */
	uint32_t tick_hz;
	uint32_t nch;                 /* channels used, <= d->naxes */
	const int64_t *initial;       /* nch: a channel's target at start without feedback */
	const bool *velocity;         /* nch: the target register takes the velocity */
	bool lockstep;                /* the loop runs on the virtual clock */
};

/* [init] The backend (not connected yet: start() connects). NULL with a
 * message in err on a bad map or out of memory. */
struct hal_axis *hal_modbus_open(const struct modbus_cfg *c, char *err, size_t errsize);

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

/* The stats of a Modbus backend: false when ax is another kind. */
bool hal_modbus_stats(struct hal_axis *ax, struct modbus_stats *s);

/* [init] One or two lines about the bus for the run's summary; nothing when
 * ax is another kind. */
void hal_modbus_report(struct hal_axis *ax, FILE *f);

#endif /* HAL_MODBUS_DEV_H */
