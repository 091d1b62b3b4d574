/* SPDX-License-Identifier: MIT */
/*
 * bad_static.c - self-test input of the freestanding checks: mutable
 * file-scope and static-local state (a cache, as libfixmath's trig has). The
 * object check must reject it.
 */
#include <stdint.h>

int32_t bad_static_last;
int32_t bad_static_cached(int32_t x);

int32_t bad_static_cached(int32_t x)
{
	static int32_t key = -1, value;

	if (x != key) {
		key = x;
		value = x * 3;
	}
	bad_static_last = value;
	return value;
}
