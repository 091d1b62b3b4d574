/* SPDX-License-Identifier: MIT */
/*
 * good.c - self-test input of the freestanding checks: everything the core
 * may do. A const table, a struct copy (may become memcpy), a 64-bit
 * division (an integer helper on 32-bit targets) and a caller-owned state.
 * Both checks must accept it, or they reject everything.
 */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct good_state {
	int64_t v[16];
};

static const int64_t good_table[4] = { 1, 3, 5, 7 };

int64_t good_step(struct good_state *out, const struct good_state *in, int64_t d);

int64_t good_step(struct good_state *out, const struct good_state *in, int64_t d)
{
	size_t i;

	*out = *in;
	for (i = 0; i < 16; i++)
		out->v[i] += good_table[i & 3];
	return d ? out->v[0] / d : 0;
}
