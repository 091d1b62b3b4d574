/* SPDX-License-Identifier: MIT */
/*
 * bad_libc.c - self-test input of the freestanding checks: it compiles
 * without a libc header, but calls libc (strlen, abs). The object check must
 * reject it.
 */
#include <stddef.h>

size_t strlen(const char *s);
int abs(int x);
size_t bad_libc_len(const char *s, int x);

size_t bad_libc_len(const char *s, int x)
{
	return strlen(s) + (size_t)abs(x);
}
