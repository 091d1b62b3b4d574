/* SPDX-License-Identifier: MIT */
/*
 * rig_auto.h - a simulated rig for a scene that describes none, so that
 * `strand play --sim` plays any scene: one simulated drive carrying every
 * joint's channel (<node>.angle, <node>.position) and, when the scene has a
 * camera, a pan/tilt/roll head on an x/y/z slider (camera.*), and one
 * simulated I/O device with a camera trigger. A joint's limits are the
 * scene's; where the scene gives no speed or acceleration limit, the rig is
 * made just capable enough for the motion: 1.25 times the largest speed and
 * acceleration the span asks of that channel, measured at every tick as
 * the limit predicate measures them (plan/limit.h, over the span as a run
 * plays it: plan/timeline.h), so that the check before the run passes by
 * construction; and at least enough acceleration to reach that speed in
 * half a second (for the run-up). Each axis stands at
 * the scene's first pose when the run starts. The scene says
 * nothing about following error, so an automatic rig does not bound it (a
 * `step` curve jumps, and no servo follows a jump).
 */
#ifndef STRAND_RIG_AUTO_H
#define STRAND_RIG_AUTO_H

#include "rig_desc.h"
#include "scene/source.h"

#define RIG_AUTO_MARGIN 1.25

struct rig_auto {
	struct rig_desc d;
	struct rig_device_desc dev[2];
	struct rig_output_desc *out;
	char **names;              /* the joints' channel names */
	uint32_t nnames;
	struct rig_trigger_desc trig;
};

/* [init] 0 or a negative errno. Each axis stands at the pose of frame
 * `home` (the run's first: no pre-roll on a rig that stands ready). */
int rig_auto_build(struct rig_auto *ra, const struct scene_desc *d, struct play_source *src,
		   int64_t home);
void rig_auto_free(struct rig_auto *ra);

#endif /* STRAND_RIG_AUTO_H */
