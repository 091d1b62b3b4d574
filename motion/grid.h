/* SPDX-License-Identifier: MIT */
/*
 * grid.h - neighbour search for particles and flocks: a uniform grid of
 * cubic cells, hashed into a table, so that finding every item within a
 * radius r <= cell of a point looks at 27 cells instead of all n items
 * (O(n k) a step for k neighbours, not O(n^2)).
 *
 * Items are inserted by index each step; a bucket's list holds the items of
 * every cell that hashes there, so a query keeps only those whose cell is
 * the one it visits (two of the 27 cells hashing to one bucket are then not
 * counted twice). Cell coordinates are floor(x / cell) with a prepared
 * reciprocal (within one unit of 2^-32 cells: a point on a boundary may
 * land on either side, and whichever it lands on it is found from every
 * point within one cell of it). All memory is the caller's; everything is
 * real-time safe.
 */
#ifndef MOT_GRID_H
#define MOT_GRID_H

#include "fix.h"

struct mot_grid {
	uint32_t mask;        /* buckets - 1 (a power of two) */
	uint32_t nitems;
	struct mot_recip inv; /* 1 / cell */
	uint32_t *head;       /* buckets: first item + 1, 0 = empty */
	uint32_t *next;       /* items: next item + 1 in its bucket */
	int32_t (*cell)[3];   /* items: its cell */
};

/* Buckets for n items: the power of two at or above 2n (at least 16). */
uint32_t mot_grid_buckets(uint32_t n);

/* Prepare with cell size `cell` (> 0, Q32.32 units) over caller arrays of
 * `buckets` (a power of two) heads and n items' next and cell. Init only. */
int mot_grid_init(struct mot_grid *g, mot_q32 cell, uint32_t buckets, uint32_t *head,
		  uint32_t *next, int32_t (*cellv)[3], uint32_t n);

/* Empty it. */
void mot_grid_clear(struct mot_grid *g);

/* Insert item i (< n) at position p. */
void mot_grid_insert(struct mot_grid *g, uint32_t i, const mot_q32 p[3]);

/* The cell of a position. */
void mot_grid_cell(const struct mot_grid *g, const mot_q32 p[3], int32_t c[3]);

/*
 * Every inserted item in the 27 cells around cell c: fn(ctx, item) for
 * each, in a fixed order (cells in x, y, z order, each bucket's items last
 * inserted first); fn returns false to stop. Returns the items visited.
 */
uint32_t mot_grid_visit(const struct mot_grid *g, const int32_t c[3],
			bool (*fn)(void *ctx, uint32_t item), void *ctx);

#endif /* MOT_GRID_H */
