/* SPDX-License-Identifier: MIT */
/* grid.c - neighbour search on a hashed uniform grid (see grid.h). */
#include "grid.h"

uint32_t mot_grid_buckets(uint32_t n)
{
	uint32_t b = 16;

	while (b < 2 * (uint64_t)n && b < (1u << 30))
		b <<= 1;
	return b;
}

int mot_grid_init(struct mot_grid *g, mot_q32 cell, uint32_t buckets, uint32_t *head,
		  uint32_t *next, int32_t (*cellv)[3], uint32_t n)
{
	if (cell <= 0 || buckets == 0 || (buckets & (buckets - 1)) || !head || !next || !cellv)
		return MOT_E_INVAL;
	if (mot_recip_init(&g->inv, cell))
		return MOT_E_INVAL;
	g->mask = buckets - 1;
	g->nitems = n;
	g->head = head;
	g->next = next;
	g->cell = cellv;
	mot_grid_clear(g);
	return MOT_OK;
}

void mot_grid_clear(struct mot_grid *g)
{
	uint32_t i;

	for (i = 0; i <= g->mask; i++)
		g->head[i] = 0;
}

static int32_t coord(const struct mot_grid *g, mot_q32 x)
{
	/* floor(x / cell): the Q32.32 ratio's integer part; coordinates beyond
	 * +-2^31 cells fold, which only merges far cells into one bucket */
	return (int32_t)(uint32_t)((uint64_t)mot_recip_ratio(x, &g->inv, NULL) >> 32);
}

void mot_grid_cell(const struct mot_grid *g, const mot_q32 p[3], int32_t c[3])
{
	c[0] = coord(g, p[0]);
	c[1] = coord(g, p[1]);
	c[2] = coord(g, p[2]);
}

static uint32_t hash(const int32_t c[3])
{
	/* Teschner et al. 2003's primes, in unsigned arithmetic */
	return ((uint32_t)c[0] * 73856093u) ^ ((uint32_t)c[1] * 19349663u) ^
	       ((uint32_t)c[2] * 83492791u);
}

void mot_grid_insert(struct mot_grid *g, uint32_t i, const mot_q32 p[3])
{
	uint32_t b;

	mot_grid_cell(g, p, g->cell[i]);
	b = hash(g->cell[i]) & g->mask;
	g->next[i] = g->head[b];
	g->head[b] = i + 1;
}

uint32_t mot_grid_visit(const struct mot_grid *g, const int32_t c[3],
			bool (*fn)(void *ctx, uint32_t item), void *ctx)
{
	uint32_t seen = 0;
	int dx, dy, dz;

	for (dx = -1; dx <= 1; dx++)
		for (dy = -1; dy <= 1; dy++)
			for (dz = -1; dz <= 1; dz++) {
				int32_t q[3] = { (int32_t)((uint32_t)c[0] + (uint32_t)dx),
						 (int32_t)((uint32_t)c[1] + (uint32_t)dy),
						 (int32_t)((uint32_t)c[2] + (uint32_t)dz) };
				uint32_t it = g->head[hash(q) & g->mask];

				for (; it; it = g->next[it - 1]) {
					const int32_t *ic = g->cell[it - 1];

					if (ic[0] != q[0] || ic[1] != q[1] || ic[2] != q[2])
						continue;
					seen++;
					if (!fn(ctx, it - 1))
						return seen;
				}
			}
	return seen;
}
