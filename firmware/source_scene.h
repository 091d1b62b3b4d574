/* SPDX-License-Identifier: MIT */
/*
 * source_scene.h - the play source of a scene: the motion core evaluates
 * the whole scene at the tick's frame time (mot_scene_eval) and the
 * outputs' channels are picked out of the pose by name, the names every
 * part of strand shares (README "Channels"):
 *
 *   <node>.x .y .z          the pivot's world position      scene units
 *   <node>.angle            a revolute joint's angle        turns (degrees in files)
 *   <node>.position         a prismatic joint's position    scene units
 *   <node>.rpm              a spin joint's speed            rpm
 *   camera.x .y .z          the eye                         scene units
 *   camera.pan .tilt .roll  the head's angles               turns
 *   <cycle>.index           a cycled object's index
 *   <attribute>             an attribute's value
 *
 * Everything is allocated by source_scene_init; eval is [rt].
 */
#ifndef STRAND_SOURCE_SCENE_H
#define STRAND_SOURCE_SCENE_H

#include "scene.h"
#include "scene_desc.h"
#include "source.h"

enum ss_kind {
	SS_POS,   /* pose.pos[index][comp] */
	SS_VALUE, /* pose.value[index] */
	SS_RPM,   /* pose.rpm[index] */
	SS_EYE,   /* pose.cam.eye[comp] */
	SS_PAN,
	SS_TILT,
	SS_ROLL,
	SS_CYCLE, /* pose.cycle[index] */
	SS_ATTR,  /* pose.attr[index] */
};

struct ss_chan {
	uint8_t kind; /* enum ss_kind */
	uint8_t comp;
	uint32_t index;
};

struct source_scene {
	struct play_source s; /* first */
	const struct scene_desc *d;
	const struct mot_scene *sc;
	struct mot_eval ev;
	struct mot_pose pose;
	uint32_t nsel;
	struct ss_chan *sel;
	bool need_eval; /* false when no channel is selected */
};

/* [init] A source over a built scene and its description (both outlive
 * the source). 0 or a negative errno. */
int source_scene_init(struct source_scene *ss, const struct scene_desc *d,
		      const struct mot_scene *sc);
void source_scene_free(struct source_scene *ss);

#endif /* STRAND_SOURCE_SCENE_H */
