/* SPDX-License-Identifier: MIT */
/*
 * co_simbus.h - a simulated CAN bus with simulated CiA 402 drives on it
 * (co_slave.h), behind the transport interface of the master (co_bus.h).
 *
 * The bus is ideal and instant: a frame the master sends reaches every
 * drive at once, and what a drive answers waits in a queue for the master's
 * next recv(). Drives see time from the clock given (virtual in the tests),
 * and wait() advances that clock no further than the next thing a drive
 * will do by itself (a heartbeat, a step of a quick stop), so heartbeats
 * come at their times even while the master waits for something else.
 *
 * Faults to inject: a drive's power cut (co_slave_power_off), a drive's own
 * faults (co_slave.h), the controller's error state (while bus-off, what
 * the master sends is refused and lost, never delivered later), and drives
 * that answer late (co_simbus_hold: what the master sends is on the bus at
 * once but reaches the drives only when released, as with a drive process
 * that gets no CPU while the master's loop catches up on late ticks).
 *
 * Every frame on the bus is logged with its time and sender, as candump
 * would record it, for the tests to read.
 *
 * [init]; the bus side runs in whichever thread the master runs in.
 */
#ifndef CO_SIMBUS_H
#define CO_SIMBUS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "co_slave.h"
#include "hal/canopen/co_bus.h"
#include "hal/clock.h"

struct co_simbus_rec {
	int64_t t;          /* clock time */
	struct co_frame f;
	int16_t from;       /* -1: the master, else the drive's node-ID */
};

struct co_simbus;

/* A bus whose master can have up to queue frames waiting, logging up to
 * log_cap frames (0: no log), into *out. 0, or -ENOMEM with a message in
 * err (err may be NULL when errsize is 0). */
int co_simbus_new(struct co_simbus **out, struct hal_clock *clk, uint32_t queue,
		  uint64_t log_cap, char *err, size_t errsize);
/* Free the bus and its drives, unless the master's transport still uses
 * it: then the last of co_simbus_free and the transport's close does. */
void co_simbus_free(struct co_simbus *b);

/* Add a drive (its send and ctx are the bus's own); powered on at once
 * unless off. 0 and the drive in *out (when out is not NULL), or a
 * negative errno (-EINVAL: the bus is full or has the node-ID already)
 * with a message in err naming the device and the node. */
int co_simbus_add(struct co_slave **out, struct co_simbus *b, const struct co_slave_cfg *cfg,
		  bool off, char *err, size_t errsize);
uint32_t co_simbus_count(const struct co_simbus *b);
struct co_slave *co_simbus_slave(struct co_simbus *b, uint32_t i);
/* The drive with a node-ID, or NULL. */
struct co_slave *co_simbus_node(struct co_simbus *b, uint8_t node);

/* The master's side: a transport named "sim". */
struct co_bus *co_simbus_bus(struct co_simbus *b);

/* The controller's state from now on (CO_BUS_OFF refuses sends). */
void co_simbus_set_state(struct co_simbus *b, enum co_bus_state s);

/* Frames held at most; more are lost (counted as overflows). */
#define CO_SIMBUS_HELD 64

/* Hold what the master sends from now on (true), or deliver everything
 * held and stop holding (false). */
void co_simbus_hold(struct co_simbus *b, bool hold);
/* Deliver the n oldest frames held, now; returns how many there were. */
uint32_t co_simbus_deliver(struct co_simbus *b, uint32_t n);

/* Let the drives' timers run up to now (recv does it too). */
void co_simbus_run(struct co_simbus *b, int64_t now);

/* The log so far. */
const struct co_simbus_rec *co_simbus_log(const struct co_simbus *b, uint64_t *n);
/* Frames lost: the master's queue or the held frames were full. */
uint64_t co_simbus_overflows(const struct co_simbus *b);

#endif /* CO_SIMBUS_H */
