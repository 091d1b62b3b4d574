/* SPDX-License-Identifier: MIT */
/*
 * extclk.h - the HAL interface of an external clock: a source of time that
 * belongs to someone else (a sound recorder's LTC timecode, a camera's or a
 * sync generator's frame pulse), seen as marks: "this frame began at this
 * instant of CLOCK_MONOTONIC".
 *
 * A backend reads its source on a thread of its own (capture never runs on
 * the loop's thread: it blocks in the driver), turns what it reads into
 * marks and hands them to the loop through a lock-free ring; poll() only
 * drains that ring. What the loop does with them (a second delay-locked
 * loop, the tick schedule, lock, freewheel, re-cue) is firmware/play's
 * business (chase.h): here are only the source's own facts.
 *
 *   LTC    (hal/ltc/) each decoded frame: its timecode label and the
 *          instant its first bit began, from its sample position and the
 *          capture's timestamps filtered by a DLL (dll.h)
 *   pulse  (hal/gpio/gpio_pulse.c) each rising edge of a frame pulse, its
 *          kernel timestamp; pulses carry no number
 *
 * On the virtual clock a backend's thread runs ahead of the loop as far as
 * its ring allows, and each mark says when it became known (avail_ns):
 * poll() waits until the thread has produced everything known by now and
 * hands out exactly that, so a run is the same every time.
 *
 * [init] and [rt] as in axis.h.
 */
#ifndef HAL_EXTCLK_H
#define HAL_EXTCLK_H

#include <stdbool.h>
#include <stdint.h>

#include "fault.h"
#include "rt.h" /* STRAND_RT */

enum hal_mark_flags {
	HAL_MARK_LABEL = 1,   /* hh:mm:ss:ff hold a timecode label */
	HAL_MARK_DROP = 2,    /* the label is drop-frame (LTC's flag) */
	HAL_MARK_REVERSE = 4, /* the frame was played backwards */
};

struct hal_mark {
	int64_t t_ns;     /* CLOCK_MONOTONIC: the frame (or pulse) began */
	int64_t avail_ns; /* when it became known (after t_ns) */
	uint8_t hh, mm, ss, ff; /* the label, with HAL_MARK_LABEL */
	uint32_t flags;   /* enum hal_mark_flags */
	float level_dbfs; /* LTC: the signal's level; 0 for pulses */
};

struct hal_extclk;

struct hal_extclk_ops {
	/* [init] Start reading the source (its thread). */
	int (*start)(struct hal_extclk *c);
	/* [rt] Move up to max marks known by now into m, oldest first: how
	 * many. Marks beyond max stay for the next call. */
	uint32_t (*poll)(struct hal_extclk *c, int64_t now_ns, struct hal_mark *m, uint32_t max);
	/* [rt] The first latched fault (the device gone, marks lost, the
	 * source ended), 0 if none. */
	int (*fault)(struct hal_extclk *c, struct hal_fault *f);
	/* [init] Stop reading. */
	int (*stop)(struct hal_extclk *c);
	/* [init] Free everything, the struct included. */
	void (*close)(struct hal_extclk *c);
};

struct hal_extclk {
	const struct hal_extclk_ops *ops; /* first: the backend's table */
	const char *name;                 /* what --chase named ("ltc:hw:1") */
	bool labelled;                    /* marks carry timecode labels */
};

static inline int hal_extclk_start(struct hal_extclk *c)
{
	return c->ops->start(c);
}

static inline uint32_t STRAND_RT hal_extclk_poll(struct hal_extclk *c, int64_t now_ns,
						 struct hal_mark *m, uint32_t max)
{
	return c->ops->poll(c, now_ns, m, max);
}

static inline int STRAND_RT hal_extclk_fault(struct hal_extclk *c, struct hal_fault *f)
{
	return c->ops->fault(c, f);
}

static inline int hal_extclk_stop(struct hal_extclk *c)
{
	return c->ops->stop(c);
}

static inline void hal_extclk_close(struct hal_extclk *c)
{
	if (c)
		c->ops->close(c);
}

#endif /* HAL_EXTCLK_H */
