/* SPDX-License-Identifier: MIT */
/*
 * drivers.c - the rig's driver table (rig_driver.h): one line per backend,
 * in the order the scene file's `driver:` lists them.
 */
#include <string.h>

#include "rig_driver.h"

extern const struct rig_driver rig_drv_sim, rig_drv_modbus, rig_drv_gpio, rig_drv_canopen,
	rig_drv_dmx;

const struct rig_driver *const rig_drivers[] = {
	&rig_drv_sim,
	&rig_drv_modbus,
	&rig_drv_gpio,
	&rig_drv_canopen,
	&rig_drv_dmx,
	NULL,
};

const struct rig_driver *const rig_driver_twin = &rig_drv_sim;

const struct rig_driver *rig_driver_find(const char *name)
{
	const struct rig_driver *const *d;

	for (d = rig_drivers; name && *d; d++)
		if (!strcmp((*d)->name, name))
			return *d;
	return NULL;
}
