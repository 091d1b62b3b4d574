/* SPDX-License-Identifier: MIT */
/*
 * rng.h - a seeded integer random generator for the particle systems and
 * flocks: the same sequence on every target, from integer operations only.
 *
 * splitmix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number
 * generators", OOPSLA 2014): a 64-bit counter stepped by the golden ratio
 * and mixed by two multiply-xorshift rounds. It passes BigCrush, needs one
 * word of state (a system's checkpoint carries it), and its 64-bit
 * products are exact on 32-bit targets (a libgcc/EABI helper on a
 * Cortex-M4). The state belongs to the caller: a generator is a value.
 */
#ifndef MOT_RNG_H
#define MOT_RNG_H

#include "fix.h"

struct mot_rng {
	uint64_t s;
};

static inline void mot_rng_seed(struct mot_rng *r, uint64_t seed)
{
	r->s = seed;
}

static inline uint64_t mot_rng_u64(struct mot_rng *r)
{
	uint64_t z = (r->s += 0x9e3779b97f4a7c15ull);

	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
	return z ^ (z >> 31);
}

/* Uniform in [0, 1) as Q32.32: the top 32 bits of a draw. */
static inline mot_q32 mot_rng_unit(struct mot_rng *r)
{
	return (mot_q32)(mot_rng_u64(r) >> 32);
}

/* Uniform in [-1, 1) as Q32.32. */
static inline mot_q32 mot_rng_sym(struct mot_rng *r)
{
	return (mot_q32)(mot_rng_u64(r) >> 31) - MOT_Q32_ONE;
}

/* lo + u (hi - lo) for u = mot_rng_unit(): uniform between two values
 * (either order), rounded once. */
static inline mot_q32 mot_rng_between(struct mot_rng *r, mot_q32 lo, mot_q32 hi, uint32_t *sat)
{
	return mot_add_sat(lo, mot_mul(mot_sub_sat(hi, lo, sat), mot_rng_unit(r), sat), sat);
}

#endif /* MOT_RNG_H */
