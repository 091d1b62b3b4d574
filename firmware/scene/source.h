/* SPDX-License-Identifier: MIT */
/*
 * source.h - where the loop's setpoints come from: named channels with a
 * value at any frame time. The scene source (source_scene.c) evaluates the
 * motion core's scene and picks channels out of the pose; tests plug in
 * analytic sources behind the same table.
 */
#ifndef STRAND_SOURCE_H
#define STRAND_SOURCE_H

#include <stdbool.h>
#include <stdint.h>

#include "motion/fix.h"
#include "motion/timing.h"
#include "scene_desc.h" /* struct sd_limits */
#include "hal/rt.h"

enum src_unit {
	SRC_UNIT_TURNS,  /* angles: core turns, degrees in files */
	SRC_UNIT_LENGTH, /* scene units */
	SRC_UNIT_RPM,    /* a spin speed: drives follow it in velocity mode */
	SRC_UNIT_PLAIN,  /* a cycle index, an attribute */
};

struct src_channel {
	enum src_unit unit;
	struct sd_limits limits; /* the scene's limits for it (file units), if any */
};

struct play_source;

struct play_source_ops {
	/* [init] Look a channel up by name: its index (>= 0) with *info
	 * filled, or -ENOENT. */
	int (*lookup)(struct play_source *s, const char *name, struct src_channel *info);
	/* [init] From now on eval() computes these channels, in this order. */
	int (*select)(struct play_source *s, const uint32_t *idx, uint32_t n);
	/* [rt] The selected channels at a frame time (Q32.32 frames), core
	 * units, into out[]. Saturation is ORed into *sat. */
	void (*eval)(struct play_source *s, mot_q32 frame, mot_q32 *out, uint32_t *sat);
};

struct play_source {
	const struct play_source_ops *ops; /* first */
	const char *name;                  /* the scene's name */
	struct mot_timing timing;
	int64_t frame_first, frame_last;   /* the span to play by default */
};

static inline int src_lookup(struct play_source *s, const char *name, struct src_channel *info)
{
	return s->ops->lookup(s, name, info);
}

static inline int src_select(struct play_source *s, const uint32_t *idx, uint32_t n)
{
	return s->ops->select(s, idx, n);
}

static inline void STRAND_RT src_eval(struct play_source *s, mot_q32 frame, mot_q32 *out, uint32_t *sat)
{
	s->ops->eval(s, frame, out, sat);
}

#endif /* STRAND_SOURCE_H */
