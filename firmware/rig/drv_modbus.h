/* SPDX-License-Identifier: MIT */
/*
 * drv_modbus.h - the Modbus driver (drv_modbus.c): a device of driver
 * modbus is one unit on a TCP or RTU bus, its `modbus:` section a struct
 * modbus_desc (hal/modbus/modbus_desc.h) behind the device's priv, its
 * outputs the map's axes.
 */
#ifndef STRAND_DRV_MODBUS_H
#define STRAND_DRV_MODBUS_H

#include "hal/modbus/modbus_desc.h"
#include "rig_driver.h"

extern const struct rig_driver rig_drv_modbus;

/* A device's bus and register map; NULL when its driver is another. */
const struct modbus_desc *rig_modbus_desc(const struct rig_device_desc *dev);

#endif /* STRAND_DRV_MODBUS_H */
