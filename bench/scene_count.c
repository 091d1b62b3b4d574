/* SPDX-License-Identifier: MIT */
/*
 * scene_count.c - one scene of scene_bench.c played once, by the core or by
 * the double twin, for counting instructions instead of timing them (the
 * build machine is a shared VM where perf counters are not available):
 *
 *     valgrind --tool=callgrind --toggle-collect=scene_count_play \
 *         build/bench/scene_count joints1000 fixed
 *
 * counts exactly the ticks scene_bench.c times; the program prints the
 * divisor (ticks x nodes) so that a script can print instructions per node
 * per tick (`make bench-count` does, for every scene and both sides).
 *
 * With a third argument, REPS, it times the same play REPS times instead
 * and prints the fastest, in ns per node per tick (TIME lines): the
 * least-disturbed run of one process, for mk/bench-time.sh, which starts
 * each run from a fresh copy of the program (one copy once ran 5% slower
 * than a byte-identical one, run after run: see there).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "dbl_scene.h"
#include "scene/scene_desc.h"
#include "scene_pick.h"

/* The timed loop of scene_bench.c's play_fixed / play_double; not inlined,
 * so that callgrind can collect exactly it. */
__attribute__((noinline)) void scene_count_play(const struct scene_built *b, struct mot_eval *ev,
						struct mot_pose *pose, const struct dbl_scene *ds,
						struct dbl_eval *dev, struct dbl_pose *dp,
						const mot_q32 *frame, uint32_t nticks, bool fixed);

void scene_count_play(const struct scene_built *b, struct mot_eval *ev, struct mot_pose *pose,
		      const struct dbl_scene *ds, struct dbl_eval *dev, struct dbl_pose *dp,
		      const mot_q32 *frame, uint32_t nticks, bool fixed)
{
	uint32_t k;

	for (k = 0; k < nticks; k++) {
		if (fixed)
			mot_scene_eval(&b->sc, ev, frame[k], pose);
		else
			dbl_scene_eval(ds, dev, (double)frame[k] / 4294967296.0, dp);
	}
}

/* The fastest of reps plays, ns per node per tick (CLOCK_MONOTONIC). */
static double fastest(const struct scene_built *b, struct mot_eval *ev, struct mot_pose *pose,
		      const struct dbl_scene *ds, struct dbl_eval *dev, struct dbl_pose *dp,
		      const mot_q32 *frame, uint32_t nticks, bool fixed, int reps)
{
	double best = 0;
	int r;

	for (r = 0; r < reps; r++) {
		struct timespec t0, t1;
		double ns;

		clock_gettime(CLOCK_MONOTONIC, &t0);
		scene_count_play(b, ev, pose, ds, dev, dp, frame, nticks, fixed);
		clock_gettime(CLOCK_MONOTONIC, &t1);
		ns = ((double)(t1.tv_sec - t0.tv_sec) * 1e9 + (double)(t1.tv_nsec - t0.tv_nsec)) /
		     ((double)nticks * b->sc.nnodes);
		if (r == 0 || ns < best)
			best = ns;
	}
	return best;
}

int main(int argc, char **argv)
{
	struct synth sy;
	struct scene_built b;
	struct scene_build_err e;
	struct mot_eval ev;
	struct mot_pose pose;
	struct dbl_scene ds;
	struct dbl_eval dev;
	struct dbl_pose dp;
	int64_t stride;
	mot_q32 *frame;
	uint32_t nticks;
	bool fixed;

	if (argc < 3 || argc > 4 || (strcmp(argv[2], "fixed") && strcmp(argv[2], "double")) ||
	    (argc == 4 && (atoi(argv[3]) < 1 || atoi(argv[3]) > 100000))) {
		fprintf(stderr, "usage: scene_count " SCENE_PICK_NAMES " fixed|double [REPS]\n");
		return 2;
	}
	fixed = !strcmp(argv[2], "fixed");
	stride = scene_pick(&sy, argv[1]);
	if (!stride) {
		fprintf(stderr, "scene_count: no scene %s\n", argv[1]);
		return 2;
	}
	if (scene_build(&b, &sy.d, &e) || scene_eval_new(&ev, &b.sc) ||
	    scene_pose_new(&pose, &b.sc) || dbl_scene_new(&ds, &sy.d) || dbl_eval_new(&dev, &ds) ||
	    dbl_pose_new(&dp, &ds)) {
		fprintf(stderr, "scene_count: cannot set up %s\n", argv[1]);
		return 1;
	}
	frame = scene_pick_frames(&b.sc.timing, &sy, stride, &nticks);
	if (!frame)
		return 1;
	if (argc == 4) {
		printf("TIME %s %s %.2f ns/node/tick\n", argv[1], argv[2],
		       fastest(&b, &ev, &pose, &ds, &dev, &dp, frame, nticks, fixed, atoi(argv[3])));
		free(frame);
		return 0;
	}
	scene_count_play(&b, &ev, &pose, &ds, &dev, &dp, frame, nticks, fixed);
	printf("COUNT %s %s units %llu\n", argv[1], argv[2],
	       (unsigned long long)nticks * b.sc.nnodes);
	free(frame);
	return 0;
}
