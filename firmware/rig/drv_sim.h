/* SPDX-License-Identifier: MIT */
/*
 * drv_sim.h - the simulated twins' driver (drv_sim.c): driver `sim`, and
 * every device under --sim. A device's outputs become one simulated drive
 * (sim/sim_drive.h), its trigger and input lines a simulated GPIO chip
 * (sim/sim_gpio.h) with a simulated camera (sim/sim_camera.h) on each
 * trigger line; the first camera says when it is ready on every
 * camera_ready input of a simulated device.
 *
 * The twin's plant comes from the device's `sim:` settings (rig_desc.h),
 * with sim/'s defaults where it gives none, and from each output: its drive
 * limits are the output's times the limit factor, it stands at the
 * output's home. rig_sim_channel() is that rule, for every twin of a drive
 * (the CANopen driver's simulated bus and strand-simdrive's too), so that
 * each twin is the one `strand play --sim` plays.
 */
#ifndef STRAND_DRV_SIM_H
#define STRAND_DRV_SIM_H

#include <stddef.h>
#include <stdint.h>

#include "rig.h"
#include "rig_driver.h"
#include "sim/sim_camera.h"
#include "sim/sim_drive.h"
#include "sim/sim_gpio.h"

extern const struct rig_driver rig_drv_sim;

/* The plant of a twin: bandwidth, damping and feed-forward from s, the
 * defaults where it gives none; no limits, at 0, position mode. */
void rig_sim_plant(const struct rig_sim_desc *s, struct sim_drive_channel *ch);

/* The twin of output o's channel: the plant, the drive's limits (the
 * output's times the limit factor; none in velocity mode), standing at the
 * output's home. */
void rig_sim_channel(const struct rig_out *o, const struct rig_sim_desc *s,
		     struct sim_drive_channel *ch);

/* [init] The simulated drive of device k of a bound rig (rig_bind): one
 * channel per axis its outputs use, at tick_hz, into *out. 0, or a negative
 * errno with a message naming the device. */
int rig_sim_drive_new(struct sim_drive **out, const struct rig *r, uint32_t k,
		      uint32_t tick_hz, char *err, size_t errsize);

/* The simulated parts of a built rig, for tests: the GPIO chip of the
 * device called name, the camera of trigger i; NULL where it is real. */
struct sim_gpio *rig_sim_gpio(const struct rig *r, const char *name);
struct sim_camera *rig_sim_camera(const struct rig *r, uint32_t trig);

/* [one thread besides the loop] Press every e-stop of the simulated
 * devices: each chain opens and closes again at once (the loop latches
 * the edge). How many there were. For `strand play`'s SIGUSR1 (a button
 * for a rig of simulated devices, the tests'). */
uint32_t rig_sim_press_estop(struct rig *r);

#endif /* STRAND_DRV_SIM_H */
