/* SPDX-License-Identifier: MIT */
/*
 * load_boards.c - `boards:` and `lockstep:` (rig_desc.h, README "Several
 * boards, one scene"): which board drives which of the rig's devices, which
 * one leads, and the lockstep's times. Every device is on exactly one
 * board, exactly one board leads, and no two boards share an address and
 * port: a scene that breaks one is refused where it does, so that no board
 * starts a run its partners read differently.
 */
#include "load_priv.h"

#include <errno.h>
#include <string.h>

/* The lockstep's times and bounds: what they may be. */
struct ls_key {
	const char *name;
	double min, max;
	const char *unit;
};

static const struct ls_key ls_keys[] = {
	{ "port", 1, 65535, "" },
	{ "start_ms", 0, 3600000, " ms" },
	{ "heartbeat_ms", 1, 60000, " ms" },
	{ "lost_ms", 2, 600000, " ms" },
	{ "join_ms", 1, 86400000, " ms" },
	{ "max_offset_us", 0.001, 1e9, " us" },
	{ "ptp_offset_ns", 1, 1e12, " ns" },
};
#define LS_NKEYS (sizeof(ls_keys) / sizeof(ls_keys[0]))

static int lockstep(struct ld *l, yaml_node_t *map, struct rig_lockstep_desc *ls)
{
	const char *names[LS_NKEYS + 1];
	double *val[LS_NKEYS] = { NULL, &ls->start_ms, &ls->heartbeat_ms, &ls->lost_ms,
				  &ls->join_ms, &ls->max_offset_us, &ls->ptp_offset_ns };
	yaml_node_t *v[LS_NKEYS];
	double port;
	size_t i;
	int err;

	for (i = 0; i < LS_NKEYS; i++)
		names[i] = ls_keys[i].name;
	names[LS_NKEYS] = NULL;
	err = ld_map(l, map, "lockstep", names, v);
	for (i = 0; !err && i < LS_NKEYS; i++) {
		if (!v[i])
			continue;
		err = yml_range(&l->y, v[i], ls_keys[i].name, ls_keys[i].min, ls_keys[i].max,
				ls_keys[i].unit, i ? val[i] : &port);
		if (!err && !i)
			ls->port = (uint32_t)port;
	}
	if (!err && v[0] && port != ls->port)
		err = ld_fail(l, v[0], -EINVAL, "port %.6g: a whole number", port);
	if (!err && !(ls->lost_ms >= 2 * ls->heartbeat_ms))
		err = ld_fail(l, v[3] ? v[3] : v[2], -EINVAL,
			      "lost_ms %.6g: at least two heartbeats (heartbeat_ms %.6g), or one "
			      "lost datagram loses a board", ls->lost_ms, ls->heartbeat_ms);
	return err;
}

/* A board's `devices: [NAME, ...]` as indices of the rig's devices; owner[]
 * says which board has each device so far (-1: none). */
static int board_devices(struct ld *l, yaml_node_t *seq, const struct rig_desc *r,
			 struct rig_board_desc *bd, uint32_t b, int32_t *owner,
			 const yaml_node_t **owner_at)
{
	const char **names;
	yaml_node_item_t *it;
	uint32_t *idx;
	size_t count, i, j;
	int err = ld_seq(l, seq, "devices", &it, &count);

	if (err)
		return err;
	idx = pool_array(l->pool, count ? count : 1, sizeof(*idx));
	names = pool_array(l->pool, r->ndevices + 1, sizeof(*names));
	if (!idx || !names)
		return ld_nomem(l);
	for (j = 0; j < r->ndevices; j++)
		names[j] = r->devices[j].name;
	for (i = 0; i < count; i++) {
		yaml_node_t *n = ld_node(l, it[i]);
		const char *name, *best;

		err = ld_str(l, n, &name);
		if (err)
			return err;
		for (j = 0; j < r->ndevices && strcmp(names[j], name); j++)
			;
		if (j == r->ndevices) {
			best = ld_suggest(name, names);
			if (best)
				return ld_fail(l, n, -EINVAL, "unknown device '%s'; did you mean '%s'?",
					       name, best);
			return ld_fail(l, n, -EINVAL, "unknown device '%s' (not in devices:)", name);
		}
		if (owner[j] >= 0)
			return ld_fail(l, n, -EINVAL, "device '%s' is already on board '%s' (line %u): "
				       "a device is driven by one board", name, bd[owner[j]].name,
				       ld_mark_of(owner_at[j]).line);
		owner[j] = (int32_t)b;
		owner_at[j] = n;
		idx[i] = (uint32_t)j;
	}
	bd[b].devices = idx;
	bd[b].ndevices = (uint32_t)count;
	return 0;
}

int ld_boards(struct ld *l, yaml_node_t *seq, yaml_node_t *ls_map, yaml_node_t *devices)
{
	static const char *const keys[] = { "name", "address", "port", "lead", "devices", NULL };
	struct rig_desc *r = &l->sf->rig;
	struct rig_board_desc *bd;
	const yaml_node_t **owner_at, *lead_at = NULL;
	size_t lead = 0;
	const char **bnames;
	yaml_node_item_t *it;
	int32_t *owner;
	size_t count, i, j;
	int err;

	r->lockstep = (struct rig_lockstep_desc)RIG_LOCKSTEP_DEFAULTS;
	if (!seq)
		return ls_map ? ld_fail(l, ls_map, -EINVAL, "lockstep: goes with boards:") : 0;
	if (!devices)
		return ld_fail(l, seq, -EINVAL, "boards: share out the rig's devices: section, and "
			       "there is none");
	if (ls_map && (err = lockstep(l, ls_map, &r->lockstep)))
		return err;
	err = ld_seq(l, seq, "boards", &it, &count);
	if (err)
		return err;
	if (count < 2)
		return ld_fail(l, seq, -EINVAL, "boards: names at least two boards (one board plays "
			       "the whole rig without it)");
	bd = pool_array(l->pool, count, sizeof(*bd));
	bnames = pool_array(l->pool, count + 1, sizeof(*bnames));
	owner = pool_array(l->pool, r->ndevices + 1, sizeof(*owner));
	owner_at = pool_array(l->pool, r->ndevices + 1, sizeof(*owner_at));
	if (!bd || !bnames || !owner || !owner_at)
		return ld_nomem(l);
	for (j = 0; j < r->ndevices; j++)
		owner[j] = -1;
	for (i = 0; i < count; i++) {
		yaml_node_t *map = ld_node(l, it[i]), *v[5];
		long long port = 0;

		err = ld_map_req(l, map, "board", keys, v, YML_REQ(0) | YML_REQ(1) | YML_REQ(4));
		if (!err)
			err = ld_name(l, v[0], &bd[i].name);
		if (!err)
			err = ld_str(l, v[1], &bd[i].address);
		if (!err && !bd[i].address[0])
			err = ld_fail(l, v[1], -EINVAL, "an empty address");
		if (!err && v[2])
			err = ld_int(l, v[2], 1, 65535, &port);
		bd[i].port = (uint32_t)port;
		if (!err && v[3])
			err = ld_bool(l, v[3], &bd[i].lead);
		if (!err && bd[i].lead && lead_at)
			err = ld_fail(l, v[3], -EINVAL, "board '%s' leads too: one board leads "
				      "(board '%s', line %u)", bd[i].name, bd[lead].name,
				      ld_mark_of(lead_at).line);
		if (!err && bd[i].lead) {
			lead_at = v[3];
			lead = i;
		}
		if (!err)
			err = board_devices(l, v[4], r, bd, (uint32_t)i, owner, owner_at);
		if (err)
			return err;
		for (j = 0; j < i; j++) {
			if (!strcmp(bd[j].name, bd[i].name))
				return ld_fail(l, v[0], -EINVAL, "board '%s' is already listed (line %u)",
					       bd[i].name, ld_mark_of(ld_node(l, it[j])).line);
			if (!strcmp(bd[j].address, bd[i].address) &&
			    (bd[j].port ? bd[j].port : r->lockstep.port) ==
				    (bd[i].port ? bd[i].port : r->lockstep.port))
				return ld_fail(l, v[1], -EINVAL, "board '%s' has the address and port of "
					       "board '%s' (line %u)", bd[i].name, bd[j].name,
					       ld_mark_of(ld_node(l, it[j])).line);
		}
		bnames[i] = bd[i].name;
	}
	if (!lead_at)
		return ld_fail(l, seq, -EINVAL, "no board leads: give one of them `lead: true`");
	for (j = 0; j < r->ndevices; j++)
		if (owner[j] < 0)
			return ld_fail(l, seq, -EINVAL, "device '%s' is on no board: every device is "
				       "driven by one", r->devices[j].name);
	r->boards = bd;
	r->nboards = (uint32_t)count;
	return 0;
}
