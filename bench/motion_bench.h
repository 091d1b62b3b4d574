/* SPDX-License-Identifier: MIT */
/*
 * motion_bench.h - the parts of the motion benchmark (`make bench`), one
 * file each, run in turn by motion_bench.c's main(). Each prints BENCH
 * lines and returns 0, or -1 when a check that makes its numbers meaningful
 * failed (the run still prints everything).
 */
#ifndef MOTION_BENCH_H
#define MOTION_BENCH_H

/* Whole scenes, fixed core against the double twin, and their errors
 * against tests/ref_scene.c (scene_bench.c). */
int bench_scenes(void);

/* The paper's two-key matrix pipeline (pipe_bench.c). */
int bench_pipeline(void);

/* Elementary functions, matrix and quaternion operations, curve kinds
 * (prim_bench.c). */
int bench_primitives(void);

#endif /* MOTION_BENCH_H */
