/* SPDX-License-Identifier: MIT */
/* curve_portable.h - motion/curve*.c, ease.c and fix.c compiled with
 * MOT_NO_INT128 (the path armhf and Cortex-M take), callable from a test
 * built with __int128. The curve structs differ between the two builds, so
 * these wrappers take only keys, options and frames. */
#ifndef CURVE_PORTABLE_H
#define CURVE_PORTABLE_H

#include <stddef.h>
#include <stdint.h>

struct mot_key;
struct mot_curve_opts;

/* Values at frames[0..m) (random access); the init's error code. */
int cvp_eval(int kind, const struct mot_key *keys, uint32_t n, const struct mot_curve_opts *opts,
	     const int64_t *frames, int64_t *out, size_t m);

/* Integrals at frames[0..m) (opts->integral set), as the two 64-bit halves. */
int cvp_integral(int kind, const struct mot_key *keys, uint32_t n, const int64_t *frames,
		 uint64_t *hi, uint64_t *lo, size_t m);

#endif
