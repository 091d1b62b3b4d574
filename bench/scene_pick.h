/* SPDX-License-Identifier: MIT */
/*
 * scene_pick.h - the scenes of scene_bench.c by name, for the programs that
 * play one of them (scene_count.c, scene_ab.c), and the frames of its ticks.
 */
#ifndef BENCH_SCENE_PICK_H
#define BENCH_SCENE_PICK_H

#include <stdint.h>

#include "motion/timing.h"
#include "tests/synth.h"

#define SCENE_PICK_NAMES \
	"arm|random1000|joints1000|kind_<k>1000|rev_axis1000|rev_tilt1000|" \
	"pri_axis1000|pri_tilt1000"

/* Fills sy with the scene called name and returns the tick stride it is
 * played at (every 16th tick for the 1,000-node scenes, as scene_bench.c),
 * or 0 for an unknown name. */
int64_t scene_pick(struct synth *sy, const char *name);

/* The frames of the scene's ticks from its first frame to its last, every
 * stride-th tick: a calloc'ed array of *nticks frames, NULL when out of
 * memory. */
mot_q32 *scene_pick_frames(const struct mot_timing *t, const struct synth *sy, int64_t stride,
			   uint32_t *nticks);

#endif
