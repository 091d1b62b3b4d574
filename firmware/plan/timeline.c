/* SPDX-License-Identifier: MIT */
/* timeline.c - a range of the scene, and just beyond it (see timeline.h). */
#include "timeline.h"

int64_t STRAND_RT timeline_tick_floor(const struct mot_timing *t, int64_t f)
{
	int64_t k = mot_timing_trigger_tick(t, f);
	/* on a tick exactly when num divides f * tick_hz * den; the product
	 * can exceed 64 bits, its remainder cannot (num < 2^24) */
	uint64_t num = t->num, fm = (uint64_t)(f % (int64_t)num + (int64_t)num) % num;

	return fm * (t->ticks_den % num) % num ? k - 1 : k;
}

/* x + m d, saturating. */
static mot_q32 STRAND_RT along(mot_q32 x, int64_t m, mot_q32 d, uint32_t *sat)
{
	int64_t step;

	if (__builtin_mul_overflow(m, d, &step)) {
		*sat |= MOT_SAT_OVERFLOW;
		return (m < 0) == (d < 0) ? MOT_Q32_MAX : MOT_Q32_MIN;
	}
	return mot_add_sat(x, step, sat);
}

void STRAND_RT timeline_init(struct timeline *tl, struct play_source *src, uint32_t n,
			     const bool *extend, int64_t first, int64_t last, mot_q32 *mem,
			     uint32_t *sat)
{
	const struct mot_timing *t = &src->timing;
	mot_q32 *next = mem + 4 * (size_t)n - n; /* d1 doubles as scratch until the end */
	uint32_t i;

	tl->src = src;
	tl->n = n;
	tl->extend = extend;
	tl->x0 = mem;
	tl->d0 = mem + n;
	tl->x1 = mem + 2 * (size_t)n;
	tl->d1 = next;
	tl->k0 = mot_timing_trigger_tick(t, first);
	tl->k1 = timeline_tick_floor(t, last);
	if (tl->k1 < tl->k0)
		tl->k1 = tl->k0; /* no tick inside: the trigger's tick, held */
	src_eval(src, mot_timing_tick_frame(t, tl->k0), tl->x0, sat);
	src_eval(src, mot_timing_tick_frame(t, tl->k1), tl->x1, sat);
	if (tl->k1 == tl->k0) {
		for (i = 0; i < n; i++)
			tl->d0[i] = tl->d1[i] = 0;
		return;
	}
	src_eval(src, mot_timing_tick_frame(t, tl->k0 + 1), next, sat);
	for (i = 0; i < n; i++)
		tl->d0[i] = extend[i] ? mot_sub_sat(next[i], tl->x0[i], sat) : 0;
	src_eval(src, mot_timing_tick_frame(t, tl->k1 - 1), next, sat);
	for (i = 0; i < n; i++)
		tl->d1[i] = extend[i] ? mot_sub_sat(tl->x1[i], next[i], sat) : 0;
}

void STRAND_RT timeline_eval(const struct timeline *tl, int64_t k, mot_q32 *out, uint32_t *sat)
{
	uint32_t i;

	if (k >= tl->k0 && k <= tl->k1) {
		src_eval(tl->src, mot_timing_tick_frame(&tl->src->timing, k), out, sat);
		return;
	}
	for (i = 0; i < tl->n; i++)
		out[i] = k > tl->k1 ? along(tl->x1[i], k - tl->k1, tl->d1[i], sat) :
				      along(tl->x0[i], k - tl->k0, tl->d0[i], sat);
}
