/* SPDX-License-Identifier: MIT */
/*
 * check_bus.c - `strand check`'s lines about the rig's devices: each
 * driver's own (rig_driver.h): for a Modbus device, what one update takes on
 * its bus and the rate it reaches; for a CANopen bus, the worst-case bits of
 * a tick against what a tick holds (the loader has already refused a rate
 * or a load it cannot carry).
 */
#include "check_bus.h"

#include "rig/rig_driver.h"

void check_buses(FILE *out, const struct rig_desc *rig, uint32_t tick_hz)
{
	uint32_t k;

	for (k = 0; k < rig->ndevices; k++) {
		const struct rig_driver *drv = rig->devices[k].driver;

		if (drv && drv->check)
			drv->check(out, rig, k, tick_hz);
	}
}
