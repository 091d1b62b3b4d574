/* SPDX-License-Identifier: MIT */
/* gpio_priv.h - what gpio_dout.c and gpio_din.c share (gpio_cfg.c). */
#ifndef HAL_GPIO_PRIV_H
#define HAL_GPIO_PRIV_H

#include "gpio.h"
#include "gpio_line.h"

/* A device's lines as one request of gpio_line.h. */
struct hal_gpio_req {
	struct gpio_req_cfg cfg;
	struct gpio_line_cfg lines[GPIO_LINE_MAX];
	bool initial[GPIO_LINE_MAX]; /* outputs: each line's deasserted level */
};

/* [init] The lines' identities into r->lines; for outputs each line's
 * deasserted physical level into r->initial, so that requesting an
 * active-low trigger does not fire it. 0, or -EINVAL with err saying why. */
int hal_gpio_req_init(struct hal_gpio_req *r, const struct hal_gpio_cfg *cfg,
		      enum gpio_req_kind kind, char *err, size_t errsize);

/* Where a chip is, as far as it matters to the loop (gpio_chip.c). */
struct hal_gpio_chip_bus {
	bool sleeps;     /* behind a bus whose transfers wait: the chip can sleep */
	char bus[24];    /* that bus: "i2c", "spi", "usb", ... */
	char device[64]; /* the device on it: "1-0020", "spi0.1" */
	char what[48];   /* its name or driver, when sysfs says: "mcp23017" */
};

/* [init] Whether chip (a kernel name, gpiochip2) sleeps, from sysfs under
 * `sysfs` (NULL: /sys): 1 and *b, 0 when it does not, or a negative errno
 * when sysfs cannot tell (no such chip there, no sysfs). */
int hal_gpio_chip_bus(const char *sysfs, const char *chip, struct hal_gpio_chip_bus *b);

/* [init] The request's chip, if it sleeps: outputs refused (-EOPNOTSUPP,
 * with err saying why and what to do) unless cfg->sleep_ok, else a
 * warning in cfg->warning (empty when there is nothing to say); each with
 * what a set or a read took at start (high: the output lines' levels
 * now, set again unchanged). 0 otherwise. */
int hal_gpio_sleep_check(struct gpio_req *req, const struct hal_gpio_cfg *cfg,
			 enum gpio_req_kind kind, const bool *high, char *err, size_t errsize);

#endif /* HAL_GPIO_PRIV_H */
