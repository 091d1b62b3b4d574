/* SPDX-License-Identifier: MIT */
/*
 * load_canopen.c - the CANopen part of the rig sections: a canopen device's
 * bus (`canopen: {interface, bitrate, sync_id, heartbeat_ms}`), an output's
 * drive on it (`node:`, `mode:`), and each bus checked once every output is
 * read: its tick's worst-case bits fit with margin, the drives' 0x60C2 can
 * say the tick, the SYNC's identifier is none of a drive's.
 */
#include "load_priv.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "rig/rig_canopen.h"
#include "scene/channel.h"

/* A COB-ID, in decimal or 0x hex: 1..0x7ff. */
static int cob_id(struct ld *l, yaml_node_t *n, uint32_t *out)
{
	const char *text;
	char *end;
	unsigned long v;
	int err = ld_str(l, n, &text);

	if (err)
		return err;
	errno = 0;
	v = strtoul(text, &end, 0);
	if (errno || end == text || *end || v < 1 || v > 0x7ff)
		return ld_fail(l, n, -EINVAL, "'%s' is not an 11-bit COB-ID (1 to 0x7ff)", text);
	*out = (uint32_t)v;
	return 0;
}

/* A canopen device's bus: {interface, bitrate, sync_id, heartbeat_ms}. */
int ld_canopen_bus(struct ld *l, yaml_node_t *map, struct rig_canopen_desc *c)
{
	static const char *const keys[] = { "interface", "bitrate", "sync_id", "heartbeat_ms",
					    NULL };
	yaml_node_t *v[4];
	long long n;
	int err = ld_map(l, map, "canopen", keys, v);

	if (!err)
		err = ld_require(l, map, "canopen", v[0], "interface");
	if (!err)
		err = ld_require(l, map, "canopen", v[1], "bitrate");
	if (!err)
		err = ld_str(l, v[0], &c->interface);
	if (!err && (!c->interface[0] || strlen(c->interface) > 15))
		err = ld_fail(l, v[0], -EINVAL, "interface '%s': a network interface name "
			      "(1 to 15 characters: can0, vcan0) or sim", c->interface);
	if (!err)
		err = ld_int(l, v[1], 10000, 1000000, &n);
	c->bitrate = (uint32_t)n;
	c->sync_id = CO_ID_SYNC;
	if (!err && v[2])
		err = cob_id(l, v[2], &c->sync_id);
	c->heartbeat_ms = RIG_CO_HEARTBEAT_MS;
	if (!err && v[3])
		err = ld_int(l, v[3], 1, 10000, &n);
	if (!err && v[3])
		c->heartbeat_ms = (uint32_t)n;
	return err;
}

/* An output on a canopen device: node: (its axis), mode: checked against
 * the channel (cyclic synchronous velocity for spin speeds only). */
int ld_canopen_output(struct ld *l, yaml_node_t *map, yaml_node_t *axis_at, yaml_node_t *node_at,
		      yaml_node_t *mode_at, const struct chan *c, struct rig_output_desc *o,
		      long long *node)
{
	static const char *const modes[] = { "csp", "csv", NULL };
	bool spin = c->kind == CHAN_RPM;
	int mode, err;

	if (axis_at)
		return ld_fail(l, axis_at, -EINVAL,
			       "an output on canopen device '%s' is placed by node:, not axis:",
			       o->device);
	err = ld_require(l, map, "output on a canopen device", node_at, "node");
	if (!err)
		err = ld_int(l, node_at, 1, CO_NODE_MAX, node);
	if (err || !mode_at) {
		o->canopen.mode = spin ? 9 : 8;
		return err;
	}
	err = ld_enum(l, mode_at, "mode", modes, &mode);
	if (!err && mode != spin)
		err = ld_fail(l, mode_at, -EINVAL, "mode %s: '%s' is %s; it needs mode %s",
			      modes[mode], o->channel, spin ? "a spin speed" : "not a spin speed",
			      modes[spin]);
	o->canopen.mode = mode ? 9 : 8;
	return err;
}

/* Each canopen bus carries its tick with margin, in the 0x60C2 format, and
 * its SYNC's identifier is no drive's. */
int ld_canopen_buses(struct ld *l, const struct rig_desc *r, yaml_node_t *const *at)
{
	uint32_t k, i, hz = l->d->tick_hz;
	uint8_t ip;
	int8_t ex;

	for (k = 0; k < r->ndevices; k++) {
		const struct rig_canopen_desc *c = &r->devices[k].canopen;
		struct co_load load;

		if (r->devices[k].driver != RIG_DRIVER_CANOPEN || !rig_canopen_drives(r, k))
			continue;
		rig_canopen_load(r, k, hz, &load);
		if (!co_load_fits(&load))
			return ld_fail(l, at[k], -EINVAL,
				       "canopen bus '%s': the worst case of a tick is %u bits (%u "
				       "drive%s, bit stuffing) of the %u a tick holds at %u bit/s "
				       "and %u ticks/s: %.0f%%, above %d%%; lower tick_hz, drive "
				       "fewer outputs on this bus or raise the bitrate",
				       r->devices[k].name, load.bits, load.drives,
				       load.drives == 1 ? "" : "s", load.capacity,
				       c->bitrate, hz, 100.0 * load.bits / load.capacity,
				       CO_LOAD_MAX_PERCENT);
		if (co_interp_period(hz, &ip, &ex) < 0)
			return ld_fail(l, at[k], -EINVAL,
				       "canopen bus '%s': tick_hz %u: a drive's interpolation period "
				       "(0x60C2: 1 to 255 times a power of ten seconds) cannot say "
				       "%.6g us within 0.1%%", r->devices[k].name, hz, 1e6 / hz);
		for (i = 0; i < r->noutputs; i++) {
			uint32_t n = r->outputs[i].axis, id = c->sync_id;

			if (strcmp(r->outputs[i].device, r->devices[k].name))
				continue;
			if (id == CO_ID_EMCY + n || id == co_tpdo_id(1, (uint8_t)n) ||
			    id == co_rpdo_id(1, (uint8_t)n) || id == CO_ID_SDO_TX + n ||
			    id == CO_ID_SDO_RX + n || id == CO_ID_HEARTBEAT + n)
				return ld_fail(l, at[k], -EINVAL,
					       "canopen bus '%s': sync_id 0x%x is an identifier of "
					       "node %u", r->devices[k].name, id, n);
		}
	}
	return 0;
}
