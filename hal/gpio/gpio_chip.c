/* SPDX-License-Identifier: MIT */
/*
 * gpio_chip.c - whether a GPIO chip sleeps in get and set (gpio_priv.h).
 *
 * The kernel knows: a driver sets struct gpio_chip.can_sleep when reaching
 * its chip takes a bus transaction (an expander behind I2C or SPI, a USB
 * bridge), and then get-values and set-values wait for that transaction
 * (hundreds of microseconds on I2C) in the calling thread: for a trigger,
 * the loop. But the kernel tells user space only in debugfs
 * (/sys/kernel/debug/gpio, "can sleep"), which is root's, often not
 * mounted, and no interface. Neither GPIO character device ABI carries it:
 * v1's struct gpioline_info flags are KERNEL, IS_OUT, ACTIVE_LOW,
 * OPEN_DRAIN, OPEN_SOURCE and BIAS_*; v2's GPIO_V2_LINE_FLAG_* are USED,
 * ACTIVE_LOW, INPUT, OUTPUT, EDGE_*, OPEN_*, BIAS_* and EVENT_CLOCK_*; and
 * so neither libgpiod 1.6's line info (gpiod_line_*) nor 2.x's
 * (gpiod_line_info_*) has it. The same is found for both APIs, then, the
 * same way, here, from the chip's kernel name that both give
 * (gpio_req_chip).
 *
 * What sysfs does show is where the chip is: /sys/bus/gpio/devices/
 * gpiochipN is the chip's device, under the device that provides it, and
 * each device's `subsystem` link names its bus. A chip with a device on a
 * bus that sleeps among its ancestors (its own I2C client, or an MFD cell
 * under one) is reached through that bus. The list below is the buses
 * whose transfers wait; every GPIO driver on them sets can_sleep
 * (gpio-pca953x, pinctrl-mcp23s08, gpio-pcf857x on I2C; gpio-74x164,
 * gpio-max7301 on SPI; cp2112, gpio-ftdi on USB). A SoC's own GPIO sits
 * under `platform` (or `amba`, `pci`, `acpi`) and is taken as not
 * sleeping.
 */
#include "gpio_priv.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal/clock.h"
#include "hal/rt.h"

static const char *const sleeping_buses[] = {
	"i2c", "i3c", "spi", "spmi", "usb", "hid", "mdio_bus", "w1", "serial", "sdio",
	"greybus", "slimbus", NULL,
};

/* src into out, cut to fit. */
static void copy(char *out, size_t size, const char *src)
{
	size_t n = strlen(src);

	if (n >= size)
		n = size - 1;
	memcpy(out, src, n);
	out[n] = 0;
}

/* The last component of a link's target, or "" when it is not a link. */
static void link_base(const char *dir, const char *link, char *out, size_t size)
{
	char path[PATH_MAX + 16], target[PATH_MAX];
	ssize_t n;
	const char *slash;

	out[0] = 0;
	snprintf(path, sizeof(path), "%s/%s", dir, link);
	n = readlink(path, target, sizeof(target) - 1);
	if (n <= 0)
		return;
	target[n] = 0;
	slash = strrchr(target, '/');
	copy(out, size, slash ? slash + 1 : target);
}

/* A short attribute's first line ("mcp23017"), or "". */
static void attr_line(const char *dir, const char *attr, char *out, size_t size)
{
	char path[PATH_MAX + 16];
	FILE *f;

	out[0] = 0;
	snprintf(path, sizeof(path), "%s/%s", dir, attr);
	f = fopen(path, "r");
	if (!f)
		return;
	if (!fgets(out, (int)size, f))
		out[0] = 0;
	fclose(f);
	out[strcspn(out, "\n")] = 0;
}

int hal_gpio_chip_bus(const char *sysfs, const char *chip, struct hal_gpio_chip_bus *b)
{
	char path[PATH_MAX + 64], *dev = NULL, *top = NULL, *slash;
	size_t ntop;
	int rc = 0, k;

	STRAND_ASSERT_NOT_RT();
	memset(b, 0, sizeof(*b));
	if (!sysfs)
		sysfs = "/sys";
	snprintf(path, sizeof(path), "%s/bus/gpio/devices/%s", sysfs, chip);
	dev = realpath(path, NULL);
	if (!dev) {
		rc = -errno;
		goto out;
	}
	snprintf(path, sizeof(path), "%s/devices", sysfs);
	top = realpath(path, NULL);
	if (!top) {
		rc = -errno;
		goto out;
	}
	ntop = strlen(top);
	if (strncmp(dev, top, ntop) || dev[ntop] != '/') {
		rc = -ENOENT; /* not a device under devices/: cannot tell */
		goto out;
	}
	/* from the device providing the chip up to the root of devices/ */
	while ((slash = strrchr(dev, '/')) && (size_t)(slash - dev) > ntop) {
		*slash = 0;
		link_base(dev, "subsystem", b->bus, sizeof(b->bus));
		for (k = 0; sleeping_buses[k]; k++)
			if (!strcmp(b->bus, sleeping_buses[k]))
				break;
		if (!sleeping_buses[k])
			continue;
		b->sleeps = true;
		copy(b->device, sizeof(b->device), strrchr(dev, '/') + 1);
		attr_line(dev, "name", b->what, sizeof(b->what));
		if (!b->what[0])
			link_base(dev, "driver", b->what, sizeof(b->what));
		rc = 1;
		goto out;
	}
	b->bus[0] = 0;
out:
	free(dev);
	free(top);
	return rc;
}

/* "gpiochip2 is on the i2c bus (1-0020, mcp23017)" */
static void where(char *buf, size_t size, const char *chip, const struct hal_gpio_chip_bus *b)
{
	snprintf(buf, size, "chip %s is on the %s bus (%s%s%s)", chip, b->bus, b->device,
		 b->what[0] ? ", " : "", b->what);
}

/* How long the chip takes, measured at start: the longest of a few
 * set-values (outputs, with the levels the lines have: nothing changes) or
 * get-values (inputs). */
#define PROBES 4

static int64_t probe_ns(struct gpio_req *req, enum gpio_req_kind kind, const bool *high)
{
	bool got[GPIO_LINE_MAX];
	int64_t t, worst = 0;
	int i;

	for (i = 0; i < PROBES; i++) {
		t = hal_mono_ns();
		if (kind == GPIO_REQ_OUTPUT ? gpio_req_set(req, high) : gpio_req_get(req, got))
			return -1;
		t = hal_mono_ns() - t;
		if (t > worst)
			worst = t;
	}
	return worst;
}

int hal_gpio_sleep_check(struct gpio_req *req, const struct hal_gpio_cfg *cfg,
			 enum gpio_req_kind kind, const bool *high, char *err, size_t errsize)
{
	const char *chip = gpio_req_chip(req);
	struct hal_gpio_chip_bus b;
	char at[200], cost[96] = "";
	int64_t ns;

	STRAND_ASSERT_NOT_RT();
	if (cfg->warning && cfg->warning_size)
		cfg->warning[0] = 0;
	if (hal_gpio_chip_bus(cfg->sysfs, chip, &b) <= 0)
		return 0; /* not on such a bus, or sysfs cannot tell: nothing to say */
	where(at, sizeof(at), chip, &b);
	ns = probe_ns(req, kind, high);
	if (ns >= 0)
		snprintf(cost, sizeof(cost), " (%s at start: %.0f us)",
			 kind == GPIO_REQ_OUTPUT ? "the longest of 4 sets" : "the longest of 4 reads",
			 ns / 1e3);
	if (kind == GPIO_REQ_OUTPUT && !cfg->sleep_ok) {
		snprintf(err, errsize,
			 "device '%s': %s: the kernel sleeps in every set of its lines for a bus "
			 "transaction%s, and the loop would wait that long in each tick a trigger "
			 "changes, the edge as late; put the triggers on a GPIO of the SoC, or "
			 "accept the delay with `allow_sleeping_chip: true` on the device",
			 cfg->device, at, cost);
		return -EOPNOTSUPP;
	}
	if (!cfg->warning || !cfg->warning_size)
		return 0;
	if (kind == GPIO_REQ_OUTPUT)
		snprintf(cfg->warning, cfg->warning_size,
			 "device '%s': %s: every change of its trigger lines makes the loop wait "
			 "for a bus transaction%s, and the edge is as late (allow_sleeping_chip)",
			 cfg->device, at, cost);
	else
		snprintf(cfg->warning, cfg->warning_size,
			 "device '%s': %s: the kernel reads such a chip in a thread when it "
			 "interrupts, a bus transaction%s, so its inputs' edges reach strand that "
			 "much later and are timestamped then: an e-stop on it acts as much later. "
			 "The loop itself never waits for the chip",
			 cfg->device, at, cost);
	return 0;
}
