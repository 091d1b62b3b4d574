/* SPDX-License-Identifier: MIT */
/* source_scene.c - channels of an evaluated scene (see source_scene.h). */
#include "source_scene.h"
#include "hal/rt.h"

#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

static enum src_unit unit_of(const struct source_scene *ss, const struct chan *c)
{
	switch (c->kind) {
	case CHAN_VALUE:
		return ss->d->nodes[c->index].kind == MOT_NODE_REVOLUTE ? SRC_UNIT_TURNS :
									  SRC_UNIT_LENGTH;
	case CHAN_RPM:
		return SRC_UNIT_RPM;
	case CHAN_CAMERA:
		return c->comp >= 3 ? SRC_UNIT_TURNS : SRC_UNIT_LENGTH;
	case CHAN_POS:
		return SRC_UNIT_LENGTH;
	case CHAN_AIM:
		return SRC_UNIT_TURNS;
	case CHAN_SYS:
		/* positions and sizes are lengths; colours and alpha plain */
		return c->unit[0] ? SRC_UNIT_TURNS :
		       c->comp < 3 || c->comp == MOT_PART_SIZE ? SRC_UNIT_LENGTH : SRC_UNIT_PLAIN;
	default:
		return SRC_UNIT_PLAIN;
	}
}

static int ss_lookup(struct play_source *s, const char *name, struct src_channel *info)
{
	struct source_scene *ss = (struct source_scene *)s;
	uint32_t i;

	memset(info, 0, sizeof(*info));
	for (i = 0; i < ss->all.n; i++) {
		const struct chan *c = &ss->all.c[i];

		if (strcmp(c->name, name))
			continue;
		info->unit = unit_of(ss, c);
		if (chan_limits(c, ss->d))
			info->limits = *chan_limits(c, ss->d);
		return (int)i;
	}
	return -ENOENT;
}

static int ss_select(struct play_source *s, const uint32_t *idx, uint32_t n)
{
	struct source_scene *ss = (struct source_scene *)s;
	struct chan *sel = calloc(n ? n : 1, sizeof(*sel));
	uint32_t i;

	if (!sel)
		return -ENOMEM;
	for (i = 0; i < n; i++) {
		if (idx[i] >= ss->all.n) {
			free(sel);
			return -EINVAL;
		}
		sel[i] = ss->all.c[idx[i]];
	}
	free(ss->sel);
	ss->sel = sel;
	ss->nsel = n;
	return 0;
}

static void STRAND_RT ss_eval(struct play_source *s, mot_q32 frame, mot_q32 *out, uint32_t *sat)
{
	struct source_scene *ss = (struct source_scene *)s;
	const struct mot_pose *p = &ss->pose;
	static const size_t cam_off[6] = {
		offsetof(struct mot_cam_pose, eye[0]), offsetof(struct mot_cam_pose, eye[1]),
		offsetof(struct mot_cam_pose, eye[2]), offsetof(struct mot_cam_pose, pan),
		offsetof(struct mot_cam_pose, tilt),   offsetof(struct mot_cam_pose, roll),
	};
	uint32_t i;

	if (!ss->nsel)
		return; /* a rig of triggers only: nothing to evaluate */
	mot_scene_eval(ss->sc, &ss->ev, frame, &ss->pose);
	*sat |= ss->ev.sat;
	for (i = 0; i < ss->nsel; i++) {
		const struct chan *c = &ss->sel[i];

		switch (c->kind) {
		case CHAN_POS:
			out[i] = p->pos[c->index][c->comp];
			break;
		case CHAN_VALUE:
			out[i] = p->value[c->index];
			break;
		case CHAN_RPM:
			out[i] = p->rpm[c->index];
			break;
		case CHAN_CAMERA:
			memcpy(&out[i], (const char *)&p->cam + cam_off[c->comp], sizeof(mot_q32));
			break;
		case CHAN_CYCLE:
			out[i] = MOT_Q32_INT(p->cycle[c->index]);
			break;
		case CHAN_SYS:
			out[i] = p->sysout[c->index];
			break;
		case CHAN_AIM:
			out[i] = p->aim[c->index][c->comp];
			break;
		default:
			out[i] = p->attr[c->index];
			break;
		}
	}
}

static const struct play_source_ops ss_ops = {
	.lookup = ss_lookup,
	.select = ss_select,
	.eval = ss_eval,
};

int source_scene_init(struct source_scene *ss, const struct scene_desc *d,
		      const struct mot_scene *sc)
{
	memset(ss, 0, sizeof(*ss));
	ss->s.ops = &ss_ops;
	ss->s.name = d->name && d->name[0] ? d->name : "scene";
	ss->s.timing = sc->timing;
	ss->s.frame_first = (int64_t)ceil(d->frame_first);
	ss->s.frame_last = (int64_t)floor(d->frame_last);
	ss->d = d;
	ss->sc = sc;
	if (chan_list_make(&ss->all, d) || scene_eval_new(&ss->ev, sc) ||
	    scene_pose_new(&ss->pose, sc)) {
		source_scene_free(ss);
		return -ENOMEM;
	}
	return 0;
}

void source_scene_free(struct source_scene *ss)
{
	chan_list_free(&ss->all);
	scene_eval_free(&ss->ev);
	scene_pose_free(&ss->pose);
	free(ss->sel);
	ss->sel = NULL;
}
