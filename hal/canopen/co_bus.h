/* SPDX-License-Identifier: MIT */
/*
 * co_bus.h - the transport under the CANopen master: one CAN interface,
 * frames in and out, the controller's error state. Implemented by SocketCAN
 * (co_socketcan.c) and by the simulated bus of the tests (sim/co_simbus.h),
 * as Lely's io2 puts a virtual CAN backend behind the same interface as the
 * real one.
 *
 * The master's side never blocks in the loop: send and recv return at once
 * with what the kernel (or the simulation) took or had. A frame the bus
 * does not take is dropped, never queued in user space to go later.
 *
 * [init] and [rt] as in axis.h. Every operation is implemented.
 */
#ifndef CO_BUS_H
#define CO_BUS_H

#include <stdint.h>

#include "co_frame.h"
#include "hal/rt.h" /* STRAND_RT */

struct co_bus;

struct co_bus_ops {
	/* [rt] Send n frames in this order: 0 when all were taken, else a
	 * negative errno (-ENOBUFS: the transmit queue is full; -ENETDOWN:
	 * the interface is down or bus-off); what was not taken is dropped. */
	int (*send)(struct co_bus *b, const struct co_frame *f, uint32_t n);
	/* [rt] Up to max of the frames received so far, oldest first: how many
	 * (0 when none), or a negative errno. Error frames are not returned:
	 * they update state(). */
	int (*recv)(struct co_bus *b, struct co_frame *f, uint32_t max);
	/* [rt] The controller's error state as of the last recv(). */
	enum co_bus_state (*state)(struct co_bus *b);
	/* [init] Wait until a frame may be received or the clock reaches
	 * until_ns, whichever is first. */
	void (*wait)(struct co_bus *b, int64_t until_ns);
	/* [init] Release the interface, the struct included. */
	void (*close)(struct co_bus *b);
};

struct co_bus {
	const struct co_bus_ops *ops; /* first: the transport's table */
	const char *name;             /* the interface: "can0", "sim" */
};

static inline int STRAND_RT co_bus_send(struct co_bus *b, const struct co_frame *f, uint32_t n)
{
	return b->ops->send(b, f, n);
}

static inline int STRAND_RT co_bus_recv(struct co_bus *b, struct co_frame *f, uint32_t max)
{
	return b->ops->recv(b, f, max);
}

static inline enum co_bus_state STRAND_RT co_bus_state(struct co_bus *b)
{
	return b->ops->state(b);
}

static inline void co_bus_wait(struct co_bus *b, int64_t until_ns)
{
	b->ops->wait(b, until_ns);
}

static inline void co_bus_close(struct co_bus *b)
{
	if (b)
		b->ops->close(b);
}

#endif /* CO_BUS_H */
