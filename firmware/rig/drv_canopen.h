/* SPDX-License-Identifier: MIT */
/*
 * drv_canopen.h - the CANopen driver (drv_canopen.c): a `canopen` device is
 * one bus, its outputs are its drives, each output's axis is its drive's
 * node-ID (the file says node:). The backend is the master
 * (hal/canopen/co_axis.h) on a SocketCAN interface or, for interface "sim",
 * on a simulated bus of simulated CiA 402 drives built from the outputs
 * (sim/co_simbus.h, the twins of drv_sim.h) - the whole protocol in-process.
 *
 *   canopen: {interface: can0, bitrate: 500000, sync_id: 0x80, heartbeat_ms: 50}
 *
 * An output's mode of operation follows its channel: cyclic synchronous
 * velocity for a spin speed (rpm), position for the rest; the file's
 * `mode:` may only say the same.
 */
#ifndef STRAND_DRV_CANOPEN_H
#define STRAND_DRV_CANOPEN_H

#include <stdint.h>

#include "rig.h"
#include "rig_driver.h"
#include "sim/co_simbus.h"

#define RIG_CO_HEARTBEAT_MS 50  /* the drives' heartbeat */
/* A drive is lost after 2.5 heartbeats: one late heartbeat is no fault. */
#define RIG_CO_HEARTBEAT_LOST(ms) (((ms) * 5 + 1) / 2)
#define RIG_CO_BOOT_MS 2000     /* reset communication to boot-up */
#define RIG_CO_SDO_MS 500       /* per SDO request */
#define RIG_CO_ENABLE_MS 2000   /* NMT start to operation enabled */
#define RIG_CO_STOP_MS 3000     /* quick stop or shutdown confirmed */
#define RIG_CO_SIM_QUEUE 4096   /* frames a simulated bus holds for the master */

/* A canopen device's bus (rig_device_desc.priv). */
struct rig_canopen_desc {
	const char *interface; /* a SocketCAN interface, or "sim": simulated drives */
	uint32_t bitrate;      /* bit/s, for the bus load check */
	uint32_t sync_id;      /* COB-ID of the SYNC (0: 0x80) */
	uint32_t heartbeat_ms; /* asked of every drive (0: RIG_CO_HEARTBEAT_MS) */
};

extern const struct rig_driver rig_drv_canopen;

/* The simulated bus of the device called name (interface "sim") of a
 * built rig, for tests; NULL when it has none. */
struct co_simbus *rig_canopen_simbus(const struct rig *r, const char *name);

#endif /* STRAND_DRV_CANOPEN_H */
