/* SPDX-License-Identifier: MIT */
/* rt.c - the loop thread's flag and the debug assertion (see rt.h). */
#include "rt.h"

#include <stdio.h>
#include <stdlib.h>

_Thread_local bool strand_rt_thread;

void strand_rt_assert_failed(const char *func)
{
	/* stderr is unbuffered: the line is out before the abort */
	fprintf(stderr, "strand: %s is [init] and was called from the real-time thread\n", func);
	abort();
}
