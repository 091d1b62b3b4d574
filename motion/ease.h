/* SPDX-License-Identifier: MIT */
/*
 * ease.h - slow-in and slow-out (FORMULAS.md section 7).
 *
 * A trapezoidal velocity profile remaps a parameter s in [0, 1]: it
 * accelerates uniformly over the first fraction a, runs at the peak speed
 * v = 1 / (1 - a/2 - b/2), and decelerates over the last fraction b:
 *     s' = v s^2 / (2a)               s < a
 *     s' = v (s - a/2)                a <= s <= 1 - b
 *     s' = 1 - v (1 - s)^2 / (2b)     s > 1 - b
 * s' is continuous with a continuous first derivative, s'(0) = 0, s'(1) = 1.
 *
 * Naming: a key's `ease_out` is the fraction spent leaving it (the a of the
 * segment that starts there), its `ease_in` the fraction spent arriving (the
 * b of the segment that ends there); a strand's `ease: {in, out}` is the same
 * over its whole span, in frames: `out` leaving the first key, `in` arriving
 * at the last.
 */
#ifndef MOT_EASE_H
#define MOT_EASE_H

#include "fix.h"

struct mot_ease {
	mot_q32 a, b; /* accelerating, decelerating fraction */
	mot_q32 v;    /* peak speed */
	mot_q32 ka;   /* v / (2a), 0 when a = 0 */
	mot_q32 kb;   /* v / (2b), 0 when b = 0 */
};

/* Prepare. a, b in [0, 1] with a + b <= 1, else MOT_E_INVAL. a = b = 0 is
 * the identity. Init only (divides). */
int mot_ease_init(struct mot_ease *e, mot_q32 a, mot_q32 b, uint32_t *sat);

static inline bool mot_ease_is_identity(const struct mot_ease *e)
{
	return e->a == 0 && e->b == 0;
}

/* s' for s in [0, 1] (s outside is taken as the nearest end). Real-time safe:
 * two products. */
mot_q32 mot_ease_apply(const struct mot_ease *e, mot_q32 s, uint32_t *sat);

#endif /* MOT_EASE_H */
