/* SPDX-License-Identifier: MIT */
/*
 * sim_ltc.h - a simulated LTC capture device (hal/ltc/ltc_cap.h) for the
 * tests: libltc's own encoder makes the timecode a recorder would send,
 * and the simulation captures it as a sound card would, against the run's
 * clock (virtual in the tests):
 *
 *   - the source's frame rate off by src_ppm, the card's sample clock off
 *     by cap_ppm (each a crystal's error against CLOCK_MONOTONIC);
 *   - every period's timestamp late by a uniform 0..jitter_ns, as a
 *     driver's interrupt is;
 *   - a script of events at given seconds: silence (a dropout: the source
 *     runs on unheard), a jump to another timecode, reverse play, forward
 *     play again, the source stopping (its frame held: the same label
 *     again and again); then the end of the script (read returns 0);
 *   - a volume (a quiet signal) and drop-frame labels at 30000/1001.
 *
 * Each frame the source sent is recorded, with the instant its first bit
 * began on the run's clock, in a log the caller owns: the truth the tests
 * hold strand's triggers to.
 */
#ifndef SIM_LTC_H
#define SIM_LTC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "hal/clock.h"
#include "hal/ltc/ltc_cap.h"

enum sim_ltc_ev {
	SIM_LTC_SILENCE, /* from now to `until` the line is silent */
	SIM_LTC_JUMP,    /* the next frame is labelled `label` */
	SIM_LTC_REVERSE, /* from the next frame on, played backwards */
	SIM_LTC_FORWARD, /* from the next frame on, forwards again */
	SIM_LTC_HOLD,    /* from the next frame to `until`, the same label repeats */
};

struct sim_ltc_event {
	double at_s;          /* seconds after capture began */
	enum sim_ltc_ev ev;
	double until_s;       /* SILENCE, HOLD */
	uint8_t hh, mm, ss, ff; /* JUMP */
};

/* A frame the source sent. */
struct sim_ltc_frame {
	int64_t t_ns;         /* its first bit, on the run's clock */
	uint8_t hh, mm, ss, ff;
	bool reverse, silent;
};

struct sim_ltc_cfg {
	uint32_t rate, period;      /* samples a second, per read */
	uint32_t fps_num, fps_den;  /* 25/1, 30000/1001 (drop-frame labels), 24/1 ... */
	uint8_t hh, mm, ss, ff;     /* the first label */
	double begin_s;             /* the source starts this long after capture */
	double end_s;               /* the script ends (read returns 0) */
	double src_ppm, cap_ppm;
	int64_t jitter_ns;          /* < a period's time */
	double volume_db;           /* the signal's peak, dBFS (0: -3) */
	uint64_t seed;
	const struct sim_ltc_event *events; /* in time order */
	uint32_t nevents;
	struct sim_ltc_frame *log;  /* the caller's, may be NULL */
	size_t log_cap;
	size_t *log_n;              /* frames sent (all, beyond log_cap too) */
};

/* [init] 0 and *out, or a negative errno with err. On the virtual clock a
 * read returns at once (time is the loop's); on the wall clock it sleeps
 * until its samples would have been captured. */
int sim_ltc_open(struct ltc_cap **out, const struct sim_ltc_cfg *cfg, struct hal_clock *clk,
		 char *err, size_t errsize);

#endif /* SIM_LTC_H */
