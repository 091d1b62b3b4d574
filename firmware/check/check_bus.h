/* SPDX-License-Identifier: MIT */
/* check_bus.h - strand check's report on the rig's buses (check_bus.c). */
#ifndef STRAND_CHECK_BUS_H
#define STRAND_CHECK_BUS_H

#include <stdint.h>
#include <stdio.h>

#include "rig/rig_desc.h"

/* Each device's lines by its driver: a bus device's update time on the bus,
 * the rate reached, the load of a tick. */
void check_buses(FILE *out, const struct rig_desc *rig, uint32_t tick_hz);

#endif /* STRAND_CHECK_BUS_H */
