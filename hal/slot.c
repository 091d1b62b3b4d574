/* SPDX-License-Identifier: MIT */
/* slot.c - triple-buffer set-up (see slot.h). */
#include "slot.h"

#include <errno.h>

int hal_slot_init(struct hal_slot *s, void *storage, uint32_t esize)
{
	if (!storage || !esize)
		return -EINVAL;
	atomic_init(&s->mid, 1);
	s->back = 0;
	s->front = 2;
	s->esize = esize;
	s->buf = storage;
	return 0;
}
