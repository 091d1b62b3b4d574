/* SPDX-License-Identifier: MIT */
/*
 * clock.h - the loop's time source, injected so that one loop runs on the
 * wall clock or on a virtual one.
 *
 *   real     CLOCK_MONOTONIC; sleep_until() is clock_nanosleep(TIMER_ABSTIME),
 *            wall() is CLOCK_REALTIME.
 *   virtual  time is a number that sleep_until() sets: the loop runs as fast
 *            as the machine computes, and every run of the same scene gives
 *            the same ticks, edges and journal, bit for bit. wall() is a fixed
 *            epoch plus the virtual time.
 *
 * Simulated devices read the same clock to timestamp their edges, so their
 * records agree with the loop's journal in either mode.
 *
 * All three operations are [rt]. Times are nanoseconds.
 */
#ifndef HAL_CLOCK_H
#define HAL_CLOCK_H

#include <stdbool.h>
#include <stdint.h>

#include "rt.h" /* STRAND_RT */

struct hal_clock;

struct hal_clock_ops {
	int64_t (*now)(struct hal_clock *c);                /* monotonic */
	void (*sleep_until)(struct hal_clock *c, int64_t t); /* returns at or after t */
	int64_t (*wall)(struct hal_clock *c);               /* since the Unix epoch */
};

struct hal_clock {
	const struct hal_clock_ops *ops; /* first */
	bool is_virtual;
	int64_t vnow; /* virtual: the present */
};

static inline int64_t STRAND_RT hal_clock_now(struct hal_clock *c)
{
	return c->ops->now(c);
}

static inline void STRAND_RT hal_clock_sleep_until(struct hal_clock *c, int64_t t)
{
	c->ops->sleep_until(c, t);
}

static inline int64_t STRAND_RT hal_clock_wall(struct hal_clock *c)
{
	return c->ops->wall(c);
}

/* The virtual clock's wall time at virtual 0: 2000-01-01T00:00:00Z. */
#define HAL_CLOCK_VIRTUAL_EPOCH_NS (946684800LL * 1000000000LL)

/* [any thread] CLOCK_MONOTONIC in nanoseconds, whatever clock a run is
 * on: for timeouts, service rounds and durations measured outside the
 * loop's time (a vDSO call, no system call). */
int64_t hal_mono_ns(void);

/* [init] A clock of either kind; virtual starts at 0. */
void hal_clock_init(struct hal_clock *c, bool is_virtual);

#endif /* HAL_CLOCK_H */
