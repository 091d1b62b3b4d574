/* SPDX-License-Identifier: MIT */
/*
 * sysfs_tree.h - a sysfs tree made the way the kernel lays one out, in a
 * temporary folder, for the tests of a GPIO chip that sleeps
 * (hal/gpio/gpio_chip.c): devices/ holds the devices, each with a
 * `subsystem` link to its bus; bus/gpio/devices/gpiochipN links to the
 * chip's device, under the device that provides it.
 *
 * The tree is a Raspberry Pi's, cut down: gpiochip0 the SoC's own (on the
 * platform bus), gpiochip2 an MCP23017 on I2C bus 1 (1-0020, name
 * "mcp23017"), gpiochip3 a 74HC595 chain on SPI (spi0.1, driver
 * gpio-74x164, a class device spi_master/spi0 in between); and gpiochip7,
 * the fake chip's name (tests/fake/gpio_line_fake.c), as one of them.
 */
#ifndef SYSFS_TREE_H
#define SYSFS_TREE_H

struct sysfs_tree {
	char root[64];
};

/* Make the tree, with gpiochip7 where chip_at is (gpiochip0, 2 or 3). */
void sysfs_tree_make(struct sysfs_tree *t, const char *chip_at);
void sysfs_tree_free(struct sysfs_tree *t);

#endif /* SYSFS_TREE_H */
