/* SPDX-License-Identifier: MIT */
/*
 * rig_desc.h - the rig as a scene file describes it (the `devices:`,
 * `outputs:`, `triggers:` and `inputs:` sections), in the file's units:
 * degrees for angles, scene units for lengths, rpm, milliseconds. The YAML
 * loader fills one; tests and `strand play --sim` on a scene without a rig
 * (rig_auto.h) build them in code. rig_build() (rig.h) turns it into
 * devices and scaled channels.
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
 * A device's driver is an entry of the driver table (rig_driver.h); what
 * only that driver knows (a Modbus register map, a CANopen bus, a GPIO
 * chip) is behind the device's priv, in the driver's own struct
 * (drv_<name>.h), read from the file by the driver itself. The rest is
 * every device's: its simulated twin, and its rig-ready line.
 *
 * The rules a description must follow are here once (rig_desc.c), for the
 * loader, which puts a refusal at its place in the file, and rig_build(),
 * which names the entry of a description made in code.
 *
 * Ownership: a description owns nothing; its strings and arrays belong to
 * whoever filled it (the loader's pool, a test).
 */
#ifndef STRAND_RIG_DESC_H
#define STRAND_RIG_DESC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "motion/timing.h"
#include "scene/scene_desc.h" /* struct sd_limits */

struct rig_driver; /* rig_driver.h */

/* The simulated twin that stands in for a device under --sim (or always,
 * for driver sim). Zero fields take the defaults of sim/sim_drive.h and
 * sim/sim_camera.h. */
struct rig_sim_desc {
	double bandwidth_hz;   /* position loop bandwidth */
	double damping;        /* zeta */
	double feedforward;    /* velocity feed-forward, 0..1 */
	double limit_factor;   /* drive's own speed/acceleration limits, x the output's */
	double exposure_ms;    /* a camera on one of its trigger lines */
	double readout_ms;
};

struct rig_device_desc {
	const char *name;
	const struct rig_driver *driver; /* rig_driver_find("modbus"), ... */
	const void *priv;      /* the driver's settings (drv_<name>.h); NULL: none */
	struct rig_sim_desc sim;
	/* a rig-ready output (a lamp, a PLC input): asserted once every
	 * device has started, deasserted when the run ends */
	bool has_ready;
	uint32_t ready_line;
	const char *ready_line_name; /* by name; NULL: by number */
	bool ready_active_low;
};

struct rig_output_desc {
	const char *channel;     /* a scene channel (README "Channels") */
	const char *device;
	uint32_t axis;           /* channel number on the device (a CANopen drive's node-ID) */
	double counts_per_unit;  /* non-zero; per degree for angles */
	double offset;           /* counts at value 0 */
	struct sd_limits limits; /* where set, they replace the node's */
	double ferror;           /* bound at full speed; 0: not checked */
	double min_ferror;       /* bound at rest (<= ferror) */
	double in_position;      /* step mode tolerance; 0: the default */
	double home;             /* where the axis stands at start when it has no feedback */
	const void *priv;        /* its device's driver's settings of it; NULL: none */
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

/*
 * boards: and lockstep: (README "Several boards, one scene"): the boards
 * that play one scene together, each driving some of its devices, one of
 * them leading (play/lockstep.h).
 */
struct rig_board_desc {
	const char *name;
	const char *address;     /* where the others reach it: an IP address or a host name */
	uint32_t port;           /* UDP; 0: lockstep's */
	bool lead;               /* exactly one board leads */
	uint32_t ndevices;
	const uint32_t *devices; /* indices into rig_desc.devices; each device on one board */
};

struct rig_lockstep_desc {
	uint32_t port;        /* UDP port of every board without its own */
	double start_ms;      /* the start instant, after the longest pre-roll */
	double heartbeat_ms;  /* every board to every other, while they play */
	double lost_ms;       /* none from a board this long: it is lost */
	double join_ms;       /* how long a board waits for the others to come up */
	double max_offset_us; /* the boards' clocks may disagree by this much */
	double ptp_offset_ns; /* ptp4l's offset from its master, for it to count as locked */
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
	uint32_t nboards;    /* 0: one board plays the whole rig */
	const struct rig_board_desc *boards;
	struct rig_lockstep_desc lockstep; /* the defaults when the scene says nothing */
};

/* lockstep:'s defaults. */
#define RIG_LOCKSTEP_PORT 47474
#define RIG_LOCKSTEP_DEFAULTS                                                              \
	{ .port = RIG_LOCKSTEP_PORT, .start_ms = 2000, .heartbeat_ms = 100, .lost_ms = 500,   \
	  .join_ms = 30000, .max_offset_us = 1000, .ptp_offset_ns = 100000 }

/* [init] The part of rig `in` that board b drives: its devices and the
 * outputs, triggers and inputs on them, into out (arrays allocated; free
 * with rig_desc_board_free). 0 or -ENOMEM. */
int rig_desc_board(const struct rig_desc *in, uint32_t b, struct rig_desc *out);
void rig_desc_board_free(struct rig_desc *d);

/* ---- the rules (rig_desc.c) ------------------------------------------------
 * [init]. Each: 0, or a negative errno with the reason in msg, which names
 * neither the file's position nor the entry (the loader puts it at the key
 * it names, rig_build() prefixes the entry). The loader applies each as
 * soon as the keys it reads are read, so that a file's first mistake is the
 * one reported. */

/*
 * The ranges of a rig's numbers (README, "The rig"), chosen so that every
 * computation made with them later is defined and means something, and so
 * that no rig a user builds is near them:
 *
 * A velocity or acceleration limit is at least RIG_LIMIT_RATE_MIN (per
 * second, per second squared, in the file's units: degrees, scene units,
 * rpm): a millionth of a degree a second is a turn in 11 years, and below
 * it the pre-roll, the moves and the stops (planned in ticks) would take
 * longer than NUM_TICKS_MAX for any distance. The largest is the core's,
 * as for every value (|v| < 2^30 core units a second).
 */
#define RIG_LIMIT_RATE_MIN 1e-6

/* A scale is at least RIG_SCALE_MIN counts per turn or unit in magnitude:
 * 10,000 turns a count is coarser than any encoder; below it the Q32.32
 * scale would round to few significant bits, or to zero. */
#define RIG_SCALE_MIN 1e-4

/* The simulated twin's plant, as strand-simdrive's options take it: a
 * bandwidth of 0.01 to 10000 Hz (the plant is stepped 20 times per radian
 * of its bandwidth, so 10 kHz at tick_hz 1 is 1.3 million steps a tick),
 * damping 0.01 to 100, a limit factor 0.01 to 1000 (the drive's own limits
 * from a hundredth to a thousand times the output's), and the simulated
 * camera's exposure and readout up to a day each (their sum in ns is added
 * to a trigger's time). */
#define RIG_SIM_BANDWIDTH_MIN 0.01
#define RIG_SIM_BANDWIDTH_MAX 10000.0
#define RIG_SIM_DAMPING_MIN 0.01
#define RIG_SIM_DAMPING_MAX 100.0
#define RIG_SIM_LIMIT_FACTOR_MIN 0.01
#define RIG_SIM_LIMIT_FACTOR_MAX 1000.0
#define RIG_SIM_CAMERA_MS_MAX 86400000.0

/* A device's sim: settings within those ranges (0: the default), and
 * feedforward 0 to 1. *key: the key at fault. -ERANGE */
int rig_sim_check(const struct rig_sim_desc *s, const char **key, char *msg, size_t size);

/* counts_per_unit: at least RIG_SCALE_MIN and below 2^31 counts per turn
 * (turns: the channel is an angle) or per unit, in magnitude. -ERANGE */
int rig_output_check_scale(const struct rig_output_desc *o, bool turns, char *msg,
			   size_t size);

/* offset: within +-9e18 counts. -ERANGE */
int rig_output_check_offset(const struct rig_output_desc *o, char *msg, size_t size);

/* Where home is in counts: home times counts_per_unit (both per degree
 * for an angle) plus the offset. */
double rig_output_home_counts(const struct rig_output_desc *o);

/* home: within +-9e18 counts, as the offset. -ERANGE */
int rig_output_check_home(const struct rig_output_desc *o, char *msg, size_t size);

/* ferror, min_ferror and in_position not negative (the output's mapping is
 * at fault), min_ferror at most ferror (*at_min: min_ferror is). -EINVAL */
int rig_output_check_ferror(const struct rig_output_desc *o, bool *at_min, char *msg,
			    size_t size);

/* The limits an output moves by: each of its own where set, else the
 * scene's for its channel (its node's; scene may be NULL). */
void rig_output_limits(const struct sd_limits *own, const struct sd_limits *scene,
		       struct sd_limits *out);

/* Velocity and acceleration limits in lim, above zero (the pre-roll, the
 * moves and every stop are planned with them), and min <= max. node: the
 * channel is a node's, whose limits would have done. -EINVAL; or -ERANGE
 * for a limit below RIG_LIMIT_RATE_MIN. */
int rig_output_check_limits(const char *channel, const struct sd_limits *lim, bool node,
			    char *msg, size_t size);

/* A trigger at timing t: its pulse in whole ticks (*width, at least one)
 * ends before the next frame's edge, its offset in ticks (*offset) is less
 * than a frame (*at_offset: the offset is at fault). -EINVAL */
int rig_trigger_check(const struct rig_trigger_desc *g, const struct mot_timing *t,
		      int64_t *width, int64_t *offset, bool *at_offset, char *msg, size_t size);

/* Where a driver's check of the whole description (rig_driver.validate)
 * found it wrong: an output, or a device's key. */
struct rig_desc_err {
	int32_t output;  /* the output at fault, or -1 */
	int32_t device;  /* else the device at fault, or -1 */
	const char *key; /* ... at this key of its mapping; NULL: the mapping */
	char msg[256];
};

/* Every driver's check of the whole description at tick_hz, in the
 * table's order: 0, or the first refusal (a negative errno) with e. */
int rig_desc_validate(const struct rig_desc *d, uint32_t tick_hz, struct rig_desc_err *e);

#endif /* STRAND_RIG_DESC_H */
