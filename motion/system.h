/* SPDX-License-Identifier: MIT */
/*
 * system.h - the seed's advanced systems as parts of a scene: soft
 * surfaces, particle systems and flocks (section 9, 10), each writing a
 * block of values into the pose (pose->sysout[out0 .. out0 + nout)), the
 * channels an array of actuators takes.
 *
 * A system's constant part (its description, curves, prepared weights,
 * checkpoints) is the scene's, read-only while it plays; what an
 * evaluation changes (the two states a tick lies between, the neighbour
 * grid, the surface's control values) is the evaluation's, one block per
 * system sized by mot_system_eval_bytes(), so that every evaluating thread
 * (the loop, check, export) reaches the same bits on its own.
 */
#ifndef MOT_SYSTEM_H
#define MOT_SYSTEM_H

#include "flock.h"
#include "particles.h"
#include "surface.h"

enum mot_sys_kind {
	MOT_SYS_SURFACE,
	MOT_SYS_PARTICLES,
	MOT_SYS_FLOCK,
};

struct mot_system {
	uint32_t kind;    /* enum mot_sys_kind */
	uint32_t out0;    /* its first value in pose->sysout */
	uint32_t nout;    /* values it writes */
	uint32_t nitems;  /* samples, slots or members */
	uint32_t per;     /* values an item (nout = nitems * per) */
	struct mot_surface *surface;
	struct mot_particles *particles;
	struct mot_flock *flock;
};

/* One evaluation's part of a system. */
struct mot_sys_eval {
	struct mot_steps_cache cache; /* stepped systems */
	mot_q32 *ctl;                 /* surfaces: control values and a row */
	struct mot_particles_scratch *ps;
	struct mot_flock_scratch *fs;
};

/* Bytes of the block mot_system_eval_init() lays out (8-byte aligned). */
size_t mot_system_eval_bytes(const struct mot_system *s);

/* Lay out e in block (mot_system_eval_bytes() of it, 8-byte aligned) and
 * reset it. MOT_E_CAPACITY when bytes is short. */
int mot_system_eval_init(struct mot_sys_eval *e, const struct mot_system *s, void *block,
			 size_t bytes);

/* Forget the cached states (the next evaluation seeks). */
void mot_system_eval_reset(struct mot_sys_eval *e);

/* Prepare the system (its kind's init: weights, the run over its span into
 * the checkpoints), with e (laid out for it) as the run's scratch. Init
 * only. */
int mot_system_init(struct mot_system *s, const struct mot_curve *curves, uint32_t ncurves,
		    struct mot_sys_eval *e, uint32_t *sat);

/* The system's values at a frame into out (nout values). Real-time safe. */
void mot_system_eval(const struct mot_system *s, const struct mot_curve *curves,
		     struct mot_cursor *cursors, struct mot_sys_eval *e, mot_q32 frame,
		     mot_q32 *out, uint32_t *sat);

#endif /* MOT_SYSTEM_H */
