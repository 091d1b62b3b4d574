/* SPDX-License-Identifier: MIT */
/*
 * scene_pick.c - the scenes of scene_bench.c by name (scene_pick.h).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_pick.h"

#define NODES 1000
#define FRAMES_1000 96
#define TICK_STRIDE 16 /* as scene_bench.c */

int64_t scene_pick(struct synth *sy, const char *name)
{
	static const char *const kind[] = { "step", "linear", "hermite", "bspline", "beta",
					    "bezier" };
	/* joints1000's tree with every joint of one form */
	static const struct {
		const char *name;
		enum synth_form form;
	} form[] = {
		{ "rev_axis1000", SYNTH_REV_AXIS },
		{ "rev_tilt1000", SYNTH_REV_TILT },
		{ "pri_axis1000", SYNTH_PRI_AXIS },
		{ "pri_tilt1000", SYNTH_PRI_TILT },
	};
	unsigned i;

	if (!strcmp(name, "arm")) {
		synth_robot_arm(sy, 1, 240);
		return 1;
	}
	if (!strcmp(name, "random1000")) {
		synth_random(sy, 1, NODES, FRAMES_1000);
		return TICK_STRIDE;
	}
	if (!strcmp(name, "joints1000")) {
		synth_joints(sy, 1, NODES, FRAMES_1000,
			     1u << MOT_INTERP_LINEAR | 1u << MOT_INTERP_HERMITE);
		return TICK_STRIDE;
	}
	for (i = 0; i < sizeof(form) / sizeof(form[0]); i++)
		if (!strcmp(name, form[i].name)) {
			synth_joints_of(sy, 1, NODES, FRAMES_1000,
					1u << MOT_INTERP_LINEAR | 1u << MOT_INTERP_HERMITE, form[i].form);
			return TICK_STRIDE;
		}
	for (i = 0; i < 6; i++) {
		char kname[32];

		snprintf(kname, sizeof(kname), "kind_%s1000", kind[i]);
		if (!strcmp(name, kname)) {
			synth_joints(sy, 1, NODES, FRAMES_1000, 1u << i);
			return TICK_STRIDE;
		}
	}
	return 0;
}

mot_q32 *scene_pick_frames(const struct mot_timing *t, const struct synth *sy, int64_t stride,
			   uint32_t *nticks)
{
	int64_t k0 = mot_timing_trigger_tick(t, (int64_t)sy->d.frame_first);
	int64_t k1 = mot_timing_trigger_tick(t, (int64_t)sy->d.frame_last), k;
	mot_q32 *frame;

	*nticks = (uint32_t)((k1 - k0) / stride + 1);
	frame = calloc(*nticks, sizeof(*frame));
	if (!frame)
		return NULL;
	for (k = 0; k < *nticks; k++)
		frame[k] = mot_timing_tick_frame(t, k0 + k * stride);
	return frame;
}
