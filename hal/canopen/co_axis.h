/* SPDX-License-Identifier: MIT */
/*
 * co_axis.h - a CANopen bus of CiA 402 drives behind the HAL axis
 * interface (axis.h): the master (co_master.h) on a transport (co_bus.h),
 * timed by the loop's clock.
 *
 * The device's channels are the drives' node-IDs (1..127), so every message
 * that names a channel names the node. start() runs the whole start-up
 * sequence and returns when every drive is in "operation enabled" holding
 * its position (or gives it up when the run's cancel request comes, with
 * every drive shut down); input() takes in what arrived, commit() sends the
 * RPDOs and one SYNC; disable() is a quick stop of every drive; stop()
 * waits until they confirm it and puts them in pre-operational.
 *
 * The loop's thread does the socket I/O itself, non-blocking, rather than
 * handing frames to an I/O thread through rings: a raw CAN socket's send
 * with MSG_DONTWAIT only copies the frames into the interface's queue and
 * returns, and a receive with MSG_DONTWAIT only copies out what is there, so
 * both are bounded; and the SYNC leaves at the moment the loop decides the
 * tick, with no thread hand-over to add its wake-up latency to the SYNC's
 * jitter. (libmodbus blocks, so the Modbus backend needs a thread; CAN does
 * not.)
 */
#ifndef CO_AXIS_H
#define CO_AXIS_H

#include <stddef.h>
#include <stdint.h>

#include "co_bus.h"
#include "co_master.h"
#include "hal/axis.h"
#include "hal/cancel.h"
#include "hal/clock.h"

/* Frames taken per recv() call, and the most input() takes in one tick: a
 * tick brings a TPDO per drive and now and then a heartbeat, so this leaves
 * room for a burst after a stall without unbounded work. */
#define CO_AXIS_RX_BATCH 32
#define CO_AXIS_RX_MAX_PER_TICK 256

struct co_axis_cfg {
	const char *name;              /* the device's name (kept) */
	struct co_master_cfg master;   /* send and ctx are the axis's own */
	const struct co_drive_cfg *drives;
	uint32_t ndrives;
	struct co_bus *bus;            /* taken over: closed by close() */
	struct hal_clock *clk;
	/* kept: when it is set while start() waits (boot-up, configuration,
	 * enabling), the start is given up, every drive shut down, and start()
	 * returns -ECANCELED; NULL: never */
	const struct hal_cancel *cancel;
};

/* [init] The backend into *out: 0, or a negative errno (-EINVAL: see
 * co_master_init; -ENOMEM) with a message in err naming the device; the
 * bus is closed then too. */
int co_axis_new(struct hal_axis **out, const struct co_axis_cfg *cfg, char *err, size_t errsize);

/* The master of an axis co_axis_new() made (tests, messages). */
struct co_master *co_axis_master(struct hal_axis *ax);

#endif /* CO_AXIS_H */
