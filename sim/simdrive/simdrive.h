/* SPDX-License-Identifier: MIT */
/*
 * simdrive.h - strand-simdrive: one device of a scene's rig played by the
 * simulated drive (sim/sim_drive.h) behind a real protocol server, for tests
 * and for trying a scene's wiring without a drive.
 *
 *   main.c          options, the scene, the model; picks a protocol
 *   model.c         the model driven by what the server receives
 *   modbus_serve.c  Modbus TCP and RTU (over a pseudo-terminal), libmodbus
 *   can.c           --can IFACE --node N: a CiA 402 drive on SocketCAN
 *                   (sim/co_slave.h around the same plant), no scene needed:
 *                   the master configures it by SDO
 *
 * The model's time: when the loop's tick arrives with the setpoints (a
 * heartbeat register), the plant advances to that tick, so a run on the
 * virtual clock is the same every time; otherwise it advances with the
 * wall clock since the first setpoint.
 */
#ifndef SIMDRIVE_H
#define SIMDRIVE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "load.h"
#include "rig.h"
#include "sim_drive.h"
#include "source_scene.h"

/* Faults to inject, each after the drive received that many setpoint
 * writes (0: never). */
struct simdrive_faults {
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

struct simdrive {
	const char *scene_path, *device;
	struct scene_file sf;
	struct scene_built b;
	struct source_scene src;
	struct hal_clock clk;
	struct rig rig;
	bool have_sf, have_b, have_src, have_rig;
	const struct rig_device_desc *dd;
	uint32_t ax;              /* the device's index in rig.axes */
	uint32_t nch;
	bool *velocity;           /* nch */
	struct sim_drive *drive;
	struct simdrive_faults faults;
	const char *listen;       /* TCP: HOST:PORT instead of the scene's */
	const char *pty;          /* RTU: the link to make instead of the scene's port */
	FILE *log;
	bool quiet;

	/* the model's state */
	uint32_t tick_hz;
	bool started, enabled;
	int64_t tick;             /* the plant's */
	int64_t writes;           /* setpoint writes received */
	int64_t t0_ns;            /* wall clock of the first write, without a heartbeat */
	int64_t *prev;            /* nch: the last targets, for the velocity feed-forward */
	int64_t prev_tick;
};

struct simdrive_proto {
	const char *name;
	/* serve until a signal or a fault that ends the program; the exit code */
	int (*serve)(struct simdrive *sd);
};

extern const struct simdrive_proto simdrive_modbus;

/* can.c: the whole program in CAN mode (its own options); the exit code. */
int simdrive_can_main(int argc, char **argv);

/* model.c */
/* Power on (the enable set) or off. */
void simdrive_enable(struct simdrive *sd, bool on);
/* New targets (nch values in counts, or counts/s for a velocity channel) for
 * the loop's tick (-1: unknown, the wall clock's). */
void simdrive_targets(struct simdrive *sd, const int64_t *val, int64_t tick);
/* Channel ch's actual position, counts. */
int64_t simdrive_actual(struct simdrive *sd, uint32_t ch);
/* true when the drive has latched a fault (tripped). */
bool simdrive_faulted(struct simdrive *sd);
/* Trip the drive now. */
void simdrive_trip(struct simdrive *sd);

#endif /* SIMDRIVE_H */
