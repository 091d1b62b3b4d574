/* SPDX-License-Identifier: MIT */
/*
 * source_scene.h - the play source of a scene: the motion core evaluates
 * the whole scene at the tick's frame time (mot_scene_eval) and the
 * outputs' channels are picked out of the pose by the names every part of
 * strand shares (channel.h), in core units: turns for angles, scene units,
 * rpm, a cycle's index, an attribute's value.
 *
 * Everything is allocated by source_scene_init; eval is [rt].
 */
#ifndef STRAND_SOURCE_SCENE_H
#define STRAND_SOURCE_SCENE_H

#include "channel.h"
#include "motion/scene.h"
#include "scene_desc.h"
#include "source.h"

struct source_scene {
	struct play_source s; /* first */
	const struct scene_desc *d;
	const struct mot_scene *sc;
	struct chan_list all;
	struct mot_eval ev;
	struct mot_pose pose;
	uint32_t nsel;
	struct chan *sel;
};

/* [init] A source over a built scene and its description (both outlive
 * the source). 0 or a negative errno. */
int source_scene_init(struct source_scene *ss, const struct scene_desc *d,
		      const struct mot_scene *sc);
void source_scene_free(struct source_scene *ss);

#endif /* STRAND_SOURCE_SCENE_H */
