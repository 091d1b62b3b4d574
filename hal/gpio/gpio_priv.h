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

#endif /* HAL_GPIO_PRIV_H */
