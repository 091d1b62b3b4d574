/* SPDX-License-Identifier: MIT */
/*
 * ltc.h - LTC timecode as an external clock (extclk.h): a capture device
 * (ltc_cap.h: ALSA, or the tests' simulation) read on a thread of its own,
 * strand-ltc, each period decoded (ltc_dec.h) and its frames handed to the
 * loop as marks through a lock-free ring.
 *
 * The thread blocks in the capture's read, so it never is the loop's. It
 * is scheduled as cfg.sched says (strand's plan: with the GPIO input
 * threads, at the loop's priority off its CPU), because a period read
 * late is a stamp read late; the DLL forgives a late stamp, not a lost
 * period. An overrun (the thread fell behind the card) restarts the
 * sample clock's fit and is counted; a device that fails or a simulated
 * source whose script is over is a latched fault.
 *
 * On the virtual clock the thread runs ahead as far as the ring lets it:
 * each mark carries when it became known, and poll() hands out exactly the
 * marks known by the loop's present, waiting for the thread when it has
 * not got that far (extclk.h).
 */
#ifndef HAL_LTC_H
#define HAL_LTC_H

#include <stddef.h>
#include <stdint.h>

#include "hal/clock.h"
#include "hal/extclk.h"
#include "hal/thread.h"
#include "ltc_cap.h"

/* Marks in flight between the capture thread and the loop. */
#define HAL_LTC_RING 64

struct hal_ltc_cfg {
	const char *name;      /* the source as --chase named it; copied */
	struct ltc_cap *cap;   /* taken over: closed with the source, or on failure */
	struct hal_clock *clk; /* the run's: virtual or not */
	double fps;            /* the frame rate expected, for the decoder's start */
	struct hal_sched sched;
};

/* [init] 0 and *out, or a negative errno with err. */
int hal_ltc_open(struct hal_extclk **out, const struct hal_ltc_cfg *cfg, char *err,
		 size_t errsize);

/* What a source did, for the run's summary. */
struct hal_ltc_stats {
	int64_t periods, frames, dropped, resyncs;
	double rate_hz;    /* the card's sample rate as the DLL measures it */
	float level_dbfs;  /* the last frame's */
};
void hal_ltc_stats(struct hal_extclk *c, struct hal_ltc_stats *s);

/* [init] ALSA capture (ltc_alsa.c): device as `arecord -D` takes it
 * ("hw:1", "hw:Loopback,1,0", "default"), mono 16-bit at rate, read in
 * periods of `period` samples, stamped on CLOCK_MONOTONIC. */
int ltc_alsa_open(struct ltc_cap **out, const char *device, uint32_t rate, uint32_t period,
		  char *err, size_t errsize);

#endif /* HAL_LTC_H */
