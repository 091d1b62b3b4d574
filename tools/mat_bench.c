/* SPDX-License-Identifier: MIT */
/*
 * mat_bench.c - ns per call of mat.h, quat.h and decomp.h, against the
 * library as `make` builds it (-O2). Not part of the build or the tests; run
 * by hand:
 *
 *   make build/libmotion.a
 *   cc -O2 -Imotion tools/mat_bench.c build/libmotion.a -o build/mat_bench
 *   build/mat_bench
 *
 * "thru": one call per element of arrays of 1024 random inputs (S.H.R.T
 * matrices, unit quaternions), results stored: calls independent, as for the
 * nodes of one level of a hierarchy. "chain" (mat_mul only): a 1000-node
 * hierarchy walked parent first, W(i) = L(i) . W(parent(i)) with the parent
 * the previous node, so every product waits for the one before: the
 * worst case of a tick. Best of 7 runs after a warm-up.
 */
#define _DEFAULT_SOURCE
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#include "decomp.h"
#include "mat.h"
#include "quat.h"

#define NIN 1024

static struct mot_mat ma[NIN], mb[NIN], mo[NIN];
static struct mot_quat qa[NIN], qb[NIN], qo[NIN];
static struct mot_slerp sl[NIN];
static struct mot_decomp dc[NIN];
static mot_q32 pt[NIN][3], po[NIN][3], tt[NIN];

static double now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1e9 + ts.tv_nsec;
}

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;

static uint64_t rng(void)
{
	rng_state ^= rng_state >> 12;
	rng_state ^= rng_state << 25;
	rng_state ^= rng_state >> 27;
	return rng_state * 2685821657736338717ull;
}

static double uni(double lo, double hi)
{
	return lo + (hi - lo) * (double)(rng() >> 11) / 9007199254740992.0;
}

static mot_q32 q32(double x)
{
	return (mot_q32)llround(x * 4294967296.0);
}

static void rand_quat(struct mot_quat *q)
{
	double u1 = uni(0, 1), u2 = uni(0, 2 * M_PI), u3 = uni(0, 2 * M_PI);

	*q = (struct mot_quat){ q32(sqrt(1 - u1) * sin(u2)), q32(sqrt(1 - u1) * cos(u2)),
				q32(sqrt(u1) * sin(u3)), q32(sqrt(u1) * cos(u3)) };
}

static void rand_mat(struct mot_mat *m)
{
	struct mot_decomp d;
	int k;

	rand_quat(&d.rot);
	mot_quat_normalize(&d.rot, &d.rot, NULL);
	if (d.rot.w < 0)
		d.rot = (struct mot_quat){ -d.rot.w, -d.rot.x, -d.rot.y, -d.rot.z };
	for (k = 0; k < 3; k++) {
		d.scale[k] = q32(exp(uni(log(0.5), log(2))));
		d.shear[k] = q32(uni(-0.2, 0.2));
		d.translate[k] = q32(uni(-100, 100));
	}
	mot_mat_compose(m, &d, NULL);
}

typedef void (*bench_fn)(int i);

static void b_mul(int i)
{
	mot_mat_mul(&mo[i], &ma[i], &mb[i], NULL);
}

static void b_apply(int i)
{
	mot_mat_apply(po[i], pt[i], &ma[i], NULL);
}

static void b_inverse(int i)
{
	mot_mat_inverse(&mo[i], &ma[i], NULL);
}

static void b_euler(int i)
{
	mot_mat_euler(&mo[i], pt[i], NULL);
}

static void b_to_mat(int i)
{
	mot_quat_to_mat(&mo[i], &qa[i], NULL);
}

static void b_from_mat(int i)
{
	mot_quat_from_mat(&qo[i], &ma[i], NULL);
}

static void b_qmul(int i)
{
	mot_quat_mul(&qo[i], &qa[i], &qb[i], NULL);
}

static void b_normalize(int i)
{
	mot_quat_normalize(&qo[i], &qa[i], NULL);
}

static void b_slerp_prepare(int i)
{
	mot_slerp_prepare(&sl[i], &qa[i], &qb[i], NULL);
}

static void b_slerp_eval(int i)
{
	mot_slerp_eval(&qo[i], &sl[i], tt[i], NULL);
}

static void b_squad_inner(int i)
{
	mot_squad_inner(&qo[i], &qa[i], &qb[i], &qa[(i + 1) % NIN], NULL);
}

static void b_squad(int i)
{
	mot_quat_squad(&qo[i], &qa[i], &qb[i], &qa[(i + 1) % NIN], &qb[(i + 1) % NIN], tt[i],
		       NULL);
}

static void b_decompose(int i)
{
	mot_mat_decompose(&dc[i], NULL, &ma[i], NULL);
}

static void b_compose(int i)
{
	mot_mat_compose(&mo[i], &dc[i], NULL);
}

static void b_edit_local(int i)
{
	mot_mat_edit_local(&mo[i], &ma[i], pt[i], NULL);
}

static double run(bench_fn f, int reps)
{
	double best = 1e30;
	int r, k, i;

	for (r = 0; r < 8; r++) {
		double t0 = now_ns(), dt;

		for (k = 0; k < reps; k++)
			for (i = 0; i < NIN; i++)
				f(i);
		dt = (now_ns() - t0) / ((double)reps * NIN);
		if (r > 0 && dt < best) /* run 0 warms up */
			best = dt;
	}
	return best;
}

static double run_chain(void)
{
	static struct mot_mat rigid[1000];
	double best = 1e30;
	uint32_t sat = 0;
	int r, k, i;

	/* rigid links (rotation, translation within 1 m) keep the chain in range */
	for (i = 0; i < 1000; i++) {
		rigid[i] = ma[i];
		mot_quat_to_mat(&rigid[i], &qa[i], NULL);
		for (k = 0; k < 3; k++)
			rigid[i].m[3][k] = q32(uni(-1, 1));
	}

	for (r = 0; r < 8; r++) {
		double t0 = now_ns(), dt;

		for (k = 0; k < 200; k++) {
			mo[0] = rigid[0];
			for (i = 1; i < 1000; i++)
				mot_mat_mul(&mo[i], &rigid[i], &mo[i - 1], &sat);
		}
		dt = (now_ns() - t0) / (200.0 * 999);
		if (r > 0 && dt < best)
			best = dt;
	}
	if (sat)
		printf("chain saturated\n");
	return best;
}

int main(void)
{
	static const struct {
		const char *name;
		bench_fn f;
		int reps;
	} b[] = {
		{ "mat_mul", b_mul, 4000 },
		{ "mat_apply", b_apply, 4000 },
		{ "mat_inverse", b_inverse, 200 },
		{ "mat_euler", b_euler, 400 },
		{ "mat_edit_local", b_edit_local, 400 },
		{ "quat_to_mat", b_to_mat, 2000 },
		{ "quat_from_mat", b_from_mat, 400 },
		{ "quat_mul", b_qmul, 2000 },
		{ "quat_normalize", b_normalize, 1000 },
		{ "slerp_prepare", b_slerp_prepare, 200 },
		{ "slerp_eval", b_slerp_eval, 1000 },
		{ "squad_inner", b_squad_inner, 100 },
		{ "quat_squad", b_squad, 100 },
		{ "mat_decompose", b_decompose, 100 },
		{ "mat_compose", b_compose, 1000 },
	};
	unsigned i;

	for (i = 0; i < NIN; i++) {
		int k;

		rand_mat(&ma[i]);
		rand_mat(&mb[i]);
		rand_quat(&qa[i]);
		rand_quat(&qb[i]);
		for (k = 0; k < 3; k++)
			pt[i][k] = q32(uni(-100, 100));
		tt[i] = (mot_q32)(rng() >> 32);
	}
	for (i = 0; i < NIN; i++) {
		mot_slerp_prepare(&sl[i], &qa[i], &qb[i], NULL);
		mot_mat_decompose(&dc[i], NULL, &ma[i], NULL);
	}
	for (i = 0; i < sizeof(b) / sizeof(b[0]); i++)
		printf("BENCH %-16s %7.1f ns/call (thru)\n", b[i].name, run(b[i].f, b[i].reps));
	printf("BENCH %-16s %7.1f ns/call (chain of 1000 nodes)\n", "mat_mul", run_chain());
	return 0;
}
