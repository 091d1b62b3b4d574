/* SPDX-License-Identifier: MIT */
/*
 * pools.h - a particle system's pool against its emission (the proof that
 * its slots are enough, or the first frame they are not), from the build's
 * run over the span (motion/particles.h: dropped, first_drop, peak). The
 * part of `strand check` and of `strand play`'s refusal that is not a
 * channel's limit.
 */
#ifndef STRAND_CHECK_POOLS_H
#define STRAND_CHECK_POOLS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "scene/scene_desc.h"

/*
 * Each emitting particle system of sc: a line on info (NULL: none) saying
 * what its pool held at most, and one on out (NULL: none) for a pool that
 * ran out by frame `to`, the first of which is also written into first
 * (size bytes, may be NULL). Returns the pools that ran out.
 */
uint32_t lim_pools(FILE *out, FILE *info, const struct scene_desc *d, const struct mot_scene *sc,
		   int64_t to, char *first, size_t size);

#endif /* STRAND_CHECK_POOLS_H */
