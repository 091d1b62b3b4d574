/* SPDX-License-Identifier: MIT */
/* rig_canopen.c - CANopen buses of the rig (see rig_canopen.h). */
#include "rig_canopen.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/canopen/co_axis.h"
#include "hal/canopen/co_socketcan.h"
#include "sim/co_simbus.h"

static bool on(const struct rig_desc *d, uint32_t k, const struct rig_output_desc *o)
{
	return o->device && !strcmp(o->device, d->devices[k].name);
}

uint32_t rig_canopen_drives(const struct rig_desc *d, uint32_t k)
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

void rig_canopen_load(const struct rig_desc *d, uint32_t k, uint32_t tick_hz, struct co_load *l)
{
	const struct rig_canopen_desc *c = &d->devices[k].canopen;

	co_load_tick(l, rig_canopen_drives(d, k), c->bitrate, tick_hz, heartbeat_ms(c));
}

/* The simulated drives of interface "sim": the twin's model, standing at
 * home, their own limits the outputs' times the limit factor. */
static struct co_bus *simulated(struct rig *r, const struct rig_device_desc *dd, uint32_t ax,
				const struct co_drive_cfg *drv, uint32_t n,
				struct hal_clock *clk, char *err, size_t size)
{
	const struct rig_sim_desc *sd = &dd->sim;
	double lf = sd->limit_factor > 0 ? sd->limit_factor : SIM_DRIVE_DEFAULT_LIMIT_FACTOR;
	struct co_simbus *sb;
	uint32_t i, j;

	if (co_simbus_new(&sb, clk, RIG_CO_SIM_QUEUE, 0, err, size))
		return NULL;
	for (i = 0, j = 0; i < r->nout && j < n; i++) {
		const struct rig_out *o = &r->out[i];
		double pu = fabs(o->scale.per_unit_d);
		struct co_slave_cfg c = {
			.node = drv[j].node,
			.name = dd->name,
			.model = {
				.bandwidth_hz = sd->bandwidth_hz > 0 ? sd->bandwidth_hz :
								       SIM_DRIVE_DEFAULT_BANDWIDTH_HZ,
				.damping = sd->damping > 0 ? sd->damping : SIM_DRIVE_DEFAULT_DAMPING,
				.feedforward = sd->feedforward > 0 ? fmin(sd->feedforward, 1) :
								     SIM_DRIVE_DEFAULT_FEEDFORWARD,
				.vel_max = o->vel_mode ? 0 : lf * o->vmax * pu,
				.acc_max = o->vel_mode ? 0 : lf * o->amax * pu,
			},
		};

		if (o->dev != ax)
			continue;
		c.initial = o->vel_mode ? 0 : (int32_t)hal_scale_counts(&o->scale, o->home, NULL);
		if (co_simbus_add(NULL, sb, &c, false, err, size)) {
			co_simbus_free(sb);
			return NULL;
		}
		j++;
	}
	r->co_sim[ax] = sb;
	return co_simbus_bus(sb);
}

int rig_canopen_make(struct rig *r, const struct rig_desc *d, uint32_t k, uint32_t ax,
		     uint32_t tick_hz, struct hal_clock *clk, char *err, size_t size)
{
	const struct rig_device_desc *dd = &d->devices[k];
	const struct rig_canopen_desc *c = &dd->canopen;
	struct co_drive_cfg drv[CO_NODE_MAX];
	uint16_t ids[4 * CO_NODE_MAX];
	struct co_rx_filter flt[4 * CO_NODE_MAX];
	struct co_axis_cfg ac = { .name = dd->name, .clk = clk };
	uint32_t i, n = 0;
	int rc;

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
		drv[n].mode = o->vel_mode ? 9 : 8;
		drv[n].quick_stop_dec = dec >= 4294967295.0 ? UINT32_MAX :
					dec < 1 ? 1 : (uint32_t)lround(dec);
		n++;
	}
	ac.drives = drv;
	ac.ndrives = n;
	ac.master.tick_hz = tick_hz;
	ac.master.sync_id = (uint16_t)(c->sync_id ? c->sync_id : CO_ID_SYNC);
	ac.master.heartbeat_ms = (uint16_t)heartbeat_ms(c);
	ac.master.heartbeat_timeout_ms = RIG_CO_HEARTBEAT_LOST(heartbeat_ms(c));
	ac.master.boot_timeout_ms = RIG_CO_BOOT_MS;
	ac.master.sdo_timeout_ms = RIG_CO_SDO_MS;
	ac.master.enable_timeout_ms = RIG_CO_ENABLE_MS;
	ac.master.stop_timeout_ms = RIG_CO_STOP_MS;
	if (c->interface && !strcmp(c->interface, "sim")) {
		ac.bus = simulated(r, dd, ax, drv, n, clk, err, size);
	} else {
		uint32_t nf = co_master_rx_ids(drv, n, ids);
		char why[160];

		for (i = 0; i < nf; i++) {
			flt[i].id = ids[i];
			flt[i].mask = 0x7ff;
		}
		rc = co_socketcan_open(&ac.bus, c->interface ? c->interface : "", flt, nf, why,
				       sizeof(why));
		if (rc) {
			snprintf(err, size, "device '%s': %s", dd->name, why);
			return rc;
		}
	}
	if (!ac.bus)
		return -ENOMEM;
	return co_axis_new(&r->axes[ax], &ac, err, size);
}
