/* SPDX-License-Identifier: MIT */
/*
 * simdrive.h - strand-simdrive: one device of a scene's rig played by the
 * simulated drive (sim/sim_drive.h) behind a real protocol server, for tests
 * and for trying a scene's wiring without a drive.
 *
 *   main.c   options, the scene, the device's simulated twin (made by the
 *            rig's sim driver alone, rig/drv_sim.h: the twin `strand play
 *            --sim` plays), then its Modbus server (sim/mb_server.h: TCP,
 *            or RTU over a pseudo-terminal) until a signal
 *   can.c    --can IFACE --node N: a CiA 402 drive on SocketCAN
 *            (sim/co_slave.h around the same plant), no scene needed: the
 *            master configures it by SDO
 */
#ifndef SIMDRIVE_H
#define SIMDRIVE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "load/load.h"
#include "rig/drv_modbus.h"
#include "rig/drv_sim.h"
#include "rig/rig.h"
#include "scene/source_scene.h"
#include "sim/mb_server.h"

struct simdrive {
	const char *scene_path, *device;
	struct scene_file sf;
	struct scene_built b;
	struct source_scene src;
	struct rig rig;           /* bound only: the outputs, scaled */
	struct sim_drive *drive;  /* the device's twin */
	bool have_sf, have_b, have_src, have_rig;
	const struct rig_device_desc *dd;
	bool *velocity;           /* nch */
	struct mb_server_cfg mb;  /* the server, its drive, faults and options */
};

/* can.c: the whole program in CAN mode (its own options); the exit code. */
int simdrive_can_main(int argc, char **argv);

#endif /* SIMDRIVE_H */
