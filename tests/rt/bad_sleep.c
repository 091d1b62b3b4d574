/* SPDX-License-Identifier: MIT */
/* bad_sleep.c - self-test input of the real-time check: an rt function
 * that sleeps a relative time (the loop's one wait is clock_nanosleep to
 * an absolute tick). It must be refused as "a call that may sleep". */
#include <time.h>

#include "hal/rt.h"

void rt_test_sleep(long ns);

void STRAND_RT rt_test_sleep(long ns)
{
	struct timespec ts = { .tv_sec = 0, .tv_nsec = ns };

	nanosleep(&ts, NULL);
}
