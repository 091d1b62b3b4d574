/* SPDX-License-Identifier: MIT */
/*
 * channel.h - the named channels of a scene, one naming everywhere (export
 * columns, check reports, plots): `<node>.x|y|z` (a pivot's world position),
 * `<node>.angle` (degrees) or `<node>.position` (a joint's value),
 * `<node>.rpm` (spin joints), `camera.x|y|z|pan|tilt|roll`, `<cycle>.index`,
 * each attribute by its name, the systems' items (`<surface>.<row>.<col>.x|y|z`,
 * `<particles>.<slot>.x|y|z|r|g|b|alpha|size`, `<flock>.<member>.x|y|z|heading`)
 * and the aims' `<aim>.pan|tilt`. Values are in the scene file's units.
 */
#ifndef STRAND_CHANNEL_H
#define STRAND_CHANNEL_H

#include <stdbool.h>
#include <stdint.h>

#include "scene_desc.h"

enum chan_kind {
	CHAN_POS,    /* node pivot, world, comp 0..2 */
	CHAN_VALUE,  /* joint value: degrees or scene units */
	CHAN_RPM,    /* spin speed */
	CHAN_CAMERA, /* comp 0..2 eye, 3..5 pan, tilt, roll (degrees) */
	CHAN_CYCLE,
	CHAN_ATTR,
	CHAN_SYS,    /* a system's value: index into pose->sysout, comp its channel of the item */
	CHAN_AIM,    /* an aim's pan (comp 0) or tilt (1), degrees */
};

struct chan {
	char name[96];
	enum chan_kind kind;
	uint32_t index; /* node, cycle, attribute, aim; a system's value */
	uint32_t comp;
	uint32_t owner; /* the system of a CHAN_SYS */
	const char *unit; /* "", "deg", "rpm" */
};

/* Every channel of a scene: node positions first (the first 3 * nnodes),
 * then joint values and speeds in node order, the camera, cycles,
 * attributes, the systems' items in their order, the aims. */
struct chan_list {
	struct chan *c;
	uint32_t n;
};

int chan_list_make(struct chan_list *l, const struct scene_desc *d);
void chan_list_free(struct chan_list *l);

/* The scene's limits of a channel: its node's, its system's for that
 * channel of an item, its aim's; NULL for the others. */
const struct sd_limits *chan_limits(const struct chan *c, const struct scene_desc *d);

/* Is it an angle (degrees in files and exports, turns in the core)? */
static inline bool chan_is_angle(const struct chan *c)
{
	return c->unit[0] == 'd';
}

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
