/* SPDX-License-Identifier: MIT */
/* pool.c - scratch memory freed all at once (see pool.h). */
#include "pool.h"

#include <stdalign.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define POOL_CHUNK 16384 /* bytes per ordinary chunk; larger requests get their own */

struct pool_chunk {
	struct pool_chunk *next;
	size_t size, used;
	alignas(max_align_t) unsigned char data[];
};

void pool_init(struct pool *p)
{
	p->head = NULL;
}

static struct pool_chunk *chunk_new(size_t size)
{
	struct pool_chunk *c = malloc(sizeof(*c) + size);

	if (!c)
		return NULL;
	c->next = NULL;
	c->size = size;
	c->used = 0;
	return c;
}

void *pool_alloc(struct pool *p, size_t n)
{
	const size_t align = alignof(max_align_t);
	struct pool_chunk *c = p->head;
	void *r;

	if (n > SIZE_MAX / 2)
		return NULL;
	n = (n + align - 1) & ~(align - 1);
	if (n == 0)
		n = align;
	if (!c || c->size - c->used < n) {
		/* a large request gets its own chunk behind the current one, so
		 * the space left in the current chunk is not wasted */
		struct pool_chunk *nc = chunk_new(n > POOL_CHUNK / 4 ? n : POOL_CHUNK);

		if (!nc)
			return NULL;
		if (c && n > POOL_CHUNK / 4) {
			nc->next = c->next;
			c->next = nc;
		} else {
			nc->next = c;
			p->head = nc;
		}
		c = nc;
	}
	r = c->data + c->used;
	c->used += n;
	memset(r, 0, n);
	return r;
}

void *pool_array(struct pool *p, size_t n, size_t size)
{
	if (size && n > SIZE_MAX / 2 / size)
		return NULL;
	return pool_alloc(p, n * size);
}

char *pool_strndup(struct pool *p, const char *s, size_t n)
{
	char *r = pool_alloc(p, n + 1);

	if (r) {
		memcpy(r, s, n);
		r[n] = '\0';
	}
	return r;
}

void pool_free(struct pool *p)
{
	struct pool_chunk *c = p->head;

	while (c) {
		struct pool_chunk *next = c->next;

		free(c);
		c = next;
	}
	p->head = NULL;
}
