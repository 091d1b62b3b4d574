/* SPDX-License-Identifier: MIT */
/* rig_modbus.c - a rig's Modbus device (see rig_modbus.h). */
#include "rig_modbus.h"

#include <errno.h>
#include <stdlib.h>

#include "hal/modbus/modbus_dev.h"

int rig_modbus_open(struct rig *r, const struct rig_desc *d, uint32_t k, uint32_t ax,
		    uint32_t tick_hz, bool lockstep, char *err, size_t size)
{
	const struct rig_device_desc *dd = &d->devices[k];
	struct modbus_cfg c = { .name = dd->name, .d = dd->modbus, .tick_hz = tick_hz,
				.lockstep = lockstep };
	int64_t *initial;
	bool *velocity;
	uint32_t i;
	int rc;

	for (i = 0; i < r->nout; i++)
		if (r->out[i].dev == ax && r->out[i].ch + 1 > c.nch)
			c.nch = r->out[i].ch + 1;
	initial = calloc(c.nch ? c.nch : 1, sizeof(*initial));
	velocity = calloc(c.nch ? c.nch : 1, sizeof(*velocity));
	if (!initial || !velocity) {
		free(initial);
		free(velocity);
		snprintf(err, size, "out of memory");
		return -ENOMEM;
	}
	for (i = 0; i < r->nout; i++) {
		const struct rig_out *o = &r->out[i];

		if (o->dev != ax)
			continue;
		velocity[o->ch] = o->vel_mode;
		initial[o->ch] = o->vel_mode ? 0 : hal_scale_counts(&o->scale, o->home, NULL);
	}
	c.initial = initial;
	c.velocity = velocity;
	rc = hal_modbus_open(&r->axes[ax], &c, err, size);
	free(initial);
	free(velocity);
	return rc;
}
