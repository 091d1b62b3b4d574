/* SPDX-License-Identifier: MIT */
/* gpio_cfg.c - from a device's configuration to a line request (gpio_priv.h). */
#include "gpio_priv.h"

#include <errno.h>
#include <stdio.h>

int hal_gpio_req_init(struct hal_gpio_req *r, const struct hal_gpio_cfg *cfg,
		      enum gpio_req_kind kind, char *err, size_t errsize)
{
	uint32_t i;

	if (!cfg->nlines || cfg->nlines > GPIO_LINE_MAX) {
		snprintf(err, errsize, "device '%s': %u lines (1 to %u on one device)", cfg->device,
			 cfg->nlines, GPIO_LINE_MAX);
		return -EINVAL;
	}
	for (i = 0; i < cfg->nlines; i++) {
		r->lines[i].name = cfg->lines[i].name;
		r->lines[i].offset = cfg->lines[i].offset;
		r->initial[i] = cfg->lines[i].active_low;
	}
	r->cfg = (struct gpio_req_cfg){ .chip = cfg->chip, .consumer = HAL_GPIO_CONSUMER,
					.kind = kind, .nlines = cfg->nlines, .lines = r->lines,
					.initial = kind == GPIO_REQ_OUTPUT ? r->initial : NULL };
	return 0;
}
