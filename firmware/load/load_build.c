/* SPDX-License-Identifier: MIT */
/*
 * load_build.c - build a loaded scene file into the core's block, and say
 * where in the file a refusal of the core comes from.
 *
 * The loader has already checked what it can name; what is left are limits
 * only the core's own preparation finds (a curve whose precomputed
 * coefficients overflow Q32.32, a camera that pans too fast for its grid).
 * scene_build() reports those by node, channel and key index, which the
 * marks kept while parsing turn back into a line and column.
 */
#include "load_priv.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

/* The marks of the curve named by a build error, or NULL. */
static const struct sf_curve_marks *curve_marks(const struct scene_file *sf,
						const struct scene_build_err *e,
						struct ld_mark *at)
{
	const struct sf_marks *mk = sf->marks;
	uint32_t i;

	if (e->node >= 0 && (uint32_t)e->node < sf->desc.nnodes) {
		const struct sf_node_marks *nm = &mk->node[e->node];

		*at = nm->at;
		if (!strcmp(e->what, "pivot"))
			*at = nm->pivot;
		else if (!strcmp(e->what, "axis"))
			*at = nm->axis;
		else if (!strcmp(e->what, "rest"))
			*at = nm->rest;
		else if (!strcmp(e->what, "ease"))
			*at = nm->ease.line ? nm->ease : nm->value.at;
		else if (!strcmp(e->what, "value"))
			return &nm->value;
		else if (!strcmp(e->what, "spin"))
			return &nm->spin;
		else if (!strncmp(e->what, "rotation", 8))
			return &nm->rot;
		for (i = 0; i < MOT_FREE_NCHANNELS; i++)
			if (!strcmp(e->what, sd_free_names[i]))
				return &nm->ch[i];
		return NULL;
	}
	*at = mk->root;
	if (!strcmp(e->what, "timing"))
		*at = mk->timing;
	else if (!strcmp(e->what, "hierarchy"))
		*at = mk->nodes;
	else if (!strncmp(e->what, "camera", 6))
		*at = mk->camera;
	for (i = 0; i < MOT_CAM_NCHANNELS; i++)
		if (!strcmp(e->what, sd_cam_names[i]))
			return &mk->cam[i];
	for (i = 0; i < sf->desc.nattrs; i++)
		if (!strcmp(e->what, sf->desc.attrs[i].name))
			return &mk->attr[i];
	for (i = 0; i < sf->desc.ncycles; i++)
		if (!strcmp(e->what, sf->desc.cycles[i].name))
			*at = mk->cycle[i];
	for (i = 0; i < sf->desc.nsys; i++)
		if (!strcmp(e->what, sd_sys_name(&sf->desc.sys[i])))
			*at = mk->sys[i];
	for (i = 0; i < sf->desc.naims; i++)
		if (!strcmp(e->what, sf->desc.aims[i].name))
			*at = mk->aim[i];
	return NULL;
}

/* Why the core refused a system or an aim (their own words). */
static const char *sys_reason(const struct scene_file *sf, const char *what, int code)
{
	uint32_t i;

	for (i = 0; i < sf->desc.naims; i++)
		if (!strcmp(what, sf->desc.aims[i].name))
			return code == MOT_E_RANGE ?
			       "the target turns the head's pan by a quarter turn or more between two "
			       "points of its grid: raise grid: (points a frame)" :
			       "its target is not in the scene";
	for (i = 0; i < sf->desc.nsys; i++) {
		const struct sd_system *s = &sf->desc.sys[i];

		if (strcmp(what, sd_sys_name(s)))
			continue;
		if (code == MOT_E_RANGE && s->kind == SD_PARTICLES)
			return "unstable at its step: the springs' stiffness (per mass) and step "
			       "want w h < 1.8 for the highest frequency w = sqrt(2 k n) of a point "
			       "with n springs, and h (drag + 2 n damping) < 1: raise step_hz or "
			       "soften the springs";
		if (code == MOT_E_RANGE)
			return "its span takes more steps than the core counts, or its values "
			       "saturated the core's Q32.32 while it ran";
		return "refused by the core (invalid settings)";
	}
	return NULL;
}

static const char *reason(int code, bool camera)
{
	switch (code) {
	case MOT_E_RANGE:
		return camera ? "the camera pans too fast between these keys for the core's pan grid: add keys" :
				"outside the core's range once prepared (its curve coefficients overflow Q32.32)";
	case MOT_E_ORDER:
		return "keys not strictly increasing";
	case MOT_E_SINGULAR:
		return "singular transform";
	case MOT_E_NOKEYS:
		return "a strand without keys";
	case MOT_E_CAPACITY:
		return "more keys than the core takes for this interpolation";
	case MOT_E_PARENT:
		return "a parent listed after its child";
	case MOT_E_KIND:
		return "a key of the wrong kind for its node";
	default:
		return "refused by the core (invalid value)";
	}
}

int scene_file_build(const struct scene_file *sf, struct scene_built *out, struct load_err *err)
{
	struct scene_build_err e;
	const struct sf_curve_marks *cm;
	struct ld_mark at = { 0, 0 };
	const char *what;
	int rc;

	memset(err, 0, sizeof(*err));
	rc = scene_build(out, &sf->desc, &e);
	if (!rc)
		return 0;
	if (rc == -ENOMEM) {
		err->code = -ENOMEM;
		snprintf(err->msg, sizeof(err->msg), "out of memory");
		return err->code;
	}
	what = e.what ? e.what : "scene";
	cm = curve_marks(sf, &e, &at);
	if (cm) {
		at = cm->at;
		if (e.key != UINT32_MAX && cm->key)
			at = cm->key[e.key];
	}
	err->code = rc == MOT_E_RANGE ? -ERANGE : -EINVAL;
	err->line = at.line;
	err->col = at.col;
	if (e.node >= 0)
		snprintf(err->msg, sizeof(err->msg), "%s of node '%s': %s", what,
			 sf->desc.nodes[e.node].name, reason(rc, false));
	else if (sys_reason(sf, what, rc))
		snprintf(err->msg, sizeof(err->msg), "'%s': %s", what, sys_reason(sf, what, rc));
	else
		snprintf(err->msg, sizeof(err->msg), "%s: %s", what,
			 reason(rc, !strncmp(what, "camera", 6)));
	return err->code;
}
