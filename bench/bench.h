/* SPDX-License-Identifier: MIT */
/*
 * bench.h - what every benchmark program of `make bench` shares: a
 * monotonic clock, the median of a few repeats and the one output format,
 *
 *     BENCH <name> <value> <unit>
 *
 * Medians, not minima: the build machine is a shared virtual machine, and a
 * minimum rewards the one lucky run while a median of interleaved repeats
 * says what a run sees. Header only; benchmarks are single programs.
 * Inputs come from the tests' seeded generator (testutil.h: tu_seed,
 * tu_uniform, and q2d/d2q between Q32.32 and double), the same numbers on
 * every run.
 */
#ifndef BENCH_H
#define BENCH_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "tests/testutil.h"

/* Repeats of every timed measurement; fixed and double alternate within. */
#define BENCH_REPEATS 9

/* Written by timed loops so that the compiler cannot drop their results. */
static volatile uint64_t bench_sink;

static inline double bench_now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* Median of n values (n <= 64); the array is left sorted. */
static inline double bench_median(double *v, int n)
{
	int i, j;

	for (i = 1; i < n; i++)
		for (j = i; j > 0 && v[j - 1] > v[j]; j--) {
			double t = v[j];

			v[j] = v[j - 1];
			v[j - 1] = t;
		}
	return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

static inline void bench_print(const char *name, double value, const char *unit)
{
	/* %.4g: timing noise on this machine is a few percent; errors are
	 * read as orders of magnitude */
	printf("BENCH %s %.4g %s\n", name, value, unit);
	fflush(stdout);
}

/* BENCH <prefix><name> ..., for the families of lines a loop prints */
static inline void bench_printf(const char *prefix, const char *name, double value,
				const char *unit)
{
	char buf[128];

	snprintf(buf, sizeof(buf), "%s%s", prefix, name);
	bench_print(buf, value, unit);
}

/* One batch of work; returns nothing, leaves its results where the caller
 * (or bench_sink) can see them. */
typedef void (*bench_batch_fn)(void *ctx);

/*
 * Time the fixed-point and the double version of the same batch side by
 * side: one untimed run of each, then BENCH_REPEATS pairs, alternating which
 * goes first so that neither always runs right after the other. Results are
 * ns per unit (units: what one batch does, e.g. ticks or calls): the median
 * of each, and the median of the per-pair ratios fixed / double (adjacent
 * runs share the machine's state of the moment, so their ratio is steadier
 * than the ratio of two medians).
 */
struct bench_pair {
	double fixed_ns, double_ns, ratio;
};

static inline void bench_run_pair(struct bench_pair *out, bench_batch_fn fx, bench_batch_fn db,
				  void *ctx, double units)
{
	double tf[BENCH_REPEATS], td[BENCH_REPEATS], tr[BENCH_REPEATS];
	int r, k;

	fx(ctx);
	db(ctx);
	for (r = 0; r < BENCH_REPEATS; r++) {
		for (k = 0; k < 2; k++) {
			bool fixed_now = (k == 0) == (r % 2 == 0);
			double t0 = bench_now_ns();

			(fixed_now ? fx : db)(ctx);
			*(fixed_now ? &tf[r] : &td[r]) = (bench_now_ns() - t0) / units;
		}
		tr[r] = tf[r] / td[r];
	}
	out->fixed_ns = bench_median(tf, BENCH_REPEATS);
	out->double_ns = bench_median(td, BENCH_REPEATS);
	out->ratio = bench_median(tr, BENCH_REPEATS);
}

/* ns per unit of one batch with no double counterpart: the median of
 * BENCH_REPEATS runs after an untimed one. */
static inline double bench_run_one(bench_batch_fn fn, void *ctx, double units)
{
	double t[BENCH_REPEATS];
	int r;

	fn(ctx);
	for (r = 0; r < BENCH_REPEATS; r++) {
		double t0 = bench_now_ns();

		fn(ctx);
		t[r] = (bench_now_ns() - t0) / units;
	}
	return bench_median(t, BENCH_REPEATS);
}

#endif /* BENCH_H */
