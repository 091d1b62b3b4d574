/* SPDX-License-Identifier: MIT */
/*
 * mb_server.h - a simulated drive (sim_drive.h) behind a real libmodbus
 * server: TCP with any number of clients at once (the loop and, say,
 * mbpoll), or RTU on a pseudo-terminal whose other end is linked where the
 * device's serial port is said to be. strand-simdrive's Modbus mode.
 *
 * Each request is read whole, the faults asked for are applied (counted in
 * setpoint writes: a function 16 that covers a target register), reads of
 * the actual and status registers are filled from the plant first, and
 * after the answer a setpoint write moves the plant and goes to the log.
 *
 * The plant's time: when the loop's tick arrives with the setpoints (a
 * heartbeat register), the plant advances to that tick, so a run on the
 * virtual clock is the same every time; otherwise it advances with the
 * wall clock since the first setpoint.
 *
 * Not real-time: a program's whole main loop.
 */
#ifndef SIM_MB_SERVER_H
#define SIM_MB_SERVER_H

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hal/modbus/modbus_desc.h"
#include "sim_drive.h"

/* Faults to inject, each after the drive received that many setpoint
 * writes (0: never). */
struct mb_server_faults {
	int64_t silent_after;    /* stop answering */
	int64_t late_after;      /* answer late_ms late */
	double late_ms;
	int64_t exception_after; /* answer with exception code `exception` */
	int exception;
	int64_t die_after;       /* exit at once, mid-request */
	int64_t drop_after;      /* close the connection once, accept again */
	int64_t trip_after;      /* the drive trips: its status shows the fault */
	bool wire_time;          /* RTU: hold answers for a real line's time */
};

struct mb_server_cfg {
	const char *name;            /* the device, for the serving line */
	const struct modbus_desc *d; /* bus and register map */
	struct sim_drive *drive;     /* the plant (borrowed), nch channels */
	uint32_t nch;
	const bool *velocity;        /* nch: channel follows a velocity */
	uint32_t tick_hz;
	struct mb_server_faults faults;
	const char *listen;          /* TCP: HOST:PORT instead of the map's */
	const char *pty;             /* RTU: the link to make instead of the map's port */
	FILE *log;                   /* W N TICK VALUE... per write, E 1|0 per enable; or NULL */
	bool quiet;                  /* no "serving" line on stdout */
	/* the server returns soon after this becomes non-zero (a signal
	 * handler's flag, owned by the program) */
	volatile sig_atomic_t *stop;
};

/* Serve until *stop: 0, or a negative errno with a message in err (the
 * listening socket, the pseudo-terminal, the link, memory). */
int mb_server_run(const struct mb_server_cfg *c, char *err, size_t errsize);

#endif /* SIM_MB_SERVER_H */
