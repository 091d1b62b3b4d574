/* SPDX-License-Identifier: MIT */
/*
 * rig_desc.h - the rig as a scene file describes it (the `devices:`,
 * `outputs:`, `triggers:` and `inputs:` sections), in the file's units:
 * degrees for angles, scene units for lengths, rpm, milliseconds. The YAML
 * loader fills one; until it does, tests and the temporary player build
 * them in code. rig_build() (rig.h) turns it into devices and scaled
 * channels.
 *
 *   devices:
 *     - {name: arm, driver: sim, sim: {bandwidth: 40, damping: 1, feedforward: 0.9}}
 *     - {name: io, driver: sim}
 *   outputs:                     # scene channels onto device channels
 *     - channel: base.angle      # any channel: <node>.angle|position|x|y|z,
 *       device: arm              #   <node>.rpm, camera.pan, an attribute, ...
 *       axis: 0                  # the channel number on the device
 *       counts_per_unit: 1000    # per degree, per scene unit, per rpm
 *       offset: 0                # counts at 0
 *       limits: {min: -170, max: 170, velocity: 90, acceleration: 360}
 *       ferror: 2                # following error bound at full speed (units)
 *       min_ferror: 0.2          # ... at rest
 *       in_position: 0.05        # step mode: close enough to shoot
 *     - {name: gpio0, driver: gpio, chip: gpiochip0,   # chip: optional
 *        ready: {line: RIG_READY, active_low: false}}  # optional
 *   triggers:                    # camera trigger lines
 *     - {name: cam, device: io, line: 0, pulse_ms: 2, active_low: false, offset_ms: -8}
 *     - {name: cam2, device: gpio0, line: CAM2_TRIG}   # a line by its name
 *   inputs:
 *     - {name: estop, device: io, line: 0, role: estop, active_low: true}
 *     - {name: ready, device: io, line: 1, role: camera_ready}
 *
 * Ownership: a description owns nothing; its strings and arrays belong to
 * whoever filled it (the loader's pool, a test).
 */
#ifndef STRAND_RIG_DESC_H
#define STRAND_RIG_DESC_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/modbus/modbus_desc.h"
#include "scene/scene_desc.h" /* struct sd_limits */

enum rig_driver {
	RIG_DRIVER_SIM,     /* always simulated */
	RIG_DRIVER_MODBUS,  /* issue 5 */
	RIG_DRIVER_GPIO,    /* issue 6 */
	RIG_DRIVER_CANOPEN, /* issue 7 */
};

/* The simulated twin that stands in for a device under --sim (or always,
 * for driver sim). Zero fields take the defaults of rig.h. */
struct rig_sim_desc {
	double bandwidth_hz;   /* position loop bandwidth */
	double damping;        /* zeta */
	double feedforward;    /* velocity feed-forward, 0..1 */
	double limit_factor;   /* drive's own speed/acceleration limits, x the output's */
	double exposure_ms;    /* a camera on one of its trigger lines */
	double readout_ms;
};

/* A CANopen bus of CiA 402 drives (driver canopen); its outputs name the
 * drives by node-ID.
 *   canopen: {interface: can0, bitrate: 500000, sync_id: 0x80, heartbeat_ms: 50} */
struct rig_canopen_desc {
	const char *interface; /* a SocketCAN interface, or "sim": simulated drives */
	uint32_t bitrate;      /* bit/s, for the bus load check */
	uint32_t sync_id;      /* COB-ID of the SYNC (default 0x80) */
	uint32_t heartbeat_ms; /* asked of every drive (default RIG_CO_HEARTBEAT_MS) */
};

struct rig_device_desc {
	const char *name;
	enum rig_driver driver;
	struct rig_sim_desc sim;
	/* the hardware backends add their settings here (issues 5-7) */
	const struct modbus_desc *modbus; /* driver modbus: bus and register map */
	const char *chip;      /* gpio: gpiochip0, /dev/gpiochip0 or a label;
				* NULL: the lines by name, on whichever chip */
	/* a rig-ready output (a lamp, a PLC input): asserted once every
	 * device has started, deasserted when the run ends */
	bool has_ready;
	uint32_t ready_line;
	const char *ready_line_name; /* by name; NULL: by number */
	bool ready_active_low;
	struct rig_canopen_desc canopen; /* driver canopen: the bus */
};

/* An output on a CANopen bus: its drive's node-ID is the output's axis
 * (the file says node:), its mode of operation follows the channel. */
struct rig_canopen_out_desc {
	uint8_t mode; /* 8 CSP, 9 CSV (rpm channels); 0: from the channel */
};

struct rig_output_desc {
	const char *channel;     /* a scene channel (README "Channels") */
	const char *device;
	uint32_t axis;           /* channel number on the device */
	double counts_per_unit;  /* non-zero; per degree for angles */
	double offset;           /* counts at value 0 */
	struct sd_limits limits; /* where set, they replace the node's */
	double ferror;           /* bound at full speed; 0: not checked */
	double min_ferror;       /* bound at rest (<= ferror) */
	double in_position;      /* step mode tolerance; 0: the default */
	double home;             /* where the axis stands at start when it has no feedback */
	struct rig_canopen_out_desc canopen; /* driver canopen: node: and mode: */
};

struct rig_trigger_desc {
	const char *name;
	const char *device;
	uint32_t line;
	double pulse_ms;  /* width; at least one tick, less than a frame */
	bool active_low;
	double offset_ms; /* edge time relative to the frame's tick; negative
			   * fires early to make up for a camera's shutter lag */
	const char *line_name; /* gpio: the line by its name; NULL: by number */
};

enum rig_input_role {
	RIG_INPUT_ESTOP,        /* stop within one tick, drives off, latch */
	RIG_INPUT_STOP,         /* a controlled stop, like SIGINT */
	RIG_INPUT_CAMERA_READY, /* step mode: the camera can take the next frame */
};

struct rig_input_desc {
	const char *name;
	const char *device;
	uint32_t line;
	enum rig_input_role role;
	bool active_low;
	const char *line_name; /* gpio: the line by its name; NULL: by number */
};

struct rig_desc {
	uint32_t ndevices;
	const struct rig_device_desc *devices;
	uint32_t noutputs;
	const struct rig_output_desc *outputs;
	uint32_t ntriggers;
	const struct rig_trigger_desc *triggers;
	uint32_t ninputs;
	const struct rig_input_desc *inputs;
};

#endif /* STRAND_RIG_DESC_H */
