/* SPDX-License-Identifier: MIT */
/*
 * gpio.h - the GPIO backend: camera trigger lines (hal_dout) and e-stop,
 * stop and camera-ready inputs (hal_din) on a Linux GPIO chip through
 * libgpiod (either API: gpio_line.h).
 *
 * The lines are requested when the device is opened, not at start(), so
 * that a line held by another process is an error at build time whose
 * message names the chip, the line and who holds it (start() returns only
 * an errno).
 *
 * Outputs: the loop stages logical levels and commit() applies the tick's
 * changes in one set-values ioctl, nothing when nothing changed. Edges
 * thus come from the loop's own schedule; no thread sleeps per pulse.
 *
 * Inputs: a thread of the backend's own (strand-gpio-DEVICE, scheduled as
 * cfg.sched says: at the loop's priority in strand's plan) waits in poll()
 * on the lines' event descriptors and hands each edge, with the kernel's CLOCK_MONOTONIC
 * timestamp, to the loop through a lock-free ring (ring.h); poll() in the
 * loop only drains that ring. A full ring is a latched fault, since a lost
 * e-stop edge must not pass silently (the loop also checks the e-stop by
 * level).
 *
 * A chip that sleeps: a GPIO expander behind I2C or SPI (MCP23017,
 * PCA9555, ...) or a USB bridge, which the kernel reaches through a bus
 * transaction in get-values and set-values, hundreds of microseconds on
 * I2C, in the calling thread. Found at open from sysfs (gpio_chip.c says
 * how, and why no libgpiod call can tell). Its output lines would make the
 * loop wait in every tick a trigger changes: refused, unless the device
 * accepts it (sleep_ok), with a warning then. Its input lines only delay
 * the edges the event thread passes on (the kernel reads the chip when it
 * interrupts), never the loop: a warning. Each message says what a set or
 * a read took at start.
 *
 * Polarity is per line and done here, so the loop sees logical levels:
 * active-low lines are asserted at physical 0 (an e-stop chain wired
 * normally closed, an opto-isolated trigger that pulls down).
 */
#ifndef HAL_GPIO_H
#define HAL_GPIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "hal/din.h"
#include "hal/dout.h"
#include "hal/thread.h"

#define HAL_GPIO_CONSUMER "strand"
/* Edges in flight between the event thread and the loop, by default. */
#define HAL_GPIO_RING_DEFAULT 256

struct hal_gpio_line {
	const char *name; /* the line's name on the chip, or NULL: offset */
	uint32_t offset;
	bool active_low;
};

struct hal_gpio_cfg {
	const char *device;  /* the device's name in the scene; copied */
	const char *chip;    /* gpiochip0, /dev/gpiochip0, a label; NULL: by line names */
	uint32_t nlines;     /* 1 .. GPIO_LINE_MAX */
	const struct hal_gpio_line *lines;
	uint32_t ring_cap;   /* inputs: a power of two, 0: HAL_GPIO_RING_DEFAULT */
	struct hal_sched sched; /* inputs: the event thread's (zero: SCHED_OTHER) */
	/* A chip that sleeps (below): outputs are refused unless sleep_ok;
	 * what to say at start goes into warning (warning_size bytes, empty
	 * when nothing; NULL: nowhere). sysfs: where sysfs is mounted, NULL
	 * for /sys (tests give a tree of their own). */
	bool sleep_ok;
	char *warning;
	size_t warning_size;
	const char *sysfs;
};

/*
 * [init] Open a device's output or input lines and request them. 0 and
 * *out, or a negative errno with err naming the device, chip and line.
 */
int hal_gpio_dout_open(struct hal_dout **out, const struct hal_gpio_cfg *cfg, char *err,
		       size_t errsize);
int hal_gpio_din_open(struct hal_din **out, const struct hal_gpio_cfg *cfg, char *err,
		      size_t errsize);

#endif /* HAL_GPIO_H */
