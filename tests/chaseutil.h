/* SPDX-License-Identifier: MIT */
/*
 * chaseutil.h - strand play --chase on the virtual clock, for the chase's
 * tests (tests/play/test_chase.c) and its benchmark (bench/chase_bench.c):
 * the arm (frames 0..last at num/den, 1 kHz) played chasing a source, each
 * fired frame's due time against the instant the source began that frame
 * (the simulation's log: sim/sim_ltc.h; or, for pulses, a table of them).
 */
#ifndef CHASEUTIL_H
#define CHASEUTIL_H

#include <stddef.h>
#include <stdint.h>

#include "hal/din.h"
#include "play/chase.h"
#include "sim/sim_ltc.h"
#include "testutil.h"

struct chase_outcome {
	int code;
	struct chase_stats st;
	int64_t recues;
	struct tu_worst phase;   /* due - the source frame's start, us */
	struct tu_worst stretch; /* frame interval against the source's, relative */
	int64_t fired, matched;
	int64_t unplayed;        /* fired while the source played no such frame then */
	int64_t first_frame, last_frame;
	double lock_frames;      /* the lock, in frames after the first mark */
	/* each matched frame's phase error, us, when the caller gives room */
	double *phase_us;
	size_t nphase, phase_cap;
};

/* Play the arm chasing spec ("ltc:sim" with sc, "gpio:sim" with din and the
 * true pulse times truth_ns); *oc's phase_us and phase_cap are kept. */
void chase_run(struct chase_outcome *oc, const char *spec, struct sim_ltc_cfg *sc,
	       struct hal_din *din, uint32_t num, uint32_t den, int64_t last,
	       const char *tc_offset, double freewheel_ms, const int64_t *truth_ns,
	       size_t ntruth);

/* 25 fps LTC from 00:00:01:00 (the scene's frame 25), 48 kHz in 10 ms
 * periods, from 0.1 s to 12 s, every stamp up to 1 ms late. */
struct sim_ltc_cfg chase_ltc25(double cap_ppm, double src_ppm);

#endif /* CHASEUTIL_H */
