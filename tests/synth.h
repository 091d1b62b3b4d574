/* SPDX-License-Identifier: MIT */
/*
 * synth.h - scene descriptions built in code, for the tests, the digest and
 * the benchmarks: the paper's robot arm with five joints, and seeded random
 * hierarchies of any size using every node kind, key kind and curve kind.
 */
#ifndef SYNTH_H
#define SYNTH_H

#include "scene/scene_desc.h"

struct synth {
	struct scene_desc d;
	/* everything the description points to, freed by synth_free */
	void **mem;
	size_t nmem, capmem;
};

/*
 * The 5-joint arm: base (revolute y), shoulder and elbow (revolute z), wrist
 * (revolute x), claw (revolute about a tilted axis), links scaled by `scale`
 * (1: an arm about 1.5 m tall; 60: a 90 m crane for the +-100 m workspace
 * test), each joint keyed with hermite keys at uneven frames over `frames`
 * frames, 24 fps, tick_hz 1000.
 */
void synth_robot_arm(struct synth *s, double scale, double frames);

/*
 * A random forest of n nodes (parents before children, depth bounded):
 * revolute joints about x/y/z and tilted axes, prismatic joints, spin joints,
 * free nodes with translate/scale/shear channels and slerp or squad rotation
 * tracks; every curve kind, uneven key times, some slow-in/slow-out. Same
 * seed, same scene.
 */
void synth_random(struct synth *s, uint64_t seed, uint32_t n, double frames);

/*
 * A random forest of n joints only, shaped like synth_random's (the same
 * parent and depth rule, revolute joints about x, y, z and tilted axes,
 * prismatic joints), each keyed with a curve whose kind is taken in turn
 * from the set `kinds` (bit k: enum mot_interp k; 0 means all). With linear
 * and hermite it is the common case of a rig; with one kind it isolates
 * that kind's cost.
 */
void synth_joints(struct synth *s, uint64_t seed, uint32_t n, double frames, unsigned kinds);

/* One form of joint for every node of synth_joints()'s forest (the same
 * parents, pivots and keys): what a joint of that form costs. */
enum synth_form {
	SYNTH_ANY,       /* synth_joints() itself */
	SYNTH_REV_AXIS,  /* revolute about x, y or z */
	SYNTH_REV_TILT,  /* revolute about a tilted axis */
	SYNTH_PRI_AXIS,  /* prismatic along x, y or z */
	SYNTH_PRI_TILT,  /* prismatic along a tilted axis */
};
void synth_joints_of(struct synth *s, uint64_t seed, uint32_t n, double frames, unsigned kinds,
		     enum synth_form form);

void synth_free(struct synth *s);

#endif /* SYNTH_H */
