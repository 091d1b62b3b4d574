/* SPDX-License-Identifier: MIT */
/*
 * source_path.h - a play source of straight lines between poses at whole
 * frames: channel i is keys[k][i] at frame first + k and moves at a
 * constant speed to keys[k + 1][i] over the next frame; before the first
 * pose and after the last it holds. What a front end that is told poses
 * rather than a scene runs through the loop: DFMoco's go-motion (bf, the
 * positions at the previous, this and the next frame), on the same code as
 * a scene's go-motion (plan/gomo.h).
 *
 * The caller owns the memory (the channels' names and the keys), sized
 * with SOURCE_PATH_KEYS_MAX poses of SOURCE_PATH_CH_MAX channels at most.
 * Keys may change only while no loop evaluates the source. eval is [rt]
 * and exact: x_k + (x_{k+1} - x_k) u rounded once, u the Q32.32 fraction of
 * the frame.
 */
#ifndef STRAND_SOURCE_PATH_H
#define STRAND_SOURCE_PATH_H

#include <stdint.h>

#include "source.h"

#define SOURCE_PATH_CH_MAX 32
#define SOURCE_PATH_KEYS_MAX 4

struct source_path {
	struct play_source s; /* first */
	uint32_t n;           /* channels */
	const char *const *names;
	const enum src_unit *units;
	uint32_t nkeys;
	mot_q32 keys[SOURCE_PATH_KEYS_MAX][SOURCE_PATH_CH_MAX]; /* core units */
	uint32_t nsel;
	uint32_t sel[SOURCE_PATH_CH_MAX];
};

/* [init] n channels (names[i], units[i], kept) at num/den frames a second
 * and tick_hz, nkeys poses from frame `first` (the span first..first +
 * nkeys - 1), every key 0 until set. 0, or -EINVAL (too many channels or
 * keys, a timing mot_timing_init refuses). Every channel selected. */
int source_path_init(struct source_path *p, const char *name, uint32_t n,
		     const char *const *names, const enum src_unit *units, uint32_t num,
		     uint32_t den, uint32_t tick_hz, int64_t first, uint32_t nkeys);

#endif /* STRAND_SOURCE_PATH_H */
