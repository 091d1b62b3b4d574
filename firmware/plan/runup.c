/* SPDX-License-Identifier: MIT */
/* runup.c - the run-up into a pass (see runup.h). */
#include "runup.h"

#include <errno.h>
#include <math.h>

#include "move.h"
#include "scene/num.h"

/* Ramps shorter than this (2^31 ticks) sum their steps in int64_t, exactly. */
#define RUNUP_EXACT (INT64_C(1) << 31)

int STRAND_RT runup_plan(struct runup_ramp *r, mot_q32 end, mot_q32 next, uint32_t tick_hz,
			 double amax, mot_q32 *start)
{
	double v = (move_q2d(next) - move_q2d(end)) * tick_hz;
	double nd = ceil(fabs(v) * tick_hz / amax * (1 + 1e-9));
	int rc = 0;

	/* a ramp longer than NUM_TICKS_MAX starts beyond the core's range */
	if (!(nd < (double)NUM_TICKS_MAX)) {
		nd = (double)NUM_TICKS_MAX;
		rc = -ERANGE;
	}
	r->v = v;
	r->n = (int64_t)nd;
	*start = r->n ? end - move_d2q(v / tick_hz * (double)(r->n + 1) / 2) : end;
	return rc;
}

mot_q32 STRAND_RT runup_at(const struct runup_ramp *r, mot_q32 end, int64_t ticks, int64_t j,
			   uint32_t tick_hz)
{
	int64_t n = r->n, m = j - (ticks - n); /* the ramps end together */
	double left;

	if (n == 0 || m >= n)
		return end;
	if (m < 0)
		m = 0;
	/* the distance still to go after step m: sum of v k / n dt, k = m+1..n;
	 * n (n + 1) overflows int64_t from n = 3e9 on: such ramps in doubles */
	if (n < RUNUP_EXACT)
		left = r->v / n / tick_hz * (double)(n * (n + 1) - m * (m + 1)) / 2;
	else
		left = r->v / n / tick_hz *
		       ((double)n * (double)(n + 1) - (double)m * (double)(m + 1)) / 2;
	return end - move_d2q(left);
}
