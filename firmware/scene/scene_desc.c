/* SPDX-License-Identifier: MIT */
/*
 * scene_desc.c - the range check shared by the loader and the builder: what
 * a number of the user's must satisfy to become a Q32.32 of the core. Kept
 * apart from scene_build.c so that the loader (and its tests) can use it
 * without linking the core.
 */
#include "scene_desc.h"

#include <math.h>

bool sd_to_q32(double v, mot_q32 *out)
{
	/* |v| < 2^30 keeps sums of a few terms inside Q32.32 (fix.h) */
	if (!isfinite(v) || fabs(v) >= 1073741824.0)
		return false;
	*out = (mot_q32)llround(v * 4294967296.0);
	return true;
}

bool sd_deg_to_turns(double deg, mot_q32 *out)
{
	return sd_to_q32(deg / 360.0, out);
}

uint32_t sd_sys_items(const struct sd_system *s)
{
	switch (s->kind) {
	case SD_SURFACE:
		return s->surface->nsu * s->surface->nsv;
	case SD_PARTICLES:
		return s->particles->emit ? s->particles->npool :
					    s->particles->lu * s->particles->lv;
	default:
		return s->flock->n;
	}
}

uint32_t sd_sys_per(const struct sd_system *s)
{
	switch (s->kind) {
	case SD_SURFACE:
		return 3;
	case SD_PARTICLES:
		return s->particles->emit ? MOT_PART_NOUT : 3;
	default:
		return MOT_FLOCK_NOUT;
	}
}

const char *sd_sys_name(const struct sd_system *s)
{
	return s->kind == SD_SURFACE ? s->surface->name :
	       s->kind == SD_PARTICLES ? s->particles->name : s->flock->name;
}

const char *sd_sys_suffix(const struct sd_system *s, uint32_t k)
{
	static const char *const part[MOT_PART_NOUT] = { "x", "y", "z", "r", "g", "b", "alpha",
							 "size" };
	static const char *const flock[MOT_FLOCK_NOUT] = { "x", "y", "z", "heading" };

	if (k >= sd_sys_per(s))
		return NULL;
	return s->kind == SD_FLOCK ? flock[k] : part[k];
}

const struct sd_limits *sd_sys_limits(const struct sd_system *s, uint32_t k)
{
	return s->kind == SD_SURFACE ? &s->surface->lim[k] :
	       s->kind == SD_PARTICLES ? &s->particles->lim[k] : &s->flock->lim[k];
}

bool sd_sys_angle(const struct sd_system *s, uint32_t k)
{
	return s->kind == SD_FLOCK && k == MOT_FLOCK_HEADING;
}
