/* SPDX-License-Identifier: MIT */
/* ring.c - SPSC ring set-up (see ring.h). */
#include "ring.h"

#include <errno.h>

int hal_ring_init(struct hal_ring *r, void *storage, uint32_t capacity, uint32_t esize)
{
	if (capacity < 2 || (capacity & (capacity - 1)) || !esize || !storage)
		return -EINVAL;
	atomic_init(&r->head, 0);
	atomic_init(&r->tail, 0);
	r->mask = capacity - 1;
	r->esize = esize;
	r->buf = storage;
	return 0;
}
