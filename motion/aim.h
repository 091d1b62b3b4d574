/* SPDX-License-Identifier: MIT */
/*
 * aim.h - a pan/tilt head that points at a moving target: a node's pivot,
 * a particle, a flock member, a surface sample. Its pan and tilt are the
 * camera's (FORMULAS section 10, mot_look) for the direction from the head
 * to the target, and its pan is continuous in the same way: the unwrapped
 * pan is sampled at init on a grid of `sub` points a frame over the span
 * (marching four times finer, refusing a target that turns the pan by a
 * quarter turn in one fine step or 3/8 turn away from its grid point: raise
 * sub), and at run time the principal pan is unwrapped to the turn nearest
 * the grid point at or before the frame. So the pan is a pure function of
 * the frame (random access equals playback) and a row of moving heads
 * never swings back through a full turn.
 */
#ifndef MOT_AIM_H
#define MOT_AIM_H

#include "fix.h"

#define MOT_AIM_SUB_MAX 64u

struct mot_aim {
	mot_q32 at[3];      /* the head's position (the centre of its pan and tilt axes) */
	uint32_t src;       /* where the target's x is: see mot_scene (aims) */
	uint32_t index;
	mot_q32 f0;         /* frame of grid point 0 */
	uint32_t sub;       /* grid points a frame, 1 to MOT_AIM_SUB_MAX */
	uint32_t nref;
	int32_t *pan_ref;   /* nref unwrapped pans, in 2^-16 turn */
};

/* Grid points for frames f0 to f1 at sub a frame. */
uint32_t mot_aim_ref_count(mot_q32 f0, mot_q32 f1, uint32_t sub);

/* Pan (continuous) and tilt in turns for target position tgt at a frame.
 * Real-time safe. */
void mot_aim_eval(const struct mot_aim *a, const mot_q32 tgt[3], mot_q32 frame, mot_q32 *pan,
		  mot_q32 *tilt, uint32_t *sat);

/* The march of init: feed the target at every fine point k = 0 .. 4 (nref
 * - 1) (frame f0 + k / (4 sub)) in order; MOT_E_RANGE as above. */
struct mot_aim_march {
	mot_q32 prev, ref;
	bool have;
};
int mot_aim_march(struct mot_aim *a, struct mot_aim_march *m, uint32_t k, const mot_q32 tgt[3],
		  uint32_t *sat);

/* The frame of fine point k. */
mot_q32 mot_aim_fine_frame(const struct mot_aim *a, uint32_t k, uint32_t *sat);

#endif /* MOT_AIM_H */
