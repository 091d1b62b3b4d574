/* SPDX-License-Identifier: MIT */
/*
 * dll.h - a delay-locked loop that filters timestamps: from noisy readings
 * (x_i, t_i) of a clock that runs at a steady rate (a sound card's sample
 * counter read against CLOCK_MONOTONIC, a frame count against the times its
 * frames were seen), a smooth estimate t(x) = t_ref + (x - x_ref) * per
 * and the rate `per` itself.
 *
 * The loop is Adriaensen's (F. Adriaensen, "Using a DLL to filter time",
 * LAC 2005), which JACK and zita-ajbridge use: a second-order loop
 *
 *     e = t_i - predicted(x_i);   t_ref += b e;   per += c e / dx
 *
 * with b = sqrt(2) w, c = w^2, w = 2 pi B dt for a bandwidth B (Hz) at an
 * update interval dt: critically damped, no steady-state error for a
 * constant rate. A narrow B filters millisecond jitter down to
 * microseconds, but would take minutes to pull in a rate 1000 ppm off. So
 * it starts as a least-squares line through every reading so far (the
 * growing-memory alpha-beta filter: b_n = 2 (2n - 1) / (n (n + 1)),
 * c_n = 6 / (n (n + 1)), which are exactly that fit's gains) and goes
 * over to the fixed loop once the fit's gain has fallen to b: the best
 * estimate of a steady rate early, a tracking loop later. Readings may come
 * at uneven steps of x (c is scaled by the nominal step over the actual).
 *
 * Doubles: t is nanoseconds near the run's start (|t| < 2^52 ns is 52 days
 * at full resolution), x whatever the caller counts. [rt]: no allocation,
 * no system call.
 */
#ifndef HAL_DLL_H
#define HAL_DLL_H

#include <stdbool.h>
#include <stdint.h>

#include "rt.h" /* STRAND_RT */

struct hal_dll {
	double per_nom;  /* nominal time per unit of x, ns */
	double dx_nom;   /* nominal step of x between readings */
	double b, c;     /* the fixed loop's gains */
	double x_ref, t_ref; /* the estimate passes through (x_ref, t_ref) */
	double per;      /* the estimated time per unit of x, ns */
	int64_t n;       /* readings taken */
};

/*
 * [rt] A loop for readings every dx_nom units of x, each unit nominally
 * per_nom ns, filtering at bw_hz once the start-up fit has narrowed to it.
 */
void hal_dll_init(struct hal_dll *d, double per_nom, double dx_nom, double bw_hz);

/* [rt] Start again from the reading (x, t), keeping the rate estimate. */
void hal_dll_restart(struct hal_dll *d, double x, double t);

/* [rt] Take the reading (x, t): x should grow from one reading to the next. */
void hal_dll_update(struct hal_dll *d, double x, double t);

/* [rt] The filtered time of x (x may lie before or after the last reading). */
static inline double STRAND_RT hal_dll_time(const struct hal_dll *d, double x)
{
	return d->t_ref + (x - d->x_ref) * d->per;
}

/* [rt] The x the estimate puts at time t. */
static inline double STRAND_RT hal_dll_at(const struct hal_dll *d, double t)
{
	return d->x_ref + (t - d->t_ref) / d->per;
}

#endif /* HAL_DLL_H */
