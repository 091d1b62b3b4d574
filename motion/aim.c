/* SPDX-License-Identifier: MIT */
/* aim.c - pan/tilt heads following a target (see aim.h). */
#include "aim.h"
#include "camera.h"

#define FINE 4u

uint32_t mot_aim_ref_count(mot_q32 f0, mot_q32 f1, uint32_t sub)
{
	int64_t frames = (f1 - f0 + MOT_Q32_ONE - 1) >> 32;

	if (f1 <= f0 || sub == 0)
		return 1;
	return (uint32_t)(frames * sub + 1);
}

mot_q32 mot_aim_fine_frame(const struct mot_aim *a, uint32_t k, uint32_t *sat)
{
	return mot_add_sat(a->f0, mot_muldiv(k, MOT_Q32_ONE, (int64_t)a->sub * FINE, sat), sat);
}

static void direction(const struct mot_aim *a, const mot_q32 tgt[3], mot_q32 d[3], uint32_t *sat)
{
	int k;

	for (k = 0; k < 3; k++)
		d[k] = mot_sub_sat(tgt[k], a->at[k], sat);
}

int mot_aim_march(struct mot_aim *a, struct mot_aim_march *m, uint32_t k, const mot_q32 tgt[3],
		  uint32_t *sat)
{
	mot_q32 d[3], pan, tilt, p;
	bool vertical;

	direction(a, tgt, d, sat);
	vertical = !mot_look(d, &pan, &tilt, sat);
	if (!m->have) {
		p = vertical ? 0 : pan;
	} else if (vertical) {
		p = m->prev;
	} else {
		mot_q32 step = mot_pan_unwrap(pan, m->prev) - m->prev;

		if (step >= MOT_Q32_ONE / 4 || step <= -MOT_Q32_ONE / 4)
			return MOT_E_RANGE;
		p = m->prev + step;
	}
	m->prev = p;
	m->have = true;
	if (k % FINE == 0) {
		if (k / FINE >= a->nref)
			return MOT_E_CAPACITY;
		if (p >= ((mot_q32)1 << 47) || p <= -((mot_q32)1 << 47))
			return MOT_E_RANGE; /* 32768 turns: beyond the grid's format */
		m->ref = p;
		a->pan_ref[k / FINE] = (int32_t)(p >> 16);
	}
	if (p - m->ref >= MOT_Q32_ONE * 3 / 8 || m->ref - p >= MOT_Q32_ONE * 3 / 8)
		return MOT_E_RANGE;
	return MOT_OK;
}

void mot_aim_eval(const struct mot_aim *a, const mot_q32 tgt[3], mot_q32 frame, mot_q32 *pan,
		  mot_q32 *tilt, uint32_t *sat)
{
	mot_q32 d[3], p, ref, g = mot_sub_sat(frame, a->f0, sat);
	int64_t idx;

	direction(a, tgt, d, sat);
	/* the grid point at or before the frame */
	idx = g <= 0 ? 0 : (g >> 32) * a->sub + (((g & 0xffffffff) * (int64_t)a->sub) >> 32);
	if (idx >= a->nref)
		idx = a->nref - 1;
	ref = (mot_q32)a->pan_ref[idx] * 65536;
	*pan = mot_look(d, &p, tilt, sat) ? mot_pan_unwrap(p, ref) : ref;
}
