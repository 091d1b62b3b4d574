/* SPDX-License-Identifier: MIT */
/*
 * modbus_desc.h - a Modbus device as a scene file describes it (file
 * units): the bus, the unit, the register map and the timing, with what can
 * be said of it before anything is opened (the update's rate and its time
 * on the bus, the registers a transaction covers). The backend
 * (modbus_dev.h), the loader, `strand check` and the simulated drive's
 * server (sim/mb_server.h) share it; it opens nothing.
 */
#ifndef HAL_MODBUS_DESC_H
#define HAL_MODBUS_DESC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

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

/* The ranges a scene's modbus: settings are held to (drv_modbus.c says
 * why): timeouts and max_silence_ms from a microsecond, timeouts up to a
 * minute, the silence up to an hour; update_hz from 0.01 Hz. */
#define MODBUS_TIMEOUT_MS_MIN 0.001
#define MODBUS_TIMEOUT_MS_MAX 60000.0
#define MODBUS_SILENCE_MS_MAX 3600000.0
#define MODBUS_UPDATE_HZ_MIN 0.01

/* "tcp HOST:PORT unit U" or "rtu PORT unit U": which unit on which bus,
 * as every message about the device says it. */
void modbus_where(char *buf, size_t size, const struct modbus_desc *d);

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

#endif /* HAL_MODBUS_DESC_H */
