/* SPDX-License-Identifier: MIT */
/* source_scene.c - channels of an evaluated scene (see source_scene.h). */
#include "source_scene.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Channel indices as lookup() hands them out: kind, component and index
 * packed into an int so that select() can unpack them. */
static int pack(enum ss_kind kind, unsigned comp, uint32_t index)
{
	return (int)((index << 8) | (comp << 4) | kind);
}

static struct ss_chan unpack(uint32_t v)
{
	struct ss_chan c = { .kind = v & 15, .comp = (v >> 4) & 15, .index = v >> 8 };

	return c;
}

/* name == prefix "." field, for a prefix of length n */
static bool split(const char *name, const char *prefix, const char **field)
{
	size_t n = strlen(prefix);

	if (strncmp(name, prefix, n) || name[n] != '.')
		return false;
	*field = name + n + 1;
	return true;
}

static int ss_lookup(struct play_source *s, const char *name, struct src_channel *info)
{
	struct source_scene *ss = (struct source_scene *)s;
	const struct scene_desc *d = ss->d;
	const char *f;
	uint32_t i;

	memset(info, 0, sizeof(*info));
	for (i = 0; i < d->nnodes; i++) {
		const struct sd_node *n = &d->nodes[i];

		if (!split(name, n->name, &f))
			continue;
		if (f[0] && !f[1] && f[0] >= 'x' && f[0] <= 'z') {
			info->unit = SRC_UNIT_LENGTH;
			return pack(SS_POS, (unsigned)(f[0] - 'x'), i);
		}
		if (!strcmp(f, "angle") && n->kind == MOT_NODE_REVOLUTE) {
			info->unit = SRC_UNIT_TURNS;
			info->limits = n->limits;
			return pack(SS_VALUE, 0, i);
		}
		if (!strcmp(f, "position") && n->kind == MOT_NODE_PRISMATIC) {
			info->unit = SRC_UNIT_LENGTH;
			info->limits = n->limits;
			return pack(SS_VALUE, 0, i);
		}
		if (!strcmp(f, "rpm") && n->kind == MOT_NODE_REVOLUTE && n->spin.nkeys) {
			info->unit = SRC_UNIT_RPM;
			return pack(SS_RPM, 0, i);
		}
	}
	if (d->has_camera && split(name, "camera", &f)) {
		static const char *const ang[] = { "pan", "tilt", "roll" };

		if (f[0] && !f[1] && f[0] >= 'x' && f[0] <= 'z') {
			info->unit = SRC_UNIT_LENGTH;
			return pack(SS_EYE, (unsigned)(f[0] - 'x'), 0);
		}
		for (i = 0; i < 3; i++)
			if (!strcmp(f, ang[i])) {
				info->unit = SRC_UNIT_TURNS;
				return pack((enum ss_kind)(SS_PAN + i), 0, 0);
			}
	}
	for (i = 0; i < d->ncycles; i++)
		if (split(name, d->cycles[i].name, &f) && !strcmp(f, "index")) {
			info->unit = SRC_UNIT_PLAIN;
			return pack(SS_CYCLE, 0, i);
		}
	for (i = 0; i < d->nattrs; i++)
		if (!strcmp(name, d->attrs[i].name)) {
			info->unit = SRC_UNIT_PLAIN;
			return pack(SS_ATTR, 0, i);
		}
	return -ENOENT;
}

static int ss_select(struct play_source *s, const uint32_t *idx, uint32_t n)
{
	struct source_scene *ss = (struct source_scene *)s;
	struct ss_chan *sel = calloc(n ? n : 1, sizeof(*sel));
	uint32_t i;

	if (!sel)
		return -ENOMEM;
	for (i = 0; i < n; i++)
		sel[i] = unpack(idx[i]);
	free(ss->sel);
	ss->sel = sel;
	ss->nsel = n;
	ss->need_eval = n > 0;
	return 0;
}

static void ss_eval(struct play_source *s, mot_q32 frame, mot_q32 *out, uint32_t *sat)
{
	struct source_scene *ss = (struct source_scene *)s;
	const struct mot_pose *p = &ss->pose;
	uint32_t i;

	if (!ss->need_eval)
		return;
	mot_scene_eval(ss->sc, &ss->ev, frame, &ss->pose);
	*sat |= ss->ev.sat;
	for (i = 0; i < ss->nsel; i++) {
		const struct ss_chan *c = &ss->sel[i];

		switch (c->kind) {
		case SS_POS:
			out[i] = p->pos[c->index][c->comp];
			break;
		case SS_VALUE:
			out[i] = p->value[c->index];
			break;
		case SS_RPM:
			out[i] = p->rpm[c->index];
			break;
		case SS_EYE:
			out[i] = p->cam.eye[c->comp];
			break;
		case SS_PAN:
			out[i] = p->cam.pan;
			break;
		case SS_TILT:
			out[i] = p->cam.tilt;
			break;
		case SS_ROLL:
			out[i] = p->cam.roll;
			break;
		case SS_CYCLE:
			out[i] = MOT_Q32_INT(p->cycle[c->index]);
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
	int rc;

	memset(ss, 0, sizeof(*ss));
	ss->s.ops = &ss_ops;
	ss->s.name = d->name ? d->name : "scene";
	ss->s.timing = sc->timing;
	ss->s.frame_first = (int64_t)ceil(d->frame_first);
	ss->s.frame_last = (int64_t)floor(d->frame_last);
	ss->d = d;
	ss->sc = sc;
	rc = scene_eval_new(&ss->ev, sc);
	if (!rc)
		rc = scene_pose_new(&ss->pose, sc);
	if (rc) {
		source_scene_free(ss);
		return -ENOMEM;
	}
	return 0;
}

void source_scene_free(struct source_scene *ss)
{
	scene_eval_free(&ss->ev);
	scene_pose_free(&ss->pose);
	free(ss->sel);
	ss->sel = NULL;
}
