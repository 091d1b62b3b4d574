/* SPDX-License-Identifier: MIT */
/*
 * ref_curve.h - a floating-point reference for the curves of motion/curve.c
 * and motion/ease.c, written from FORMULAS.md sections 6 to 8 as literally as
 * possible and sharing no code with them. Test-only: never linked into the
 * core.
 *
 * It computes in long double (64-bit significand on x86_64, 113 on aarch64),
 * so that a Q32.32 key frame or value converts exactly; solves the
 * approximating kinds by bisection to the last bit; and integrates in closed
 * form. Keys and options are read from the core's own structs and converted
 * once.
 */
#ifndef REF_CURVE_H
#define REF_CURVE_H

#include "motion/curve.h"

typedef long double ref_t;

/* s' of the trapezoidal profile with fractions a, b (FORMULAS section 7). */
ref_t ref_ease(ref_t a, ref_t b, ref_t s);

/* Value at frame f (frames as a real number). */
ref_t ref_curve_eval(enum mot_interp kind, const struct mot_key *keys, uint32_t n,
		     const struct mot_curve_opts *opts, ref_t f);

/* The largest one-sided slope |dv/df| around f over +-df frames (for error
 * bounds that scale with the slope). */
ref_t ref_curve_slope(enum mot_interp kind, const struct mot_key *keys, uint32_t n,
		      const struct mot_curve_opts *opts, ref_t f, ref_t df);

/* The frame after the strand-wide warp, and with keys also after the key
 * interval's warp: where an eased curve takes its value from the plain one. */
ref_t ref_curve_warp(const struct mot_key *keys, uint32_t n, const struct mot_curve_opts *opts,
		     ref_t f, bool keys_too);

/* Integral from frame 0 to f (value x frames), step/linear/hermite only. */
ref_t ref_curve_integral(enum mot_interp kind, const struct mot_key *keys, uint32_t n, ref_t f);

static inline ref_t ref_q(mot_q32 x)
{
	return (ref_t)x / 4294967296.0L;
}

#endif /* REF_CURVE_H */
