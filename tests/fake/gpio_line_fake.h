/* SPDX-License-Identifier: MIT */
/* gpio_line_fake.h - the test's handle on the fake chip (gpio_line_fake.c). */
#ifndef GPIO_LINE_FAKE_H
#define GPIO_LINE_FAKE_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/gpio/gpio_line.h"

#define FAKE_LINES 16

struct fake_chip {
	const char *name;
	const char *line_name[FAKE_LINES];
	const char *holder[FAKE_LINES]; /* consumer of a held line, or NULL */
	bool high[FAKE_LINES];          /* physical level */
	unsigned sets;                  /* gpio_req_set calls that went through */
	int set_error;                  /* the next sets fail with it */
};

extern struct fake_chip fake_chip;

void fake_reset(void);
/* An edge on input line `line` (index in the last input request). */
void fake_edge(uint32_t line, bool rising, int64_t ts_ns);
/* A level changes with no event (the kernel lost it). */
void fake_level(uint32_t offset, bool high);
/* The line's descriptor hangs up, as when the chip goes away. */
void fake_unplug(uint32_t line);

#endif /* GPIO_LINE_FAKE_H */
