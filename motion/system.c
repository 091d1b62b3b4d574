/* SPDX-License-Identifier: MIT */
/* system.c - surfaces, particles and flocks as parts of a scene (see system.h). */
#include "system.h"

/* The layout of an evaluation's block, measured (base NULL) or made. */
struct lay {
	unsigned char *base;
	size_t used;
};

static void *take(struct lay *l, size_t n)
{
	void *p = l->base ? l->base + l->used : NULL;

	l->used += (n + 7) & ~(size_t)7;
	return p;
}

static size_t layout(struct mot_sys_eval *e, const struct mot_system *s, unsigned char *base)
{
	struct lay l = { base, 0 };
	struct mot_sys_eval tmp;
	uint32_t n, buckets;

	if (!e)
		e = &tmp;
	e->ctl = NULL;
	e->ps = NULL;
	e->fs = NULL;
	e->cache.a = e->cache.b = NULL;
	switch (s->kind) {
	case MOT_SYS_SURFACE:
		e->ctl = take(&l, sizeof(mot_q32) * mot_surface_scratch_count(s->surface));
		break;
	case MOT_SYS_PARTICLES:
		n = s->particles->npool;
		e->cache.a = take(&l, mot_particles_state_bytes(n));
		e->cache.b = take(&l, mot_particles_state_bytes(n));
		e->ps = take(&l, sizeof(*e->ps));
		if (e->ps) {
			e->ps->has_grid = false;
			e->ps->vp = take(&l, sizeof(mot_q32[3]) * n);
			e->ps->deg = take(&l, sizeof(uint32_t) * n);
		} else {
			take(&l, sizeof(mot_q32[3]) * n);
			take(&l, sizeof(uint32_t) * n);
		}
		if (s->particles->pair_radius > 0) {
			uint32_t *head, *next;
			int32_t(*cell)[3];

			buckets = mot_grid_buckets(n);
			head = take(&l, sizeof(uint32_t) * buckets);
			next = take(&l, sizeof(uint32_t) * n);
			cell = take(&l, sizeof(int32_t[3]) * n);
			if (e->ps)
				e->ps->has_grid = mot_grid_init(&e->ps->grid, s->particles->pair_radius,
								buckets, head, next, cell, n) == MOT_OK;
		}
		break;
	case MOT_SYS_FLOCK:
		n = s->flock->n;
		e->cache.a = take(&l, mot_flock_state_bytes(n));
		e->cache.b = take(&l, mot_flock_state_bytes(n));
		e->fs = take(&l, sizeof(*e->fs));
		buckets = mot_grid_buckets(n);
		{
			uint32_t *head = take(&l, sizeof(uint32_t) * buckets);
			uint32_t *next = take(&l, sizeof(uint32_t) * n);
			int32_t(*cell)[3] = take(&l, sizeof(int32_t[3]) * n);

			if (e->fs)
				mot_grid_init(&e->fs->grid, s->flock->radius, buckets, head, next, cell,
					      n);
		}
		break;
	default:
		break;
	}
	e->cache.n = -1;
	e->cache.b_ok = false;
	return l.used;
}

size_t mot_system_eval_bytes(const struct mot_system *s)
{
	return layout(NULL, s, NULL);
}

int mot_system_eval_init(struct mot_sys_eval *e, const struct mot_system *s, void *block,
			 size_t bytes)
{
	if (bytes < mot_system_eval_bytes(s) || (!block && bytes))
		return MOT_E_CAPACITY;
	layout(e, s, block);
	return MOT_OK;
}

void mot_system_eval_reset(struct mot_sys_eval *e)
{
	e->cache.n = -1;
	e->cache.b_ok = false;
}

int mot_system_init(struct mot_system *s, const struct mot_curve *curves, uint32_t ncurves,
		    struct mot_sys_eval *e, uint32_t *sat)
{
	int err;

	mot_system_eval_reset(e);
	switch (s->kind) {
	case MOT_SYS_SURFACE:
		err = mot_surface_init(s->surface, ncurves, sat);
		s->nitems = s->surface->nsu * s->surface->nsv;
		s->per = 3;
		break;
	case MOT_SYS_PARTICLES:
		err = mot_particles_init(s->particles, curves, ncurves, e->cache.a, e->cache.b, e->ps,
					 sat);
		s->nitems = s->particles->npool;
		s->per = s->particles->nout;
		break;
	case MOT_SYS_FLOCK:
		err = mot_flock_init(s->flock, curves, ncurves, e->cache.a, e->cache.b, e->fs, sat);
		s->nitems = s->flock->n;
		s->per = MOT_FLOCK_NOUT;
		break;
	default:
		return MOT_E_INVAL;
	}
	mot_system_eval_reset(e);
	s->nout = s->nitems * s->per;
	return err;
}

void mot_system_eval(const struct mot_system *s, const struct mot_curve *curves,
		     struct mot_cursor *cursors, struct mot_sys_eval *e, mot_q32 frame,
		     mot_q32 *out, uint32_t *sat)
{
	switch (s->kind) {
	case MOT_SYS_SURFACE:
		mot_surface_eval(s->surface, curves, cursors, frame, e->ctl, out, sat);
		break;
	case MOT_SYS_PARTICLES:
		mot_particles_eval(s->particles, curves, &e->cache, e->ps, frame, out, sat);
		break;
	case MOT_SYS_FLOCK:
		mot_flock_eval(s->flock, curves, &e->cache, e->fs, frame, out, sat);
		break;
	default:
		break;
	}
}
