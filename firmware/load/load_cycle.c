/* SPDX-License-Identifier: MIT */
/* load_cycle.c - the `cycles:` section: cycled objects (FORMULAS section 9). */
#include "load_priv.h"

#include <errno.h>

#define CYCLE_LIMIT 1073741823LL

static int cycle(struct ld *l, yaml_node_t *map, struct sd_cycle *c)
{
	static const char *const keys[] = { "name", "first", "last", "skip", "mode",
					    "frames_per_step", "start_frame", NULL };
	static const char *const modes[] = { "loop", "bounce", "growth", NULL };
	enum { Y_NAME, Y_FIRST, Y_LAST, Y_SKIP, Y_MODE, Y_FPS, Y_START, Y_COUNT };
	yaml_node_t *v[Y_COUNT];
	long long first, last, skip = 1, fps = 1, start = 0;
	int mode = MOT_CYCLE_LOOP, err;

	err = ld_map_req(l, map, "cycle", keys, v,
			 YML_REQ(Y_NAME) | YML_REQ(Y_FIRST) | YML_REQ(Y_LAST));
	if (!err)
		err = ld_name(l, v[Y_NAME], &c->name);
	if (!err)
		err = ld_int(l, v[Y_FIRST], -CYCLE_LIMIT, CYCLE_LIMIT, &first);
	if (!err)
		err = ld_int(l, v[Y_LAST], -CYCLE_LIMIT, CYCLE_LIMIT, &last);
	if (!err && v[Y_SKIP])
		err = ld_int(l, v[Y_SKIP], 1, CYCLE_LIMIT, &skip);
	if (!err && v[Y_MODE])
		err = ld_enum(l, v[Y_MODE], "cycle mode", modes, &mode);
	if (!err && v[Y_FPS])
		err = ld_int(l, v[Y_FPS], 1, CYCLE_LIMIT, &fps);
	if (!err && v[Y_START])
		err = ld_int(l, v[Y_START], -CYCLE_LIMIT, CYCLE_LIMIT, &start);
	if (err)
		return err;
	if (last < first)
		return ld_fail(l, v[Y_LAST], -EINVAL, "cycle last %lld is before first %lld", last,
			       first);
	c->first = (int32_t)first;
	c->last = (int32_t)last;
	c->skip = (int32_t)skip;
	c->mode = (enum mot_cycle_mode)mode;
	c->frames_per_step = fps;
	c->start_frame = start;
	return 0;
}

int ld_cycles(struct ld *l, yaml_node_t *seq)
{
	struct sd_cycle *cycles;
	yaml_node_item_t *it;
	size_t count, i;
	int err = ld_seq(l, seq, "cycles", &it, &count);

	if (err)
		return err;
	cycles = pool_array(l->pool, count, sizeof(*cycles));
	l->mk->cycle = pool_array(l->pool, count, sizeof(*l->mk->cycle));
	if (!cycles || !l->mk->cycle)
		return ld_nomem(l);
	for (i = 0; i < count; i++) {
		yaml_node_t *map = ld_node(l, it[i]);

		l->mk->cycle[i] = ld_mark_of(map);
		err = cycle(l, map, &cycles[i]);
		if (err)
			return err;
	}
	l->d->cycles = cycles;
	l->d->ncycles = (uint32_t)count;
	return 0;
}
