/* SPDX-License-Identifier: MIT */
/* bad_printf.c - self-test input of the real-time check: an rt function
 * that prints. It must be refused as "stdio". */
#include <stdio.h>

#include "hal/rt.h"

void rt_test_printf(int tick);

void STRAND_RT rt_test_printf(int tick)
{
	printf("tick %d\n", tick);
}
