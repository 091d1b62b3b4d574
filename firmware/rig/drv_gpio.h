/* SPDX-License-Identifier: MIT */
/*
 * drv_gpio.h - the GPIO driver (drv_gpio.c): a device's trigger lines,
 * rig-ready line and inputs on one GPIO chip (hal/gpio/gpio.h), requested
 * when the rig starts, so that a line held by another process is an error
 * of the start naming the chip and the line.
 *
 *   - {name: io, driver: gpio, chip: gpiochip0}   # chip: optional
 *     allow_sleeping_chip: true    # optional: triggers on a chip that sleeps
 *
 * A chip that sleeps (an expander behind I2C or SPI: hal/gpio/gpio.h) is
 * refused for trigger lines unless the device allows it, and said at
 * start when it is allowed or carries inputs; a device with no trigger
 * (a rig-ready lamp alone, set at start and at the end) costs the loop
 * nothing there, and is taken without a word.
 */
#ifndef STRAND_DRV_GPIO_H
#define STRAND_DRV_GPIO_H

#include "rig_driver.h"

extern const struct rig_driver rig_drv_gpio;

/* A gpio device's settings (rig_device_desc.priv; NULL: the defaults). */
struct rig_gpio_desc {
	const char *chip; /* gpiochip0, /dev/gpiochip0 or a label; NULL: the
			   * lines by name, on whichever chip */
	bool allow_sleeping_chip; /* triggers on a chip that sleeps, with a warning */
};

/* The libgpiod this strand was built with ("1.6.3", "2.2.1"), for
 * `strand --version`: two builds differ by it (mk/gpiod2.mk). */
const char *rig_gpio_lib_version(void);

#endif /* STRAND_DRV_GPIO_H */
