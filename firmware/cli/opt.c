/* SPDX-License-Identifier: MIT */
/* opt.c - numbers on a command line (see opt.h). */
#include "opt.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>

bool opt_long(const char *s, long long min, long long max, long long *out)
{
	char *end;

	errno = 0;
	*out = strtoll(s, &end, 10);
	return *s && !*end && !errno && *out >= min && *out <= max;
}

bool opt_double(const char *s, double min, double max, double *out)
{
	char *end;

	errno = 0;
	*out = strtod(s, &end);
	return *s && !*end && !errno && isfinite(*out) && *out >= min && *out <= max;
}
