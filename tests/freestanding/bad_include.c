/* SPDX-License-Identifier: MIT */
/*
 * bad_include.c - self-test input of the freestanding checks: a header the
 * core may not use. <float.h> compiles freestanding (the compiler ships it),
 * so only the include check can reject it.
 */
#include <float.h>
#include <stdint.h>

int32_t bad_include_radix(void);

int32_t bad_include_radix(void)
{
	return FLT_RADIX;
}
