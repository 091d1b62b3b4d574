/* SPDX-License-Identifier: MIT */
/*
 * channel.h - the named channels of a scene, one naming everywhere (export
 * columns, check reports, plots): `<node>.x|y|z` (a pivot's world position),
 * `<node>.angle` (degrees) or `<node>.position` (a joint's value),
 * `<node>.rpm` (spin joints), `camera.x|y|z|pan|tilt|roll`, `<cycle>.index`,
 * and each attribute by its name. Values are in the scene file's units.
 */
#ifndef STRAND_CHANNEL_H
#define STRAND_CHANNEL_H

#include <stdint.h>

#include "scene_desc.h"

enum chan_kind {
	CHAN_POS,    /* node pivot, world, comp 0..2 */
	CHAN_VALUE,  /* joint value: degrees or scene units */
	CHAN_RPM,    /* spin speed */
	CHAN_CAMERA, /* comp 0..2 eye, 3..5 pan, tilt, roll (degrees) */
	CHAN_CYCLE,
	CHAN_ATTR,
};

struct chan {
	char name[96];
	enum chan_kind kind;
	uint32_t index; /* node, cycle or attribute */
	uint32_t comp;
	const char *unit; /* "", "deg", "rpm" */
};

/* Every channel of a scene: node positions first (the first 3 * nnodes),
 * then joint values and speeds in node order, the camera, cycles and
 * attributes. */
struct chan_list {
	struct chan *c;
	uint32_t n;
};

int chan_list_make(struct chan_list *l, const struct scene_desc *d);
void chan_list_free(struct chan_list *l);

/* A channel's value in a pose, in the file's units. Real-time safe. */
double chan_value(const struct chan *c, const struct mot_pose *p);

/* The same from the channel's value in the core's units (Q32.32: turns for
 * an angle, a cycle's index as a whole number), as a play source gives it. */
double chan_value_q32(const struct chan *c, mot_q32 v);

/* Turns to degrees and Q32.32 to double, exactly as export prints them. */
static inline double chan_q32(mot_q32 v)
{
	return (double)v * (1.0 / 4294967296.0);
}

static inline double chan_turns_deg(mot_q32 v)
{
	return (double)v * (360.0 / 4294967296.0); /* 360 / 2^32 is exact */
}

#endif /* STRAND_CHANNEL_H */
