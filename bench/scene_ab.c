/* SPDX-License-Identifier: MIT */
/*
 * scene_ab.c - this build's core against another build's, in one process:
 *
 *     scene_ab SCENE PAIRS
 *
 * plays one of scene_bench.c's scenes (scene_pick.h) with this tree's
 * mot_scene_eval() and with the other core's (linked in with every symbol
 * prefixed ab_, mk/bench-ab.sh), one play after the other, PAIRS pairs, the
 * order swapped every pair, and prints each side's median and the median and
 * quartiles of the other/this ratio of each pair (an AB line).
 *
 * Why: on this project's VM the speed of the machine drifts by tens of
 * percent over seconds (another tenant), which a comparison of separate
 * runs can only average away over many rounds (mk/bench-time.sh); two plays
 * of a few milliseconds each, side by side, see the same machine, and their
 * ratio keeps the difference between the builds. The two cores get the
 * same scene, built by this tree's scene builder: the other core must read
 * the same structures (a change inside the core, not to its data's layout).
 * With the other build this very build, the ratio shows what placement in
 * memory alone gives (the A/A control).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scene/scene_desc.h"
#include "scene_pick.h"

/* the other core (mk/bench-ab.sh prefixes its symbols with ab_) */
void ab_mot_scene_eval(const struct mot_scene *sc, struct mot_eval *ev, mot_q32 frame,
		       struct mot_pose *out);
int ab_mot_eval_reset(struct mot_eval *ev, const struct mot_scene *sc);

/* the one libc function a core object may call (make check-freestanding) */
void *ab_memcpy(void *dst, const void *src, size_t n);
void *ab_memcpy(void *dst, const void *src, size_t n)
{
	return memcpy(dst, src, n);
}

typedef void eval_fn(const struct mot_scene *sc, struct mot_eval *ev, mot_q32 frame,
		     struct mot_pose *out);

/* One play of every tick, ns per node per tick. */
static double play(eval_fn *eval, const struct mot_scene *sc, struct mot_eval *ev,
		   struct mot_pose *pose, const mot_q32 *frame, uint32_t nticks)
{
	struct timespec t0, t1;
	uint32_t k;

	clock_gettime(CLOCK_MONOTONIC, &t0);
	for (k = 0; k < nticks; k++)
		eval(sc, ev, frame[k], pose);
	clock_gettime(CLOCK_MONOTONIC, &t1);
	return ((double)(t1.tv_sec - t0.tv_sec) * 1e9 + (double)(t1.tv_nsec - t0.tv_nsec)) /
	       ((double)nticks * sc->nnodes);
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

/* the value at fraction q of the sorted v[0..n) */
static double quantile(double *v, int n, double q)
{
	qsort(v, (size_t)n, sizeof(*v), cmp_double);
	return v[(int)(q * (n - 1) + 0.5)];
}

/*
 * The median ratio of the pairs whose play of this core was among the faster
 * half, and of the slower half. The VM runs in two states (this project's:
 * the 1,000 joints at about 27 ns a joint or about 40, for seconds at a
 * time, presumably another tenant on the core's sibling thread), and a
 * change can pay in one and not the other: the faster half is the quiet
 * state whenever the run saw both.
 */
static void split_ratio(double *const t[2], const double *ratio, int n, double half[2])
{
	double *key = calloc((size_t)n, sizeof(double)), *r[2], cut;
	int cnt[2] = { 0, 0 }, i, h;

	r[0] = calloc((size_t)n, sizeof(double));
	r[1] = calloc((size_t)n, sizeof(double));
	half[0] = half[1] = 0;
	if (key && r[0] && r[1]) {
		memcpy(key, t[0], (size_t)n * sizeof(double));
		cut = quantile(key, n, 0.5);
		for (i = 0; i < n; i++) {
			h = t[0][i] > cut;
			r[h][cnt[h]++] = ratio[i];
		}
		for (h = 0; h < 2; h++)
			half[h] = cnt[h] ? quantile(r[h], cnt[h], 0.5) : 0;
	}
	free(r[1]);
	free(r[0]);
	free(key);
}

int main(int argc, char **argv)
{
	struct synth sy;
	struct scene_built b;
	struct scene_build_err e;
	struct mot_eval ev[2];
	struct mot_pose pose[2];
	eval_fn *const eval[2] = { mot_scene_eval, ab_mot_scene_eval };
	double *t[2], *ratio, half[2];
	int64_t stride;
	mot_q32 *frame;
	uint32_t nticks;
	int pairs, i, s;

	if (argc != 3 || atoi(argv[2]) < 1 || atoi(argv[2]) > 100000) {
		fprintf(stderr, "usage: scene_ab " SCENE_PICK_NAMES " PAIRS\n");
		return 2;
	}
	pairs = atoi(argv[2]);
	stride = scene_pick(&sy, argv[1]);
	if (!stride) {
		fprintf(stderr, "scene_ab: no scene %s\n", argv[1]);
		return 2;
	}
	if (scene_build(&b, &sy.d, &e) || scene_eval_new(&ev[0], &b.sc) ||
	    scene_pose_new(&pose[0], &b.sc) || scene_eval_new(&ev[1], &b.sc) ||
	    scene_pose_new(&pose[1], &b.sc) || ab_mot_eval_reset(&ev[1], &b.sc)) {
		fprintf(stderr, "scene_ab: cannot set up %s\n", argv[1]);
		return 1;
	}
	frame = scene_pick_frames(&b.sc.timing, &sy, stride, &nticks);
	t[0] = calloc((size_t)pairs, sizeof(double));
	t[1] = calloc((size_t)pairs, sizeof(double));
	ratio = calloc((size_t)pairs, sizeof(double));
	if (!frame || !t[0] || !t[1] || !ratio)
		return 1;
	for (s = 0; s < 2; s++) /* warm both: caches, memos */
		play(eval[s], &b.sc, &ev[s], &pose[s], frame, nticks);
	for (i = 0; i < pairs; i++) {
		for (s = 0; s < 2; s++) {
			int side = s ^ (i & 1); /* ABBAAB...: neither always goes first */

			t[side][i] = play(eval[side], &b.sc, &ev[side], &pose[side], frame, nticks);
		}
		ratio[i] = t[1][i] / t[0][i];
	}
	split_ratio(t, ratio, pairs, half);
	printf("AB %s this %.2f other %.2f ns/node/tick, other/this %.4f (quartiles %.4f to %.4f, "
	       "%d pairs; the faster half %.4f, the slower %.4f)%s\n",
	       argv[1], quantile(t[0], pairs, 0.5), quantile(t[1], pairs, 0.5),
	       quantile(ratio, pairs, 0.5), quantile(ratio, pairs, 0.25),
	       quantile(ratio, pairs, 0.75), pairs, half[0], half[1],
	       memcmp(pose[0].world, pose[1].world, b.sc.nnodes * sizeof(*pose[0].world)) ?
		       ", results differ" :
		       "");
	free(ratio);
	free(t[1]);
	free(t[0]);
	free(frame);
	return 0;
}
