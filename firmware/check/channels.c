/* SPDX-License-Identifier: MIT */
/* channels.c - what a run holds to limits (see channels.h). */
#include "channels.h"

#include <errno.h>
#include <stdlib.h>

static bool any(const struct sd_limits *l)
{
	return l->has_min || l->has_max || l->has_vel || l->has_acc;
}

int lim_channels(struct source_scene *ss, const struct rig_desc *rig, struct lim_channel **out,
		 uint32_t *n)
{
	uint32_t nout = rig ? rig->noutputs : 0, i, k = 0;
	struct lim_channel *c = calloc(nout + ss->all.n + 1, sizeof(*c));
	bool *driven = calloc(ss->all.n + 1, sizeof(*driven));

	*out = NULL;
	*n = 0;
	if (!c || !driven) {
		free(c);
		free(driven);
		return -ENOMEM;
	}
	for (i = 0; i < nout; i++) {
		const struct rig_output_desc *od = &rig->outputs[i];
		struct src_channel sc;
		struct sd_limits lim;
		int idx = src_lookup(&ss->s, od->channel, &sc);

		if (idx < 0) {
			free(c);
			free(driven);
			return -ENOENT;
		}
		rig_output_limits(&od->limits, &sc.limits, &lim);
		driven[idx] = true;
		c[k++] = (struct lim_channel){ .name = od->channel, .src = (uint32_t)idx,
					       .unit = sc.unit, .lim = lim_bounds_of(&lim, sc.unit) };
	}
	for (i = 0; i < ss->all.n; i++) {
		struct src_channel sc;

		if (driven[i] || src_lookup(&ss->s, ss->all.c[i].name, &sc) != (int)i ||
		    !any(&sc.limits))
			continue;
		c[k++] = (struct lim_channel){ .name = ss->all.c[i].name, .src = i, .unit = sc.unit,
					       .lim = lim_bounds_of(&sc.limits, sc.unit) };
	}
	free(driven);
	*out = c;
	*n = k;
	return 0;
}

void lim_run_triggers(const struct rig_desc *rig, const struct mot_timing *t, int64_t *lead,
		      int64_t *tail)
{
	uint32_t i;

	*lead = *tail = 0;
	for (i = 0; rig && i < rig->ntriggers; i++) {
		int64_t width, off;
		bool at_offset;
		char msg[160];

		if (rig_trigger_check(&rig->triggers[i], t, &width, &off, &at_offset, msg,
				      sizeof(msg)))
			continue;
		if (-off > *lead)
			*lead = -off;
		if (off > *tail)
			*tail = off;
	}
}
