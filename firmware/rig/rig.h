/* SPDX-License-Identifier: MIT */
/*
 * rig.h - a rig ready to run: devices opened behind the HAL, each output
 * bound to a source channel and a device channel with its scale and limits
 * in core units, trigger and input lines resolved to (device, line).
 *
 * Building allocates everything the loop will touch (Klipper's "configure,
 * then seal"); nothing is allocated once the loop runs. A device whose
 * driver is `gpio` has its trigger lines and inputs on a GPIO chip
 * (hal/gpio.h), requested by rig_start(): a line held elsewhere is a
 * device error whose message names the chip and the line. Under --sim, or for a device whose driver is `sim`, every
 * device is its simulated twin: a
 * drive (sim/sim_drive.h) for outputs, a GPIO chip (sim/sim_gpio.h) for triggers
 * and inputs, and a camera (sim/sim_camera.h) on every trigger line.
 */
#ifndef STRAND_RIG_H
#define STRAND_RIG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "hal/axis.h"
#include "hal/clock.h"
#include "hal/din.h"
#include "hal/dout.h"
#include "hal/gpio/gpio.h"
#include "rig_desc.h"
#include "scale.h"
#include "scene/source.h"

struct rig_out {
	const char *channel;
	uint32_t src;        /* the source's channel index */
	uint32_t dev, ch;    /* rig.axes[dev], its channel ch */
	struct hal_scale scale;
	bool vel_mode;       /* the device follows the value as a velocity */
	enum src_unit unit;
	double min, max;     /* core units; -/+INFINITY when unlimited */
	double vmax, amax;   /* core units per s and s^2; always set */
	double ferror, min_ferror; /* core units; ferror 0: unchecked */
	double in_position;  /* core units */
	mot_q32 home;
};

struct rig_trig {
	const char *name;
	uint32_t dev, line;  /* rig.douts[dev], line index on it */
	int64_t width;       /* ticks, >= 1 */
	int64_t offset;      /* ticks, signed */
};

struct rig_in {
	const char *name;
	uint32_t dev, line;  /* rig.dins[dev] */
	enum rig_input_role role;
};

struct rig_line {
	uint32_t dev, line;
};

/* A device's trigger or input lines on a GPIO chip, requested at start. */
struct rig_gpio {
	bool trig;                   /* douts[at], else dins[at] */
	uint32_t at;
	struct hal_gpio_cfg cfg;
	struct hal_gpio_line *lines;
};

struct rig {
	uint32_t naxes, ndouts, ndins;
	struct hal_axis **axes;
	struct hal_dout **douts;
	struct hal_din **dins;
	uint32_t nout, ntrig, nin;
	struct rig_out *out;
	struct rig_trig *trig;
	struct rig_in *in;
	/* the simulated parts (NULL where a device is real) */
	struct sim_drive **sim_drive;  /* naxes */
	uint32_t nsim_gpio;
	struct sim_gpio **sim_gpio;
	struct sim_camera **camera;    /* ntrig */
	struct co_simbus **co_sim;     /* naxes: a CANopen bus with interface "sim" */
	uint32_t nready;               /* rig-ready outputs: douts[dev], line */
	struct rig_line *ready;
	uint32_t ngpio;                /* real GPIO lines (gpio.h): rig_start requests */
	struct rig_gpio *gpio;         /* them into douts[at] or dins[at] */
	bool *started_axes, *started_douts, *started_dins;
};

struct rig_opts {
	bool sim;               /* every device by its simulated twin */
	const char *camera_log; /* the first simulated camera's log file, or NULL */
	uint64_t camera_cap;    /* exposures each simulated camera keeps */
	int gpio_priority;      /* the GPIO input event thread's SCHED_FIFO priority, 0: none */
};

/* [init] Build the rig for a source. 0, or a negative errno with a message
 * in err naming the section entry and what is wrong. */
int rig_build(struct rig *r, const struct rig_desc *d, struct play_source *src,
	      struct hal_clock *clk, const struct rig_opts *o, char *err, size_t errsize);

/* [init] Start every device; on failure stop those started. */
int rig_start(struct rig *r, char *err, size_t errsize);
/* [init] Stop every started device (drives disabled, lines deasserted). */
void rig_stop(struct rig *r);
void rig_free(struct rig *r);

/* Core value -> file units (degrees for angles), for messages. */
double rig_file_units(enum src_unit unit, double v);
const char *rig_unit_name(enum src_unit unit);

#endif /* STRAND_RIG_H */
