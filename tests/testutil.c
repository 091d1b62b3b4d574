/* SPDX-License-Identifier: MIT */
#include "testutil.h"

#include <stdio.h>

void tu_bound(const char *name, const struct tu_worst *w, double bound, const char *unit)
{
	printf("BOUND %s worst=%.3g bound=%.3g %s (at %.10g)\n", name, w->err, bound, unit, w->at);
	fflush(stdout);
	if (!(w->err <= bound))
		fail_msg("%s: worst error %.3g %s exceeds the bound %.3g (at %.10g)", name, w->err,
			 unit, bound, w->at);
}
