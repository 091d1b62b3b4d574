/* SPDX-License-Identifier: MIT */
/*
 * scene_build_priv.h - what the two files of the builder share
 * (scene_build.c: nodes, strands, camera, cycles, attributes;
 * scene_build_sys.c: surfaces, particle systems, flocks, aims). Not a
 * public interface (see scene_desc.h).
 */
#ifndef STRAND_SCENE_BUILD_PRIV_H
#define STRAND_SCENE_BUILD_PRIV_H

#include "motion/arena.h"
#include "scene_desc.h"

/* Where the layout pass puts things; filled on the real pass. */
struct layout {
	struct mot_arena *a;
	struct mot_scene *sc;
	struct mot_node *nodes;
	struct mot_curve *curves;
	struct mot_rot_track *rot;
	struct mot_free_strand *free;
	struct mot_camera *camera;
	struct mot_cycle *cycles;
	int32_t *attr_curve;
	uint32_t ncurves, nrot, nfree;
	struct mot_system *sys;
	struct mot_aim *aims;
	uint32_t nsysout;
};

#define ALLOC(a, type, n) ((type *)mot_arena_alloc((a), sizeof(type) * (size_t)(n), _Alignof(type)))

static inline bool curve_used(const struct sd_curve *c)
{
	return c->nkeys > 0;
}

/* One curve: its keys and segments from the arena, converted by `scale`
 * (1/360 for degrees), prepared. *bad_key: the key at fault. */
int sb_curve(struct layout *l, struct mot_curve *c, const struct sd_curve *sc, double scale,
	     bool integral, uint32_t *bad_key);

/* Record where the build failed; returns code. */
int sb_err(struct scene_build_err *e, int code, int node, const char *what, uint32_t key);

/* The curves the systems need (for the count). */
uint32_t sb_sys_curves(const struct scene_desc *d);

/* The systems' and aims' layout and fill (curves from *ci on). */
int sb_systems(struct layout *l, const struct scene_desc *d, uint32_t *ci,
	       struct scene_build_err *e);

/* The systems' runs over their span, then the aims' pan grids (the fill
 * pass, once the scene is complete). */
int sb_systems_init(struct layout *l, const struct scene_desc *d, struct scene_build_err *e);
int sb_aims_init(struct layout *l, const struct scene_desc *d, struct scene_build_err *e);

#endif /* STRAND_SCENE_BUILD_PRIV_H */
