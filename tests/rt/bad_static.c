/* SPDX-License-Identifier: MIT */
/* bad_static.c - self-test input of the real-time check: an rt function
 * that calls an untagged static function of its own object (noinline, as a
 * large one would be), reached as .text plus an offset. It must be refused
 * as "not STRAND_RT", with the helper named. */
#include "hal/rt.h"

int rt_test_calls_static(int x);

static __attribute__((noinline)) int untagged_helper(int x)
{
	return x * 3 + 1;
}

int STRAND_RT rt_test_calls_static(int x)
{
	return untagged_helper(x) + untagged_helper(x + 1);
}
