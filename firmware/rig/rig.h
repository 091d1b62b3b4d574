/* SPDX-License-Identifier: MIT */
/*
 * rig.h - a rig ready to run: devices opened behind the HAL, each output
 * bound to a source channel and a device channel with its scale and limits
 * in core units, trigger and input lines resolved to (device, line).
 *
 * Building allocates everything the loop will touch (Klipper's "configure,
 * then seal"); nothing is allocated once the loop runs. Each device is made
 * by its driver (rig_driver.h), which owns what it makes; under --sim, or
 * for a device whose driver is `sim`, by the simulated twin's (drv_sim.h):
 * a drive (sim/sim_drive.h) for outputs, a GPIO chip (sim/sim_gpio.h) for
 * triggers and inputs, and a camera (sim/sim_camera.h) on every trigger
 * line.
 */
#ifndef STRAND_RIG_H
#define STRAND_RIG_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hal/axis.h"
#include "hal/cancel.h"
#include "hal/clock.h"
#include "hal/din.h"
#include "hal/dout.h"
#include "hal/thread.h"
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

/* A device of the rig, as its driver made it. */
struct rig_dev {
	const struct rig_device_desc *desc;
	const struct rig_driver *drv; /* the driver that made it: the sim's under --sim */
	int32_t axis, dout, din;      /* its place in axes[], douts[], dins[]; -1: none */
	void *priv;                   /* the driver's own (what to free) */
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
	uint32_t ndev;                 /* the description's devices, in its order */
	struct rig_dev *dev;
	uint32_t nready;               /* rig-ready outputs: douts[dev], line */
	struct rig_line *ready;
	bool *started_axes, *started_douts, *started_dins;
	const struct hal_cancel *cancel; /* rig_opts.cancel */
};

struct rig_opts {
	bool sim;               /* every device by its simulated twin */
	const char *camera_log; /* the first simulated camera's log file, or NULL */
	uint64_t camera_cap;    /* exposures each simulated camera keeps */
	/* the scheduling of the threads devices start (play/rt.h's plan):
	 * input event threads (GPIO), bus I/O threads (Modbus); zero: SCHED_OTHER */
	struct hal_sched events, io;
	FILE *warn;             /* what a device has to say at start, or NULL: nothing */
	const char *gpio_sysfs; /* where GPIO chips are looked up, NULL: /sys (tests) */
	/* A stop asked for while the devices start (a signal): rig_start()
	 * and the backends' waits give up (hal/cancel.h). NULL: never. */
	const struct hal_cancel *cancel;
};

/* [init] Build the rig for a source. 0, or a negative errno with a message
 * in err naming the section entry and what is wrong. */
int rig_build(struct rig *r, const struct rig_desc *d, struct play_source *src,
	      struct hal_clock *clk, const struct rig_opts *o, char *err, size_t errsize);

/* [init] The first half of rig_build(): the outputs bound to the source's
 * channels and scaled, each device's place among the axes (dev[k].axis),
 * nothing made or opened. For a program that makes one device itself
 * (strand-simdrive); rig_free() frees it. */
int rig_bind(struct rig *r, const struct rig_desc *d, struct play_source *src, char *err,
	     size_t errsize);

/* [init] Start every device; on failure stop those started. -ECANCELED
 * when the run's cancel request (rig_opts.cancel) came meanwhile: the
 * devices started are stopped then too, drives disabled. */
int rig_start(struct rig *r, char *err, size_t errsize);
/* [init] Stop every started device (drives disabled, lines deasserted). */
void rig_stop(struct rig *r);
void rig_free(struct rig *r);

/* [init] Each device's lines for the run's summary (its driver's). */
void rig_report(const struct rig *r, FILE *f);

/* The index of the device called name, or -1. */
int rig_device(const struct rig *r, const char *name);

/* Channels of axis device ax: one past the highest its outputs use. */
uint32_t rig_axis_channels(const struct rig *r, uint32_t ax);

/* Counts an output's axis stands at when the run starts and the device has
 * no feedback: its home (0 for a velocity channel). */
int64_t rig_out_initial(const struct rig_out *o);

/* Core value -> file units (degrees for angles), for messages. */
double rig_file_units(enum src_unit unit, double v);
const char *rig_unit_name(enum src_unit unit);

#endif /* STRAND_RIG_H */
