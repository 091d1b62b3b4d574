/* SPDX-License-Identifier: MIT */
/*
 * fix.h - the number formats of the strand motion core, and the integer
 * arithmetic every other file of motion/ is built on.
 *
 * One format, Q32.32 in an int64_t, holds every real quantity the core
 * computes with. What changes from one quantity to the next is the unit:
 *
 *   quantity                       unit                  resolution      range
 *   ------------------------------ --------------------- --------------- ----------------
 *   length, position, translation  the scene's unit (m)  2.3e-10 unit    +-2^30 units (*)
 *   matrix entry (rot/scale/shear) dimensionless         2.3e-10         +-2^31
 *   quaternion component           dimensionless         2.3e-10         +-2^31
 *   angle                          turns (1 = 360 deg)   1.46e-9 rad     +-2^31 turns
 *   time of a key or a sample      frames                2.3e-10 frame   +-2^31 frames
 *   curve parameter, ease fraction dimensionless, [0,1]  2.3e-10
 *   spin speed                     revolutions/minute    2.3e-10 rpm     +-2^31 rpm
 *
 *   (*) lengths are limited to +-2^30 units so that the sum of a translation
 *       and a rotated offset cannot overflow; the scene loader enforces it.
 *
 * Why Q32.32 and not something narrower. The core must hold a 5-joint chain
 * within 1e-6 rad and 1 um of a double-precision reference over a +-100 m
 * workspace. An int32 length can have either the range (Q8.24 is +-128 m at
 * 60 nm) or headroom for millimetre scenes, not both; int32 matrix entries
 * in Q2.30 reach 0.1 um at 100 m but cannot hold a scale above 2. Q16.16
 * (libfixmath) misses both goals by an order of magnitude (15 um, 1.5e-5
 * rad). With 64-bit storage everything has 32 fractional bits, a scene may be
 * in metres or millimetres, and rounding stays three to four orders of
 * magnitude below the goals, so a long chain of products cannot eat the
 * margin.
 *
 * Why turns for angles. A turn is a power of two: the fractional 32 bits are
 * the phase on the circle, so sin/cos index their table without a division,
 * quarter turns are exact (0.25 turn = 2^30), and a joint that has spun
 * through a million revolutions keeps full resolution within the turn.
 * Degrees exist only at the edges (scene files, export).
 *
 * Intermediates. A product of two Q32.32 values is Q64.64 and needs 128
 * bits. Sums of products (dot products, matrix rows) accumulate in 128 bits
 * and are rounded once. On 64-bit targets the compiler's __int128 is used;
 * on 32-bit targets (armhf, Cortex-M) a two-word struct does the same exact
 * integer arithmetic, so results are bit-identical everywhere. Define
 * MOT_NO_INT128 to force the portable path (the tests do, to prove it).
 *
 * Rounding. Every narrowing rounds to nearest, ties toward +infinity
 * (floor(x + 1/2)): one rule, independent of sign, cheap, deterministic.
 *
 * Saturation. Narrowing saturates to MOT_Q32_MAX / MOT_Q32_MIN and reports it
 * through a sticky status word that the caller owns (mot_sat_*); the value is
 * never used as an in-band error marker. The loader bounds every input so that
 * playback of a valid scene never saturates; the flag proves it in the tests.
 *
 * Only <stdint.h>, <stddef.h> and <stdbool.h> are used: no libc, no floating
 * point, no allocation, no global mutable state.
 */
#ifndef MOT_FIX_H
#define MOT_FIX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef int64_t mot_q32; /* Q32.32: value = raw / 2^32 */

#define MOT_Q32_FRAC 32
#define MOT_Q32_ONE ((mot_q32)1 << 32)
#define MOT_Q32_HALF ((mot_q32)1 << 31)
#define MOT_Q32_MAX INT64_MAX
#define MOT_Q32_MIN INT64_MIN
#define MOT_Q32_INT(n) ((mot_q32)(n) * MOT_Q32_ONE) /* integer n, |n| < 2^31 */

/* Largest length magnitude the core accepts from a scene (see the table above). */
#define MOT_LEN_LIMIT ((mot_q32)1 << 62)

/* Error codes of the core: 0 or one of these negative values. */
enum mot_err {
	MOT_OK = 0,
	MOT_E_INVAL = -1,    /* argument outside its documented domain */
	MOT_E_RANGE = -2,    /* a result would not fit its format */
	MOT_E_ORDER = -3,    /* keys not strictly increasing in frame */
	MOT_E_SINGULAR = -4, /* a matrix with a (near) zero scale */
	MOT_E_NOKEYS = -5,   /* a strand without keys */
	MOT_E_CAPACITY = -6, /* caller-provided memory is too small */
	MOT_E_PARENT = -7,   /* a parent index at or after its child */
	MOT_E_KIND = -8,     /* a key or strand of the wrong kind for its node */
};

/* Sticky status bits, accumulated by the caller across many operations. */
enum mot_sat {
	MOT_SAT_OVERFLOW = 1u << 0, /* a result saturated */
	MOT_SAT_DOMAIN = 1u << 1,   /* an input outside a function's domain was mapped */
};

/* ---- 128-bit intermediates ------------------------------------------------ */

#if defined(__SIZEOF_INT128__) && !defined(MOT_NO_INT128)
#define MOT_HAVE_INT128 1
__extension__ typedef __int128 mot_acc;
__extension__ typedef unsigned __int128 mot_uacc;
#else
#define MOT_HAVE_INT128 0
/* Two's complement 128-bit value: hi holds bits 127..64 (sign in bit 63). */
typedef struct {
	uint64_t lo;
	uint64_t hi;
} mot_acc;
#endif

/* 0 */
static inline mot_acc mot_acc_zero(void)
{
#if MOT_HAVE_INT128
	return 0;
#else
	mot_acc r = { 0, 0 };
	return r;
#endif
}

/* a sign-extended to 128 bits, scaled by 2^shift (0 <= shift < 64). */
static inline mot_acc mot_acc_from(int64_t a, unsigned shift)
{
#if MOT_HAVE_INT128
	return (mot_acc)a * ((mot_acc)1 << shift);
#else
	mot_acc r;
	uint64_t ua = (uint64_t)a;
	uint64_t sx = a < 0 ? ~(uint64_t)0 : 0;

	if (shift == 0) {
		r.lo = ua;
		r.hi = sx;
	} else {
		r.lo = ua << shift;
		r.hi = (sx << shift) | (ua >> (64 - shift));
	}
	return r;
#endif
}

/* The 128-bit value hi * 2^64 + lo (two's complement). */
static inline mot_acc mot_acc_make(uint64_t hi, uint64_t lo)
{
#if MOT_HAVE_INT128
	return (mot_acc)(((mot_uacc)hi << 64) | lo);
#else
	mot_acc r;

	r.lo = lo;
	r.hi = hi;
	return r;
#endif
}

/* The exact 128-bit product a * b. */
static inline mot_acc mot_acc_mul(int64_t a, int64_t b)
{
#if MOT_HAVE_INT128
	return (mot_acc)a * b;
#else
	/* Unsigned 64x64 from four 32x32 products, then the two's complement
	 * correction for negative operands (subtract the other operand from the
	 * high word). */
	uint64_t ua = (uint64_t)a, ub = (uint64_t)b;
	uint64_t a0 = ua & 0xffffffffu, a1 = ua >> 32;
	uint64_t b0 = ub & 0xffffffffu, b1 = ub >> 32;
	uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
	uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);
	mot_acc r;

	r.lo = (mid << 32) | (p00 & 0xffffffffu);
	r.hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
	if (a < 0)
		r.hi -= ub;
	if (b < 0)
		r.hi -= ua;
	return r;
#endif
}

static inline mot_acc mot_acc_add(mot_acc x, mot_acc y)
{
#if MOT_HAVE_INT128
	/* Wrap-around is impossible for the magnitudes the core uses (<2^126),
	 * but do it unsigned so that it is defined either way. */
	return (mot_acc)((mot_uacc)x + (mot_uacc)y);
#else
	mot_acc r;

	r.lo = x.lo + y.lo;
	r.hi = x.hi + y.hi + (r.lo < x.lo);
	return r;
#endif
}

static inline mot_acc mot_acc_neg(mot_acc x)
{
#if MOT_HAVE_INT128
	return (mot_acc)(-(mot_uacc)x);
#else
	mot_acc r;

	r.lo = ~x.lo + 1;
	r.hi = ~x.hi + (r.lo == 0);
	return r;
#endif
}

static inline mot_acc mot_acc_sub(mot_acc x, mot_acc y)
{
	return mot_acc_add(x, mot_acc_neg(y));
}

/* acc + a * b */
static inline mot_acc mot_acc_mac(mot_acc acc, int64_t a, int64_t b)
{
	return mot_acc_add(acc, mot_acc_mul(a, b));
}

/* Bits 127..64 and 63..0 of x. */
static inline uint64_t mot_acc_hi(mot_acc x)
{
#if MOT_HAVE_INT128
	return (uint64_t)((mot_uacc)x >> 64);
#else
	return x.hi;
#endif
}

static inline uint64_t mot_acc_lo(mot_acc x)
{
#if MOT_HAVE_INT128
	return (uint64_t)x;
#else
	return x.lo;
#endif
}

static inline bool mot_acc_is_neg(mot_acc x)
{
#if MOT_HAVE_INT128
	return x < 0;
#else
	return (int64_t)x.hi < 0;
#endif
}

/*
 * Bits shift..shift + 63 of the 128-bit word hi:lo, 0 < shift < 64: the
 * low word of a 128-bit shift. On x86-64 as two shifts and an add, not the
 * OR (or the 128-bit shift) that gcc makes one SHRD of: AMD's cores run
 * SHRD as several micro-ops (this project's Zen 3 VM: four took 2.2 to 3.5
 * ns where four adds took 0.4 to 0.8), and the hot kernels end every sum
 * with one (make bench-ab, with PRE_SHIFT in scene.c: the arm 6 to 7%
 * faster, the 1,000 joints 0 to 6% by the VM's state, at 9 to 13% more
 * instructions). The bits do not overlap: the same value either way.
 */
static inline uint64_t mot_dw_shr(uint64_t hi, uint64_t lo, unsigned shift)
{
#if defined(__x86_64__)
	return (hi << (64 - shift)) + (lo >> shift);
#else
	return (hi << (64 - shift)) | (lo >> shift);
#endif
}

/*
 * Round x / 2^shift to nearest (ties toward +inf) and narrow to int64,
 * saturating. 1 <= shift <= 126. Sets MOT_SAT_OVERFLOW in *sat on saturation
 * (sat may be NULL when the caller has proven the result fits).
 */
static inline int64_t mot_acc_round(mot_acc x, unsigned shift, uint32_t *sat)
{
	bool neg = mot_acc_is_neg(x);
	uint64_t lo, hi, xl, xh;

	x = mot_acc_add(x, shift <= 64 ? mot_acc_make(0, (uint64_t)1 << (shift - 1)) :
					 mot_acc_make((uint64_t)1 << (shift - 65), 0));
	xl = mot_acc_lo(x);
	xh = mot_acc_hi(x);
	if (shift < 64) {
		lo = mot_dw_shr(xh, xl, shift);
		hi = (uint64_t)((int64_t)xh >> shift);
	} else {
		lo = (uint64_t)((int64_t)xh >> (shift - 64));
		hi = (int64_t)xh < 0 ? ~(uint64_t)0 : 0;
	}
	/* Fits iff hi is the sign extension of lo. */
	if (hi != ((int64_t)lo < 0 ? ~(uint64_t)0 : 0)) {
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		return neg ? INT64_MIN : INT64_MAX;
	}
	return (int64_t)lo;
}

/*
 * The kernel of the hot paths (matrix products, joint updates): a short sum
 * of exact products rounded once, with the overflow test taken out of the
 * sum's way. A sum starts at mot_acc_start(c, shift), an addend c at the
 * sum's scale 2^shift plus the half unit that makes the final floor a
 * rounding to nearest (ties toward +inf, as mot_acc_round); products join
 * with mot_acc_mac(); mot_acc_floor_ov() ends it without a branch and
 * without saturating: it ORs a nonzero value into *ov when the result does
 * not fit int64. A caller checks ov once for a whole matrix and, only then,
 * redoes the matrix with the saturating functions. Results are those of
 * mot_acc_round() bit for bit whenever they fit.
 *
 * Wrap-around. With up to three products of any int64 factors and an
 * addend c (any c at shift 32, |c| <= 2^62 at shift 62) a true sum that
 * leaves the signed 128-bit range lands, after wrapping, far outside what
 * fits, so it is reported too (tests/test_fix.c checks both paths). Longer
 * sums must bound their terms (see each caller).
 *
 * The shift is a constant in every caller, 1 <= shift <= 63 (32 for
 * Q32.32 products, 62 for products with a factor in Q2.62).
 */
static inline mot_acc mot_acc_start(int64_t c, unsigned shift)
{
	/* c * 2^shift has shift zero low bits: the half unit just fills one */
	return mot_acc_make((uint64_t)(c >> (64 - shift)),
			    ((uint64_t)c << shift) | ((uint64_t)1 << (shift - 1)));
}

static inline int64_t mot_acc_floor_ov(mot_acc x, unsigned shift, uint64_t *ov)
{
	uint64_t hi = mot_acc_hi(x);

	/* floor(x / 2^shift) fits int64 iff hi is in [-2^(shift-1), 2^(shift-1)) */
	*ov |= (hi + ((uint64_t)1 << (shift - 1))) >> shift;
	return (int64_t)mot_dw_shr(hi, mot_acc_lo(x), shift);
}

/* round(x / 2^shift), the kernel's way: mot_acc_round() without saturation */
static inline int64_t mot_acc_round_ov(mot_acc x, unsigned shift, uint64_t *ov)
{
	return mot_acc_floor_ov(mot_acc_add(x, mot_acc_start(0, shift)), shift, ov);
}

/* round(a0*b0 + a1*b1 + c * 2^shift) / 2^shift and the like: the sums the
 * hot paths are made of, each rounded once (see above). */
static inline int64_t mot_sum2_ov(int64_t a0, int64_t b0, int64_t a1, int64_t b1, int64_t c,
				  unsigned shift, uint64_t *ov)
{
	mot_acc s = mot_acc_mac(mot_acc_start(c, shift), a0, b0);

	return mot_acc_floor_ov(mot_acc_mac(s, a1, b1), shift, ov);
}

static inline int64_t mot_sum3_ov(int64_t a0, int64_t b0, int64_t a1, int64_t b1, int64_t a2,
				  int64_t b2, int64_t c, unsigned shift, uint64_t *ov)
{
	mot_acc s = mot_acc_mac(mot_acc_start(c, shift), a0, b0);

	s = mot_acc_mac(s, a1, b1);
	return mot_acc_floor_ov(mot_acc_mac(s, a2, b2), shift, ov);
}

/* ---- Q32.32 arithmetic ---------------------------------------------------- */

/* a * b, rounded, saturating. */
static inline mot_q32 mot_mul(mot_q32 a, mot_q32 b, uint32_t *sat)
{
	return mot_acc_round(mot_acc_mul(a, b), MOT_Q32_FRAC, sat);
}

/* a0*b0 + a1*b1 + a2*b2, rounded once. */
static inline mot_q32 mot_dot3(const mot_q32 a[3], const mot_q32 b[3], uint32_t *sat)
{
	mot_acc acc = mot_acc_mul(a[0], b[0]);

	acc = mot_acc_mac(acc, a[1], b[1]);
	acc = mot_acc_mac(acc, a[2], b[2]);
	return mot_acc_round(acc, MOT_Q32_FRAC, sat);
}

/*
 * round(sum of a[i] * b[i], i < n) in Q32.32, rounded once, for any inputs.
 * An addend c joins as the pair (c, MOT_Q32_ONE). When no factor reaches
 * 2^62 in magnitude (every real use: lengths are below 2^30 units), the
 * products stay below 2^124 and up to eight of them are summed inline in 128
 * bits. Otherwise mot_sum_prod_wide() watches the sum for wrap-around, so a
 * sum that cannot fit saturates with its true sign (a plain 128-bit sum of
 * extreme products can wrap, and saturate with the wrong one).
 */
mot_q32 mot_sum_prod_wide(const mot_q32 *a, const mot_q32 *b, unsigned n, uint32_t *sat);

static inline mot_q32 mot_sum_prod(const mot_q32 *a, const mot_q32 *b, unsigned n, uint32_t *sat)
{
	const mot_q32 lim = (mot_q32)1 << 62;
	mot_acc acc = mot_acc_zero();
	bool small = n <= 8;
	unsigned i;

	if (n <= 3) {
		/* up to three products: the kernel's overflow test sees every
		 * sum that does not fit, wrapped or not, with any factors */
		uint64_t ov = 0;
		mot_q32 r;

		acc = mot_acc_start(0, MOT_Q32_FRAC);
		for (i = 0; i < n; i++)
			acc = mot_acc_mac(acc, a[i], b[i]);
		r = mot_acc_floor_ov(acc, MOT_Q32_FRAC, &ov);
		return ov ? mot_sum_prod_wide(a, b, n, sat) : r;
	}
	for (i = 0; i < n; i++)
		small = small && a[i] < lim && a[i] > -lim && b[i] < lim && b[i] > -lim;
	if (!small)
		return mot_sum_prod_wide(a, b, n, sat);
	for (i = 0; i < n; i++)
		acc = mot_acc_mac(acc, a[i], b[i]);
	return mot_acc_round(acc, MOT_Q32_FRAC, sat);
}

/* p * q for |p|, |q| <= 1 rounded to Q2.62, not Q32.32, so that a third
 * factor can follow without a second rounding at Q32.32 resolution
 * (products of sines and cosines). */
static inline int64_t mot_mul_q62(mot_q32 p, mot_q32 q)
{
	return mot_acc_round(mot_acc_mul(p, q), 2, NULL);
}

/* round(p * c + q * d) to Q32.32, for p, q in Q2.62 and |c|, |d| <= 1. */
static inline mot_q32 mot_sum2_q62(int64_t p, mot_q32 c, int64_t q, mot_q32 d)
{
	return mot_acc_round(mot_acc_mac(mot_acc_mul(p, c), q, d), 62, NULL);
}

static inline mot_q32 mot_add_sat(mot_q32 a, mot_q32 b, uint32_t *sat)
{
	mot_q32 r;

	if (__builtin_add_overflow(a, b, &r)) {
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		return a < 0 ? MOT_Q32_MIN : MOT_Q32_MAX;
	}
	return r;
}

static inline mot_q32 mot_sub_sat(mot_q32 a, mot_q32 b, uint32_t *sat)
{
	mot_q32 r;

	if (__builtin_sub_overflow(a, b, &r)) {
		if (sat)
			*sat |= MOT_SAT_OVERFLOW;
		return a < 0 ? MOT_Q32_MIN : MOT_Q32_MAX;
	}
	return r;
}

static inline mot_q32 mot_abs(mot_q32 a)
{
	return a < 0 ? (a == MOT_Q32_MIN ? MOT_Q32_MAX : -a) : a;
}

/* Number of leading zero bits of x (64 for 0). */
static inline unsigned mot_clz64(uint64_t x)
{
	/* two 32-bit counts: on x86_64 a 64-bit __builtin_clzll made atan2
	 * and rsqrt twice as slow (make bench, prim_*), and 32-bit targets
	 * need no libgcc call */
	unsigned n = 0;

	if (x == 0)
		return 64;
	if ((x >> 32) == 0) {
		n += 32;
		x <<= 32;
	}
	return n + (unsigned)__builtin_clz((unsigned)(x >> 32));
}

/*
 * Exact divisions, rounded to nearest with ties toward +inf like everything
 * else. They cost tens of nanoseconds: use them to prepare, and for the few
 * per-tick divisions by run-time values.
 */

/* round(a * 2^32 / b), saturating; b == 0 saturates with the sign of a and
 * sets MOT_SAT_DOMAIN. */
mot_q32 mot_div(mot_q32 a, mot_q32 b, uint32_t *sat);

/* round(a * m / d) for d > 0 with the product in 128 bits, saturating. */
int64_t mot_muldiv(int64_t a, int64_t m, int64_t d, uint32_t *sat);

/* floor(n / d) for d > 0, and the remainder in [0, d). Exact for all n. */
int64_t mot_floordiv(int64_t n, int64_t d, int64_t *rem);

/* |v| as an unsigned number, exact for every v (INT64_MIN included) */
static inline uint64_t mot_mag(int64_t v)
{
	return v < 0 ? 0 - (uint64_t)v : (uint64_t)v;
}

/* The unsigned 128-bit product a * b: the high word, the low one in *lo. */
static inline uint64_t mot_umul_hi(uint64_t a, uint64_t b, uint64_t *lo)
{
#if MOT_HAVE_INT128
	mot_uacc p = (mot_uacc)a * b;

	*lo = (uint64_t)p;
	return (uint64_t)(p >> 64);
#else
	uint64_t a0 = a & 0xffffffffu, a1 = a >> 32, b0 = b & 0xffffffffu, b1 = b >> 32;
	uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
	uint64_t mid = (p00 >> 32) + (p01 & 0xffffffffu) + (p10 & 0xffffffffu);

	*lo = (mid << 32) | (p00 & 0xffffffffu);
	return p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
#endif
}

/*
 * Division of 128-bit numbers by one 64-bit divisor d, many times: d
 * normalised (d << s, top bit set) and its reciprocal v = floor((2^128 - 1)
 * / dn) - 2^64, prepared once (mot_udiv_inv_init(), a division), then each
 * quotient from two products and at most two corrections (Moeller and
 * Granlund, "Improved division by invariant integers", 2011, algorithm 4):
 * exact, the same quotient and remainder as mot_acc_udiv().
 */
struct mot_udiv_inv {
	uint64_t dn; /* d << s */
	uint64_t v;
	uint32_t s;
};

/* Prepare for d > 0 (d == 0 gives MOT_E_INVAL). Init only. */
int mot_udiv_inv_init(struct mot_udiv_inv *in, uint64_t d);

/* floor((hi 2^64 + lo) / d) and the remainder in *rem, for hi < d (the
 * quotient fits 64 bits: callers hold it). Real-time safe, no division. */
static inline uint64_t mot_udiv_by_inv(uint64_t hi, uint64_t lo, const struct mot_udiv_inv *in,
				       uint64_t *rem)
{
	uint64_t u1 = in->s ? (hi << in->s) | (lo >> (64 - in->s)) : hi, u0 = lo << in->s;
	uint64_t q0, q1, r;

	/* q = v u1 + (u1 + 1) 2^64 + u0, q1 its high word */
	q1 = mot_umul_hi(in->v, u1, &q0);
	q0 += u0;
	q1 += u1 + 1 + (q0 < u0);
	r = u0 - q1 * in->dn;
	if (r > q0) {
		q1--;
		r += in->dn;
	}
	if (r >= in->dn) {
		q1++;
		r -= in->dn;
	}
	*rem = r >> in->s;
	return q1;
}

/* Unsigned 128 / 64 division: floor(x / d), remainder in *rem. x must be
 * non-negative and the quotient must fit 64 bits; otherwise returns
 * UINT64_MAX and sets MOT_SAT_OVERFLOW. */
uint64_t mot_acc_udiv(mot_acc x, uint64_t d, uint64_t *rem, uint32_t *sat);

/*
 * A prepared reciprocal, for dividing many numbers by one d > 0 with a
 * product instead of a division: m / 2^shift ~ 2^32 / d with m in
 * [2^62, 2^63), relative error below 2^-62.
 */
struct mot_recip {
	int64_t m;
	uint32_t shift;
};

/* Prepare 1/d for d > 0 (d <= 0 gives MOT_E_INVAL). Init only (a division). */
int mot_recip_init(struct mot_recip *r, int64_t d);

/* round(x * 2^32 / d) within 1 LSB, saturating: the Q32.32 ratio x/d when x
 * and d have the same scale. Real-time safe (one product). */
static inline mot_q32 mot_recip_ratio(int64_t x, const struct mot_recip *r, uint32_t *sat)
{
	return mot_acc_round(mot_acc_mul(x, r->m), r->shift, sat);
}

/* ---- conversions used at the edges (integers only) ------------------------ */

/* round(num / den) in Q32.32, den > 0, exact rational conversion. */
static inline mot_q32 mot_q32_ratio(int64_t num, int64_t den, uint32_t *sat)
{
	return mot_muldiv(num, MOT_Q32_ONE, den, sat);
}

#endif /* MOT_FIX_H */
