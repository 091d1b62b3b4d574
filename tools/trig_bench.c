/* SPDX-License-Identifier: MIT */
/*
 * trig_bench.c - ns per call of trig.h, against the library as `make` builds
 * it. Not part of the build or the tests; run by hand:
 *
 *   make build/libmotion.a
 *   cc -O2 -Imotion tools/trig_bench.c build/libmotion.a -o build/trig_bench
 *   build/trig_bench
 *
 * "thru": one call per element of an array of 4096 random inputs, results
 * stored (what a loop over the joints of a tick does, calls independent).
 * "lat": each input depends on the previous result, so calls cannot overlap.
 * Best of 7 runs of 2^24 calls, after a warm-up that lets the clock settle.
 */
#define _POSIX_C_SOURCE 199309L
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#include "trig.h"

#define NIN 4096
#define ROUNDS (1 << 12) /* ROUNDS * NIN = 2^24 calls */

static mot_q32 in_a[NIN], in_b[NIN], out[NIN];
static volatile mot_q32 sink;

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

static mot_q32 f_sincos(mot_q32 a, mot_q32 b)
{
	mot_q32 s, c;

	mot_sincos(a, &s, &c);
	return s ^ c;
}

static mot_q32 f_sin(mot_q32 a, mot_q32 b)
{
	return mot_sin(a);
}

static mot_q32 f_atan2(mot_q32 a, mot_q32 b)
{
	return mot_atan2(a, b);
}

static mot_q32 f_acos(mot_q32 a, mot_q32 b)
{
	return mot_acos(a >> 31, NULL);
}

static mot_q32 f_sqrt(mot_q32 a, mot_q32 b)
{
	return mot_sqrt(a & MOT_Q32_MAX, NULL);
}

static mot_q32 f_rsqrt(mot_q32 a, mot_q32 b)
{
	return mot_rsqrt((a & MOT_Q32_MAX) | 1, NULL);
}

static mot_q32 f_norm3(mot_q32 a, mot_q32 b)
{
	mot_q32 v[3] = { a >> 24, b >> 2, (a ^ b) >> 26 }; /* lengths to ~2^8 units */

	return mot_norm3(v, NULL);
}

static mot_q32 f_isqrt(mot_q32 a, mot_q32 b)
{
	return (mot_q32)mot_isqrt_acc(mot_acc_make((uint64_t)a >> 2, (uint64_t)b), NULL);
}

/* The bodies are inlined into each loop (one copy per function). */
#define BENCH(name, fn)                                                                  \
	static void bench_##fn(void)                                                      \
	{                                                                                 \
		double thru = 1e30, lat = 1e30, t0, t;                                    \
		int rep, r, i;                                                            \
                                                                                          \
		for (rep = 0; rep < 7; rep++) {                                           \
			mot_q32 acc = 0;                                                  \
                                                                                          \
			t0 = now_ns();                                                    \
			for (r = 0; r < ROUNDS; r++)                                      \
				for (i = 0; i < NIN; i++)                                 \
					out[i] = fn(in_a[i] + r, in_b[i]);                \
			t = (now_ns() - t0) / ((double)ROUNDS * NIN);                     \
			thru = t < thru ? t : thru;                                       \
			t0 = now_ns();                                                    \
			for (r = 0; r < ROUNDS; r++)                                      \
				for (i = 0; i < NIN; i++)                                 \
					acc = fn(in_a[i] ^ (acc & 0xff), in_b[i]);        \
			t = (now_ns() - t0) / ((double)ROUNDS * NIN);                     \
			lat = t < lat ? t : lat;                                          \
			sink = acc ^ out[rep];                                            \
		}                                                                         \
		printf("BENCH trig.%-10s thru %6.2f ns/call   lat %6.2f ns/call\n", name, \
		       thru, lat);                                                        \
	}

BENCH("sincos", f_sincos)
BENCH("sin", f_sin)
BENCH("atan2", f_atan2)
BENCH("acos", f_acos)
BENCH("sqrt", f_sqrt)
BENCH("rsqrt", f_rsqrt)
BENCH("norm3", f_norm3)
BENCH("isqrt_acc", f_isqrt)

int main(void)
{
	double t0;
	int i;

	for (i = 0; i < NIN; i++) {
		in_a[i] = (mot_q32)rng();
		in_b[i] = (mot_q32)rng() >> (rng() % 40);
	}
	t0 = now_ns();
	while (now_ns() - t0 < 3e8) /* warm-up */
		for (i = 0; i < NIN; i++)
			out[i] = f_sincos(in_a[i] + i, 0);
	bench_f_sincos();
	bench_f_sin();
	bench_f_atan2();
	bench_f_acos();
	bench_f_sqrt();
	bench_f_rsqrt();
	bench_f_norm3();
	bench_f_isqrt();
	return 0;
}
