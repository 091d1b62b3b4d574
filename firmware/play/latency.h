/* SPDX-License-Identifier: MIT */
/*
 * latency.h - the loop's timing statistics, as cyclictest keeps them.
 *
 * Wake-up latency is how late the loop woke for a tick: the clock right
 * after clock_nanosleep returned, minus the tick's absolute start. It is
 * sampled once per sleep, as cyclictest samples it: a tick whose start had
 * already passed when the previous one ended is run at once without
 * sleeping (a catch-up tick: counted, with the worst lateness of any tick,
 * but no wake-up sample; cyclictest skips such periods altogether). min, avg
 * and max, and a histogram of 1 us buckets up to LAT_HIST_US (later ones in
 * an overflow count) from which percentiles are read at 1 us resolution,
 * the same resolution as cyclictest's -h histogram they are compared with.
 * An overrun is a tick whose work ended after the next tick should have
 * started.
 *
 * lat_add is [rt]: a few additions and comparisons, and the histogram's
 * bucket by one 32-bit division by a constant, which compilers turn into a
 * multiplication (a 64-bit division would be a library call on armhf).
 */
#ifndef STRAND_LATENCY_H
#define STRAND_LATENCY_H

#include <stdint.h>

#include "hal/rt.h"

#define LAT_HIST_US 10000

struct lat_stats {
	int64_t n;
	int64_t min_ns, max_ns;
	int64_t sum_ns;
	int64_t max_at_tick;   /* the tick of the worst wake-up */
	int64_t overruns;
	int64_t catchup;       /* ticks run late without sleeping */
	int64_t late_max_ns;   /* the latest any tick started, catch-up ones included */
	int64_t work_max_ns;   /* longest tick body */
	int64_t overflow;      /* samples >= LAT_HIST_US us */
	uint32_t hist[LAT_HIST_US];
};

void lat_reset(struct lat_stats *s);

static inline void STRAND_RT lat_add(struct lat_stats *s, int64_t tick, int64_t ns)
{
	if (ns < s->min_ns)
		s->min_ns = ns;
	if (ns > s->max_ns) {
		s->max_ns = ns;
		s->max_at_tick = tick;
	}
	s->sum_ns += ns;
	s->n++;
	/* early (ns < 0) counts as 0 us; the histogram's range fits 32 bits */
	if (ns < 0)
		s->hist[0]++;
	else if (ns < LAT_HIST_US * 1000)
		s->hist[(uint32_t)ns / 1000u]++;
	else
		s->overflow++;
}

/* The latency that a fraction q (0..1) of the samples do not exceed, in
 * whole us (truncated, as cyclictest files them); -1 without samples. */
double lat_percentile_us(const struct lat_stats *s, double q);

/* [init] The histogram as cyclictest writes one ("us count" lines, its
 * summary comments) into path: 0 or a negative errno. */
int lat_write_hist(const char *path, const struct lat_stats *s);

#endif /* STRAND_LATENCY_H */
