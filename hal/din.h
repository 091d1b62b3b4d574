/* SPDX-License-Identifier: MIT */
/*
 * din.h - the HAL interface of digital inputs with edge events: an e-stop
 * chain, a camera-ready signal, a stop button.
 *
 * A device has nlines lines, numbered from 0 in the order the rig configured
 * them; levels are logical (true = asserted) after each line's configured
 * polarity. Edges carry the time they happened on CLOCK_MONOTONIC (a kernel
 * timestamp for libgpiod), so the journal can say when an e-stop opened,
 * not when the loop noticed. A backend that must block to wait for events
 * reads them on a thread of its own and hands them over through a lock-free
 * ring; poll() only drains that ring.
 *
 * [init] and [rt] as in axis.h. Every operation is implemented.
 */
#ifndef HAL_DIN_H
#define HAL_DIN_H

#include <stdbool.h>
#include <stdint.h>

#include "fault.h"
#include "rt.h" /* STRAND_RT */

struct hal_edge {
	uint32_t line;
	bool asserted; /* the logical level after the edge */
	int64_t ts_ns; /* CLOCK_MONOTONIC */
};

struct hal_din;

struct hal_din_ops {
	/* [init] Request the lines and start watching them. */
	int (*start)(struct hal_din *d);
	/* [rt] Move up to max edges that happened by now into ev, oldest
	 * first; returns how many. Edges beyond max stay for the next call. */
	uint32_t (*poll)(struct hal_din *d, int64_t now_ns, struct hal_edge *ev, uint32_t max);
	/* [rt] A line's newest logical level: after every edge the backend
	 * has seen by now, those that poll() has not handed out yet included.
	 * The loop takes a bounded number of edges per tick (loop.h), and
	 * checks the e-stop by this level every tick: an e-stop edge queued
	 * behind many others must not wait for them. */
	bool (*level)(struct hal_din *d, uint32_t line);
	/* [rt] The first latched fault (lost events, a line gone), 0 if none. */
	int (*fault)(struct hal_din *d, struct hal_fault *f);
	/* [init] Stop watching and release the lines. */
	int (*stop)(struct hal_din *d);
	/* [init] Free everything, the struct included. */
	void (*close)(struct hal_din *d);
};

struct hal_din {
	const struct hal_din_ops *ops; /* first: the backend's table */
	const char *name;              /* the device's name in the scene */
	uint32_t nlines;
};

static inline int hal_din_start(struct hal_din *d)
{
	return d->ops->start(d);
}

static inline uint32_t STRAND_RT hal_din_poll(struct hal_din *d, int64_t now_ns,
					      struct hal_edge *ev, uint32_t max)
{
	return d->ops->poll(d, now_ns, ev, max);
}

static inline bool STRAND_RT hal_din_level(struct hal_din *d, uint32_t line)
{
	return d->ops->level(d, line);
}

static inline int STRAND_RT hal_din_fault(struct hal_din *d, struct hal_fault *f)
{
	return d->ops->fault(d, f);
}

static inline int hal_din_stop(struct hal_din *d)
{
	return d->ops->stop(d);
}

static inline void hal_din_close(struct hal_din *d)
{
	if (d)
		d->ops->close(d);
}

#endif /* HAL_DIN_H */
