/* SPDX-License-Identifier: MIT */
/*
 * dout.h - the HAL interface of digital outputs: camera trigger lines, a
 * rig-ready lamp. A device has nlines lines, numbered from 0 in the order
 * the rig configured them.
 *
 * Levels are logical: true means asserted. Each line's polarity (active high
 * or low) is part of its configuration when the backend opens it, so the
 * loop never thinks about wiring. The loop stages levels with set() and
 * applies every change of a tick with one commit() (libgpiod: one bulk
 * set-values call), then reads the clock: that instant is the edge's time in
 * the journal.
 *
 * [init] and [rt] as in axis.h. Every operation is implemented.
 */
#ifndef HAL_DOUT_H
#define HAL_DOUT_H

#include <stdbool.h>
#include <stdint.h>

#include "fault.h"
#include "rt.h" /* STRAND_RT */

struct hal_dout;

struct hal_dout_ops {
	/* [init] Request the lines and drive each one deasserted. */
	int (*start)(struct hal_dout *d);
	/* [rt] Stage a line's logical level for this tick. */
	void (*set)(struct hal_dout *d, uint32_t line, bool asserted);
	/* [rt] Apply the staged levels: 0 or a negative errno (fault latched). */
	int (*commit)(struct hal_dout *d, int64_t tick);
	/* [rt] The first latched fault, 0 when healthy. */
	int (*fault)(struct hal_dout *d, struct hal_fault *f);
	/* [init] Deassert every line and release them. */
	int (*stop)(struct hal_dout *d);
	/* [init] Free everything, the struct included. */
	void (*close)(struct hal_dout *d);
};

struct hal_dout {
	const struct hal_dout_ops *ops; /* first: the backend's table */
	const char *name;               /* the device's name in the scene */
	uint32_t nlines;
};

static inline int hal_dout_start(struct hal_dout *d)
{
	return d->ops->start(d);
}

static inline void STRAND_RT hal_dout_set(struct hal_dout *d, uint32_t line, bool asserted)
{
	d->ops->set(d, line, asserted);
}

static inline int STRAND_RT hal_dout_commit(struct hal_dout *d, int64_t tick)
{
	return d->ops->commit(d, tick);
}

static inline int STRAND_RT hal_dout_fault(struct hal_dout *d, struct hal_fault *f)
{
	return d->ops->fault(d, f);
}

static inline int hal_dout_stop(struct hal_dout *d)
{
	return d->ops->stop(d);
}

static inline void hal_dout_close(struct hal_dout *d)
{
	if (d)
		d->ops->close(d);
}

#endif /* HAL_DOUT_H */
