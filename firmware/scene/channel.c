/* SPDX-License-Identifier: MIT */
/* channel.c - the named channels of a scene (see channel.h). */
#include "channel.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

static struct chan *add(struct chan_list *l, enum chan_kind kind, uint32_t index,
			uint32_t comp, const char *unit)
{
	struct chan *c = &l->c[l->n++];

	c->kind = kind;
	c->index = index;
	c->comp = comp;
	c->unit = unit;
	return c;
}

int chan_list_make(struct chan_list *l, const struct scene_desc *d)
{
	static const char *const cam[6] = { "x", "y", "z", "pan", "tilt", "roll" };
	size_t max = (size_t)d->nnodes * 5 + 6 + d->ncycles + d->nattrs;
	uint32_t i, k;

	l->n = 0;
	l->c = calloc(max ? max : 1, sizeof(*l->c));
	if (!l->c)
		return -ENOMEM;
	for (i = 0; i < d->nnodes; i++)
		for (k = 0; k < 3; k++)
			snprintf(add(l, CHAN_POS, i, k, "")->name, sizeof(l->c->name), "%s.%c",
				 d->nodes[i].name, "xyz"[k]);
	for (i = 0; i < d->nnodes; i++) {
		const struct sd_node *n = &d->nodes[i];

		if (n->kind == MOT_NODE_FREE)
			continue;
		if (n->kind == MOT_NODE_REVOLUTE)
			snprintf(add(l, CHAN_VALUE, i, 0, "deg")->name, sizeof(l->c->name), "%s.angle",
				 n->name);
		else
			snprintf(add(l, CHAN_VALUE, i, 0, "")->name, sizeof(l->c->name),
				 "%s.position", n->name);
		if (n->spin.nkeys)
			snprintf(add(l, CHAN_RPM, i, 0, "rpm")->name, sizeof(l->c->name), "%s.rpm",
				 n->name);
	}
	if (d->has_camera)
		for (k = 0; k < 6; k++)
			snprintf(add(l, CHAN_CAMERA, 0, k, k < 3 ? "" : "deg")->name,
				 sizeof(l->c->name), "camera.%s", cam[k]);
	for (i = 0; i < d->ncycles; i++)
		snprintf(add(l, CHAN_CYCLE, i, 0, "")->name, sizeof(l->c->name), "%s.index",
			 d->cycles[i].name);
	for (i = 0; i < d->nattrs; i++)
		snprintf(add(l, CHAN_ATTR, i, 0, "")->name, sizeof(l->c->name), "%s",
			 d->attrs[i].name);
	return 0;
}

void chan_list_free(struct chan_list *l)
{
	free(l->c);
	l->c = NULL;
	l->n = 0;
}

double chan_value_q32(const struct chan *c, mot_q32 v)
{
	/* angles: a joint's and the camera's pan, tilt and roll */
	return c->unit[0] == 'd' ? chan_turns_deg(v) : chan_q32(v);
}

double chan_value(const struct chan *c, const struct mot_pose *p)
{
	switch (c->kind) {
	case CHAN_POS:
		return chan_q32(p->pos[c->index][c->comp]);
	case CHAN_VALUE:
		return chan_value_q32(c, p->value[c->index]);
	case CHAN_RPM:
		return chan_q32(p->rpm[c->index]);
	case CHAN_CAMERA:
		return chan_value_q32(c, c->comp < 3 ? p->cam.eye[c->comp] :
					 c->comp == 3 ? p->cam.pan :
					 c->comp == 4 ? p->cam.tilt : p->cam.roll);
	case CHAN_CYCLE:
		return (double)p->cycle[c->index];
	case CHAN_ATTR:
		return chan_q32(p->attr[c->index]);
	}
	return 0;
}
