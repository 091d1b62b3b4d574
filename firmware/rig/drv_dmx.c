/* SPDX-License-Identifier: MIT */
/*
 * drv_dmx.c - lights and anything else on DMX512 (hal/dmx/dmx.h has the
 * wire): a device's `dmx:` section,
 *
 *   - name: lights
 *     driver: dmx
 *     dmx:
 *       protocol: sacn             # sacn (E1.31) | artnet
 *       destination: 239.255.0.1   # required: an address, or `multicast` (each
 *                                  #   universe to its sACN group 239.255.hi.lo)
 *       port: 5568                 # default: the protocol's (5568, 6454)
 *       interface: 192.168.1.10    # the local address multicast leaves from
 *       ttl: 1                     # multicast hops (default 1)
 *       refresh_hz: 44             # frames a second (default 44)
 *       universes: [1, 2]          # sACN universes 1-63999, Art-Net port-addresses 0-32767
 *       priority: 100              # sACN, 0-200 (default 100)
 *       source_name: strand        # sACN (default: the device's name)
 *       tick_slots: {universe: 1, address: 509}   # the loop's tick, 4 slots (tests)
 *
 * and an output's place on it: `universe:` (default the device's first),
 * `address:` (its first slot, 1-512) and `bits:` (8 or 16: coarse then
 * fine). Everything play would refuse is refused when the file is read:
 * a slot beyond 512, two outputs on one slot, an unknown universe.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "hal/dmx/dmx.h"
#include "rig.h"
#include "rig_driver.h"
#include "scene/channel.h"
#include "yaml/yml.h"

extern const struct rig_driver rig_drv_dmx;

/* An output's width, behind its priv. */
struct dmx_out {
	uint8_t bits;
};

static const struct dmx_desc *desc_of(const struct rig_device_desc *dev)
{
	return dev->driver == &rig_drv_dmx ? dev->priv : NULL;
}

static int universes(struct yml *y, yaml_node_t *n, struct dmx_desc *d)
{
	long long max = d->protocol == DMX_E131 ? DMX_E131_UNIVERSE_MAX : DMX_ARTNET_UNIVERSE_MAX;
	long long min = d->protocol == DMX_E131 ? 1 : 0, v;
	yaml_node_item_t *it;
	uint16_t *u;
	size_t c, i, j;
	int err = yml_seq(y, n, "universes", &it, &c);

	if (err)
		return err;
	if (!c || c > DMX_UNIVERSES_MAX)
		return yml_fail(y, n, -EINVAL, "1 to %d universes a device, found %zu",
				DMX_UNIVERSES_MAX, c);
	u = pool_array(y->pool, c, sizeof(*u));
	if (!u)
		return yml_nomem(y);
	for (i = 0; i < c; i++) {
		err = yml_int(y, yml_node(y, it[i]), min, max, &v);
		if (err)
			return err;
		u[i] = (uint16_t)v;
		for (j = 0; j < i; j++)
			if (u[j] == u[i])
				return yml_fail(y, yml_node(y, it[i]), -EINVAL,
						"universe %u is listed twice", u[i]);
	}
	d->universes = u;
	d->nuniverses = (uint32_t)c;
	return 0;
}

/* {universe, address} into a channel: universe index * 512 + slot - 1 */
static int place(struct yml *y, const struct dmx_desc *d, yaml_node_t *univ, yaml_node_t *addr,
		 uint32_t width, long long *ch)
{
	long long u = d->universes[0], a;
	uint32_t i;
	int err = 0;

	if (univ)
		err = yml_int(y, univ, 0, 65535, &u);
	if (!err)
		err = yml_int(y, addr, 1, DMX_SLOTS, &a);
	if (err)
		return err;
	for (i = 0; i < d->nuniverses && d->universes[i] != u; i++)
		;
	if (i == d->nuniverses)
		return yml_fail(y, univ, -EINVAL, "universe %lld is not among the device's "
				"(dmx: universes:)", u);
	if (a + width - 1 > DMX_SLOTS)
		return yml_fail(y, addr, -EINVAL, "%u slots from address %lld go past slot 512",
				width, a);
	*ch = (long long)i * DMX_SLOTS + a - 1;
	return 0;
}

static int dmx_parse_device(const struct rig_parse *p, struct rig_device_desc *dev)
{
	static const char *const keys[] = { "protocol", "destination", "port", "interface",
					    "ttl", "refresh_hz", "universes", "priority",
					    "source_name", "tick_slots", NULL };
	static const char *const protocols[] = { "sacn", "artnet", NULL };
	enum { D_PROTO, D_DEST, D_PORT, D_IF, D_TTL, D_HZ, D_UNIV, D_PRIO, D_NAME, D_TICK, D_N };
	struct yml *y = p->y;
	yaml_node_t *map = p->v[0], *v[D_N];
	struct dmx_desc *d;
	long long n;
	int proto = DMX_E131, err;

	if (!map)
		return yml_fail(y, p->map, -EINVAL, "a device of driver dmx needs its dmx: section");
	d = pool_array(y->pool, 1, sizeof(*d));
	if (!d)
		return yml_nomem(y);
	err = yml_map(y, map, "dmx", keys, v);
	if (!err)
		err = yml_require(y, map, "dmx", v[D_DEST], "destination");
	if (!err)
		err = yml_require(y, map, "dmx", v[D_UNIV], "universes");
	if (!err && v[D_PROTO])
		err = yml_enum(y, v[D_PROTO], "protocol", protocols, &proto);
	d->protocol = (enum dmx_protocol)proto;
	d->priority = 100;
	d->ttl = 1;
	d->refresh_hz = DMX_REFRESH_DEFAULT;
	d->source_name = dev->name;
	/* never a destination of strand's choosing: the scene names it */
	if (!err)
		err = yml_str(y, v[D_DEST], &d->destination);
	if (!err && !d->destination[0])
		err = yml_fail(y, v[D_DEST], -EINVAL, "an empty destination");
	if (!err && !strcmp(d->destination, "multicast") && d->protocol != DMX_E131)
		err = yml_fail(y, v[D_DEST], -EINVAL, "'multicast' is sACN's universe groups; "
			       "Art-Net takes an address");
	if (!err && v[D_PORT] && !(err = yml_int(y, v[D_PORT], 1, 65535, &n)))
		d->port = (uint16_t)n;
	if (!err && v[D_IF])
		err = yml_str(y, v[D_IF], &d->interface);
	if (!err && v[D_TTL] && !(err = yml_int(y, v[D_TTL], 1, 255, &n)))
		d->ttl = (uint32_t)n;
	if (!err && v[D_HZ])
		err = yml_range(y, v[D_HZ], "refresh_hz", 0.1, DMX_REFRESH_MAX, " Hz", &d->refresh_hz);
	if (!err && v[D_HZ] && d->refresh_hz > p->tick_hz)
		err = yml_fail(y, v[D_HZ], -EINVAL, "refresh_hz %g is above the tick rate %u",
			       d->refresh_hz, p->tick_hz);
	if (!err)
		err = universes(y, v[D_UNIV], d);
	if (!err && v[D_PRIO]) {
		if (d->protocol != DMX_E131)
			err = yml_fail(y, v[D_PRIO], -EINVAL, "priority is sACN's");
		else if (!(err = yml_int(y, v[D_PRIO], 0, 200, &n)))
			d->priority = (uint8_t)n;
	}
	if (!err && v[D_NAME])
		err = yml_str(y, v[D_NAME], &d->source_name);
	if (!err && v[D_TICK]) {
		static const char *const tk[] = { "universe", "address", NULL };
		yaml_node_t *w[2];
		long long ch;

		err = yml_map(y, v[D_TICK], "tick_slots", tk, w);
		if (!err)
			err = yml_require(y, v[D_TICK], "tick_slots", w[1], "address");
		if (!err)
			err = place(y, d, w[0], w[1], 4, &ch);
		d->has_tick_slot = !err;
		d->tick_slot = (uint32_t)ch;
	}
	dev->priv = d;
	return err;
}

static int dmx_parse_output(const struct rig_parse *p, yaml_node_t *axis_at, const struct chan *c,
			    struct rig_output_desc *o, long long *axis, yaml_node_t **at)
{
	struct yml *y = p->y;
	const struct dmx_desc *d = NULL;
	struct dmx_out *out;
	long long bits = 8;
	int err;

	(void)c;
	if (axis_at)
		return yml_fail(y, axis_at, -EINVAL, "an output on dmx device '%s' is placed by "
				"universe: and address:, not axis:", o->device);
	err = yml_require(y, p->map, "output on a dmx device", p->v[1], "address");
	if (!err && p->v[2])
		err = yml_int(y, p->v[2], 8, 16, &bits);
	if (!err && bits != 8 && bits != 16)
		err = yml_fail(y, p->v[2], -EINVAL, "bits: 8 or 16");
	if (err)
		return err;
	d = p->dev ? desc_of(p->dev) : NULL;
	if (!d)
		return yml_fail(y, p->map, -EINVAL, "device '%s' has no dmx: settings", o->device);
	err = place(y, d, p->v[0], p->v[1], (uint32_t)bits / 8, axis);
	out = pool_array(y->pool, 1, sizeof(*out));
	if (!out)
		return yml_nomem(y);
	out->bits = (uint8_t)bits;
	o->priv = out;
	*at = p->v[1];
	return err;
}

/* Every output's slots on its device, once: no two on one slot, none on
 * the tick's. */
static int dmx_validate(const struct rig_desc *rd, uint32_t tick_hz, struct rig_desc_err *e)
{
	uint32_t k, i, s;

	for (k = 0; k < rd->ndevices; k++) {
		const struct dmx_desc *d = desc_of(&rd->devices[k]);
		int32_t *owner;

		if (rd->devices[k].driver != &rig_drv_dmx)
			continue;
		if (!d) {
			e->device = (int32_t)k;
			snprintf(e->msg, sizeof(e->msg), "device '%s': driver dmx without its dmx: "
				 "settings", rd->devices[k].name);
			return -EINVAL;
		}
		owner = calloc((size_t)d->nuniverses * DMX_SLOTS, sizeof(*owner));
		if (!owner)
			return -ENOMEM;
		for (s = 0; d->has_tick_slot && s < 4; s++)
			owner[d->tick_slot + s] = -2;
		for (i = 0; i < rd->noutputs; i++) {
			const struct rig_output_desc *o = &rd->outputs[i];
			const struct dmx_out *w = o->priv;
			uint32_t width = w && w->bits == 16 ? 2 : 1;

			if (!o->device || strcmp(o->device, rd->devices[k].name))
				continue;
			for (s = 0; s < width; s++) {
				uint32_t ch = o->axis + s;

				/* place() kept the first of a pattern inside; its stride
				 * may run on into the next universe, not off the last or
				 * across a universe's end */
				if (ch >= d->nuniverses * DMX_SLOTS ||
				    (s == 0 && ch % DMX_SLOTS + width > DMX_SLOTS)) {
					e->output = (int32_t)i;
					snprintf(e->msg, sizeof(e->msg), "'%s' would take slot %u of "
						 "universe %u's 512", o->channel,
						 ch % DMX_SLOTS + width, d->universes[ch / DMX_SLOTS <
						 d->nuniverses ? ch / DMX_SLOTS : 0]);
					free(owner);
					return -EINVAL;
				}
				if (owner[ch]) {
					e->output = (int32_t)i;
					snprintf(e->msg, sizeof(e->msg), "slot %u of universe %u is "
						 "already taken by %s%s%s", ch % DMX_SLOTS + 1,
						 d->universes[ch / DMX_SLOTS],
						 owner[ch] == -2 ? "the tick (tick_slots:)" : "'",
						 owner[ch] == -2 ? "" :
						 rd->outputs[owner[ch] - 1].channel,
						 owner[ch] == -2 ? "" : "'");
					free(owner);
					return -EINVAL;
				}
				owner[ch] = (int32_t)i + 1;
			}
		}
		free(owner);
	}
	(void)tick_hz;
	return 0;
}

static void dmx_check(FILE *out, const struct rig_desc *rd, uint32_t k, uint32_t tick_hz)
{
	const struct dmx_desc *d = desc_of(&rd->devices[k]);
	uint32_t i, n = 0, slots = 0, every;

	if (!d)
		return;
	for (i = 0; i < rd->noutputs; i++) {
		const struct dmx_out *w = rd->outputs[i].priv;

		if (!rd->outputs[i].device || strcmp(rd->outputs[i].device, rd->devices[k].name))
			continue;
		n++;
		slots += w && w->bits == 16 ? 2 : 1;
	}
	every = dmx_every(d, tick_hz);
	fprintf(out, "device '%s': %s to %s port %u, %u universe%s (", rd->devices[k].name,
		d->protocol == DMX_E131 ? "sACN" : "Art-Net", d->destination,
		d->port ? d->port : d->protocol == DMX_E131 ? DMX_E131_PORT : DMX_ARTNET_PORT,
		d->nuniverses, d->nuniverses == 1 ? "" : "s");
	for (i = 0; i < d->nuniverses; i++)
		fprintf(out, "%s%u", i ? ", " : "", d->universes[i]);
	fprintf(out, "): %u output%s on %u slots, a frame every %u tick%s (%.4g a second)\n", n,
		n == 1 ? "" : "s", slots, every, every == 1 ? "" : "s", (double)tick_hz / every);
}

static int dmx_make_axes(struct rig_make *mk, uint32_t k, char *err, size_t errsize)
{
	struct rig *r = mk->r;
	const struct rig_dev *dv = &r->dev[k];
	uint32_t ax = (uint32_t)dv->axis, i, nch = rig_axis_channels(r, ax);
	const struct dmx_desc *d = dv->desc->priv;
	struct dmx_cfg c = { .name = dv->desc->name, .d = d, .tick_hz = mk->t->tick_hz,
			     .nch = nch, .lockstep = mk->clk->is_virtual, .sched = mk->o->io };
	struct dmx_chan *chan = calloc(nch ? nch : 1, sizeof(*chan));
	int64_t *initial = calloc(nch ? nch : 1, sizeof(*initial));
	int rc = -ENOMEM;

	if (!chan || !initial) {
		snprintf(err, errsize, "device '%s': out of memory", dv->desc->name);
		goto out;
	}
	for (i = 0; i < r->nout; i++) {
		const struct rig_out *o = &r->out[i];
		const struct dmx_out *w = mk->d->outputs[i].priv;

		if (o->dev != ax)
			continue;
		chan[o->ch].used = true;
		chan[o->ch].bits = w && w->bits == 16 ? 16 : 8;
		initial[o->ch] = rig_out_initial(o);
	}
	c.chan = chan;
	c.initial = initial;
	rc = hal_dmx_open(&r->axes[ax], &c, err, errsize);
out:
	free(chan);
	free(initial);
	return rc;
}

static void dmx_report(const struct rig *r, uint32_t k, FILE *f)
{
	if (r->dev[k].axis >= 0)
		hal_dmx_report(r->axes[r->dev[k].axis], f);
}

static void dmx_free(struct rig *r, uint32_t k)
{
	if (r->dev[k].axis >= 0) {
		hal_axis_close(r->axes[r->dev[k].axis]);
		r->axes[r->dev[k].axis] = NULL;
	}
}

static const char *const device_keys[] = { "dmx", NULL };
static const char *const output_keys[] = { "universe", "address", "bits", NULL };

const struct rig_driver rig_drv_dmx = {
	.name = "dmx",
	.device_keys = device_keys,
	.device_foreign = "a dmx: section belongs to a device of driver dmx",
	.parse_device = dmx_parse_device,
	.output_keys = output_keys,
	.output_foreign = "universe:, address: and bits: place an output on a dmx device",
	.axis_name = "slot",
	.parse_output = dmx_parse_output,
	.validate = dmx_validate,
	.check = dmx_check,
	.make_axes = dmx_make_axes,
	.report = dmx_report,
	.free = dmx_free,
};
