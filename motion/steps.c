/* SPDX-License-Identifier: MIT */
/* steps.c - the time line of a simulated system (see steps.h). */
#include "steps.h"

int mot_steps_init(struct mot_steps *s, const struct mot_timing *t, mot_q32 f0, mot_q32 f1,
		   uint32_t rate_num, uint32_t rate_den, uint32_t every, uint32_t state_bytes)
{
	uint32_t sat = 0;
	mot_q32 last;

	if (!t->num || rate_num < 1 || rate_den < 1 || rate_num > MOT_STEP_HZ_MAX ||
	    rate_den > MOT_STEP_HZ_MAX || rate_num > (uint64_t)MOT_STEP_HZ_MAX * rate_den ||
	    f1 < f0 || every < 1 || state_bytes == 0 || state_bytes % 8)
		return MOT_E_INVAL;
	s->f0 = f0;
	s->pos_num = (int64_t)t->den * rate_num;
	s->pos_den = (int64_t)t->num * rate_den;
	s->rate_num = rate_num;
	s->rate_den = rate_den;
	s->every = every;
	s->state_bytes = state_bytes;
	s->ckpt = NULL;
	if (mot_recip_init(&s->rate, MOT_Q32_INT(rate_num)))
		return MOT_E_INVAL;
	if (f1 - f0 >= ((int64_t)1 << 62))
		return MOT_E_RANGE;
	last = mot_muldiv(f1 - f0, s->pos_num, s->pos_den, &sat);
	if (sat || last >= MOT_STEPS_MAX * MOT_Q32_ONE)
		return MOT_E_RANGE;
	/* the step at or after f1, and at least one step */
	s->nsteps = (last + MOT_Q32_ONE - 1) >> 32;
	if (s->nsteps < 1)
		s->nsteps = 1;
	return MOT_OK;
}

mot_q32 mot_steps_pos(const struct mot_steps *s, mot_q32 frame, uint32_t *sat)
{
	mot_q32 d = mot_sub_sat(frame, s->f0, sat), p;

	if (d <= 0)
		return 0;
	if (d >= ((int64_t)1 << 62))
		return s->nsteps * MOT_Q32_ONE;
	p = mot_muldiv(d, s->pos_num, s->pos_den, sat);
	return p > s->nsteps * MOT_Q32_ONE ? s->nsteps * MOT_Q32_ONE : p;
}

mot_q32 mot_steps_frame(const struct mot_steps *s, mot_q32 pos, uint32_t *sat)
{
	return mot_add_sat(s->f0, mot_muldiv(pos, s->pos_den, s->pos_num, sat), sat);
}

static void *ckpt_at(const struct mot_steps *s, int64_t k)
{
	return s->ckpt + (size_t)k * s->state_bytes;
}

void mot_steps_seek(const struct mot_steps *s, struct mot_steps_cache *c, int64_t n,
		    mot_step_fn fn, const void *sys, const struct mot_curve *curves, void *scratch,
		    uint32_t *sat)
{
	void *t;

	if (n < 0)
		n = 0;
	if (n >= s->nsteps)
		n = s->nsteps - 1;
	if (c->n < 0 || n < c->n || n - c->n > (int64_t)s->every) {
		int64_t k = n / s->every;

		mot_copy(c->a, ckpt_at(s, k), s->state_bytes);
		c->n = k * s->every;
		c->b_ok = false;
	}
	while (c->n < n) {
		if (!c->b_ok)
			fn(sys, curves, c->a, c->b, c->n, scratch, sat);
		t = c->a;
		c->a = c->b;
		c->b = t;
		c->n++;
		c->b_ok = false;
	}
	if (!c->b_ok) {
		fn(sys, curves, c->a, c->b, c->n, scratch, sat);
		c->b_ok = true;
	}
}

void mot_steps_run(const struct mot_steps *s, void *a, void *b, mot_step_fn fn,
		   const void *sys, const struct mot_curve *curves, void *scratch,
		   void (*watch)(const void *sys, const void *state, int64_t n, void *ctx),
		   void *ctx, uint32_t *sat)
{
	int64_t n;
	void *t;

	mot_copy(a, s->ckpt, s->state_bytes);
	if (watch)
		watch(sys, a, 0, ctx);
	for (n = 0; n < s->nsteps; n++) {
		fn(sys, curves, a, b, n, scratch, sat);
		t = a;
		a = b;
		b = t;
		if ((n + 1) % s->every == 0)
			mot_copy(ckpt_at(s, (n + 1) / s->every), a, s->state_bytes);
		if (watch)
			watch(sys, a, n + 1, ctx);
	}
}
