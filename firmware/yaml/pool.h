/* SPDX-License-Identifier: MIT */
/*
 * pool.h - a scene file's memory: many small allocations that all live as
 * long as one loaded scene file and are freed together (the loader's and
 * the rig drivers' settings alike, yml.h).
 *
 * The scene file's description (names, key arrays, marks) is built piece by
 * piece while the YAML is walked, with sizes known only as each sequence is
 * reached; a pool keeps that simple and leak-free on every error path. It is
 * not the core's block: scene_build() copies what the core needs into one
 * measured allocation. Not real-time.
 */
#ifndef STRAND_POOL_H
#define STRAND_POOL_H

#include <stddef.h>

struct pool_chunk;

struct pool {
	struct pool_chunk *head;
};

/* An empty pool (a zeroed struct pool is one too). */
void pool_init(struct pool *p);

/* n zeroed bytes aligned for any type, or NULL when memory runs out. */
void *pool_alloc(struct pool *p, size_t n);

/* n elements of `size` bytes, zeroed; NULL on overflow of n * size too. */
void *pool_array(struct pool *p, size_t n, size_t size);

/* A NUL-terminated copy of the first n bytes of s. */
char *pool_strndup(struct pool *p, const char *s, size_t n);

/* Free everything the pool handed out; the pool is empty again. */
void pool_free(struct pool *p);

#endif /* STRAND_POOL_H */
