/* SPDX-License-Identifier: MIT */
/* strand.c - rotation tracks, strand time warps and spin (see strand.h). */
#include "strand.h"

/* ---- rotation tracks -------------------------------------------------------- */

static void quat_neg(struct mot_quat *q)
{
	q->w = -q->w;
	q->x = -q->x;
	q->y = -q->y;
	q->z = -q->z;
}

/* b, flipped if needed onto a's side of the sphere. */
static void quat_align(struct mot_quat *out, const struct mot_quat *a, const struct mot_quat *b)
{
	*out = *b;
	if (mot_quat_dot(a, b, NULL) < 0)
		quat_neg(out);
}

/* The matrices of the held end keys (struct mot_rot_track), once the rest
 * of the track is set. */
static void rot_ends(struct mot_rot_track *r)
{
	struct mot_quat q[2];
	uint32_t sat = 0;
	bool ok = true;
	unsigned e;

	r->ends_ok = false;
	/* the quaternions the track holds (the first key's side of the sphere
	 * or the last's, as its arcs have them) */
	mot_rot_track_eval(&q[0], r, NULL, r->keys[0].frame, NULL);
	mot_rot_track_eval(&q[1], r, NULL, r->keys[r->nkeys - 1].frame, NULL);
	for (e = 0; e < 2; e++)
		ok = mot_quat_to_rot_q62(r->end[e].r, &q[e], &sat) == MOT_OK && ok;
	r->ends_ok = ok && !sat;
}

int mot_rot_track_init(struct mot_rot_track *r, const struct mot_rot_key *keys, uint32_t nkeys,
		       bool squad, struct mot_rot_seg *seg, uint32_t nseg, uint32_t *sat)
{
	struct mot_quat prev, cur, next, s_cur, s_next;
	uint32_t i;
	int err;

	if (nkeys == 0)
		return MOT_E_NOKEYS;
	if (nseg < nkeys - 1)
		return MOT_E_CAPACITY;
	for (i = 0; i < nkeys; i++) {
		if (keys[i].ease_in < 0 || keys[i].ease_in > MOT_Q32_ONE || keys[i].ease_out < 0 ||
		    keys[i].ease_out > MOT_Q32_ONE)
			return MOT_E_INVAL;
		if (i > 0 && keys[i].frame <= keys[i - 1].frame)
			return MOT_E_ORDER;
	}
	/*
	 * Walk the keys with a window (prev, cur, next) of sign-aligned
	 * quaternions: q and -q are the same rotation, and both slerp and
	 * squad's inner points need consecutive keys on one hemisphere.
	 */
	cur = keys[0].q;
	prev = cur;
	s_cur = cur;
	for (i = 0; i + 1 < nkeys; i++) {
		struct mot_rot_seg *sg = &seg[i];

		quat_align(&next, &cur, &keys[i + 1].q);
		err = mot_ease_init(&sg->ease, keys[i].ease_out, keys[i + 1].ease_in, sat);
		if (err)
			return err;
		err = mot_recip_init(&sg->inv_h, keys[i + 1].frame - keys[i].frame);
		if (err)
			return err;
		mot_slerp_prepare(&sg->arc, &cur, &next, sat);
		if (squad) {
			struct mot_quat after;

			if (i == 0)
				mot_squad_inner(&s_cur, &prev, &cur, &next, sat);
			if (i + 2 < nkeys)
				quat_align(&after, &next, &keys[i + 2].q);
			else
				after = next;
			mot_squad_inner(&s_next, &cur, &next, &after, sat);
			mot_slerp_prepare(&sg->inner, &s_cur, &s_next, sat);
			s_cur = s_next;
		} else {
			sg->inner = sg->arc;
		}
		prev = cur;
		cur = next;
	}
	/* near-unit arcs give near-unit quaternions (mot_slerp_prepare(),
	 * mot_squad_eval()); a single key is always held (its matrix made at
	 * init, or, not made, not near unit) */
	r->unit = nkeys > 1;
	for (i = 0; i + 1 < nkeys; i++)
		r->unit = r->unit && seg[i].arc.unit && (!squad || seg[i].inner.unit);
	r->nkeys = nkeys;
	r->squad = squad;
	r->compact = false;
	r->keys = keys;
	r->seg = seg;
	rot_ends(r);
	return MOT_OK;
}

int mot_rot_track_init_compact(struct mot_rot_track *r, const struct mot_rot_key *keys,
			       uint32_t nkeys)
{
	uint32_t i;

	if (nkeys == 0)
		return MOT_E_NOKEYS;
	for (i = 0; i < nkeys; i++) {
		if (keys[i].ease_in || keys[i].ease_out)
			return MOT_E_INVAL;
		if (i > 0 && keys[i].frame <= keys[i - 1].frame)
			return MOT_E_ORDER;
	}
	r->nkeys = nkeys;
	r->squad = false;
	r->compact = true;
	r->unit = false; /* one-shot slerps of keys not checked */
	r->keys = keys;
	r->seg = NULL;
	rot_ends(r);
	return MOT_OK;
}

/* Index i of the key interval [f(i), f(i+1)) holding frame (0 .. n-2), for
 * frames inside the keys. O(1) when the cursor is on it or the next one. */
static uint32_t rot_find(const struct mot_rot_track *r, struct mot_cursor *cur, mot_q32 frame)
{
	const struct mot_rot_key *k = r->keys;
	uint32_t lo = 0, hi = r->nkeys - 1; /* invariant: k[lo].frame <= frame < k[hi].frame */

	if (cur) {
		uint32_t i = cur->seg;

		if (i + 1 < r->nkeys && k[i].frame <= frame) {
			if (frame < k[i + 1].frame)
				return i;
			if (i + 2 < r->nkeys && frame < k[i + 2].frame) {
				cur->seg = i + 1;
				return i + 1;
			}
		}
	}
	while (hi - lo > 1) {
		uint32_t mid = lo + (hi - lo) / 2;

		if (k[mid].frame <= frame)
			lo = mid;
		else
			hi = mid;
	}
	if (cur)
		cur->seg = lo;
	return lo;
}

const struct mot_rot_q62 *mot_rot_track_eval(struct mot_quat *out,
					     const struct mot_rot_track *r,
					     struct mot_cursor *cur, mot_q32 frame,
					     uint32_t *sat)
{
	const struct mot_rot_seg *sg;
	mot_q32 s;
	uint32_t i;

	if (r->nkeys == 1 || frame <= r->keys[0].frame) {
		*out = r->nkeys == 1 || r->compact ? r->keys[0].q : r->seg[0].arc.a;
		return r->ends_ok ? &r->end[0] : NULL;
	}
	if (frame >= r->keys[r->nkeys - 1].frame) {
		*out = r->compact ? r->keys[r->nkeys - 1].q : r->seg[r->nkeys - 2].arc.b;
		return r->ends_ok ? &r->end[1] : NULL;
	}
	i = rot_find(r, cur, frame);
	if (r->compact) {
		const struct mot_rot_key *k = r->keys;

		s = mot_muldiv(frame - k[i].frame, MOT_Q32_ONE, k[i + 1].frame - k[i].frame, sat);
		mot_quat_slerp(out, &k[i].q, &k[i + 1].q, s, sat);
		return NULL;
	}
	sg = &r->seg[i];
	s = mot_rot_seg_t(sg, frame - r->keys[i].frame);
	if (!mot_ease_is_identity(&sg->ease))
		s = mot_ease_apply(&sg->ease, s, sat);
	if (r->squad)
		mot_squad_eval(out, &sg->arc, &sg->inner, s, sat);
	else
		mot_slerp_eval(out, &sg->arc, s, sat);
	return NULL;
}

/* ---- strand-wide warp ----------------------------------------------------------- */

int mot_warp_init(struct mot_warp *w, mot_q32 f0, mot_q32 f1, mot_q32 ease_out_frames,
		  mot_q32 ease_in_frames, uint32_t *sat)
{
	mot_q32 span = f1 - f0;
	int err;

	w->on = false;
	w->f0 = f0;
	w->f1 = f1;
	if (ease_out_frames < 0 || ease_in_frames < 0)
		return MOT_E_INVAL;
	if (ease_out_frames == 0 && ease_in_frames == 0)
		return MOT_OK;
	if (span <= 0 || ease_out_frames > span || ease_in_frames > span - ease_out_frames)
		return MOT_E_INVAL;
	/* the fractions exactly, frames over frames */
	err = mot_ease_init_ratio(&w->ease, ease_out_frames, ease_in_frames, span, sat);
	if (err)
		return err;
	w->on = true;
	return MOT_OK;
}

mot_q32 mot_warp_apply(const struct mot_warp *w, mot_q32 frame, uint32_t *sat)
{
	int64_t s;
	mot_q32 span = w->f1 - w->f0;

	if (!w->on || frame <= w->f0 || frame >= w->f1)
		return frame;
	/* s and s' in Q2.62: a span of millions of frames keeps its resolution
	 * until the warped frame is rounded once, back to Q32.32 */
	s = mot_muldiv(frame - w->f0, MOT_Q62_ONE, span, sat);
	s = mot_ease_apply62(&w->ease, s);
	return w->f0 + mot_acc_round(mot_acc_mul(s, span), 62, sat);
}

/* ---- spin ----------------------------------------------------------------------- */

mot_q32 mot_spin_turns(const struct mot_curve *rpm, struct mot_cursor *cur,
		       const struct mot_timing *t, mot_q32 frame, uint32_t *sat)
{
	/* turns = integral(rpm dt) / 60 with dt = df * den / num seconds:
	 * the curve's integral I in rpm x frames (Q64.64) times den / (60 num),
	 * rounded once (mot_spin_turns_of()). Nothing is summed from tick to
	 * tick. */
	mot_acc integ;

	if (mot_curve_integral(&integ, rpm, cur, frame, sat) != MOT_OK) {
		if (sat)
			*sat |= MOT_SAT_DOMAIN;
		return 0;
	}
	return mot_spin_turns_of(integ, t, sat);
}
