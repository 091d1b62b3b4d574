/* SPDX-License-Identifier: MIT */
/* num.c - checked conversions of numbers from outside (see num.h). */
#include "num.h"

#include <errno.h>

int num_to_i64(double v, enum num_round r, int64_t min, int64_t max, int64_t *out)
{
	double x = num_round(v, r);
	int64_t i;

	if (!num_fits_i64(x))
		return -ERANGE;
	i = (int64_t)x;
	if (i < min || i > max)
		return -ERANGE;
	*out = i;
	return 0;
}

int num_s_to_ticks(double s, uint32_t hz, enum num_round r, int64_t min, int64_t max,
		   int64_t *out)
{
	return num_to_i64(s * hz, r, min, max, out);
}

int num_ms_to_ticks(double ms, uint32_t hz, enum num_round r, int64_t min, int64_t max,
		    int64_t *out)
{
	return num_to_i64(ms * hz / 1000, r, min, max, out);
}

int num_ms_to_ns(double ms, enum num_round r, int64_t min, int64_t max, int64_t *out)
{
	return num_to_i64(ms * 1e6, r, min, max, out);
}
