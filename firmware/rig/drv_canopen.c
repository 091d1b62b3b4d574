/* SPDX-License-Identifier: MIT */
/*
 * drv_canopen.c - CANopen buses of CiA 402 drives (see drv_canopen.h): a
 * device's bus (`canopen: {interface, bitrate, sync_id, heartbeat_ms}`), an
 * output's drive on it (`node:`, `mode:`), each bus checked once every
 * output is read (its tick's worst-case bits fit with margin, the drives'
 * 0x60C2 can say the tick, the SYNC's identifier is none of a drive's),
 * strand check's line about its load, and the master on the bus.
 */
#include "drv_canopen.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drv_sim.h"
#include "hal/canopen/co_axis.h"
#include "hal/canopen/co_load.h"
#include "hal/canopen/co_socketcan.h"
#include "scene/channel.h"
#include "yaml/yml.h"

/* What the driver made for a device besides its axis. */
struct co_dev {
	struct co_simbus *sim; /* interface "sim": the simulated bus, or NULL */
};

/* ---- the scene file ---- */

/* A COB-ID, in decimal or 0x hex: 1..0x7ff. */
static int cob_id(struct yml *y, yaml_node_t *n, uint32_t *out)
{
	const char *text;
	char *end;
	unsigned long v;
	int err = yml_str(y, n, &text);

	if (err)
		return err;
	errno = 0;
	v = strtoul(text, &end, 0);
	if (errno || end == text || *end || v < 1 || v > 0x7ff)
		return yml_fail(y, n, -EINVAL, "'%s' is not an 11-bit COB-ID (1 to 0x7ff)", text);
	*out = (uint32_t)v;
	return 0;
}

static const char *const device_keys[] = { "canopen", NULL };

/* A canopen device's bus: {interface, bitrate, sync_id, heartbeat_ms}. */
static int co_parse_device(const struct rig_parse *p, struct rig_device_desc *dev)
{
	static const char *const keys[] = { "interface", "bitrate", "sync_id", "heartbeat_ms",
					    NULL };
	struct yml *y = p->y;
	yaml_node_t *map = p->v[0], *v[4];
	struct rig_canopen_desc *c;
	long long n;
	int err;

	if (!map)
		return yml_fail(y, p->map, -EINVAL,
				"a device of driver canopen needs its canopen: section");
	c = pool_array(y->pool, 1, sizeof(*c));
	if (!c)
		return yml_nomem(y);
	dev->priv = c;
	err = yml_map(y, map, "canopen", keys, v);
	if (!err)
		err = yml_require(y, map, "canopen", v[0], "interface");
	if (!err)
		err = yml_require(y, map, "canopen", v[1], "bitrate");
	if (!err)
		err = yml_str(y, v[0], &c->interface);
	if (!err && (!c->interface[0] || strlen(c->interface) > 15))
		err = yml_fail(y, v[0], -EINVAL, "interface '%s': a network interface name "
			       "(1 to 15 characters: can0, vcan0) or sim", c->interface);
	if (!err)
		err = yml_int(y, v[1], 10000, 1000000, &n);
	c->bitrate = (uint32_t)n;
	c->sync_id = CO_ID_SYNC;
	if (!err && v[2])
		err = cob_id(y, v[2], &c->sync_id);
	c->heartbeat_ms = RIG_CO_HEARTBEAT_MS;
	if (!err && v[3])
		err = yml_int(y, v[3], 1, 10000, &n);
	if (!err && v[3])
		c->heartbeat_ms = (uint32_t)n;
	return err;
}

static const char *const output_keys[] = { "node", "mode", NULL };

/* An output on a canopen device: node: (its axis), and mode: only checked
 * against the channel (cyclic synchronous velocity for spin speeds only):
 * the channel decides the drive's mode. */
static int co_parse_output(const struct rig_parse *p, yaml_node_t *axis_at,
			   const struct chan *c, struct rig_output_desc *o, long long *node,
			   yaml_node_t **at)
{
	static const char *const modes[] = { "csp", "csv", NULL };
	yaml_node_t *node_at = p->v[0], *mode_at = p->v[1];
	bool spin = c->kind == CHAN_RPM;
	int mode, err;

	if (axis_at)
		return yml_fail(p->y, axis_at, -EINVAL,
				"an output on canopen device '%s' is placed by node:, not axis:",
				o->device);
	*at = node_at;
	err = yml_require(p->y, p->map, "output on a canopen device", node_at, "node");
	if (!err)
		err = yml_int(p->y, node_at, 1, CO_NODE_MAX, node);
	if (err || !mode_at)
		return err;
	err = yml_enum(p->y, mode_at, "mode", modes, &mode);
	if (!err && mode != spin)
		err = yml_fail(p->y, mode_at, -EINVAL, "mode %s: '%s' is %s; it needs mode %s",
			       modes[mode], o->channel, spin ? "a spin speed" : "not a spin speed",
			       modes[spin]);
	return err;
}

/* ---- the description ---- */

static bool on(const struct rig_desc *d, uint32_t k, const struct rig_output_desc *o)
{
	return o->device && !strcmp(o->device, d->devices[k].name);
}

static uint32_t drives(const struct rig_desc *d, uint32_t k)
{
	uint32_t i, n = 0;

	for (i = 0; i < d->noutputs; i++)
		n += on(d, k, &d->outputs[i]);
	return n;
}

static uint32_t heartbeat_ms(const struct rig_canopen_desc *c)
{
	return c->heartbeat_ms ? c->heartbeat_ms : RIG_CO_HEARTBEAT_MS;
}

static uint32_t sync_id(const struct rig_canopen_desc *c)
{
	return c->sync_id ? c->sync_id : CO_ID_SYNC;
}

/* The worst case of device k's bus at tick_hz (co_load.h). */
static void load(const struct rig_desc *d, uint32_t k, uint32_t tick_hz, struct co_load *l)
{
	const struct rig_canopen_desc *c = d->devices[k].priv;

	co_load_tick(l, drives(d, k), c->bitrate, tick_hz, heartbeat_ms(c));
}

/* Each drive's node-ID is one; each bus carries its tick with margin, in
 * the 0x60C2 format, and its SYNC's identifier is no drive's. */
static int co_validate(const struct rig_desc *d, uint32_t hz, struct rig_desc_err *e)
{
	uint32_t k, i;
	uint8_t ip;
	int8_t ex;

	for (i = 0; i < d->noutputs; i++) {
		int32_t dk = -1, j;

		for (j = 0; j < (int32_t)d->ndevices; j++)
			if (on(d, (uint32_t)j, &d->outputs[i]))
				dk = j;
		if (dk < 0 || d->devices[dk].driver != &rig_drv_canopen)
			continue;
		if (!d->devices[dk].priv) {
			e->device = dk;
			snprintf(e->msg, sizeof(e->msg), "device '%s': driver canopen without its "
				 "canopen: settings", d->devices[dk].name);
			return -EINVAL;
		}
		if (d->outputs[i].axis < 1 || d->outputs[i].axis > CO_NODE_MAX) {
			e->output = (int32_t)i;
			snprintf(e->msg, sizeof(e->msg), "node-ID %u: must be 1 to 127",
				 d->outputs[i].axis);
			return -EINVAL;
		}
		/* a CiA 402 position (0x607A, 0x6064) is an INTEGER32: a drive,
		 * and its simulated twin, starts there */
		if (fabs(rig_output_home_counts(&d->outputs[i])) > INT32_MAX) {
			e->output = (int32_t)i;
			e->key = "home";
			snprintf(e->msg, sizeof(e->msg),
				 "home %.10g is %.6g counts, beyond a CiA 402 drive's 32-bit "
				 "position", d->outputs[i].home,
				 rig_output_home_counts(&d->outputs[i]));
			return -ERANGE;
		}
	}
	for (k = 0; k < d->ndevices; k++) {
		const struct rig_canopen_desc *c = d->devices[k].priv;
		struct co_load l;

		if (d->devices[k].driver != &rig_drv_canopen || !c || !drives(d, k))
			continue;
		e->device = (int32_t)k;
		e->key = "canopen";
		load(d, k, hz, &l);
		if (!co_load_fits(&l)) {
			snprintf(e->msg, sizeof(e->msg),
				 "canopen bus '%s': the worst case of a tick is %u bits (%u "
				 "drive%s, bit stuffing) of the %u a tick holds at %u bit/s and "
				 "%u ticks/s: %.0f%%, above %d%%; lower tick_hz, drive fewer "
				 "outputs on this bus or raise the bitrate", d->devices[k].name,
				 l.bits, l.drives, l.drives == 1 ? "" : "s", l.capacity,
				 c->bitrate, hz, 100.0 * l.bits / l.capacity, CO_LOAD_MAX_PERCENT);
			return -EINVAL;
		}
		if (co_interp_period(hz, &ip, &ex) < 0) {
			snprintf(e->msg, sizeof(e->msg),
				 "canopen bus '%s': tick_hz %u: a drive's interpolation "
				 "period (0x60C2: 1 to 255 times a power of ten seconds) cannot "
				 "say %.6g us within 0.1%%", d->devices[k].name, hz, 1e6 / hz);
			return -EINVAL;
		}
		for (i = 0; i < d->noutputs; i++) {
			uint32_t n = d->outputs[i].axis, id = sync_id(c);

			if (!on(d, k, &d->outputs[i]))
				continue;
			if (id == CO_ID_EMCY + n || id == co_tpdo_id(1, (uint8_t)n) ||
			    id == co_rpdo_id(1, (uint8_t)n) || id == CO_ID_SDO_TX + n ||
			    id == CO_ID_SDO_RX + n || id == CO_ID_HEARTBEAT + n) {
				snprintf(e->msg, sizeof(e->msg),
					 "canopen bus '%s': sync_id 0x%x is an identifier of "
					 "node %u", d->devices[k].name, id, n);
				return -EINVAL;
			}
		}
		e->device = -1;
		e->key = NULL;
	}
	return 0;
}

/* Its worst-case bits per tick against what a tick holds. */
static void co_check(FILE *out, const struct rig_desc *d, uint32_t k, uint32_t tick_hz)
{
	const struct rig_device_desc *dd = &d->devices[k];
	const struct rig_canopen_desc *c = dd->priv;
	struct co_load l;

	if (!c)
		return;
	load(d, k, tick_hz, &l);
	if (!l.drives || !l.capacity)
		return;
	fprintf(out, "device '%s': canopen %s at %u bit/s: %u drive%s, worst case %u of %u bits "
		"per tick with bit stuffing (%.0f%%, at most %d%%)\n", dd->name, c->interface,
		c->bitrate, l.drives, l.drives == 1 ? "" : "s", l.bits, l.capacity,
		100.0 * l.bits / l.capacity, CO_LOAD_MAX_PERCENT);
}

/* ---- the run ---- */

/* The simulated drives of interface "sim": the twins of drv_sim.h. */
static int simulated(struct rig_make *m, uint32_t k, const struct co_drive_cfg *drv, uint32_t n,
		     struct co_dev *cd, struct co_bus **bus, char *err, size_t size)
{
	const struct rig *r = m->r;
	const struct rig_device_desc *dd = r->dev[k].desc;
	uint32_t ax = (uint32_t)r->dev[k].axis, i, j;
	int rc;

	rc = co_simbus_new(&cd->sim, m->clk, RIG_CO_SIM_QUEUE, 0, err, size);
	if (rc)
		return rc;
	for (i = 0, j = 0; i < r->nout && j < n; i++) {
		const struct rig_out *o = &r->out[i];
		struct co_slave_cfg c = { .node = drv[j].node, .name = dd->name };

		if (o->dev != ax)
			continue;
		rig_sim_channel(o, &dd->sim, &c.model);
		/* co_validate held home to 32 bits; rounding can still reach past */
		if (c.model.initial < INT32_MIN || c.model.initial > INT32_MAX) {
			snprintf(err, size,
				 "outputs[%u] (%s): home is %lld counts, beyond a CiA 402 drive's "
				 "32-bit position", i, o->channel,
				 (long long)c.model.initial);
			return -ERANGE;
		}
		c.initial = (int32_t)c.model.initial;
		rc = co_simbus_add(NULL, cd->sim, &c, false, err, size);
		if (rc)
			return rc;
		j++;
	}
	*bus = co_simbus_bus(cd->sim);
	return 0;
}

static int co_make_axes(struct rig_make *m, uint32_t k, char *err, size_t size)
{
	struct rig *r = m->r;
	const struct rig_device_desc *dd = r->dev[k].desc;
	const struct rig_canopen_desc *c = dd->priv;
	uint32_t ax = (uint32_t)r->dev[k].axis, i, n = 0;
	struct co_drive_cfg drv[CO_NODE_MAX];
	uint16_t ids[4 * CO_NODE_MAX];
	struct co_rx_filter flt[4 * CO_NODE_MAX];
	struct co_axis_cfg ac = { .name = dd->name, .clk = m->clk, .cancel = m->o->cancel };
	struct co_dev *cd = calloc(1, sizeof(*cd));
	int rc;

	if (!cd) {
		snprintf(err, size, "out of memory");
		return -ENOMEM;
	}
	r->dev[k].priv = cd;
	for (i = 0; i < r->nout; i++) {
		const struct rig_out *o = &r->out[i];
		/* the quick stop brakes at the output's acceleration limit */
		double dec = o->amax * fabs(o->scale.per_unit_d);

		if (o->dev != ax)
			continue;
		if (n == CO_NODE_MAX || o->ch < 1 || o->ch > CO_NODE_MAX) {
			snprintf(err, size, "outputs[%u] (%s): node-ID %u: must be 1 to 127", i,
				 o->channel, o->ch);
			return -EINVAL;
		}
		drv[n].node = (uint8_t)o->ch;
		drv[n].mode = o->vel_mode ? CO402_MODE_CSV : CO402_MODE_CSP;
		drv[n].quick_stop_dec = dec >= 4294967295.0 ? UINT32_MAX :
					dec < 1 ? 1 : (uint32_t)lround(dec);
		n++;
	}
	ac.drives = drv;
	ac.ndrives = n;
	ac.master.tick_hz = m->t->tick_hz;
	ac.master.sync_id = (uint16_t)sync_id(c);
	ac.master.heartbeat_ms = (uint16_t)heartbeat_ms(c);
	ac.master.heartbeat_timeout_ms = RIG_CO_HEARTBEAT_LOST(heartbeat_ms(c));
	ac.master.boot_timeout_ms = RIG_CO_BOOT_MS;
	ac.master.sdo_timeout_ms = RIG_CO_SDO_MS;
	ac.master.enable_timeout_ms = RIG_CO_ENABLE_MS;
	ac.master.stop_timeout_ms = RIG_CO_STOP_MS;
	if (c->interface && !strcmp(c->interface, "sim")) {
		rc = simulated(m, k, drv, n, cd, &ac.bus, err, size);
	} else {
		uint32_t nf = co_master_rx_ids(drv, n, ids);
		char why[160];

		for (i = 0; i < nf; i++) {
			flt[i].id = ids[i];
			flt[i].mask = 0x7ff;
		}
		rc = co_socketcan_open(&ac.bus, c->interface ? c->interface : "", flt, nf, why,
				       sizeof(why));
		if (rc)
			snprintf(err, size, "device '%s': %s", dd->name, why);
	}
	if (rc)
		return rc;
	return co_axis_new(&r->axes[ax], &ac, err, size);
}

/* The SYNCs by phase: what a record of the bus (candump) is matched
 * against, since the start-up's cycles and the loop's carry the same
 * controlword and a start-up takes as many cycles as the drives need to
 * answer in time. */
static void co_report(const struct rig *r, uint32_t k, FILE *f)
{
	const struct co_master *m;
	unsigned long long ran, late = 0;
	uint32_t i;

	if (r->dev[k].axis < 0)
		return;
	m = co_axis_master(r->axes[r->dev[k].axis]);
	if (!m->syncs_started)
		return;
	ran = m->syncs_ran ? m->syncs_ran : m->syncs;
	for (i = 0; i < m->nnodes; i++)
		late += m->node[i].tpdo_late;
	fprintf(f, "  canopen '%s': %llu SYNCs: %llu of the start-up, %llu of the run, %llu of "
		"the stop; %llu TPDOs after the next SYNC\n", r->dev[k].desc->name,
		(unsigned long long)m->syncs, (unsigned long long)m->syncs_started,
		ran - m->syncs_started, (unsigned long long)m->syncs - ran, late);
}

static void co_free(struct rig *r, uint32_t k)
{
	struct co_dev *cd = r->dev[k].priv;

	if (r->dev[k].axis >= 0) {
		hal_axis_close(r->axes[r->dev[k].axis]);
		r->axes[r->dev[k].axis] = NULL;
	}
	/* the bus goes with the last of its master's close and this */
	if (cd)
		co_simbus_free(cd->sim);
	free(cd);
	r->dev[k].priv = NULL;
}

struct co_simbus *rig_canopen_simbus(const struct rig *r, const char *name)
{
	int k = rig_device(r, name);
	const struct co_dev *cd;

	if (k < 0 || r->dev[k].drv != &rig_drv_canopen)
		return NULL;
	cd = r->dev[k].priv;
	return cd ? cd->sim : NULL;
}

const struct rig_driver rig_drv_canopen = {
	.name = "canopen",
	.device_keys = device_keys,
	.device_foreign = "a canopen: section belongs to a device of driver canopen",
	.parse_device = co_parse_device,
	.output_keys = output_keys,
	.output_foreign = "node: and mode: place an output on a canopen device",
	.axis_name = "node",
	.parse_output = co_parse_output,
	.validate = co_validate,
	.check = co_check,
	.make_axes = co_make_axes,
	.report = co_report,
	.free = co_free,
};
