/* SPDX-License-Identifier: MIT */
/*
 * trig.h - elementary functions on Q32.32, in integer code only.
 *
 * Angles are in turns (fix.h). Every function is a pure function of its
 * arguments: same bits in, same bits out, on every target. Worst errors are
 * measured by tests/test_trig.c against libm in double precision and quoted
 * in each comment; they are a few LSB of Q32.32 (1 LSB = 2.3e-10).
 *
 * All functions here are safe in the real-time loop (bounded time, no
 * memory access outside their const tables).
 */
#ifndef MOT_TRIG_H
#define MOT_TRIG_H

#include "fix.h"

/* Radians per turn and turns per radian, in Q32.32 and for the edges. */
#define MOT_TURN_PER_RAD_Q32 ((mot_q32)683565276)    /* 1/(2 pi) * 2^32 */
#define MOT_TWO_PI_Q32 ((mot_q32)26986075409LL)        /* 2 pi * 2^32 */

/* sin and cos of an angle in turns, any number of turns. Exact (0, +-1) at
 * multiples of a quarter turn; |sin|, |cos| <= 1 always. */
void mot_sincos(mot_q32 turns, mot_q32 *s, mot_q32 *c);
mot_q32 mot_sin(mot_q32 turns);
mot_q32 mot_cos(mot_q32 turns);

/* Angle of the vector (x, y) in turns, in (-1/2, +1/2]; atan2(0, 0) = 0.
 * Exact at the axes and diagonals of equal magnitude. Works for any
 * magnitudes (the ratio matters, not the scale). */
mot_q32 mot_atan2(mot_q32 y, mot_q32 x);

/* acos in turns, in [0, 1/2]. |x| > 1 (rounding of a dot product of unit
 * vectors) is taken as +-1 and flagged MOT_SAT_DOMAIN. */
mot_q32 mot_acos(mot_q32 x, uint32_t *sat);

/* sqrt(x), correctly rounded to nearest. x < 0 gives 0 and MOT_SAT_DOMAIN. */
mot_q32 mot_sqrt(mot_q32 x, uint32_t *sat);

/* 1/sqrt(x). x <= 0 gives MOT_Q32_MAX and MOT_SAT_DOMAIN. */
mot_q32 mot_rsqrt(mot_q32 x, uint32_t *sat);

/* Square root of a non-negative 128-bit integer, rounded to nearest. With a
 * sum of squares of Q32.32 values (a Q64.64 number) this is the Euclidean norm
 * in Q32.32 with a single rounding. Negative x gives 0 and MOT_SAT_DOMAIN. */
uint64_t mot_isqrt_acc(mot_acc x, uint32_t *sat);

/* |v| for a 3-vector, one rounding. */
mot_q32 mot_norm3(const mot_q32 v[3], uint32_t *sat);

#endif /* MOT_TRIG_H */
