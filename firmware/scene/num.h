/* SPDX-License-Identifier: MIT */
/*
 * num.h - numbers that come in from outside (a scene file, a command line,
 * a driver's settings) made into the integers the program counts in, with
 * the range checked: a double converted to an integer type that cannot
 * hold it is undefined behaviour (C11 6.3.1.4), and llround()'s result is
 * then unspecified (7.12.9.7). Beside sd_to_q32() (scene_desc.h), which
 * does the same for the core's Q32.32.
 *
 * Two kinds, after the kernel's check_mul_overflow() family:
 *   num_to_i64 and the tick/nanosecond conversions are for where a value
 *   enters: 0, or -ERANGE when the value is not finite or its result falls
 *   outside [min, max] (*out is then untouched). They print nothing: the
 *   caller knows the key or the option and names it in its message.
 *   num_sat_i64 is for where a value is computed ([rt]): it clamps to
 *   [min, max] and ORs MOT_SAT_OVERFLOW into *sat when it had to, so the
 *   saturation travels with the result as the core's does (motion/fix.h).
 *
 * Seconds and milliseconds become ticks as `s * hz` and `ms * hz / 1000`,
 * in that order, so a value rounds exactly as it did before these existed.
 */
#ifndef STRAND_NUM_H
#define STRAND_NUM_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "motion/fix.h"
#include "hal/rt.h"

/*
 * The most ticks anything is planned or counted over (a move, a run-up, a
 * timeout, --duration): 2^53, exact in a double, so that tick counts and
 * their doubles agree, and a sum of a few of them stays far inside
 * int64_t. That is 285 years at tick_hz 1048576 (the most a scene may
 * have) and 285,000 years at 1 kHz: no shoot reaches it.
 */
#define NUM_TICKS_MAX (INT64_C(1) << 53)

enum num_round {
	NUM_ROUND_NEAREST, /* halfway cases away from zero, as llround() */
	NUM_ROUND_UP,      /* ceil() */
	NUM_ROUND_DOWN,    /* floor() */
};

/* Does the whole number r (already rounded) convert to int64_t? False for
 * NaN and the infinities. [rt] */
static inline bool STRAND_RT num_fits_i64(double r)
{
	return r >= -9223372036854775808.0 && r < 9223372036854775808.0;
}

static inline double STRAND_RT num_round(double v, enum num_round r)
{
	return r == NUM_ROUND_UP ? ceil(v) : r == NUM_ROUND_DOWN ? floor(v) : round(v);
}

/* v rounded to nearest and clamped to [min, max]; NaN gives 0. Either
 * ORs MOT_SAT_OVERFLOW into *sat (when sat is not NULL). [rt] */
static inline int64_t STRAND_RT num_sat_i64(double v, int64_t min, int64_t max, uint32_t *sat)
{
	double r = round(v);
	int64_t i;

	if (num_fits_i64(r))
		i = (int64_t)r;
	else
		i = r > 0 ? INT64_MAX : r < 0 ? INT64_MIN : 0; /* NaN: neither */
	if (i < min || i > max || !num_fits_i64(r)) {
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		i = i < min ? min : i > max ? max : i;
	}
	return i;
}

/* v rounded by r: 0 with *out in [min, max], or -ERANGE. */
int num_to_i64(double v, enum num_round r, int64_t min, int64_t max, int64_t *out);

/* Seconds at hz ticks a second, rounded by r, as ticks in [min, max]. */
int num_s_to_ticks(double s, uint32_t hz, enum num_round r, int64_t min, int64_t max,
		   int64_t *out);

/* Milliseconds at hz ticks a second, rounded by r, as ticks in [min, max]. */
int num_ms_to_ticks(double ms, uint32_t hz, enum num_round r, int64_t min, int64_t max,
		    int64_t *out);

/* Milliseconds as nanoseconds rounded by r, in [min, max]. */
int num_ms_to_ns(double ms, enum num_round r, int64_t min, int64_t max, int64_t *out);

#endif /* STRAND_NUM_H */
