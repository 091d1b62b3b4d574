/* SPDX-License-Identifier: MIT */
/*
 * testutil.h - shared helpers for the unit tests: Q32.32 <-> double, a seeded
 * random generator (the same sequence on every machine), and the bound check
 * every accuracy test ends with.
 */
#ifndef TESTUTIL_H
#define TESTUTIL_H

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "motion/fix.h"

#define TU_Q32 4294967296.0

static inline double q2d(mot_q32 x)
{
	return (double)x / TU_Q32;
}

static inline mot_q32 d2q(double x)
{
	return (mot_q32)llround(x * TU_Q32);
}

/* turns <-> radians and degrees, for comparing with libm. */
static inline double turns2rad(mot_q32 t)
{
	return q2d(t) * 2.0 * M_PI;
}

static inline mot_q32 deg2turns(double deg)
{
	return d2q(deg / 360.0);
}

/* xorshift64*: deterministic, seeded per test. */
struct tu_rng {
	uint64_t s;
};

static inline void tu_seed(struct tu_rng *r, uint64_t seed)
{
	r->s = seed ? seed : 0x9e3779b97f4a7c15ull;
}

static inline uint64_t tu_u64(struct tu_rng *r)
{
	r->s ^= r->s >> 12;
	r->s ^= r->s << 25;
	r->s ^= r->s >> 27;
	return r->s * 2685821657736338717ull;
}

/* Uniform double in [lo, hi). */
static inline double tu_uniform(struct tu_rng *r, double lo, double hi)
{
	return lo + (hi - lo) * (double)(tu_u64(r) >> 11) * (1.0 / 9007199254740992.0);
}

/* Random int64 with a random magnitude (log-uniform bit length). */
static inline int64_t tu_i64(struct tu_rng *r)
{
	unsigned bits = (unsigned)(tu_u64(r) % 64);
	int64_t v = (int64_t)tu_u64(r);

	return bits == 63 ? v : v >> (63 - bits);
}

/* Running worst error. */
struct tu_worst {
	double err;
	double at; /* input that gave it (for the message) */
};

static inline void tu_worst_add(struct tu_worst *w, double err, double at)
{
	err = fabs(err);
	if (err > w->err || isnan(err)) {
		w->err = err;
		w->at = at;
	}
}

/*
 * Every accuracy test ends here: prints one line
 *   BOUND <name> worst=<w> bound=<b> <unit> (at <input>)
 * and fails the test when the worst error exceeds the stated bound.
 * `make test` collects these lines into its report.
 */
void tu_bound(const char *name, const struct tu_worst *w, double bound, const char *unit);

#endif /* TESTUTIL_H */
