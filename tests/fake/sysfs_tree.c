/* SPDX-License-Identifier: MIT */
/* sysfs_tree.c - a sysfs tree for the tests (see sysfs_tree.h). */
#include "sysfs_tree.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

static void sys_mkdir(const struct sysfs_tree *t, const char *rel)
{
	char path[512], *p;

	snprintf(path, sizeof(path), "%s/%s", t->root, rel);
	for (p = path + strlen(t->root) + 1; *p; p++)
		if (*p == '/') {
			*p = 0;
			mkdir(path, 0755);
			*p = '/';
		}
	mkdir(path, 0755);
}

static void sys_link(const struct sysfs_tree *t, const char *rel, const char *to_rel)
{
	char path[512], to[512];

	snprintf(path, sizeof(path), "%s/%s", t->root, rel);
	snprintf(to, sizeof(to), "%s/%s", t->root, to_rel);
	unlink(path);
	assert_int_equal(symlink(to, path), 0);
}

static void sys_file(const struct sysfs_tree *t, const char *rel, const char *text)
{
	char path[512];
	FILE *f;

	snprintf(path, sizeof(path), "%s/%s", t->root, rel);
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(text, f);
	fclose(f);
}

/* A device at rel on bus `bus`. */
static void sys_dev(const struct sysfs_tree *t, const char *rel, const char *bus)
{
	char sub[512], b[128];

	sys_mkdir(t, rel);
	snprintf(sub, sizeof(sub), "%s/subsystem", rel);
	snprintf(b, sizeof(b), "bus/%s", bus);
	sys_mkdir(t, b);
	sys_link(t, sub, b);
}

#define SPI0 "devices/platform/soc/fe204000.spi/spi_master/spi0"

void sysfs_tree_make(struct sysfs_tree *t, const char *chip_at)
{
	char link[128];

	snprintf(t->root, sizeof(t->root), "/tmp/strand-sysfs-XXXXXX");
	assert_non_null(mkdtemp(t->root));
	sys_dev(t, "devices/platform/soc", "platform");
	sys_dev(t, "devices/platform/soc/fe200000.gpio", "platform");
	sys_dev(t, "devices/platform/soc/fe200000.gpio/gpiochip0", "gpio");
	sys_dev(t, "devices/platform/soc/fe804000.i2c", "platform");
	sys_dev(t, "devices/platform/soc/fe804000.i2c/i2c-1", "i2c");
	sys_dev(t, "devices/platform/soc/fe804000.i2c/i2c-1/1-0020", "i2c");
	sys_file(t, "devices/platform/soc/fe804000.i2c/i2c-1/1-0020/name", "mcp23017\n");
	sys_dev(t, "devices/platform/soc/fe804000.i2c/i2c-1/1-0020/gpiochip2", "gpio");
	sys_dev(t, "devices/platform/soc/fe204000.spi", "platform");
	sys_mkdir(t, "class/spi_master");
	sys_mkdir(t, SPI0);
	sys_link(t, SPI0 "/subsystem", "class/spi_master");
	sys_dev(t, SPI0 "/spi0.1", "spi");
	sys_mkdir(t, "bus/spi/drivers/gpio-74x164");
	sys_link(t, SPI0 "/spi0.1/driver", "bus/spi/drivers/gpio-74x164");
	sys_dev(t, SPI0 "/spi0.1/gpiochip3", "gpio");
	sys_mkdir(t, "bus/gpio/devices");
	sys_link(t, "bus/gpio/devices/gpiochip0", "devices/platform/soc/fe200000.gpio/gpiochip0");
	sys_link(t, "bus/gpio/devices/gpiochip2",
		 "devices/platform/soc/fe804000.i2c/i2c-1/1-0020/gpiochip2");
	sys_link(t, "bus/gpio/devices/gpiochip3", SPI0 "/spi0.1/gpiochip3");
	/* a link to a link: realpath follows both */
	snprintf(link, sizeof(link), "bus/gpio/devices/%s", chip_at);
	sys_link(t, "bus/gpio/devices/gpiochip7", link);
}

void sysfs_tree_free(struct sysfs_tree *t)
{
	char cmd[128];

	snprintf(cmd, sizeof(cmd), "rm -rf %s", t->root);
	assert_int_equal(system(cmd), 0);
}
