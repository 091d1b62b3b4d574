/* SPDX-License-Identifier: MIT */
/*
 * chase_bench.c - `make bench-ltc`: strand play --chase against LTC from
 * libltc's encoder behind the simulated capture device (sim/sim_ltc.h), on
 * the virtual clock, with the card's clock 0, +-100 and +-1000 ppm off and
 * every timestamp up to 1 ms late, ten seeds of that jitter each:
 *
 *   lock     from the first frame decoded to the lock (frames, ms): the
 *            median and the worst of the ten
 *   phase    each trigger's due time against the instant the source began
 *            its frame, less the scene's own rounding to a tick (us):
 *            median and 99th percentile of |error| over every frame of the
 *            ten runs after the cue
 *   rate     the source's rate as the chase has it 10 s after the source
 *            began, against the truth (ppm): the median and the worst
 *
 * BENCH lines, one figure each. The bounds the tests hold these to are
 * tests/play/test_chase.c's; here are the figures themselves.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chaseutil.h"

#define SEEDS 10
#define MAXF 1024

static int cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

static double quantile(const double *v, size_t n, double q)
{
	size_t k = (size_t)(q * (double)n);

	return n ? v[k < n ? k : n - 1] : NAN;
}

int main(void)
{
	static const double ppm[] = { 0, 100, -100, 1000, -1000 };
	static double phase[SEEDS * MAXF], all[SEEDS * MAXF];
	double lk_f[SEEDS], lk_ms[SEEDS], rt[SEEDS];
	unsigned i, s;

	printf("bench-ltc: 25 fps LTC, 48 kHz, stamps up to 1 ms late, the card's clock off by "
	       "PPM, %d seeds of the jitter each; 1 kHz tick, virtual clock\n", SEEDS);
	for (i = 0; i < sizeof(ppm) / sizeof(ppm[0]); i++) {
		size_t n = 0;

		for (s = 0; s < SEEDS; s++) {
			struct sim_ltc_cfg c = chase_ltc25(ppm[i], 0);
			struct chase_outcome oc = { .phase_us = phase, .phase_cap = MAXF };
			size_t k;

			c.seed = 5 + 7 * s;
			/* frame 250 is 00:00:10:00 of the source, 10 s after it began */
			chase_run(&oc, "ltc:sim", &c, NULL, 25, 1, 250, NULL, 500, NULL, 0);
			if (oc.code != 0 || oc.st.lock_ns < 0) {
				fprintf(stderr, "bench-ltc: %+.0f ppm, seed %u: the run ended %d\n",
					ppm[i], s, oc.code);
				return 1;
			}
			lk_f[s] = oc.lock_frames;
			lk_ms[s] = (double)(oc.st.lock_ns - oc.st.first_mark_ns) / 1e6;
			rt[s] = fabs(oc.st.rate - 1) * 1e6;
			for (k = 0; k < oc.nphase; k++)
				all[n++] = fabs(oc.phase_us[k]);
		}
		qsort(all, n, sizeof(all[0]), cmp);
		qsort(lk_f, SEEDS, sizeof(double), cmp);
		qsort(lk_ms, SEEDS, sizeof(double), cmp);
		qsort(rt, SEEDS, sizeof(double), cmp);
		printf("BENCH ltc_lock_frames_%+.0fppm %.1f (median; worst %.1f)\n", ppm[i],
		       quantile(lk_f, SEEDS, 0.5), lk_f[SEEDS - 1]);
		printf("BENCH ltc_lock_ms_%+.0fppm %.1f (median; worst %.1f)\n", ppm[i],
		       quantile(lk_ms, SEEDS, 0.5), lk_ms[SEEDS - 1]);
		printf("BENCH ltc_phase_p50_us_%+.0fppm %.1f (%zu triggers)\n", ppm[i],
		       quantile(all, n, 0.5), n);
		printf("BENCH ltc_phase_p99_us_%+.0fppm %.1f\n", ppm[i], quantile(all, n, 0.99));
		printf("BENCH ltc_phase_max_us_%+.0fppm %.1f\n", ppm[i], all[n - 1]);
		printf("BENCH ltc_rate_error_10s_ppm_%+.0fppm %.2f (median; worst %.2f)\n", ppm[i],
		       quantile(rt, SEEDS, 0.5), rt[SEEDS - 1]);
	}
	return 0;
}
