/* SPDX-License-Identifier: MIT */
/* rig_modbus.h - a Modbus device of a rig (rig.c's block for driver modbus). */
#ifndef STRAND_RIG_MODBUS_H
#define STRAND_RIG_MODBUS_H

#include "rig.h"

/* [init] Open device k of d as r->axes[ax]: its channels are the outputs
 * bound to it, velocity-mode where the output is, standing at home where
 * the drive has no actual-position register. lockstep on the virtual clock.
 * 0, or a negative errno with a message. */
int rig_modbus_open(struct rig *r, const struct rig_desc *d, uint32_t k, uint32_t ax,
		    uint32_t tick_hz, bool lockstep, char *err, size_t size);

#endif /* STRAND_RIG_MODBUS_H */
