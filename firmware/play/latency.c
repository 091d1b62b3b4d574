/* SPDX-License-Identifier: MIT */
/* latency.c - loop timing statistics (see latency.h). */
#include "latency.h"

#include <errno.h>
#include <stdio.h>

#include <string.h>

void lat_reset(struct lat_stats *s)
{
	memset(s, 0, sizeof(*s));
	s->min_ns = INT64_MAX;
	s->max_ns = INT64_MIN;
}

double lat_percentile_us(const struct lat_stats *s, double q)
{
	int64_t want, seen = 0;
	uint32_t i;

	if (s->n <= 0)
		return -1;
	/* the smallest bucket with at least q of the samples at or below it,
	 * named by its lower edge: whole microseconds, truncated, the way
	 * cyclictest files a sample */
	want = (int64_t)(q * (double)s->n + 0.999999);
	if (want < 1)
		want = 1;
	for (i = 0; i < LAT_HIST_US; i++) {
		seen += s->hist[i];
		if (seen >= want)
			return i;
	}
	return (double)s->max_ns / 1000.0;
}

int lat_write_hist(const char *path, const struct lat_stats *s)
{
	FILE *f = fopen(path, "w");
	uint32_t i;

	if (!f)
		return -errno;
	fprintf(f, "# strand wake-up latency, 1 us buckets\n");
	for (i = 0; i < LAT_HIST_US; i++)
		if (s->hist[i])
			fprintf(f, "%06u %06u\n", i, s->hist[i]);
	fprintf(f, "# Total: %lld\n# Overflow: %lld\n# Max Latencies: %.3f\n", (long long)s->n,
		(long long)s->overflow, s->n ? s->max_ns / 1000.0 : 0.0);
	return fclose(f) ? -errno : 0;
}
