/* SPDX-License-Identifier: MIT */
/*
 * strand.h - the timeline of one node (the seed paper's "strand"): rotation
 * tracks and the free strand that combines a node's channels.
 *
 * A joint node's strand is a single scalar curve (curve.h): a revolute angle
 * in turns or a prismatic position in scene units, or an rpm curve that is
 * integrated in closed form (mot_spin_turns). A free node's strand has up to
 * nine scalar channels (translate xyz, scale xyz, shear hxy hxz hyz), each a
 * curve over the keys that set it, and a rotation track of unit quaternions
 * interpolated by slerp or squad. A channel without keys holds its rest
 * value (translate 0, scale 1, shear 0, no rotation).
 *
 * Everything here is prepared at init into caller-owned memory and is
 * real-time safe to evaluate.
 */
#ifndef MOT_STRAND_H
#define MOT_STRAND_H

#include "curve.h"
#include "ease.h"
#include "fix.h"
#include "mat.h"
#include "quat.h"
#include "timing.h"

/* ---- rotation tracks ------------------------------------------------------ */

struct mot_rot_key {
	mot_q32 frame;     /* strictly increasing */
	struct mot_quat q; /* unit (the loader normalises) */
	mot_q32 ease_in, ease_out;
};

struct mot_rot_seg {
	struct mot_slerp arc;   /* q(i) -> q(i+1) */
	struct mot_slerp inner; /* squad: s(i) -> s(i+1) */
	struct mot_ease ease;
	struct mot_recip inv_h; /* 1 / (f(i+1) - f(i)) */
};

/*
 * Outside its keys a track holds its first or last key, and a free node
 * there needs that key's matrix on every evaluation: both are made at init
 * (end: mot_quat_to_rot_q62() of the quaternion the track holds), where
 * they come out without saturating (ends_ok: unit keys always do), so that
 * an evaluation gets the same bits without the ~150 instructions. 144
 * bytes a track.
 */
struct mot_rot_track {
	uint32_t nkeys;
	bool squad;
	bool compact; /* keys only: each slerp prepared when it is evaluated */
	bool ends_ok; /* end[] made */
	bool unit;    /* every quaternion it gives (two keys or more) below 2 in
		       * its components, |q|^2 within 1/4 of 1 (every arc's
		       * unit, quat.h): mot_quat_rot_q62_unit() takes it */
	const struct mot_rot_key *keys;
	struct mot_rot_seg *seg; /* nkeys - 1 entries; NULL when compact */
	struct mot_rot_q62 end[2]; /* before the first key, after the last */
};

/*
 * The parameter t of an offset x in [0, h) into a key interval of width h,
 * before its ease: mot_recip_ratio()'s round(x 2^32 / h) through the
 * interval's reciprocal m / 2^shift, at most 1 (its rounding reaches 1 and
 * an LSB). x < h <= 2^(shift - 30) (mot_recip_init()), so x moved up by
 * 93 - shift (0 .. 63) stays below 2^63 and the rounding's shift is then
 * 93: the high word of x' m plus 2^28 (the half, which no carry from the
 * low word can reach) shifted by 29, the same bits without a variable
 * 128-bit shift or a saturation test.
 */
static inline mot_q32 mot_rot_seg_t(const struct mot_rot_seg *sg, int64_t x)
{
	const struct mot_recip *r = &sg->inv_h;
	mot_acc p = mot_acc_mul((int64_t)((uint64_t)x << (93 - r->shift)), r->m);
	mot_q32 s = (mot_q32)(mot_acc_hi(p) + ((uint64_t)1 << 28)) >> 29;

	return s > MOT_Q32_ONE ? MOT_Q32_ONE : s;
}

/* Validate (MOT_E_NOKEYS, MOT_E_ORDER, MOT_E_INVAL for ease fractions,
 * MOT_E_CAPACITY when nseg < nkeys - 1) and prepare. Init only. */
int mot_rot_track_init(struct mot_rot_track *r, const struct mot_rot_key *keys, uint32_t nkeys,
		       bool squad, struct mot_rot_seg *seg, uint32_t nseg, uint32_t *sat);

/* A slerp track kept as its keys alone, for sampled motion (a key every
 * frame): 56 bytes a key where a prepared track takes 56 +
 * sizeof(struct mot_rot_seg). Each evaluation prepares the slerp of its
 * interval (mot_quat_slerp: the shorter arc, one-shot) and takes
 * its parameter with one division; no squad, no ease (MOT_E_INVAL for an
 * ease fraction), otherwise mot_rot_track_init()'s checks. Init only. */
int mot_rot_track_init_compact(struct mot_rot_track *r, const struct mot_rot_key *keys,
			       uint32_t nkeys);

/* Rotation at a frame; holds the end keys outside them, and returns there
 * the held key's matrix made at init (NULL elsewhere, or when it was not
 * made): what mot_quat_to_rot_q62(*out) gives. Between them it leaves
 * cur->seg on the key interval [f(i), f(i+1)) of the frame (scene.c's memo
 * learns it there). Real-time safe. */
const struct mot_rot_q62 *mot_rot_track_eval(struct mot_quat *out,
					     const struct mot_rot_track *r,
					     struct mot_cursor *cur, mot_q32 frame,
					     uint32_t *sat);

/* ---- strand-wide time warp -------------------------------------------------- */

/* The slow-in/slow-out of a whole strand (FORMULAS section 7), a remap of
 * the frame over the span [f0, f1]. */
struct mot_warp {
	bool on;
	mot_q32 f0, f1;
	struct mot_ease ease;
};

/* ease_out_frames leaving f0, ease_in_frames arriving at f1; both 0 turns the
 * warp off. MOT_E_INVAL when they are negative or exceed the span. */
int mot_warp_init(struct mot_warp *w, mot_q32 f0, mot_q32 f1, mot_q32 ease_out_frames,
		  mot_q32 ease_in_frames, uint32_t *sat);
mot_q32 mot_warp_apply(const struct mot_warp *w, mot_q32 frame, uint32_t *sat);

/* ---- free strands ------------------------------------------------------------- */

enum mot_free_channel {
	MOT_FREE_TX, MOT_FREE_TY, MOT_FREE_TZ,
	MOT_FREE_SX, MOT_FREE_SY, MOT_FREE_SZ,
	MOT_FREE_HXY, MOT_FREE_HXZ, MOT_FREE_HYZ,
	MOT_FREE_NCHANNELS,
};

/*
 * A free node's rotation is a track of unit quaternions (rot), or four
 * scalar curves of w, x, y, z whose value is normalised at every evaluation
 * (quat): a rotation interpolated component by component, as glTF's
 * CUBICSPLINE and STEP rotations are (a cubic through the keys with their
 * tangents, then q / |q|). At most one of the two; a zero quaternion
 * evaluates to the identity and sets MOT_SAT_DOMAIN.
 */
struct mot_free_strand {
	int32_t channel[MOT_FREE_NCHANNELS]; /* curve index in the scene, or -1 */
	int32_t rot;                         /* rotation track index, or -1 */
	struct mot_warp warp;
	int32_t quat[4];                     /* curves of w, x, y, z, or all -1 */
};

/* ---- spin (FORMULAS section 8) ------------------------------------------------ */

/* Turns a spin has made by `frame`: 360 deg * integral of rpm / 60 over the
 * seconds from frame 0, from the rpm curve's closed-form integral, rounded
 * once. Exact to the last bit after any run length. Real-time safe. */
mot_q32 mot_spin_turns(const struct mot_curve *rpm, struct mot_cursor *cur,
		       const struct mot_timing *t, mot_q32 frame, uint32_t *sat);

/*
 * mot_spin_turns() from the curve's integral I (rpm x frames, Q64.64,
 * mot_curve_integral()'s): turns = I den / (60 num), rounded once to
 * Q32.32. With N = |I| den (up to 151 bits, three 64-bit words) and D = 60
 * num (below 2^31), round(floor(N / D) / 2^32) = floor((N + D 2^31) / (D
 * 2^32)) = floor(floor((N + D 2^31) / 2^32) / D), one exact division of 128
 * bits by D through the timing's reciprocal of it (where the schoolbook
 * long division took three, a word each). Inline: scene.c's spin joints
 * take it on their own path, from an integral of their own (the same bits).
 */
static inline mot_q32 mot_spin_turns_of(mot_acc integ, const struct mot_timing *t, uint32_t *sat)
{
	uint64_t w2, w1, w0, pl, r, hi, lo, q, dd, half;
	bool neg = mot_acc_is_neg(integ);

	if (neg)
		integ = mot_acc_neg(integ);
	/* N = (H 2^64 + L) den, H < 2^63 */
	w1 = mot_umul_hi(mot_acc_lo(integ), t->den, &w0);
	w2 = mot_umul_hi(mot_acc_hi(integ), t->den, &pl);
	w1 += pl;
	w2 += w1 < pl;
	/* + D 2^31 (below 2^62: num <= MOT_RATE_MAX) */
	dd = t->per_turn.dn >> t->per_turn.s;
	half = dd << 31;
	w0 += half;
	w1 += w0 < half;
	w2 += w1 == 0 && w0 < half;
	/* / 2^32: the quotient by D fits 64 bits only for hi < D */
	hi = (w2 << 32) | (w1 >> 32);
	lo = (w1 << 32) | (w0 >> 32);
	if ((w2 >> 32) == 0 && hi < dd) {
		q = mot_udiv_by_inv(hi, lo, &t->per_turn, &r);
		if ((q >> 63) == 0)
			return neg ? -(mot_q32)q : (mot_q32)q;
	}
	if (sat)
		*sat |= MOT_SAT_OVERFLOW;
	return neg ? MOT_Q32_MIN : MOT_Q32_MAX;
}

#endif /* MOT_STRAND_H */
