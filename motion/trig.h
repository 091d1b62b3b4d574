/* SPDX-License-Identifier: MIT */
/*
 * trig.h - elementary functions on Q32.32, in integer code only.
 *
 * Angles are in turns (fix.h). Every function is a pure function of its
 * arguments: same bits in, same bits out, on every target. Worst errors are
 * measured by tests/test_trig.c against libm in double precision and quoted
 * in each comment; none is above about half an LSB of Q32.32 (1 LSB = 2.3e-10).
 *
 * All functions here are safe in the real-time loop (bounded time, no
 * memory access outside their const tables, no division). Times are ns per
 * call on the x86_64 build machine at -O2, independent calls / one call's
 * latency, as measured when written; `make bench` prints the first (its
 * prim_* lines, next to libm's).
 */
#ifndef MOT_TRIG_H
#define MOT_TRIG_H

#include "fix.h"

/* Radians per turn and turns per radian, in Q32.32 and for the edges. */
#define MOT_TURN_PER_RAD_Q32 ((mot_q32)683565276)    /* 1/(2 pi) * 2^32 */
#define MOT_TWO_PI_Q32 ((mot_q32)26986075409LL)        /* 2 pi * 2^32 */

/* sin and cos of an angle in turns, any number of turns (only the phase
 * within the turn matters). Exact (0, +-1) at multiples of a quarter turn;
 * |sin|, |cos| <= 1 always. Worst error 0.52 LSB. *s and *c must not alias.
 * About 5 ns / 8 ns; mot_sin and mot_cos cost nearly the same. */
void mot_sincos(mot_q32 turns, mot_q32 *s, mot_q32 *c);

/* The same, returned as a pair (in registers where the ABI allows: the hot
 * path of a scene's evaluation). */
struct mot_sc {
	mot_q32 s, c;
};
struct mot_sc mot_sincos_pair(mot_q32 turns);

/*
 * The same computation in parts, for trig.c and for an inline copy in a hot
 * loop (mot_sincos_in): the phase's table point j (0..1023 of a turn) and
 * its offset d from it (2^-32 turn, in [-2^21, 2^21)), then, from sin a
 * and cos a of that point (Q62), the angle addition (trig.c says how).
 */
static inline uint32_t mot_sincos_point(mot_q32 turns, int64_t *d)
{
	uint32_t phase = (uint32_t)(uint64_t)turns; /* 2^-32 turn; whole turns dropped */
	int64_t low = phase & ((1u << 22) - 1);     /* 2^22 phases a table point */

	*d = low - ((low & (1 << 21)) << 1);
	return ((uint32_t)(phase + (1u << 21)) >> 22) & 1023;
}

/* round(x / 2^92) of a sum known to fit (|sin|, |cos| <= 1): mot_acc_round()'s
 * bits without its saturation, whose result the compiler would have to
 * carry as a possible 2^63 - 1 into every product made with it */
static inline int64_t mot_sincos_round92(mot_acc x)
{
	return (int64_t)mot_acc_hi(mot_acc_add(x, mot_acc_make((uint64_t)1 << 27, 0))) >> 28;
}

/* dr and dr6: the offset delta and delta/6 in rad, Q70 (|dr| < 2^62) */
static inline struct mot_sc mot_sincos_add_rad(int64_t sa, int64_t ca, int64_t dr, int64_t dr6)
{
	int64_t half_sq = (int64_t)mot_acc_hi(mot_acc_mul(dr, dr)) >> 15; /* delta^2/2, Q62 */
	int64_t cd = ((int64_t)1 << 62) - half_sq;                        /* cos delta, Q62 */
	int64_t sd = (dr >> 8) - ((int64_t)mot_acc_hi(mot_acc_mul(half_sq, dr6)) >> 5);
	struct mot_sc r; /* Q124 sums, one rounding each */

	r.s = mot_sincos_round92(mot_acc_mac(mot_acc_mul(sa, cd), ca, sd));
	r.c = mot_sincos_round92(mot_acc_mac(mot_acc_mul(ca, cd), -sa, sd));
	return r;
}

/* k and k6: 2 pi / 2^32 and that over 6 (rad per phase), Q70 */
static inline struct mot_sc mot_sincos_add(int64_t sa, int64_t ca, int64_t d, int64_t k,
					   int64_t k6)
{
	return mot_sincos_add_rad(sa, ca, d * k, d * k6);
}

/*
 * The same for a phase of 64 bits (2^-64 turn: the low word of a Q64.64
 * angle, t theta without its rounding): the table point j and the offset
 * d in [-2^53, 2^53), whose radians are a 128-bit product with
 * mot_sincos_add()'s k and k6 times 2^22, then 2^-54: Q70 as there, the
 * same dr where the low 32 bits are zero (so mot_sincos()'s bits), floored
 * elsewhere (k's own rounding costs below 2^-50 rad). One rounding of each
 * result, where a Q32.32 angle and a first-order term for the rest rounded
 * twice.
 */
#define MOT_TRIG_2PI_Q60 ((int64_t)1727108826179LL << 22)
#define MOT_TRIG_2PI6_Q60 ((int64_t)287851471030LL << 22)
static inline uint32_t mot_sincos_point64(uint64_t phase, int64_t *dr, int64_t *dr6)
{
	uint64_t p = phase + ((uint64_t)1 << 53);
	int64_t d = (int64_t)(p & (((uint64_t)1 << 54) - 1)) - ((int64_t)1 << 53);
	uint64_t ov = 0; /* |d 2 pi 2^60| < 2^116: fits */

	*dr = mot_acc_floor_ov(mot_acc_mul(d, MOT_TRIG_2PI_Q60), 54, &ov);
	*dr6 = mot_acc_floor_ov(mot_acc_mul(d, MOT_TRIG_2PI6_Q60), 54, &ov);
	return (uint32_t)(p >> 54) & 1023;
}

/* sin and cos of phase 2^-64 turn, worst error 0.52 LSB (tests/test_trig.c) */
struct mot_sc mot_sincos64(uint64_t phase);

/* floor(a b / 2^shift), 1 <= shift <= 63, known to fit */
static inline int64_t mot_trig_mulsh(int64_t a, int64_t b, unsigned shift)
{
	mot_acc p = mot_acc_mul(a, b);

	return (int64_t)mot_dw_shr(mot_acc_hi(p), mot_acc_lo(p), shift);
}

/*
 * Goldschmidt on m in [2^60, 2^62), a = m / 2^62: *g = sqrt(a) and
 * *h = 1 / (2 sqrt(a)), both Q62, within a few units of 2^-62 relative
 * (trig.c says how), from tab, trig.c's seeds of 1/sqrt(a) in Q14. For
 * trig.c's square roots and an inline copy in a hot loop
 * (mot_isqrt_inv_unit_in()).
 */
static inline __attribute__((always_inline)) void mot_sqrt_core(uint64_t m, const uint16_t *tab,
								  int64_t *g, int64_t *h)
{
	int64_t y0 = tab[(m >> 54) - 64];                      /* 1/sqrt(a), Q14 */
	int64_t hh = y0 << 47;                                 /* y0 / 2, Q62 */
	int64_t gg = mot_trig_mulsh((int64_t)m, hh, 61);       /* a y0, Q62 */
	int k;

#if MOT_HAVE_INT128
	_Pragma("GCC unroll 3") /* gcc -O2 keeps the loop and its counter */
#endif
	for (k = 0; k < 3; k++) {
		int64_t r = ((int64_t)1 << 62) - mot_trig_mulsh(gg, hh, 61); /* 1/2 - g h, Q63 */

		gg += mot_trig_mulsh(gg, r, 63);
		hh += mot_trig_mulsh(hh, r, 63);
	}
	*g = gg;
	*h = hh;
}

#if MOT_HAVE_INT128
/* What mot_sincos_in() reads: trig.c's table of sin(j/1024 turn), j =
 * 0..1279 (cos is entry j + 256), and the two constants of
 * mot_sincos_add(). */
struct mot_trig_turn {
	const int64_t *sin;
	int64_t k, k6;
	const uint16_t *rsqrt; /* mot_sqrt_core()'s seeds */
};
extern const struct mot_trig_turn mot_trig_turn;

/* mot_sincos_pair() inline (where 128-bit integers are native): the same
 * bits without a call in the caller's loop. */
static inline __attribute__((always_inline)) struct mot_sc mot_sincos_in(mot_q32 turns)
{
	int64_t d;
	uint32_t j = mot_sincos_point(turns, &d);

	return mot_sincos_add(mot_trig_turn.sin[j], mot_trig_turn.sin[j + 256], d,
			      mot_trig_turn.k, mot_trig_turn.k6);
}

/*
 * mot_isqrt_acc_inv_near() inline for x = 4 x62, x62 in [2^42, 2^63) (the
 * square of the part of a near-unit quaternion orthogonal to another, Q62,
 * its root 2^-10 or more; x in Q64.64): the root within 1/2 + 2^-8 and
 * 1/sqrt(x) = *inv 2^-*sh, *sh in [84, 94], with the relative error of
 * mot_sqrt_core(), without the general scaling and its tests.
 */
static inline __attribute__((always_inline)) uint64_t mot_isqrt_inv_unit_in(int64_t x62,
									    int64_t *inv,
									    unsigned *sh)
{
	uint64_t v = (uint64_t)x62 >> 2; /* x / 16, in [2^40, 2^61) */
	unsigned s = (mot_clz64(v) - 2) & ~1u; /* v << s: 61 or 62 bits */
	int64_t g, h;

	/* floor(x 2^(s - 4)), below 2^62 as v 2^s */
	mot_sqrt_core(((uint64_t)x62 << s) >> 2, mot_trig_turn.rsqrt, &g, &h);
	/* sqrt(x) = 4 sqrt(v 2^s) 2^(-s/2) = g 2^(-29 - s/2), 1/sqrt(x) =
	 * h 2^(s/2 - 94) */
	*inv = h;
	*sh = 94 - s / 2;
	return ((uint64_t)g + ((uint64_t)1 << (28 + s / 2))) >> (29 + s / 2);
}

/* mot_sincos64() inline, the same way */
static inline __attribute__((always_inline)) struct mot_sc mot_sincos64_in(uint64_t phase)
{
	int64_t dr, dr6;
	uint32_t j = mot_sincos_point64(phase, &dr, &dr6);

	return mot_sincos_add_rad(mot_trig_turn.sin[j], mot_trig_turn.sin[j + 256], dr, dr6);
}
#endif
mot_q32 mot_sin(mot_q32 turns);
mot_q32 mot_cos(mot_q32 turns);

/* Angle of the vector (x, y) in turns, in (-1/2, +1/2]; atan2(0, 0) = 0.
 * Exact at the axes and diagonals of equal magnitude. Works for any
 * magnitudes (the ratio matters, not the scale: (2^k y, 2^k x) gives the same
 * bits). atan2(-y, x) = -atan2(y, x), except that an angle that rounds to
 * -1/2 is returned as +1/2. Worst error 0.50 LSB (1.2e-10 turn).
 * About 11 ns / 25 ns. */
mot_q32 mot_atan2(mot_q32 y, mot_q32 x);

/*
 * The angle of (x, y), x, y >= 0, with x^2 + y^2 within 2^-16 of 1 (the
 * cosine and sine of an arc between unit quaternions), in turns Q62
 * (value * 2^62), without a division: the nearest of 256 points of the
 * quarter turn from asin of the smaller coordinate's series, then the
 * angle left after rotating back by it (below 0.01 rad) as asin of its
 * sine, divided by the vector's length to first order. Within 0.05 LSB of
 * Q32.32 turns (tests/test_trig.c). Other vectors take mot_atan2(), its
 * result times 2^30. About as many instructions as mot_atan2() (103
 * against 112 on x86_64), but no rounding of the angle to Q32.32.
 */
int64_t mot_atan2_unit_q62(mot_q32 y, mot_q32 x);

/* acos in turns, in [0, 1/2]. |x| > 1 (rounding of a dot product of unit
 * vectors) is taken as +-1 and flagged MOT_SAT_DOMAIN. Exact at -1, 0, 1;
 * worst error 0.50 LSB (1.2e-10 turn) for the given x, also next to +-1
 * where acos is steep. About 30 ns / 46 ns. */
mot_q32 mot_acos(mot_q32 x, uint32_t *sat);

/* sqrt(x), correctly rounded to nearest (0.5 LSB). x < 0 gives 0 and
 * MOT_SAT_DOMAIN. About 12 ns / 23 ns. */
mot_q32 mot_sqrt(mot_q32 x, uint32_t *sat);

/* 1/sqrt(x), worst error 0.50 LSB (not always the nearest: within 2^-10 LSB
 * of it). x <= 0 gives MOT_Q32_MAX and MOT_SAT_DOMAIN. About 10 ns / 19 ns. */
mot_q32 mot_rsqrt(mot_q32 x, uint32_t *sat);

/* Square root of a non-negative 128-bit integer, rounded to nearest. With a
 * sum of squares of Q32.32 values (a Q64.64 number) this is the Euclidean norm
 * in Q32.32 with a single rounding. Negative x gives 0 and MOT_SAT_DOMAIN.
 * Exact for every x (tested against __int128). About 20 ns / 30 ns. */
uint64_t mot_isqrt_acc(mot_acc x, uint32_t *sat);

/* The same root of x > 0, and its reciprocal for a division by the root
 * without a division: 1/sqrt(x) = *inv 2^-*sh, inv in [2^61, 2^62], sh in
 * [62, 125], relative error below 2^-58 (tests/test_trig.c). The Newton
 * iteration of the root makes it on the way. x <= 0 gives 0, *inv = 0. */
uint64_t mot_isqrt_acc_inv(mot_acc x, int64_t *inv, unsigned *sh);
/* The same without the root's last correction (the remainder's square and
 * two tests): for x below 2^102 within 1/2 + 2^-8 of sqrt(x), the nearest
 * integer but next to a half (tests/test_trig.c), a few units for larger
 * x; the same inv and sh. */
uint64_t mot_isqrt_acc_inv_near(mot_acc x, int64_t *inv, unsigned *sh);

/* |v| for a 3-vector: the root of the exact 128-bit sum of squares, rounded
 * once to nearest (0.5 LSB). A norm above MOT_Q32_MAX (possible only with
 * components beyond 2^62 raw) saturates and sets MOT_SAT_OVERFLOW.
 * About 16 ns / 26 ns. */
mot_q32 mot_norm3(const mot_q32 v[3], uint32_t *sat);

#endif /* MOT_TRIG_H */
