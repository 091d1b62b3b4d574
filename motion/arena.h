/* SPDX-License-Identifier: MIT */
/*
 * arena.h - hand out one caller-owned block while configuring, then seal it.
 *
 * The scene loader places every array the core uses in one block: it counts
 * first (an arena with no memory only measures), allocates exactly that much
 * once, and builds again into it. Once sealed, nothing more is handed out,
 * so the real-time loop cannot grow the scene by accident. Alignment is
 * relative to base, which must itself be 64-byte aligned.
 */
#ifndef MOT_ARENA_H
#define MOT_ARENA_H

#include "fix.h"

struct mot_arena {
	unsigned char *base; /* NULL: measure only */
	size_t size;
	size_t used;
	bool sealed;
	bool failed; /* a request did not fit (or came after sealing) */
};

void mot_arena_init(struct mot_arena *a, void *base, size_t size);

/* n bytes aligned to `align` (a power of two, at most 64), zeroed. Returns
 * NULL when measuring, when it does not fit, or after sealing (then
 * a->failed is set). */
void *mot_arena_alloc(struct mot_arena *a, size_t n, size_t align);

static inline void mot_arena_seal(struct mot_arena *a)
{
	a->sealed = true;
}

#endif /* MOT_ARENA_H */
