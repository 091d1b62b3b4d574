/* SPDX-License-Identifier: MIT */
/*
 * ltc_cap.h - where LTC audio comes from: a capture device that fills
 * periods of mono 16-bit samples and says when it captured them. Two
 * implementations: ALSA (ltc_alsa.c, libasound) and the simulated one of
 * the tests (sim/sim_ltc.c, libltc's encoder behind a clock error, jitter,
 * dropouts, jumps).
 *
 * A read's timestamp pairs an instant of CLOCK_MONOTONIC with the sample
 * position (counted from the first sample captured) that the device had
 * reached then: ALSA's position update and its time, which jitter by up to
 * a jiffy. The decoder (ltc_dec.h) filters them.
 *
 * [capture thread] every operation but open: it may block.
 */
#ifndef HAL_LTC_CAP_H
#define HAL_LTC_CAP_H

#include <stdint.h>

struct ltc_cap;

struct ltc_stamp {
	int64_t t_ns; /* CLOCK_MONOTONIC (the virtual clock for the simulation) */
	int64_t pos;  /* the sample position the device had reached at t_ns */
};

struct ltc_cap_ops {
	/* Fill buf with the next n samples (blocking until they are
	 * captured) and stamp them: n, 0 when the source has ended (the
	 * simulation's script is over), or a negative errno. */
	int (*read)(struct ltc_cap *c, int16_t *buf, uint32_t n, struct ltc_stamp *st);
	/* Close the device and free everything, the struct included. */
	void (*close)(struct ltc_cap *c);
};

struct ltc_cap {
	const struct ltc_cap_ops *ops; /* first */
	uint32_t rate;   /* samples per second, nominal */
	uint32_t period; /* samples per read */
};

static inline int ltc_cap_read(struct ltc_cap *c, int16_t *buf, uint32_t n, struct ltc_stamp *st)
{
	return c->ops->read(c, buf, n, st);
}

static inline void ltc_cap_close(struct ltc_cap *c)
{
	if (c)
		c->ops->close(c);
}

#endif /* HAL_LTC_CAP_H */
