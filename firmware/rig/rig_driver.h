/* SPDX-License-Identifier: MIT */
/*
 * rig_driver.h - the rig's drivers: one entry per backend, each the whole of
 * what strand knows about its kind of device, from the scene file to the
 * run's summary. Generic code (the loader, rig_build(), strand check, the
 * summary) goes through the table and never tests a device's type, so a
 * new backend is one new file (drv_<name>.c) and its line in drivers.c.
 * The kernel's model: a driver reads its own device-tree properties through
 * a generic API (here yaml/yml.h) and owns what it makes.
 *
 *   drv_sim.c      the simulated twins (sim/): drives, GPIO chips, cameras;
 *                  under --sim it makes every device, whatever its driver
 *   drv_modbus.c   Modbus drives (hal/modbus/)
 *   drv_gpio.c     trigger and input lines on a GPIO chip (hal/gpio/)
 *   drv_canopen.c  a CANopen bus of CiA 402 drives (hal/canopen/), or its
 *                  simulated bus (interface "sim")
 *   drv_dmx.c      lights on DMX512 universes over E1.31 or Art-Net (hal/dmx/)
 *
 * Every hook is [init]. A hook left NULL is a thing the driver does not
 * do: a driver without make_axes drives no output, one without make_lines
 * has no trigger or input lines; the other hooks are optional.
 */
#ifndef STRAND_RIG_DRIVER_H
#define STRAND_RIG_DRIVER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <yaml.h>

#include "rig_desc.h"

struct chan;
struct hal_clock;
struct rig;
struct rig_opts;
struct yml;

/* What a driver's parse hook reads: a device's or an output's mapping. */
struct rig_parse {
	struct yml *y;          /* the readers, their positions and the pool */
	uint32_t tick_hz;       /* the scene's */
	yaml_node_t *map;       /* the device's or the output's mapping */
	yaml_node_t *const *v;  /* the values of the driver's keys, in its order; NULL: absent */
	const struct rig_device_desc *dev; /* parse_output: the output's device */
};

/* What a driver's make hooks build on: the rig, its outputs bound and
 * scaled (rig_bind), and the run. */
struct rig_make {
	struct rig *r;
	const struct rig_desc *d;
	struct hal_clock *clk;
	const struct rig_opts *o;
	const struct mot_timing *t;
};

struct rig_driver {
	const char *name; /* the file's `driver:` */

	/* ---- the scene file (the loader) ---- */
	/* The keys of its settings in a device's mapping (NULL-terminated;
	 * NULL: none), and the refusal of one of them on another driver's
	 * device. */
	const char *const *device_keys;
	const char *device_foreign;
	/* A device of this driver: its settings from p->v (the values of
	 * device_keys) into dev->priv, from the scene file's pool. */
	int (*parse_device)(const struct rig_parse *p, struct rig_device_desc *dev);
	/* The same for an output on one of its devices: output_keys, and the
	 * start of the refusal of one of them on another driver's device
	 * ("...; '<device>' is not one" follows). */
	const char *const *output_keys;
	const char *output_foreign;
	/* What its outputs' axis is called in messages ("node"); NULL: "axis". */
	const char *axis_name;
	/* An output on one of its devices (o->channel and o->device set; c its
	 * channel): its axis into *axis from p->v or from axis_at, the output's
	 * axis: (NULL when absent), with *at where the file gave it, and
	 * o->priv. NULL: the axis is axis:, 0 to 1023. */
	int (*parse_output)(const struct rig_parse *p, yaml_node_t *axis_at, const struct chan *c,
			    struct rig_output_desc *o, long long *axis, yaml_node_t **at);
	/* The whole description, once every output is read (register maps,
	 * bus loads, identifiers): 0, or a negative errno with e saying where.
	 * The loader puts it at its place; rig_build() runs it for a
	 * description made in code. */
	int (*validate)(const struct rig_desc *d, uint32_t tick_hz, struct rig_desc_err *e);
	/* strand check's lines about device k of d (its bus, say). */
	void (*check)(FILE *out, const struct rig_desc *d, uint32_t k, uint32_t tick_hz);

	/* ---- the run ---- */
	/* Device k's axes: r->axes[r->dev[k].axis], with what it needs kept
	 * in r->dev[k].priv. 0, or a negative errno with a message naming the
	 * device. */
	int (*make_axes)(struct rig_make *m, uint32_t k, char *err, size_t errsize);
	/* Device k's nt output lines (its triggers in file order, then its
	 * rig-ready line) as r->douts[dev.dout], its ni inputs as
	 * r->dins[dev.din] (an index is -1 where the count is 0). */
	int (*make_lines)(struct rig_make *m, uint32_t k, uint32_t nt, uint32_t ni, char *err,
			  size_t errsize);
	/* Trigger i (trig) or input i is line `line` of device k: its
	 * polarity, what listens to it. NULL: make_lines did it all. */
	int (*bind)(struct rig_make *m, uint32_t k, bool trig, uint32_t i, uint32_t line,
		    char *err, size_t errsize);
	/* What only a run takes, before the devices start (GPIO requests its
	 * lines here: one held elsewhere is an error of the start). */
	int (*start)(struct rig *r, uint32_t k, char *err, size_t errsize);
	/* Its lines in the run's summary (after the loop). */
	void (*report)(const struct rig *r, uint32_t k, FILE *f);
	/* Release everything it made for device k, its HAL objects included. */
	void (*free)(struct rig *r, uint32_t k);
};

/* The table, NULL-terminated, in the order `driver:` lists them (drivers.c). */
extern const struct rig_driver *const rig_drivers[];

/* The driver of every device's simulated twin: it makes every device under
 * --sim (drv_sim.h). */
extern const struct rig_driver *const rig_driver_twin;

/* The driver called name, or NULL. */
const struct rig_driver *rig_driver_find(const char *name);

#endif /* STRAND_RIG_DRIVER_H */
