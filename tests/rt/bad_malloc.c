/* SPDX-License-Identifier: MIT */
/* bad_malloc.c - self-test input of the real-time check: an rt function
 * that allocates. It must be refused as "an allocator". */
#include <stdlib.h>

#include "hal/rt.h"

void *rt_test_malloc(size_t n);

void STRAND_RT *rt_test_malloc(size_t n)
{
	return malloc(n);
}
