/* SPDX-License-Identifier: MIT */
/* particles.c - emitted, scripted and Newtonian particles (see particles.h). */
#include "particles.h"
#include "rng.h"
#include "trig.h"

#define ONE MOT_Q32_ONE

static struct mot_particles_head *head_of(void *state)
{
	return state;
}

static struct mot_particle *pool_of(void *state)
{
	return (struct mot_particle *)((char *)state + sizeof(struct mot_particles_head));
}

static const struct mot_particle *cpool_of(const void *state)
{
	return (const struct mot_particle *)((const char *)state +
					     sizeof(struct mot_particles_head));
}

/* A keyed value at a frame (curves without cursors: a step's few
 * evaluations need none, and random access gives the same bits). */
static mot_q32 val(const struct mot_particles *ps, const struct mot_curve *curves, int k,
		   mot_q32 frame, uint32_t *sat)
{
	int32_t c = ps->curve[k];

	return c < 0 ? ps->value[k] : mot_curve_eval(&curves[c], NULL, frame, sat);
}

/* x h: a rate times the step's length in seconds */
static mot_q32 hmul(const struct mot_particles *ps, mot_q32 x, uint32_t *sat)
{
	return mot_steps_seconds(&ps->steps, x, sat);
}

static mot_q32 half(mot_q32 x)
{
	return (x >> 1) + (x & 1); /* round half toward +inf */
}

/* ---- forces ----------------------------------------------------------------------- */

/* Unary forces on a particle at p with velocity v: gravity and drag. */
static void unary(const struct mot_particles *ps, const mot_q32 v[3], mot_q32 a[3],
		  uint32_t *sat)
{
	int k;

	for (k = 0; k < 3; k++)
		a[k] = mot_sub_sat(ps->gravity[k], mot_mul(ps->drag, v[k], sat), sat);
}

struct pair_ctx {
	const struct mot_particles *ps;
	struct mot_particle *pool;
	uint32_t i;
	uint32_t *sat;
};

/* The pairwise force between i and j > i: strength (1 - d/R) along their
 * line, pushing apart for a positive strength. */
static bool pair_visit(void *vctx, uint32_t j)
{
	struct pair_ctx *c = vctx;
	const struct mot_particles *ps = c->ps;
	struct mot_particle *pi = &c->pool[c->i], *pj = &c->pool[j];
	mot_q32 d[3], len, f, inv;
	int k;

	if (j <= c->i)
		return true;
	for (k = 0; k < 3; k++)
		d[k] = mot_sub_sat(pj->p[k], pi->p[k], c->sat);
	len = mot_norm3(d, c->sat);
	if (len >= ps->pair_radius || len == 0)
		return true;
	f = mot_mul(ps->pair_strength,
		    ONE - mot_div(len, ps->pair_radius, c->sat), c->sat);
	inv = mot_div(f, len, c->sat); /* f / |d| */
	for (k = 0; k < 3; k++) {
		mot_q32 fk = mot_mul(d[k], inv, c->sat);

		pi->a[k] = mot_sub_sat(pi->a[k], fk, c->sat);
		pj->a[k] = mot_add_sat(pj->a[k], fk, c->sat);
	}
	return true;
}

static bool alive_at(const struct mot_particle *p, mot_q32 t)
{
	return p->used && p->birth <= t && t < p->death;
}

/*
 * a = F(p, v) / m for every particle alive at step position t, with v the
 * velocity predictor: unary forces, springs with damping along them,
 * pairwise forces. Pinned particles are set afterwards by their pins.
 */
static void forces(const struct mot_particles *ps, struct mot_particle *pool,
		   mot_q32 (*vp)[3], mot_q32 t, struct mot_particles_scratch *sc, uint32_t *sat)
{
	uint32_t i, s;
	int k;

	for (i = 0; i < ps->npool; i++)
		if (alive_at(&pool[i], t))
			unary(ps, vp[i], pool[i].a, sat);
	for (s = 0; s < ps->nsprings; s++) {
		const struct mot_spring *sp = &ps->springs[s];
		struct mot_particle *a = &pool[sp->i], *b = &pool[sp->j];
		mot_q32 d[3], dv[3], len, inv, f;

		for (k = 0; k < 3; k++) {
			d[k] = mot_sub_sat(b->p[k], a->p[k], sat);
			dv[k] = mot_sub_sat(vp[sp->j][k], vp[sp->i][k], sat);
		}
		len = mot_norm3(d, sat);
		if (len == 0)
			continue;
		inv = mot_div(ONE, len, sat);
		/* k (|d| - L) + c (dv . d / |d|), then along d / |d| */
		f = mot_add_sat(mot_mul(ps->spring_k, mot_sub_sat(len, sp->rest, sat), sat),
				mot_mul(ps->spring_c, mot_mul(mot_dot3(dv, d, sat), inv, sat), sat),
				sat);
		f = mot_mul(f, inv, sat);
		for (k = 0; k < 3; k++) {
			mot_q32 fk = mot_mul(f, d[k], sat);

			a->a[k] = mot_add_sat(a->a[k], fk, sat);
			b->a[k] = mot_sub_sat(b->a[k], fk, sat);
		}
	}
	if (ps->pair_radius > 0 && sc && sc->has_grid) {
		struct pair_ctx c = { ps, pool, 0, sat };
		int32_t cell[3];

		mot_grid_clear(&sc->grid);
		for (i = 0; i < ps->npool; i++)
			if (alive_at(&pool[i], t))
				mot_grid_insert(&sc->grid, i, pool[i].p);
		for (i = 0; i < ps->npool; i++) {
			if (!alive_at(&pool[i], t))
				continue;
			c.i = i;
			mot_grid_cell(&sc->grid, pool[i].p, cell);
			mot_grid_visit(&sc->grid, cell, pair_visit, &c);
		}
	}
}

/* A pin's position at a frame: its rest position plus its keyed offset. */
static void pin_pos(const struct mot_particles *ps, const struct mot_curve *curves,
		    const struct mot_pin *pin, mot_q32 frame, mot_q32 p[3], uint32_t *sat)
{
	int k;

	for (k = 0; k < 3; k++) {
		mot_q32 o = pin->ch[k] < 0 ? 0 :
			    mot_curve_eval(&curves[pin->ch[k]], NULL, frame, sat);

		p[k] = mot_add_sat(ps->rest[pin->i][k], o, sat);
	}
}

/* ---- the Hermite curve between two states --------------------------------------- */

/* Position and velocity at fraction s of [t0, t1] (H seconds long) on the
 * cubic through (p0, v0) and (p1, v1). */
static void hermite(mot_q32 p[3], mot_q32 v[3], const mot_q32 p0[3], const mot_q32 v0[3],
		    const mot_q32 p1[3], const mot_q32 v1[3], mot_q32 s, mot_q32 H,
		    uint32_t *sat)
{
	mot_q32 s2 = mot_mul(s, s, sat), s3 = mot_mul(s2, s, sat);
	mot_q32 w[4] = { 2 * s3 - 3 * s2 + ONE, s3 - 2 * s2 + s, 3 * s2 - 2 * s3, s3 - s2 };
	/* derivatives d/ds of the weights, over H for a velocity */
	mot_q32 dw[4] = { 6 * s2 - 6 * s, 3 * s2 - 4 * s + ONE, 6 * s - 6 * s2, 3 * s2 - 2 * s };
	int k;

	for (k = 0; k < 3; k++) {
		mot_q32 y[4] = { p0[k], mot_mul(H, v0[k], sat), p1[k], mot_mul(H, v1[k], sat) };

		p[k] = mot_sum_prod(w, y, 4, sat);
		if (v) {
			mot_q32 d = mot_sum_prod(dw, y, 4, sat);

			v[k] = H > 0 ? mot_div(d, H, sat) : v0[k];
		}
	}
}

/* ---- a step ------------------------------------------------------------------------ */

/* A newborn's position and velocity dt seconds after its birth, under the
 * unary forces at birth (a partial first step). */
static void newborn(const struct mot_particles *ps, struct mot_particle *q, mot_q32 dt,
		    uint32_t *sat)
{
	mot_q32 a[3];
	int k;

	unary(ps, q->v0, a, sat);
	for (k = 0; k < 3; k++) {
		mot_q32 at = mot_mul(a[k], dt, sat);

		q->p[k] = mot_add_sat(q->p0[k],
				      mot_mul(mot_add_sat(q->v0[k], half(at), sat), dt, sat), sat);
		q->v[k] = mot_add_sat(q->v0[k], at, sat);
		q->a[k] = a[k];
	}
}

/* The particles released in (n, n + 1]: into the lowest free slots. */
static void emit(const struct mot_particles *ps, const struct mot_curve *curves,
		 struct mot_particles_head *h, struct mot_particle *pool, int64_t n,
		 uint32_t *sat)
{
	mot_q32 end = (n + 1) * ONE, frame = mot_steps_frame(&ps->steps, end, sat), rate;
	struct mot_rng r;
	int64_t count, i;
	uint32_t s = 0;

	r.s = h->rng;
	/* N = M + r V, particles a second */
	rate = mot_add_sat(val(ps, curves, MOT_PC_RATE, frame, sat),
			   mot_mul(mot_rng_sym(&r), val(ps, curves, MOT_PC_SPREAD, frame, sat), sat),
			   sat);
	if (rate > 0)
		h->carry = mot_add_sat(h->carry, hmul(ps, rate, sat), sat);
	count = h->carry >> 32;
	h->carry -= count * ONE;
	for (i = 0; i < count; i++) {
		mot_q32 birth = n * ONE + mot_muldiv(i + 1, ONE, count, sat), life, lo, hi;
		struct mot_particle *q;
		int k;

		/* every draw is made whether the particle finds a slot or not:
		 * the sequence does not depend on the pool's size */
		mot_q32 d[12];

		for (k = 0; k < 12; k++)
			d[k] = mot_rng_unit(&r);
		while (s < ps->npool && pool[s].used && pool[s].death > birth)
			s++;
		if (s == ps->npool) {
			if (h->first_drop < 0)
				h->first_drop = n + 1;
			h->dropped++;
			continue;
		}
		life = 0;
		lo = val(ps, curves, MOT_PC_LIFE_LO, frame, sat);
		hi = val(ps, curves, MOT_PC_LIFE_HI, frame, sat);
		life = mot_add_sat(lo, mot_mul(mot_sub_sat(hi, lo, sat), d[6], sat), sat);
		if (life < ONE / 1000000)
			continue; /* a lifetime under a microsecond: never shown */
		q = &pool[s];
		for (k = 0; k < 3; k++) {
			lo = val(ps, curves, MOT_PC_POS_LO + k, frame, sat);
			hi = val(ps, curves, MOT_PC_POS_HI + k, frame, sat);
			q->p0[k] = mot_add_sat(lo, mot_mul(mot_sub_sat(hi, lo, sat), d[k], sat), sat);
			lo = val(ps, curves, MOT_PC_VEL_LO + k, frame, sat);
			hi = val(ps, curves, MOT_PC_VEL_HI + k, frame, sat);
			q->v0[k] = mot_add_sat(lo, mot_mul(mot_sub_sat(hi, lo, sat), d[3 + k], sat),
					       sat);
			lo = val(ps, curves, MOT_PC_COL_LO + k, frame, sat);
			hi = val(ps, curves, MOT_PC_COL_HI + k, frame, sat);
			q->col[k] = mot_add_sat(lo, mot_mul(mot_sub_sat(hi, lo, sat), d[8 + k], sat),
						sat);
		}
		lo = val(ps, curves, MOT_PC_SIZE_LO, frame, sat);
		hi = val(ps, curves, MOT_PC_SIZE_HI, frame, sat);
		q->size = mot_add_sat(lo, mot_mul(mot_sub_sat(hi, lo, sat), d[7], sat), sat);
		lo = val(ps, curves, MOT_PC_ALPHA_LO, frame, sat);
		hi = val(ps, curves, MOT_PC_ALPHA_HI, frame, sat);
		q->alpha = mot_add_sat(lo, mot_mul(mot_sub_sat(hi, lo, sat), d[11], sat), sat);
		q->used = 1;
		q->birth = birth;
		q->death = mot_add_sat(birth,
				       mot_muldiv(life, ps->steps.rate_num, ps->steps.rate_den, sat),
				       sat);
		q->inv_life = mot_div(ONE, life, sat);
		if (ps->motion == MOT_PARTICLES_NEWTON) {
			mot_q32 t = q->death < end ? q->death : end;

			newborn(ps, q, hmul(ps, t - birth, sat), sat);
		}
		s++;
	}
	h->rng = r.s;
}

/* Deaths in (n, n + 1] of particles alive at n: their state at death, on
 * the step's Hermite curve (Newtonian) or their script (scripted: nothing
 * to keep). */
static void deaths(const struct mot_particles *ps, const struct mot_particle *a,
		   struct mot_particle *b, int64_t n, uint32_t *sat)
{
	mot_q32 t0 = n * ONE, t1 = (n + 1) * ONE, H = hmul(ps, ONE, sat);
	uint32_t i;

	if (ps->motion != MOT_PARTICLES_NEWTON)
		return;
	for (i = 0; i < ps->npool; i++) {
		struct mot_particle *q = &b[i];
		mot_q32 p[3], v[3];
		int k;

		if (!alive_at(&a[i], t0) || q->death > t1)
			continue;
		hermite(p, v, a[i].p, a[i].v, q->p, q->v, q->death - t0, H, sat);
		for (k = 0; k < 3; k++) {
			q->p[k] = p[k];
			q->v[k] = v[k];
			q->a[k] = 0;
		}
	}
}

/* Velocity Verlet over one step for every particle alive at n (newborns
 * of the step are placed by emit()). */
static void verlet(const struct mot_particles *ps, const struct mot_curve *curves,
		   const struct mot_particle *a, struct mot_particle *b, int64_t n,
		   struct mot_particles_scratch *sc, uint32_t *sat)
{
	mot_q32 t0 = n * ONE, t1 = (n + 1) * ONE, frame1 = mot_steps_frame(&ps->steps, t1, sat);
	mot_q32(*vp)[3] = sc->vp;
	uint32_t i;
	int k;

	for (i = 0; i < ps->npool; i++) {
		struct mot_particle *q = &b[i];

		if (!alive_at(&a[i], t0))
			continue;
		for (k = 0; k < 3; k++) {
			mot_q32 ah = half(hmul(ps, a[i].a[k], sat));

			q->v[k] = mot_add_sat(a[i].v[k], ah, sat);      /* v + a h/2 */
			q->p[k] = mot_add_sat(a[i].p[k], hmul(ps, q->v[k], sat), sat);
			vp[i][k] = mot_add_sat(q->v[k], ah, sat);       /* v + a h */
		}
		if (ps->ground && q->p[1] < ps->ground_y) {
			/* bounce: the depth below the plane reflected and scaled */
			q->p[1] = mot_add_sat(ps->ground_y,
					      mot_mul(mot_sub_sat(ps->ground_y, q->p[1], sat),
						      ps->restitution, sat), sat);
			if (q->v[1] < 0)
				q->v[1] = -mot_mul(q->v[1], ps->restitution, sat);
			if (vp[i][1] < 0)
				vp[i][1] = -mot_mul(vp[i][1], ps->restitution, sat);
		}
	}
	for (i = 0; i < ps->npins; i++) {
		const struct mot_pin *pin = &ps->pins[i];

		pin_pos(ps, curves, pin, frame1, b[pin->i].p, sat);
	}
	forces(ps, b, vp, t0, sc, sat);
	for (i = 0; i < ps->npool; i++) {
		if (!alive_at(&a[i], t0))
			continue;
		for (k = 0; k < 3; k++)
			b[i].v[k] = mot_add_sat(b[i].v[k], half(hmul(ps, b[i].a[k], sat)), sat);
	}
	/* a pin moves as its keys say: its velocity the step's mean, no
	 * acceleration of its own */
	for (i = 0; i < ps->npins; i++) {
		const struct mot_pin *pin = &ps->pins[i];
		struct mot_particle *q = &b[pin->i];

		for (k = 0; k < 3; k++) {
			q->v[k] = mot_muldiv(mot_sub_sat(q->p[k], a[pin->i].p[k], sat),
					     ps->steps.rate_num, ps->steps.rate_den, sat);
			q->a[k] = 0;
		}
	}
}

void mot_particles_step(const void *sys, const struct mot_curve *curves, const void *in,
			void *out, int64_t n, void *scratch, uint32_t *sat)
{
	const struct mot_particles *ps = sys;
	const struct mot_particle *a = cpool_of(in);
	struct mot_particle *b;
	struct mot_particles_head *h;
	mot_q32 t1 = (n + 1) * ONE;
	uint32_t i;

	mot_copy(out, in, ps->steps.state_bytes);
	h = head_of(out);
	b = pool_of(out);
	if (ps->motion == MOT_PARTICLES_NEWTON)
		verlet(ps, curves, a, b, n, scratch, sat);
	deaths(ps, a, b, n, sat);
	if (ps->emit)
		emit(ps, curves, h, b, n, sat);
	h->live = 0;
	for (i = 0; i < ps->npool; i++)
		h->live += alive_at(&b[i], t1);
}

/* ---- the build ---------------------------------------------------------------------- */

static bool curves_ok(const struct mot_particles *ps, uint32_t ncurves)
{
	uint32_t i;
	int k;

	for (k = 0; k < MOT_PC_COUNT; k++)
		if (ps->curve[k] < -1 || (ps->curve[k] >= 0 && (uint32_t)ps->curve[k] >= ncurves))
			return false;
	for (i = 0; i < ps->npins; i++)
		for (k = 0; k < 3; k++)
			if (ps->pins[i].ch[k] < -1 ||
			    (ps->pins[i].ch[k] >= 0 && (uint32_t)ps->pins[i].ch[k] >= ncurves))
				return false;
	return true;
}

/*
 * Verlet's stability: w h < 2 for the highest frequency w of the springs,
 * bounded by Gershgorin's theorem: w^2 <= max over particles of 2 k deg
 * (deg springs meet there); and explicit damping: h (drag + 2 c deg) < 1.
 * Kept with a margin (w h < 1.8).
 */
static int stable(const struct mot_particles *ps, uint32_t *deg, uint32_t *sat)
{
	mot_q32 h = hmul(ps, ONE, sat), h2 = mot_mul(h, h, sat);
	uint32_t i, maxdeg = 0;

	for (i = 0; i < ps->npool; i++)
		deg[i] = 0;
	for (i = 0; i < ps->nsprings; i++) {
		deg[ps->springs[i].i]++;
		deg[ps->springs[i].j]++;
	}
	for (i = 0; i < ps->npool; i++)
		maxdeg = deg[i] > maxdeg ? deg[i] : maxdeg;
	if (!maxdeg)
		return mot_mul(h, ps->drag, sat) < ONE ? MOT_OK : MOT_E_RANGE;
	if (mot_mul(h2, mot_mul(MOT_Q32_INT(2 * (int64_t)maxdeg), ps->spring_k, sat), sat) >=
	    MOT_Q32_INT(324) / 100)
		return MOT_E_RANGE;
	if (mot_mul(h, mot_add_sat(ps->drag, mot_mul(MOT_Q32_INT(2 * (int64_t)maxdeg),
						     ps->spring_c, sat), sat), sat) >= ONE)
		return MOT_E_RANGE;
	return MOT_OK;
}

static void watch(const void *sys, const void *state, int64_t n, void *ctx)
{
	const struct mot_particles_head *h = state;
	struct mot_particles *ps = ctx;

	(void)sys;
	(void)n;
	if (h->live > ps->peak)
		ps->peak = h->live;
	ps->dropped = h->dropped;
	ps->first_drop = h->first_drop;
}

int mot_particles_init(struct mot_particles *ps, const struct mot_curve *curves,
		       uint32_t ncurves, void *a, void *b, struct mot_particles_scratch *sc,
		       uint32_t *sat)
{
	struct mot_particles_head *h;
	struct mot_particle *pool;
	uint32_t i;
	int k, err;

	if (ps->motion > MOT_PARTICLES_NEWTON || !ps->npool || !curves_ok(ps, ncurves) ||
	    !ps->steps.ckpt || ps->steps.state_bytes != mot_particles_state_bytes(ps->npool) ||
	    (!ps->emit && !ps->rest) || (ps->nsprings && !ps->springs) ||
	    (ps->npins && !ps->pins) || !sc || !sc->vp || !sc->deg || ps->pair_radius < 0 ||
	    (ps->ground && (ps->restitution < 0 || ps->restitution > ONE)))
		return MOT_E_INVAL;
	for (i = 0; i < ps->nsprings; i++)
		if (ps->springs[i].i >= ps->npool || ps->springs[i].j >= ps->npool ||
		    ps->springs[i].i == ps->springs[i].j || ps->springs[i].rest < 0)
			return MOT_E_INVAL;
	for (i = 0; i < ps->npins; i++)
		if (ps->pins[i].i >= ps->npool || !ps->rest)
			return MOT_E_INVAL;
	if (ps->motion == MOT_PARTICLES_SCRIPTED && (ps->nsprings || ps->npins || !ps->emit))
		return MOT_E_INVAL;
	if (ps->pair_radius > 0 && !sc->has_grid)
		return MOT_E_INVAL;
	ps->nout = ps->emit ? MOT_PART_NOUT : 3;
	err = stable(ps, sc->deg, sat);
	if (err)
		return err;
	/* step 0: the lattice at rest, or an empty pool */
	h = head_of(ps->steps.ckpt);
	pool = pool_of(ps->steps.ckpt);
	h->rng = ps->seed;
	h->carry = 0;
	h->dropped = 0;
	h->first_drop = -1;
	h->live = ps->emit ? 0 : ps->npool;
	for (i = 0; i < ps->npool; i++) {
		struct mot_particle *q = &pool[i];

		for (k = 0; k < 3; k++) {
			q->p[k] = q->p0[k] = ps->rest ? ps->rest[i][k] : 0;
			q->v[k] = q->v0[k] = q->a[k] = 0;
			q->col[k] = 0;
		}
		q->size = q->alpha = 0;
		q->used = !ps->emit;
		q->birth = 0;
		q->death = ps->emit ? 0 : MOT_Q32_MAX;
		q->inv_life = 0;
		if (!ps->emit)
			for (k = 0; k < 3; k++)
				sc->vp[i][k] = 0;
	}
	if (!ps->emit) {
		const struct mot_curve *c = curves;
		mot_q32 f0 = ps->steps.f0;

		for (i = 0; i < ps->npins; i++)
			pin_pos(ps, c, &ps->pins[i], f0, pool[ps->pins[i].i].p, sat);
		if (ps->motion == MOT_PARTICLES_NEWTON)
			forces(ps, pool, sc->vp, 0, sc, sat);
		for (i = 0; i < ps->npins; i++)
			for (k = 0; k < 3; k++)
				pool[ps->pins[i].i].a[k] = 0;
	}
	ps->peak = h->live;
	ps->dropped = 0;
	ps->first_drop = -1;
	mot_steps_run(&ps->steps, a, b, mot_particles_step, ps, curves, sc, watch, ps, sat);
	return MOT_OK;
}

/* ---- evaluation --------------------------------------------------------------------- */

/* The look of a particle of age `age` seconds (alive) or dead. */
static void look(const struct mot_particles *ps, const struct mot_curve *curves,
		 const struct mot_particle *q, mot_q32 age, bool alive, mot_q32 *o,
		 uint32_t *sat)
{
	mot_q32 f = alive ? mot_mul(age, q->inv_life, sat) : ONE;
	int k;

	f = f < 0 ? 0 : f > ONE ? ONE : f;
	for (k = 0; k < 3; k++)
		o[MOT_PART_R + k] = mot_mul(q->col[k], val(ps, curves, MOT_PC_AGE_R + k, f, sat),
					    sat);
	o[MOT_PART_ALPHA] = alive ? mot_mul(q->alpha, val(ps, curves, MOT_PC_AGE_ALPHA, f, sat),
					    sat) : 0;
	o[MOT_PART_SIZE] = alive ? mot_mul(q->size, val(ps, curves, MOT_PC_AGE_SIZE, f, sat),
					   sat) : 0;
}

/* Where a scripted particle is at step position t (its death held). */
static void scripted(const struct mot_particles *ps, const struct mot_particle *q, mot_q32 t,
		     mot_q32 p[3], uint32_t *sat)
{
	mot_q32 age = hmul(ps, (t < q->death ? t : q->death) - q->birth, sat);
	mot_q32 a2 = half(mot_mul(age, age, sat));
	int k;

	for (k = 0; k < 3; k++)
		p[k] = mot_add_sat(mot_add_sat(q->p0[k], mot_mul(q->v0[k], age, sat), sat),
				   mot_mul(ps->gravity[k], a2, sat), sat);
}

/* One slot at step position t in [n, n + 1]: a holds step n, b step n + 1. */
static void slot(const struct mot_particles *ps, const struct mot_curve *curves,
		 const struct mot_particle *a, const struct mot_particle *b, int64_t n,
		 mot_q32 t, mot_q32 *o, uint32_t *sat)
{
	mot_q32 t0 = n * ONE, t1 = (n + 1) * ONE;
	const struct mot_particle *q;
	bool alive;
	int k;

	/* the slot's particle at t: b's, unless b's is born after t (then the
	 * one before it, a's) */
	q = b->used && b->birth <= t ? b : a;
	if (!q->used) {
		for (k = 0; k < 3; k++)
			o[k] = q->p[k];
		if (ps->emit) {
			o[MOT_PART_R] = o[MOT_PART_G] = o[MOT_PART_B] = 0;
			o[MOT_PART_ALPHA] = o[MOT_PART_SIZE] = 0;
		}
		return;
	}
	alive = t < q->death;
	if (ps->motion == MOT_PARTICLES_SCRIPTED) {
		scripted(ps, q, t, o, sat);
	} else if (q == a && a != b && !(b->used && b->birth == a->birth)) {
		/* the particle b replaced: from where it was at n, under its
		 * acceleration then, to its death (before b's birth) */
		mot_q32 dt = hmul(ps, (t < a->death ? t : a->death) - t0, sat);

		for (k = 0; k < 3; k++)
			o[k] = a->death <= t0 ? a->p[k] :
			       mot_add_sat(mot_add_sat(a->p[k], mot_mul(a->v[k], dt, sat), sat),
					   mot_mul(half(a->a[k]), mot_mul(dt, dt, sat), sat), sat);
	} else if (q->death <= t0) {
		for (k = 0; k < 3; k++)
			o[k] = q->p[k];
	} else {
		/* on the Hermite curve from its state at n (or its birth) to its
		 * state at n + 1 (or its death) */
		bool born = q->birth > t0;
		mot_q32 s0 = born ? q->birth : t0, s1 = q->death < t1 ? q->death : t1;
		mot_q32 tt = t < s1 ? t : s1, s;

		if (s0 == t0 && s1 == t1)
			s = tt - t0;
		else
			s = s1 > s0 ? mot_div(tt - s0, s1 - s0, sat) : ONE;
		hermite(o, NULL, born ? q->p0 : a->p, born ? q->v0 : a->v, b->p, b->v, s,
			hmul(ps, s1 - s0, sat), sat);
	}
	if (ps->emit)
		look(ps, curves, q, hmul(ps, t - q->birth, sat), alive, o, sat);
}

void mot_particles_eval(const struct mot_particles *ps, const struct mot_curve *curves,
			struct mot_steps_cache *c, struct mot_particles_scratch *sc,
			mot_q32 frame, mot_q32 *out, uint32_t *sat)
{
	mot_q32 t = mot_steps_pos(&ps->steps, frame, sat);
	int64_t n = t >> 32;
	const struct mot_particle *a, *b;
	uint32_t i;

	if (n >= ps->steps.nsteps)
		n = ps->steps.nsteps - 1;
	mot_steps_seek(&ps->steps, c, n, mot_particles_step, ps, curves, sc, sat);
	a = cpool_of(c->a);
	b = cpool_of(c->b);
	for (i = 0; i < ps->npool; i++)
		slot(ps, curves, &a[i], &b[i], n, t, out + (size_t)i * ps->nout, sat);
}
