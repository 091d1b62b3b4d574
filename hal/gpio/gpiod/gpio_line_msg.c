/* SPDX-License-Identifier: MIT */
/* gpio_line_msg.c - what the libgpiod 1.x and 2.x request code share: the
 * wording of its errors, so that both APIs say the same thing. */
#include "hal/gpio/gpio_line.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* "chip gpiochip0 line 5" or "chip gpiochip0 line 'estop'" (the name as
 * the scene gave it). */
static int line_where(char *buf, size_t size, const char *chip, const struct gpio_line_cfg *l)
{
	const char *c = chip ? chip : "(any chip)";

	if (!l)
		return snprintf(buf, size, "chip %s", c);
	if (l->name)
		return snprintf(buf, size, "chip %s line '%s'", c, l->name);
	return snprintf(buf, size, "chip %s line %u", c, l->offset);
}

int gpio_line_fail(char *err, size_t errsize, int code, const char *chip,
		   const struct gpio_line_cfg *l, const char *fmt, ...)
{
	va_list ap;
	int n;

	if (!err || !errsize)
		return code;
	n = line_where(err, errsize, chip, l);
	if (n < 0 || (size_t)n >= errsize - 2)
		return code;
	err[n++] = ':';
	err[n++] = ' ';
	va_start(ap, fmt);
	vsnprintf(err + n, errsize - (size_t)n, fmt, ap);
	va_end(ap);
	return code;
}

int gpio_line_busy(char *err, size_t errsize, const char *chip, const struct gpio_line_cfg *l,
		   uint32_t offset, const char *consumer)
{
	if (consumer && *consumer)
		return gpio_line_fail(err, errsize, -EBUSY, chip, l,
				      "offset %u is held by another user (consumer \"%s\"); "
				      "`gpioinfo %s` shows it", offset, consumer, chip);
	return gpio_line_fail(err, errsize, -EBUSY, chip, l,
			      "offset %u is held by another user (a process or the kernel); "
			      "`gpioinfo %s` shows it", offset, chip);
}
