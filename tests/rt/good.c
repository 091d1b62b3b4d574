/* SPDX-License-Identifier: MIT */
/*
 * good.c - self-test input of the real-time check (mk/check-rt.sh): every
 * kind of reference rt code may make, which the check must accept: another
 * rt function (static, not inlined, and global), a tagged inline of a
 * header, the motion core and a copy of one of its header's inlines, the
 * allowed libc (memcpy, clock_gettime), data.
 * Untagged functions may do anything; rt_test_untagged is the project
 * function bad_untagged.c calls.
 */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "hal/ring.h"
#include "hal/rt.h"
#include "motion/fix.h"

int64_t rt_test_tick(struct hal_ring *r, const void *e, mot_q32 a);
int rt_test_untagged(int x);

static int64_t counter;
static const int64_t table[4] = { 1, 2, 3, 5 };

/* noinline: a call between rt functions, not one body */
static __attribute__((noinline)) int64_t STRAND_RT rt_test_helper(int64_t x)
{
	return x * table[x & 3] + counter;
}

int64_t STRAND_RT rt_test_tick(struct hal_ring *r, const void *e, mot_q32 a)
{
	/* its address taken, the inline is kept as a copy in this object's
	 * .text, as the compiler keeps any inline it does not inline */
	mot_q32 (*volatile add)(mot_q32, mot_q32, uint32_t *) = mot_add_sat;
	struct timespec ts;
	unsigned char copy[32];
	uint32_t sat = 0;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	memcpy(copy, e, sizeof(copy));
	hal_ring_push(r, copy);
	counter += rt_test_helper(ts.tv_nsec);
	return add(mot_div(a, a + 1, &sat), counter, &sat);
}

int rt_test_untagged(int x)
{
	return printf("%d\n", x);
}
