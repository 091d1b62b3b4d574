/* SPDX-License-Identifier: MIT */
/*
 * channels.h - what a run holds to limits, from the scene and its rig:
 * every output (its own limits where it gives them, its node's otherwise,
 * as the rig will enforce them), and every joint with limits of its own
 * that no output drives (the scene's word on what the joint can do, on
 * any rig). And the triggers' offsets, which widen each pass.
 */
#ifndef STRAND_CHECK_CHANNELS_H
#define STRAND_CHECK_CHANNELS_H

#include <stdint.h>

#include "limit_check.h"
#include "motion/timing.h"
#include "rig/rig_desc.h"
#include "scene/source_scene.h"

/* [init] The channels into *out (malloc'd; n of them): 0 or -ENOMEM, or
 * -ENOENT for an output whose channel the scene does not have. rig NULL:
 * the joints alone. */
int lim_channels(struct source_scene *ss, const struct rig_desc *rig, struct lim_channel **out,
		 uint32_t *n);

/* The earliest (lead: ticks before a frame's tick) and latest (tail:
 * after) of the rig's trigger edges; 0 without triggers. The rig
 * description has been validated (its offsets fit between frames). */
void lim_run_triggers(const struct rig_desc *rig, const struct mot_timing *t, int64_t *lead,
		      int64_t *tail);

#endif /* STRAND_CHECK_CHANNELS_H */
