/* SPDX-License-Identifier: MIT */
/*
 * rig_canopen.h - the CANopen part of the rig: a `canopen` device is one
 * bus, its outputs are its drives, each output's axis is its drive's
 * node-ID. The loader checks the bus load with these; rig_build() makes the
 * backend: the master (hal/canopen/) on a SocketCAN interface, or, for
 * interface "sim", on a simulated bus of simulated CiA 402 drives built
 * from the outputs (sim/co_simbus.h) - the whole protocol in-process.
 */
#ifndef STRAND_RIG_CANOPEN_H
#define STRAND_RIG_CANOPEN_H

#include <stddef.h>
#include <stdint.h>

#include "hal/canopen/co_load.h"
#include "hal/canopen/co_master.h"
#include "rig.h"

#define RIG_CO_HEARTBEAT_MS 50  /* the drives' heartbeat */
/* A drive is lost after 2.5 heartbeats: one late heartbeat is no fault. */
#define RIG_CO_HEARTBEAT_LOST(ms) (((ms) * 5 + 1) / 2)
#define RIG_CO_BOOT_MS 2000     /* reset communication to boot-up */
#define RIG_CO_SDO_MS 500       /* per SDO request */
#define RIG_CO_ENABLE_MS 2000   /* NMT start to operation enabled */
#define RIG_CO_STOP_MS 3000     /* quick stop or shutdown confirmed */
#define RIG_CO_SIM_QUEUE 4096   /* frames a simulated bus holds for the master */

/* Outputs on device k. */
uint32_t rig_canopen_drives(const struct rig_desc *d, uint32_t k);

/* The worst case of device k's bus at tick_hz (co_load.h). */
void rig_canopen_load(const struct rig_desc *d, uint32_t k, uint32_t tick_hz,
		      struct co_load *l);

/* [init] Make device k (rig axis ax) from the rig's built outputs: 0, or a
 * negative errno with a message in err. */
int rig_canopen_make(struct rig *r, const struct rig_desc *d, uint32_t k, uint32_t ax,
		     uint32_t tick_hz, struct hal_clock *clk, char *err, size_t size);

#endif /* STRAND_RIG_CANOPEN_H */
