/* SPDX-License-Identifier: MIT */
/*
 * scene_build_sys.c - the systems of a scene description (surfaces,
 * particle systems, flocks) and its aims into the core's block, on the
 * builder's two passes (scene_build.c): measured, then filled. A system's
 * checkpoints are in the block too; its run over the span, and the aims'
 * march, happen once the scene is complete.
 */
#include "scene_build_priv.h"
#include "motion/trig.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Checkpoints: every CKPT_EVERY steps at least, more sparse when a
 * system's would take more than CKPT_BYTES. */
#define CKPT_EVERY 16u
#define CKPT_BYTES ((uint64_t)64 << 20)

uint32_t sb_sys_curves(const struct scene_desc *d)
{
	uint32_t i, k, n = 0;

	for (i = 0; i < d->nsys; i++) {
		const struct sd_system *s = &d->sys[i];

		if (s->kind == SD_SURFACE) {
			for (k = 0; k < s->surface->ncu * s->surface->ncv * 3; k++)
				n += curve_used(&s->surface->curve[k]);
		} else if (s->kind == SD_PARTICLES) {
			const struct sd_particles *p = s->particles;

			for (k = 0; k < MOT_PC_COUNT; k++)
				n += curve_used(&p->c[k]);
			for (k = 0; k < p->npins * 3; k++)
				n += curve_used(&p->pins[k / 3].off[k % 3]);
		} else {
			for (k = 0; k < 3; k++)
				n += curve_used(&s->flock->goal_c[k]);
		}
	}
	return n;
}

/* A curve into the next slot (ci), its index into *idx; -1 when unused. */
static int curve(struct layout *l, const struct sd_curve *c, double scale, uint32_t *ci,
		 int32_t *idx, const char *name, struct scene_build_err *e)
{
	bool fill = l->a->base != NULL;
	uint32_t bad = UINT32_MAX;
	int err;

	if (idx)
		*idx = -1;
	if (!curve_used(c))
		return 0;
	err = sb_curve(l, fill ? &l->curves[*ci] : NULL, c, scale, false, &bad);
	if (err)
		return sb_err(e, err, -1, name, bad);
	if (idx)
		*idx = (int32_t)*ci;
	(*ci)++;
	return 0;
}

static int q32(double v, mot_q32 *out, const char *name, struct scene_build_err *e)
{
	return sd_to_q32(v, out) ? 0 : sb_err(e, MOT_E_RANGE, -1, name, UINT32_MAX);
}

static int vec(const double *v, mot_q32 *out, const char *name, struct scene_build_err *e)
{
	int k;

	for (k = 0; k < 3; k++)
		if (!sd_to_q32(v[k], &out[k]))
			return sb_err(e, MOT_E_RANGE, -1, name, UINT32_MAX);
	return 0;
}

/* The time line over the scene's span, checkpoints laid out. */
static int steps(struct layout *l, const struct scene_desc *d, struct mot_steps *st,
		 uint32_t rate_num, uint32_t rate_den, uint32_t sbytes, const char *name,
		 struct scene_build_err *e)
{
	struct mot_timing t;
	struct mot_steps tmp;
	mot_q32 f0, f1;
	uint64_t every, all;
	int err;

	if (!st)
		st = &tmp;
	err = mot_timing_init(&t, d->rate_num, d->rate_den, d->tick_hz);
	if (!err && (!sd_to_q32(d->frame_first, &f0) || !sd_to_q32(d->frame_last, &f1)))
		err = MOT_E_RANGE;
	if (!err)
		err = mot_steps_init(st, &t, f0, f1, rate_num, rate_den, 1, sbytes);
	if (err)
		return sb_err(e, err, -1, name, UINT32_MAX);
	all = (uint64_t)(st->nsteps + 1) * sbytes;
	every = d->ckpt_every ? d->ckpt_every : CKPT_EVERY;
	if (all / every > CKPT_BYTES)
		every = (all + CKPT_BYTES - 1) / CKPT_BYTES;
	if (every > (uint64_t)st->nsteps)
		every = (uint64_t)st->nsteps;
	st->every = (uint32_t)every;
	st->ckpt = mot_arena_alloc(l->a, (size_t)mot_steps_ckpt_count(st) * sbytes, 64);
	if (l->a->base && !st->ckpt)
		return sb_err(e, MOT_E_CAPACITY, -1, name, UINT32_MAX);
	return 0;
}

static int surface(struct layout *l, const struct sd_surface *sd, struct mot_system *sys,
		   uint32_t *ci, struct scene_build_err *e)
{
	uint32_t n = sd->ncu * sd->ncv * 3, i;
	struct mot_surface *s = ALLOC(l->a, struct mot_surface, 1);
	int32_t *idx = ALLOC(l->a, int32_t, n);
	mot_q32 *rest = ALLOC(l->a, mot_q32, n);
	struct mot_surface_w *wu = ALLOC(l->a, struct mot_surface_w, sd->nsu);
	struct mot_surface_w *wv = ALLOC(l->a, struct mot_surface_w, sd->nsv);
	mot_q32 *fixed = ALLOC(l->a, mot_q32, (size_t)sd->nsu * sd->nsv * 3);
	bool fill = l->a->base != NULL;
	int err;

	if (fill && (!s || !idx || !rest || !wu || !wv || !fixed))
		return sb_err(e, MOT_E_CAPACITY, -1, sd->name, UINT32_MAX);
	for (i = 0; i < n; i++) {
		err = curve(l, &sd->curve[i], 1.0, ci, fill ? &idx[i] : NULL, sd->name, e);
		if (!err && fill)
			err = q32(sd->rest[i], &rest[i], sd->name, e);
		if (err)
			return err;
	}
	if (!fill)
		return 0;
	memset(s, 0, sizeof(*s));
	s->basis = sd->basis;
	s->ncu = sd->ncu;
	s->ncv = sd->ncv;
	s->nsu = sd->nsu;
	s->nsv = sd->nsv;
	s->curve = idx;
	s->rest = rest;
	s->wu = wu;
	s->wv = wv;
	s->fixed = fixed;
	sys->kind = MOT_SYS_SURFACE;
	sys->surface = s;
	return 0;
}

/* The springs of a lattice: rows and columns, and both diagonals with shear. */
static uint32_t lattice_springs(const struct sd_particles *p, struct mot_spring *out,
				const mot_q32 (*rest)[3])
{
	uint32_t i, j, n = 0;

	for (i = 0; i < p->lu; i++)
		for (j = 0; j < p->lv; j++) {
			uint32_t a = i * p->lv + j, b[4], k, nb = 0;

			if (j + 1 < p->lv)
				b[nb++] = a + 1;
			if (i + 1 < p->lu)
				b[nb++] = a + p->lv;
			if (p->shear && i + 1 < p->lu && j + 1 < p->lv)
				b[nb++] = a + p->lv + 1;
			if (p->shear && i + 1 < p->lu && j > 0)
				b[nb++] = a + p->lv - 1;
			for (k = 0; k < nb; k++, n++) {
				mot_q32 d[3];
				uint32_t sat = 0;
				int c;

				if (!out)
					continue;
				for (c = 0; c < 3; c++)
					d[c] = rest[b[k]][c] - rest[a][c];
				out[n] = (struct mot_spring){ a, b[k], mot_norm3(d, &sat) };
			}
		}
	return n;
}

static int particles(struct layout *l, const struct scene_desc *d, const struct sd_particles *sd,
		     struct mot_system *sys, uint32_t *ci, struct scene_build_err *e)
{
	bool fill = l->a->base != NULL;
	uint32_t npool = sd->emit ? sd->npool : sd->lu * sd->lv, nspr = 0, i, k;
	struct mot_particles *p = ALLOC(l->a, struct mot_particles, 1);
	mot_q32(*rest)[3] = NULL;
	struct mot_spring *springs = NULL;
	struct mot_pin *pins = ALLOC(l->a, struct mot_pin, sd->npins ? sd->npins : 1);
	int err;

	if (!sd->emit) {
		rest = (mot_q32(*)[3])mot_arena_alloc(l->a, sizeof(mot_q32[3]) * npool, 8);
		nspr = lattice_springs(sd, NULL, NULL);
		springs = ALLOC(l->a, struct mot_spring, nspr ? nspr : 1);
	}
	if (fill && (!p || !pins || (!sd->emit && (!rest || !springs))))
		return sb_err(e, MOT_E_CAPACITY, -1, sd->name, UINT32_MAX);
	if (fill)
		memset(p, 0, sizeof(*p));
	for (k = 0; k < MOT_PC_COUNT; k++) {
		err = curve(l, &sd->c[k], 1.0, ci, fill ? &p->curve[k] : NULL, sd->name, e);
		if (!err && fill)
			err = q32(sd->v[k], &p->value[k], sd->name, e);
		if (err)
			return err;
	}
	for (i = 0; i < sd->npins; i++)
		for (k = 0; k < 3; k++) {
			err = curve(l, &sd->pins[i].off[k], 1.0, ci, fill ? &pins[i].ch[k] : NULL,
				    sd->name, e);
			if (err)
				return err;
		}
	err = steps(l, d, fill ? &p->steps : NULL, sd->rate_num, sd->rate_den,
		    mot_particles_state_bytes(npool), sd->name, e);
	if (err || !fill)
		return err;
	p->motion = sd->motion;
	p->npool = npool;
	p->emit = sd->emit;
	p->seed = sd->seed;
	err = vec(sd->gravity, p->gravity, sd->name, e);
	if (!err)
		err = q32(sd->drag, &p->drag, sd->name, e);
	if (!err)
		err = q32(sd->ground_y, &p->ground_y, sd->name, e);
	if (!err)
		err = q32(sd->restitution, &p->restitution, sd->name, e);
	if (!err)
		err = q32(sd->pair_radius, &p->pair_radius, sd->name, e);
	if (!err)
		err = q32(sd->pair_strength, &p->pair_strength, sd->name, e);
	if (!err)
		err = q32(sd->spring_k, &p->spring_k, sd->name, e);
	if (!err)
		err = q32(sd->spring_c, &p->spring_c, sd->name, e);
	if (err)
		return err;
	p->ground = sd->ground;
	if (!sd->emit) {
		for (i = 0; i < sd->lu; i++)
			for (k = 0; k < sd->lv; k++) {
				double r[3] = { sd->origin[0] + k * sd->spacing[0], sd->origin[1],
						sd->origin[2] + i * sd->spacing[1] };

				err = vec(r, rest[i * sd->lv + k], sd->name, e);
				if (err)
					return err;
			}
		lattice_springs(sd, springs, (const mot_q32(*)[3])rest);
		p->rest = (const mot_q32(*)[3])rest;
		p->springs = springs;
		p->nsprings = nspr;
	}
	for (i = 0; i < sd->npins; i++)
		pins[i].i = sd->pins[i].row * sd->lv + sd->pins[i].col;
	p->pins = pins;
	p->npins = sd->npins;
	sys->kind = MOT_SYS_PARTICLES;
	sys->particles = p;
	return 0;
}

static int flock(struct layout *l, const struct scene_desc *d, const struct sd_flock *sd,
		 struct mot_system *sys, uint32_t *ci, struct scene_build_err *e)
{
	bool fill = l->a->base != NULL;
	struct mot_flock *f = ALLOC(l->a, struct mot_flock, 1);
	struct mot_obstacle *ob = ALLOC(l->a, struct mot_obstacle, sd->nobst ? sd->nobst : 1);
	uint32_t i, k;
	int err = 0;

	if (fill && (!f || !ob))
		return sb_err(e, MOT_E_CAPACITY, -1, sd->name, UINT32_MAX);
	if (fill)
		memset(f, 0, sizeof(*f));
	for (k = 0; k < 3; k++) {
		err = curve(l, &sd->goal_c[k], 1.0, ci, fill ? &f->goal_ch[k] : NULL, sd->name, e);
		if (!err && fill)
			err = q32(sd->goal_v[k], &f->goal_value[k], sd->name, e);
		if (err)
			return err;
	}
	err = steps(l, d, fill ? &f->steps : NULL, sd->rate_num, sd->rate_den,
		    mot_flock_state_bytes(sd->n), sd->name, e);
	if (err || !fill)
		return err;
	f->n = sd->n;
	f->seed = sd->seed;
	f->max_neighbours = sd->max_neighbours;
	f->goal = sd->goal;
	{
		const double *v[] = { &sd->start_r, &sd->start_dv, &sd->radius, &sd->sep,
				      &sd->w_sep, &sd->w_coh, &sd->w_ali, &sd->w_goal, &sd->w_obst,
				      &sd->margin, &sd->vmax, &sd->amax };
		mot_q32 *q[] = { &f->start_r, &f->start_dv, &f->radius, &f->sep, &f->w_sep,
				 &f->w_coh, &f->w_ali, &f->w_goal, &f->w_obst, &f->margin,
				 &f->vmax, &f->amax };

		for (k = 0; !err && k < sizeof(q) / sizeof(q[0]); k++)
			err = q32(*v[k], q[k], sd->name, e);
	}
	if (!err)
		err = vec(sd->start_c, f->start_c, sd->name, e);
	if (!err)
		err = vec(sd->start_v, f->start_v, sd->name, e);
	for (i = 0; !err && i < sd->nobst; i++) {
		err = vec(sd->obst[i].c, ob[i].c, sd->name, e);
		if (!err)
			err = q32(sd->obst[i].r, &ob[i].r, sd->name, e);
	}
	if (err)
		return err;
	f->obst = ob;
	f->nobst = sd->nobst;
	sys->kind = MOT_SYS_FLOCK;
	sys->flock = f;
	return 0;
}

/* The aims' grid: at least the densest any asks for. */
static uint32_t aim_sub(const struct scene_desc *d)
{
	uint32_t i, sub = 1;

	for (i = 0; i < d->naims; i++)
		sub = d->aims[i].sub > sub ? d->aims[i].sub : sub;
	return sub > MOT_AIM_SUB_MAX ? MOT_AIM_SUB_MAX : sub;
}

int sb_systems(struct layout *l, const struct scene_desc *d, uint32_t *ci,
	       struct scene_build_err *e)
{
	bool fill = l->a->base != NULL;
	uint32_t i, out = 0, sub = aim_sub(d), nref;
	mot_q32 f0 = 0, f1 = 0;
	int err = 0;

	l->sys = ALLOC(l->a, struct mot_system, d->nsys ? d->nsys : 1);
	l->aims = ALLOC(l->a, struct mot_aim, d->naims ? d->naims : 1);
	if (fill && (!l->sys || !l->aims))
		return sb_err(e, MOT_E_CAPACITY, -1, "scene", UINT32_MAX);
	for (i = 0; i < d->nsys; i++) {
		const struct sd_system *s = &d->sys[i];
		struct mot_system *sys = fill ? &l->sys[i] : NULL;

		if (sys)
			memset(sys, 0, sizeof(*sys));
		if (s->kind == SD_SURFACE)
			err = surface(l, s->surface, sys, ci, e);
		else if (s->kind == SD_PARTICLES)
			err = particles(l, d, s->particles, sys, ci, e);
		else
			err = flock(l, d, s->flock, sys, ci, e);
		if (err)
			return err;
		if (sys) {
			sys->out0 = out;
			sys->nitems = sd_sys_items(s);
			sys->per = sd_sys_per(s);
			sys->nout = sys->nitems * sys->per;
		}
		out += sd_sys_items(s) * sd_sys_per(s);
	}
	l->nsysout = out;
	sd_to_q32(d->frame_first, &f0);
	sd_to_q32(d->frame_last, &f1);
	nref = mot_aim_ref_count(f0, f1, sub);
	for (i = 0; i < d->naims; i++) {
		const struct sd_aim *sa = &d->aims[i];
		int32_t *ref = ALLOC(l->a, int32_t, nref);
		struct mot_aim *a = fill ? &l->aims[i] : NULL;

		if (!a)
			continue;
		if (!ref)
			return sb_err(e, MOT_E_CAPACITY, -1, sa->name, UINT32_MAX);
		memset(a, 0, sizeof(*a));
		err = vec(sa->at, a->at, sa->name, e);
		if (err)
			return err;
		if (sa->node >= 0) {
			a->src = MOT_AIM_SRC_NODE;
			a->index = (uint32_t)sa->node;
		} else {
			if (sa->sys < 0 || (uint32_t)sa->sys >= d->nsys ||
			    sa->item >= l->sys[sa->sys].nitems)
				return sb_err(e, MOT_E_INVAL, -1, sa->name, UINT32_MAX);
			a->src = MOT_AIM_SRC_SYS;
			a->index = l->sys[sa->sys].out0 + sa->item * l->sys[sa->sys].per;
		}
		a->f0 = f0;
		a->sub = sub;
		a->nref = nref;
		a->pan_ref = ref;
	}
	if (fill) {
		l->sc->nsys = d->nsys;
		l->sc->sys = l->sys;
		l->sc->nsysout = out;
		l->sc->naims = d->naims;
		l->sc->aims = l->aims;
	}
	return 0;
}

int sb_systems_init(struct layout *l, const struct scene_desc *d, struct scene_build_err *e)
{
	uint32_t i;

	for (i = 0; i < d->nsys; i++) {
		struct mot_system *s = &l->sys[i];
		size_t bytes = mot_system_eval_bytes(s);
		void *block = aligned_alloc(64, (bytes + 63) & ~(size_t)63);
		struct mot_sys_eval ev;
		uint32_t sat = 0, nout = s->nout;
		int err;

		if (!block)
			return sb_err(e, -ENOMEM, -1, "scene", UINT32_MAX);
		mot_system_eval_init(&ev, s, block, bytes);
		err = mot_system_init(s, l->curves, l->ncurves, &ev, &sat);
		free(block);
		if (!err && (sat || s->nout != nout))
			err = MOT_E_RANGE;
		if (err)
			return sb_err(e, err, -1, sd_sys_name(&d->sys[i]), UINT32_MAX);
	}
	return 0;
}

int sb_aims_init(struct layout *l, const struct scene_desc *d, struct scene_build_err *e)
{
	struct mot_aim_march *m;
	struct mot_eval ev;
	struct mot_pose pose;
	uint32_t bad = 0;
	int err;

	if (!d->naims)
		return 0;
	m = calloc(d->naims, sizeof(*m));
	if (!m || scene_eval_new(&ev, l->sc)) {
		free(m);
		return sb_err(e, -ENOMEM, -1, "scene", UINT32_MAX);
	}
	if (scene_pose_new(&pose, l->sc)) {
		scene_eval_free(&ev);
		free(m);
		return sb_err(e, -ENOMEM, -1, "scene", UINT32_MAX);
	}
	err = mot_scene_aims_init(l->sc, l->aims, &ev, &pose, m, &bad);
	scene_pose_free(&pose);
	scene_eval_free(&ev);
	free(m);
	return err ? sb_err(e, err, -1, d->aims[bad].name, UINT32_MAX) : 0;
}
