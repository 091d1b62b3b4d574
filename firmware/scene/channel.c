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
	c->owner = 0;
	c->unit = unit;
	return c;
}

/* Values the systems write, in pose->sysout's order. */
static size_t sys_values(const struct scene_desc *d)
{
	size_t n = 0;
	uint32_t i;

	for (i = 0; i < d->nsys; i++)
		n += (size_t)sd_sys_items(&d->sys[i]) * sd_sys_per(&d->sys[i]);
	return n;
}

static void sys_channels(struct chan_list *l, const struct scene_desc *d)
{
	uint32_t i, it, k, out = 0;

	for (i = 0; i < d->nsys; i++) {
		const struct sd_system *s = &d->sys[i];
		uint32_t per = sd_sys_per(s), n = sd_sys_items(s);

		for (it = 0; it < n; it++)
			for (k = 0; k < per; k++, out++) {
				struct chan *c = add(l, CHAN_SYS, out, k, sd_sys_angle(s, k) ? "deg" : "");

				c->owner = i;
				if (s->kind == SD_SURFACE)
					snprintf(c->name, sizeof(c->name), "%s.%u.%u.%s",
						 s->surface->name, it / s->surface->nsv,
						 it % s->surface->nsv, sd_sys_suffix(s, k));
				else
					snprintf(c->name, sizeof(c->name), "%s.%u.%s", sd_sys_name(s),
						 it, sd_sys_suffix(s, k));
			}
	}
	for (i = 0; i < d->naims; i++)
		for (k = 0; k < 2; k++)
			snprintf(add(l, CHAN_AIM, i, k, "deg")->name, sizeof(l->c->name), "%s.%s",
				 d->aims[i].name, k ? "tilt" : "pan");
}

int chan_list_make(struct chan_list *l, const struct scene_desc *d)
{
	static const char *const cam[6] = { "x", "y", "z", "pan", "tilt", "roll" };
	size_t max = (size_t)d->nnodes * 5 + 6 + d->ncycles + d->nattrs + sys_values(d) +
		     (size_t)d->naims * 2;
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
	sys_channels(l, d);
	return 0;
}

void chan_list_free(struct chan_list *l)
{
	free(l->c);
	l->c = NULL;
	l->n = 0;
}

const struct sd_limits *chan_limits(const struct chan *c, const struct scene_desc *d)
{
	switch (c->kind) {
	case CHAN_VALUE:
		return &d->nodes[c->index].limits;
	case CHAN_SYS:
		return sd_sys_limits(&d->sys[c->owner], c->comp);
	case CHAN_AIM:
		return &d->aims[c->index].lim[c->comp];
	default:
		return NULL;
	}
}

double chan_value_q32(const struct chan *c, mot_q32 v)
{
	/* angles: a joint's, the camera's pan, tilt and roll, a heading, an aim's */
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
	case CHAN_SYS:
		return chan_value_q32(c, p->sysout[c->index]);
	case CHAN_AIM:
		return chan_value_q32(c, p->aim[c->index][c->comp]);
	}
	return 0;
}
