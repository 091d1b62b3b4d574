/* SPDX-License-Identifier: MIT */
/*
 * bad_float.c - self-test input of the freestanding checks: floating point.
 * With -mgeneral-regs-only (x86_64) the compiler must refuse it; with a
 * soft-float ABI (Cortex-M) it compiles to __aeabi_* float helpers, which the
 * object check must reject.
 */
#include <stdint.h>

int64_t bad_float_scale(int64_t x, int32_t k);

int64_t bad_float_scale(int64_t x, int32_t k)
{
	double y = (double)x * 1.5;

	return (int64_t)(y / (float)k);
}
