/* SPDX-License-Identifier: MIT */
/* clock.c - the real and the virtual time source (see clock.h). */
#include "clock.h"

#include <errno.h>
#include <time.h>

#include "rt.h"

static int64_t STRAND_RT ts_ns(const struct timespec *ts)
{
	return (int64_t)ts->tv_sec * 1000000000 + ts->tv_nsec;
}

int64_t STRAND_RT hal_mono_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts_ns(&ts);
}

static int64_t STRAND_RT real_now(struct hal_clock *c)
{
	return hal_mono_ns();
}

static void STRAND_RT real_sleep_until(struct hal_clock *c, int64_t t)
{
	struct timespec ts = { .tv_sec = t / 1000000000, .tv_nsec = t % 1000000000 };

	/* absolute: a signal that interrupts the sleep does not shift the tick */
	while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR)
		;
}

static int64_t STRAND_RT real_wall(struct hal_clock *c)
{
	struct timespec ts;

	clock_gettime(CLOCK_REALTIME, &ts);
	return ts_ns(&ts);
}

static int64_t STRAND_RT virt_now(struct hal_clock *c)
{
	return c->vnow;
}

static void STRAND_RT virt_sleep_until(struct hal_clock *c, int64_t t)
{
	if (t > c->vnow)
		c->vnow = t;
}

static int64_t STRAND_RT virt_wall(struct hal_clock *c)
{
	return HAL_CLOCK_VIRTUAL_EPOCH_NS + c->vnow;
}

static const struct hal_clock_ops real_ops = {
	.now = real_now,
	.sleep_until = real_sleep_until,
	.wall = real_wall,
};

static const struct hal_clock_ops virt_ops = {
	.now = virt_now,
	.sleep_until = virt_sleep_until,
	.wall = virt_wall,
};

void hal_clock_init(struct hal_clock *c, bool is_virtual)
{
	c->ops = is_virtual ? &virt_ops : &real_ops;
	c->is_virtual = is_virtual;
	c->vnow = 0;
}
