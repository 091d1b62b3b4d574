/* SPDX-License-Identifier: MIT */
/* arena.c - see arena.h. */
#include "arena.h"

void mot_arena_init(struct mot_arena *a, void *base, size_t size)
{
	a->base = base;
	a->size = base ? size : SIZE_MAX;
	a->used = 0;
	a->sealed = false;
	a->failed = false;
}

void *mot_arena_alloc(struct mot_arena *a, size_t n, size_t align)
{
	size_t start, i;
	unsigned char *p;

	if (a->sealed || align == 0 || align > 64 || (align & (align - 1)) != 0) {
		a->failed = true;
		return NULL;
	}
	start = (a->used + align - 1) & ~(align - 1);
	if (start < a->used || n > a->size - start || start > a->size) {
		a->failed = true;
		return NULL;
	}
	a->used = start + n;
	if (!a->base)
		return NULL;
	p = a->base + start;
	/* no memset: the core links against nothing, and this runs at init */
	for (i = 0; i < n; i++)
		p[i] = 0;
	return p;
}
