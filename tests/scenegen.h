/* SPDX-License-Identifier: MIT */
/*
 * scenegen.h - random valid scenes for the property test of strand's
 * promise (tests/check/test_promise.c): every joint kind (revolute and
 * prismatic, about a coordinate axis or a tilted one), free nodes, every
 * interpolation and ease, rpm strands, cycles, attributes and a camera;
 * spans from a second to a day, tick rates from 100 Hz to 10 kHz, 24, 25
 * and 30000/1001 fps; with limits on some joints and none on others; now
 * and then a surface, particles, a flock and a head aiming at an item. The
 * same seed gives the same scene on every machine.
 */
#ifndef SCENEGEN_H
#define SCENEGEN_H

#include <stddef.h>
#include <stdint.h>

struct scenegen {
	int64_t max_ticks;  /* the span's ticks at most: long spans go with slow rates */
	char *yaml;         /* the scene, NUL-terminated (malloc'd) */
	size_t len, cap;
	/* what the scene is, for the run and the summary */
	uint32_t tick_hz, num, den;
	int64_t first, last;
	int64_t ticks;      /* of the span */
	/* a run other than the whole span once: the options to give check and
	 * play alike ("" for none) */
	char run[96];
};

/* The scene of `seed` into g->yaml. */
void scenegen_make(struct scenegen *g, uint64_t seed);
void scenegen_free(struct scenegen *g);

#endif /* SCENEGEN_H */
