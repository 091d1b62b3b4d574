/* SPDX-License-Identifier: MIT */
/* bad_untagged.c - self-test input of the real-time check: an rt function
 * that calls a function of the project that is not STRAND_RT
 * (rt_test_untagged, in good.c, checked with it). It must be refused as
 * "not STRAND_RT", however harmless the callee may look: the check does
 * not follow untagged code. */
#include "hal/rt.h"

int rt_test_calls_untagged(int x);
int rt_test_untagged(int x);

int STRAND_RT rt_test_calls_untagged(int x)
{
	return rt_test_untagged(x) + 1;
}
