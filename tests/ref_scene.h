/* SPDX-License-Identifier: MIT */
/*
 * ref_scene.h - a floating-point reference evaluation of a whole scene,
 * written from FORMULAS.md sections 3-10 on top of the curve and matrix
 * references (ref_curve.h, ref_mat.h). It reads a scene description,
 * quantises every input exactly as scene_build() does, and evaluates in
 * long double / double with libm, so that comparing it with the core
 * measures the core's arithmetic alone. Test and benchmark code only.
 */
#ifndef REF_SCENE_H
#define REF_SCENE_H

#include "ref_mat.h"
#include "scene/scene_desc.h"

struct ref_scene; /* opaque: the quantised inputs */

struct ref_pose {
	struct ref_mat *world; /* nnodes */
	double (*pos)[3];      /* nnodes */
	double *value;         /* nnodes: turns or units */
	double *rpm;           /* nnodes */
	double eye[3], look[3];
	double pan, tilt, roll; /* turns; pan is the principal value (-1/2, 1/2] */
	int32_t *cycle;
	double *attr;
};

/* NULL when the description cannot be quantised (the same cases as
 * scene_build's MOT_E_RANGE). */
struct ref_scene *ref_scene_new(const struct scene_desc *d);
void ref_scene_free(struct ref_scene *r);

int ref_pose_new(struct ref_pose *p, const struct scene_desc *d);
void ref_pose_free(struct ref_pose *p);

/* Evaluate at a frame given as Q32.32 (the same instant the core sees). */
void ref_scene_eval(const struct ref_scene *r, mot_q32 frame, struct ref_pose *out);

/* The angle (radians) of the rotation between the linear parts of two
 * orthonormal matrices, accurate for small angles. */
double ref_rot_angle_diff(const struct ref_mat *a, const struct ref_mat *b);

#endif /* REF_SCENE_H */
