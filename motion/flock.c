/* SPDX-License-Identifier: MIT */
/* flock.c - Reynolds' flocks at a fixed step (see flock.h). */
#include "camera.h"
#include "flock.h"
#include "rng.h"
#include "trig.h"

#define ONE MOT_Q32_ONE

static mot_q32 half(mot_q32 x)
{
	return (x >> 1) + (x & 1);
}

/* v cut to length at most lim (a projection onto the ball: it moves v by
 * no more than any other point of the ball is from it). */
static void cut(mot_q32 v[3], mot_q32 lim, uint32_t *sat)
{
	mot_q32 len = mot_norm3(v, sat), s;
	int k;

	if (len <= lim || len == 0)
		return;
	s = mot_div(lim, len, sat);
	for (k = 0; k < 3; k++)
		v[k] = mot_mul(v[k], s, sat);
	/* rounding may leave it an LSB long: shorten toward zero */
	while (mot_norm3(v, sat) > lim)
		for (k = 0; k < 3; k++)
			v[k] -= v[k] > 0 ? 1 : v[k] < 0 ? -1 : 0;
}

struct steer_ctx {
	const struct mot_flock *f;
	const struct mot_member *m;
	uint32_t i, count;
	mot_q32 sep[3];
	mot_q32 dp[3], dv[3]; /* sums of p_j - p_i and v_j - v_i: small, no overflow */
	mot_acc r2, s2;       /* radius^2, sep^2 (Q64.64) */
	uint32_t *sat;
};

static bool mate(void *vctx, uint32_t j)
{
	struct steer_ctx *c = vctx;
	const struct mot_flock *f = c->f;
	const struct mot_member *mi = &c->m[c->i], *mj = &c->m[j];
	mot_q32 d[3], len;
	mot_acc d2;
	int k;

	if (j == c->i)
		return true;
	for (k = 0; k < 3; k++)
		d[k] = mot_sub_sat(mi->p[k], mj->p[k], c->sat);
	/* within reach by the exact squared distance: a square root only for
	 * the mates close enough to push apart */
	d2 = mot_acc_mac(mot_acc_mac(mot_acc_mul(d[0], d[0]), d[1], d[1]), d[2], d[2]);
	if (!mot_acc_is_neg(mot_acc_sub(d2, c->r2)))
		return true;
	for (k = 0; k < 3; k++) {
		c->dp[k] = mot_sub_sat(c->dp[k], d[k], c->sat);
		c->dv[k] = mot_add_sat(c->dv[k], mot_sub_sat(mj->v[k], mi->v[k], c->sat), c->sat);
	}
	if (mot_acc_is_neg(mot_acc_sub(d2, c->s2)) &&
	    (len = (mot_q32)mot_isqrt_acc(d2, c->sat)) > 0 && len < f->sep) {
		/* (sep - d) / (sep d) along d */
		mot_q32 w = mot_div(mot_sub_sat(f->sep, len, c->sat),
				    mot_mul(f->sep, len, c->sat), c->sat);

		for (k = 0; k < 3; k++)
			c->sep[k] = mot_add_sat(c->sep[k], mot_mul(d[k], w, c->sat), c->sat);
	}
	return ++c->count < f->max_neighbours;
}

static mot_q32 keyed(const struct mot_flock *f, const struct mot_curve *curves, int k,
		     mot_q32 frame, uint32_t *sat)
{
	int32_t c = f->goal_ch[k];

	return c < 0 ? f->goal_value[k] : mot_curve_eval(&curves[c], NULL, frame, sat);
}

void mot_flock_steer(const struct mot_flock *f, const struct mot_curve *curves,
		     const struct mot_member *m, uint32_t i, mot_q32 frame,
		     struct mot_flock_scratch *sc, mot_q32 a[3], uint32_t *sat)
{
	struct steer_ctx c;
	const struct mot_member *mi = &m[i];
	int32_t cell[3];
	uint32_t o;
	int k;

	c.f = f;
	c.m = m;
	c.i = i;
	c.count = 0;
	c.sat = sat;
	c.r2 = mot_acc_mul(f->radius, f->radius);
	c.s2 = mot_acc_mul(f->sep, f->sep);
	for (k = 0; k < 3; k++) {
		c.sep[k] = c.dp[k] = c.dv[k] = 0;
		a[k] = 0;
	}
	if (f->max_neighbours) {
		mot_grid_cell(&sc->grid, mi->p, cell);
		mot_grid_visit(&sc->grid, cell, mate, &c);
	}
	for (k = 0; k < 3; k++)
		a[k] = mot_mul(f->w_sep, c.sep[k], sat);
	if (c.count) {
		for (k = 0; k < 3; k++) {
			/* the mates' mean position and velocity relative to
			 * the member's, each rounded once */
			mot_q32 pm = mot_muldiv(c.dp[k], 1, c.count, sat);
			mot_q32 vm = mot_muldiv(c.dv[k], 1, c.count, sat);

			a[k] = mot_add_sat(a[k], mot_mul(f->w_coh, mot_recip_ratio(pm, &f->inv_radius,
										    sat), sat), sat);
			a[k] = mot_add_sat(a[k], mot_mul(f->w_ali, mot_recip_ratio(vm, &f->inv_vmax,
										    sat), sat), sat);
		}
	}
	if (f->goal != MOT_FLOCK_GOAL_NONE) {
		mot_q32 g[3], u[3], len, s;

		for (k = 0; k < 3; k++) {
			g[k] = keyed(f, curves, k, frame, sat);
			u[k] = f->goal == MOT_FLOCK_GOAL_POINT ? mot_sub_sat(g[k], mi->p[k], sat) :
								 g[k];
		}
		len = mot_norm3(u, sat);
		/* a unit vector, shorter within `radius` of a goal point */
		s = len == 0 ? 0 :
		    f->goal == MOT_FLOCK_GOAL_POINT && len < f->radius ?
			    mot_recip_ratio(ONE, &f->inv_radius, sat) : mot_div(ONE, len, sat);
		for (k = 0; k < 3; k++) {
			mot_q32 want = mot_mul(mot_mul(u[k], s, sat), f->vmax, sat);

			a[k] = mot_add_sat(a[k], mot_mul(f->w_goal,
							 mot_recip_ratio(mot_sub_sat(want, mi->v[k], sat),
									 &f->inv_vmax, sat), sat), sat);
		}
	}
	for (o = 0; o < f->nobst; o++) {
		const struct mot_obstacle *ob = &f->obst[o];
		mot_q32 d[3], len, e, w;

		for (k = 0; k < 3; k++)
			d[k] = mot_sub_sat(mi->p[k], ob->c[k], sat);
		len = mot_norm3(d, sat);
		e = mot_sub_sat(len, ob->r, sat);
		if (len == 0 || e >= f->margin)
			continue;
		/* (m - e) / m, more than 1 inside the sphere */
		w = mot_div(mot_sub_sat(f->margin, e, sat), mot_mul(f->margin, len, sat), sat);
		for (k = 0; k < 3; k++)
			a[k] = mot_add_sat(a[k], mot_mul(f->w_obst, mot_mul(d[k], w, sat), sat), sat);
	}
}

/* The heading of velocity v unwrapped near ref; ref where v is zero. */
static mot_q32 heading(const mot_q32 v[3], mot_q32 ref)
{
	if (v[0] == 0 && v[2] == 0)
		return ref;
	return mot_pan_unwrap(mot_atan2(-v[0], -v[2]), ref);
}

void mot_flock_step(const void *sys, const struct mot_curve *curves, const void *in, void *out,
		    int64_t n, void *scratch, uint32_t *sat)
{
	const struct mot_flock *f = sys;
	struct mot_flock_scratch *sc = scratch;
	const struct mot_member *m = in;
	struct mot_member *o = out;
	mot_q32 frame = mot_steps_frame(&f->steps, n * ONE, sat);
	uint32_t i;
	int k;

	if (f->max_neighbours) {
		mot_grid_clear(&sc->grid);
		for (i = 0; i < f->n; i++)
			mot_grid_insert(&sc->grid, i, m[i].p);
	}
	for (i = 0; i < f->n; i++) {
		mot_q32 a[3], dv[3];

		mot_flock_steer(f, curves, m, i, frame, sc, a, sat);
		cut(a, f->amax, sat);
		for (k = 0; k < 3; k++)
			o[i].v[k] = mot_add_sat(m[i].v[k], mot_steps_seconds(&f->steps, a[k], sat), sat);
		cut(o[i].v, f->vmax, sat);
		for (k = 0; k < 3; k++) {
			dv[k] = mot_sub_sat(o[i].v[k], m[i].v[k], sat);
			o[i].p[k] = mot_add_sat(m[i].p[k],
						mot_steps_seconds(&f->steps,
								  mot_add_sat(m[i].v[k], half(dv[k]),
									      sat), sat), sat);
		}
		o[i].heading = heading(o[i].v, m[i].heading);
	}
}

int mot_flock_init(struct mot_flock *f, const struct mot_curve *curves, uint32_t ncurves,
		   void *a, void *b, struct mot_flock_scratch *sc, uint32_t *sat)
{
	struct mot_member *m = (struct mot_member *)(void *)f->steps.ckpt;
	struct mot_rng r;
	uint32_t i;
	int k;

	if (!f->n || !m || f->steps.state_bytes != mot_flock_state_bytes(f->n) || !sc ||
	    f->radius <= 0 || f->sep < 0 || f->vmax <= 0 || f->amax <= 0 || f->margin < 0 ||
	    f->goal > MOT_FLOCK_GOAL_DIRECTION || (f->nobst && !f->obst) ||
	    (f->nobst && f->margin <= 0))
		return MOT_E_INVAL;
	for (k = 0; k < 3; k++)
		if (f->goal_ch[k] < -1 || (f->goal_ch[k] >= 0 && (uint32_t)f->goal_ch[k] >= ncurves))
			return MOT_E_INVAL;
	if (mot_recip_init(&f->inv_radius, f->radius) || mot_recip_init(&f->inv_vmax, f->vmax))
		return MOT_E_INVAL;
	mot_rng_seed(&r, f->seed);
	for (i = 0; i < f->n; i++) {
		for (k = 0; k < 3; k++)
			m[i].p[k] = mot_add_sat(f->start_c[k],
						mot_mul(f->start_r, mot_rng_sym(&r), sat), sat);
		for (k = 0; k < 3; k++)
			m[i].v[k] = mot_add_sat(f->start_v[k],
						mot_mul(f->start_dv, mot_rng_sym(&r), sat), sat);
		cut(m[i].v, f->vmax, sat);
		m[i].heading = heading(m[i].v, 0);
	}
	mot_steps_run(&f->steps, a, b, mot_flock_step, f, curves, sc, NULL, NULL, sat);
	return MOT_OK;
}

void mot_flock_eval(const struct mot_flock *f, const struct mot_curve *curves,
		    struct mot_steps_cache *c, struct mot_flock_scratch *sc, mot_q32 frame,
		    mot_q32 *out, uint32_t *sat)
{
	mot_q32 t = mot_steps_pos(&f->steps, frame, sat), tau;
	int64_t n = t >> 32;
	const struct mot_member *a, *b;
	uint32_t i;
	int k;

	if (n >= f->steps.nsteps)
		n = f->steps.nsteps - 1;
	tau = t - n * ONE;
	mot_steps_seek(&f->steps, c, n, mot_flock_step, f, curves, sc, sat);
	a = c->a;
	b = c->b;
	for (i = 0; i < f->n; i++) {
		mot_q32 *o = out + (size_t)i * MOT_FLOCK_NOUT, v[3];

		/* p + h (v tau + dv tau^2 / 2), v + dv tau: the step's constant
		 * acceleration, tau = 1 giving step n + 1's state exactly */
		for (k = 0; k < 3; k++) {
			mot_q32 dv = mot_sub_sat(b[i].v[k], a[i].v[k], sat);
			mot_q32 x = mot_add_sat(mot_mul(a[i].v[k], tau, sat),
						half(mot_mul(dv, mot_mul(tau, tau, sat), sat)), sat);

			if (tau == ONE)
				x = mot_add_sat(a[i].v[k], half(dv), sat);
			o[k] = mot_add_sat(a[i].p[k], mot_steps_seconds(&f->steps, x, sat), sat);
			v[k] = mot_add_sat(a[i].v[k], mot_mul(dv, tau, sat), sat);
		}
		o[MOT_FLOCK_HEADING] = heading(v, a[i].heading);
	}
}
