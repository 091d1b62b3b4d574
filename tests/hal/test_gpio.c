/* SPDX-License-Identifier: MIT */
/*
 * test_gpio.c - the GPIO backend (hal/gpio_dout.c, hal/gpio_din.c) over a
 * fake chip (tests/fake/gpio_line_fake.c): polarity, one set per change,
 * no glitch when an active-low trigger is requested, edges through the
 * event thread and the ring with their timestamps, levels at start, lost
 * edges and a vanished chip as faults, and the messages for a held or a
 * missing line; a chip that sleeps (an expander behind I2C or SPI), found
 * in a sysfs tree made the way the kernel lays it out: triggers on it
 * refused unless allowed, inputs on it a warning. The real chip is tested
 * in the VM (tests/vm/t_gpio_*.sh).
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "hal/gpio/gpio.h"
#include "hal/gpio/gpio_priv.h"
#include "tests/fake/gpio_line_fake.h"
#include "tests/fake/sysfs_tree.h"

static char err[512];

static void fake_lines(void)
{
	fake_reset();
	fake_chip.line_name[0] = "cam";
	fake_chip.line_name[1] = "lamp";
	fake_chip.line_name[2] = "estop";
	fake_chip.line_name[3] = "ready";
}

static struct hal_dout *open_dout(const struct hal_gpio_line *l, uint32_t n)
{
	struct hal_gpio_cfg cfg = { .device = "io", .chip = "gpiochip7", .nlines = n, .lines = l };
	struct hal_dout *d = NULL;

	assert_int_equal(hal_gpio_dout_open(&d, &cfg, err, sizeof(err)), 0);
	assert_non_null(d);
	return d;
}

/* Requesting an active-low trigger must not fire it: the line is high
 * (deasserted) from the request on, before start(). */
static void test_dout_polarity(void **state)
{
	const struct hal_gpio_line l[2] = { { .name = "cam", .active_low = true },
					    { .offset = 1 } };
	struct hal_dout *d;

	fake_lines();
	d = open_dout(l, 2);
	assert_true(fake_chip.high[0]);
	assert_false(fake_chip.high[1]);
	assert_string_equal(fake_chip.holder[0], HAL_GPIO_CONSUMER);
	assert_int_equal(hal_dout_start(d), 0);
	assert_true(fake_chip.high[0]);
	hal_dout_set(d, 0, true);
	hal_dout_set(d, 1, true);
	assert_int_equal(hal_dout_commit(d, 1), 0);
	assert_false(fake_chip.high[0]); /* asserted: pulled low */
	assert_true(fake_chip.high[1]);
	hal_dout_set(d, 0, false);
	assert_int_equal(hal_dout_commit(d, 2), 0);
	assert_true(fake_chip.high[0]);
	hal_dout_set(d, 1, true);
	assert_int_equal(hal_dout_stop(d), 0);
	assert_true(fake_chip.high[0]);   /* stop deasserts every line */
	assert_false(fake_chip.high[1]);
	assert_null(fake_chip.holder[0]); /* and releases them */
	hal_dout_close(d);
}

/* One set-values call per tick with a change, none without. */
static void test_dout_one_set_per_change(void **state)
{
	const struct hal_gpio_line l[2] = { { .offset = 0 }, { .offset = 1 } };
	struct hal_dout *d;
	unsigned before;

	fake_lines();
	d = open_dout(l, 2);
	assert_int_equal(hal_dout_start(d), 0);
	before = fake_chip.sets;
	assert_int_equal(hal_dout_commit(d, 1), 0);
	assert_int_equal(fake_chip.sets, before);
	hal_dout_set(d, 0, true);
	hal_dout_set(d, 1, true);
	assert_int_equal(hal_dout_commit(d, 2), 0);
	assert_int_equal(fake_chip.sets, before + 1);
	hal_dout_set(d, 0, true);
	assert_int_equal(hal_dout_commit(d, 3), 0);
	assert_int_equal(fake_chip.sets, before + 1);
	hal_dout_close(d);
}

/* A failing set is a latched fault, and the loop learns it from commit. */
static void test_dout_fault(void **state)
{
	const struct hal_gpio_line l[1] = { { .offset = 0 } };
	struct hal_fault f;
	struct hal_dout *d;

	fake_lines();
	d = open_dout(l, 1);
	assert_int_equal(hal_dout_start(d), 0);
	assert_int_equal(hal_dout_fault(d, &f), 0);
	fake_chip.set_error = -EIO;
	hal_dout_set(d, 0, true);
	assert_int_equal(hal_dout_commit(d, 1), -EIO);
	fake_chip.set_error = 0;
	assert_int_equal(hal_dout_commit(d, 2), -EIO); /* latched */
	assert_int_equal(hal_dout_fault(d, &f), -EIO);
	assert_int_equal(f.channel, -1);
	assert_non_null(f.cause);
	hal_dout_close(d);
}

/* Held elsewhere, missing, or past the chip's end: the message names the
 * device, the chip and the line, and for a held line who holds it. */
static void test_open_errors(void **state)
{
	const struct hal_gpio_line held[2] = { { .name = "lamp" }, { .name = "cam" } };
	const struct hal_gpio_line missing[1] = { { .name = "shutter" } };
	const struct hal_gpio_line past[1] = { { .offset = 40 } };
	struct hal_gpio_cfg cfg = { .device = "io", .chip = "gpiochip7", .nlines = 2,
				    .lines = held };
	struct hal_dout *d = NULL;
	struct hal_din *in = NULL;

	fake_lines();
	fake_chip.holder[0] = "gpioset";
	assert_int_equal(hal_gpio_dout_open(&d, &cfg, err, sizeof(err)), -EBUSY);
	assert_null(d);
	assert_string_equal(err, "device 'io': chip gpiochip7 line 'cam': offset 0 is held by "
				 "another user (consumer \"gpioset\"); `gpioinfo gpiochip7` shows it");
	assert_null(fake_chip.holder[1]); /* nothing half-requested is left */

	cfg.nlines = 1;
	cfg.lines = missing;
	assert_int_equal(hal_gpio_din_open(&in, &cfg, err, sizeof(err)), -ENOENT);
	assert_string_equal(err, "device 'io': chip gpiochip7 line 'shutter': no line of that name "
				 "on the chip");
	cfg.lines = past;
	assert_int_equal(hal_gpio_din_open(&in, &cfg, err, sizeof(err)), -EINVAL);
	assert_string_equal(err, "device 'io': chip gpiochip7 line 40: the chip has lines 0 to 15");
	cfg.chip = "gpiochip9";
	assert_int_equal(hal_gpio_dout_open(&d, &cfg, err, sizeof(err)), -ENOENT);
	assert_string_equal(err, "device 'io': chip gpiochip9: no such GPIO chip");
	cfg.nlines = 0;
	assert_int_equal(hal_gpio_dout_open(&d, &cfg, err, sizeof(err)), -EINVAL);
}

static struct hal_din *open_din(const struct hal_gpio_line *l, uint32_t n, uint32_t ring)
{
	struct hal_gpio_cfg cfg = { .device = "io", .chip = "gpiochip7", .nlines = n, .lines = l,
				    .ring_cap = ring };
	struct hal_din *d = NULL;

	assert_int_equal(hal_gpio_din_open(&d, &cfg, err, sizeof(err)), 0);
	assert_non_null(d);
	return d;
}

/* Poll until n edges came through the thread (it runs on its own time). */
static uint32_t poll_edges(struct hal_din *d, struct hal_edge *ev, uint32_t n)
{
	struct timespec ms = { 0, 1000000 };
	uint32_t got = 0;
	int tries;

	for (tries = 0; tries < 5000 && got < n; tries++) {
		got += hal_din_poll(d, 0, ev + got, n - got);
		if (got < n)
			nanosleep(&ms, NULL);
	}
	return got;
}

/* Wait until the event thread latched a fault: its code. */
static int wait_fault(struct hal_din *d, struct hal_fault *f)
{
	struct timespec ms = { 0, 1000000 };
	int i, code = 0;

	for (i = 0; i < 5000 && !(code = hal_din_fault(d, f)); i++)
		nanosleep(&ms, NULL);
	return code;
}

/* Levels at start, with polarity; edges queued before start are dropped;
 * edges after it arrive in order with the kernel's timestamps. */
static void test_din_edges(void **state)
{
	const struct hal_gpio_line l[2] = { { .name = "estop", .active_low = true },
					    { .name = "ready" } };
	struct hal_edge ev[4];
	struct hal_fault f;
	struct hal_din *d;

	fake_lines();
	d = open_din(l, 2, 0);
	fake_edge(0, false, 100); /* the chain opened before the run... */
	fake_edge(0, true, 200);  /* ...and closed again: history */
	fake_chip.high[3] = true;
	assert_int_equal(hal_din_start(d), 0);
	assert_false(hal_din_level(d, 0)); /* high on an active-low line: not asserted */
	assert_true(hal_din_level(d, 1));
	fake_edge(0, false, 1000); /* the chain opens: e-stop asserted */
	fake_edge(1, false, 1500);
	assert_int_equal(poll_edges(d, ev, 2), 2);
	assert_int_equal(ev[0].line, 0);
	assert_true(ev[0].asserted);
	assert_int_equal(ev[0].ts_ns, 1000);
	assert_int_equal(ev[1].line, 1);
	assert_false(ev[1].asserted);
	assert_int_equal(ev[1].ts_ns, 1500);
	assert_true(hal_din_level(d, 0));
	assert_false(hal_din_level(d, 1));
	assert_int_equal(hal_din_poll(d, 0, ev, 4), 0);
	assert_int_equal(hal_din_fault(d, &f), 0);
	assert_int_equal(hal_din_stop(d), 0);
	assert_null(fake_chip.holder[2]);
	hal_din_close(d);
}

/* A line's level is the newest the thread passed on, ahead of the edges
 * still in the ring: an e-stop shows in the level before the loop has
 * polled its edge, which may wait behind others (din.h). */
static void test_din_level_ahead_of_poll(void **state)
{
	const struct hal_gpio_line l[2] = { { .name = "estop", .active_low = true },
					    { .name = "ready" } };
	struct timespec ms = { 0, 1000000 };
	struct hal_edge ev[4];
	struct hal_din *d;
	int i;

	fake_lines();
	fake_chip.high[2] = true; /* the chain is closed */
	d = open_din(l, 2, 0);
	assert_int_equal(hal_din_start(d), 0);
	assert_false(hal_din_level(d, 0));
	fake_edge(0, false, 300); /* it opens */
	for (i = 0; i < 5000 && !hal_din_level(d, 0); i++)
		nanosleep(&ms, NULL);
	assert_true(hal_din_level(d, 0)); /* nothing polled yet */
	assert_int_equal(poll_edges(d, ev, 1), 1);
	assert_int_equal(ev[0].line, 0);
	assert_true(ev[0].asserted);
	assert_int_equal(ev[0].ts_ns, 300);
	assert_true(hal_din_level(d, 0));
	hal_din_close(d);
}

/* The kernel labelled an edge wrong (the v1 ABI reads the line in its
 * thread, after the fact) or lost one: the read-back after the events
 * sets the level right with an edge of its own. */
static void test_din_read_back(void **state)
{
	const struct hal_gpio_line l[1] = { { .name = "estop", .active_low = true } };
	struct hal_edge ev[4];
	struct hal_din *d;

	fake_lines();
	fake_chip.high[2] = true; /* the chain is closed */
	d = open_din(l, 1, 0);
	assert_int_equal(hal_din_start(d), 0);
	assert_false(hal_din_level(d, 0));
	/* it opens, and closes, but the kernel loses the closing edge */
	fake_edge(0, false, 1000);
	fake_level(2, true);
	assert_int_equal(poll_edges(d, ev, 2), 2);
	assert_true(ev[0].asserted);
	assert_int_equal(ev[0].ts_ns, 1000);
	assert_false(ev[1].asserted); /* from the read-back, dated by the thread */
	assert_true(ev[1].ts_ns > 1000);
	assert_false(hal_din_level(d, 0));
	hal_din_close(d);
}

/* More edges than the ring holds before the loop polls: a fault, since a
 * lost e-stop edge must not pass silently. */
static void test_din_lost_edges(void **state)
{
	const struct hal_gpio_line l[1] = { { .name = "ready" } };
	struct hal_edge ev[4];
	struct hal_fault f;
	struct hal_din *d;
	int i;

	fake_lines();
	d = open_din(l, 1, 4);
	assert_int_equal(hal_din_start(d), 0);
	for (i = 0; i < 6; i++)
		fake_edge(0, i % 2 == 0, 10 + i);
	assert_int_equal(wait_fault(d, &f), -ENOBUFS);
	assert_int_equal(f.code, -ENOBUFS);
	assert_non_null(strstr(f.cause, "lost"));
	assert_int_equal(hal_din_poll(d, 0, ev, 4), 4); /* the first four are there */
	assert_int_equal(ev[0].ts_ns, 10);
	assert_int_equal(ev[3].ts_ns, 13);
	hal_din_close(d);
}

/* The chip going away while the run goes on: a fault, not a hang. */
static void test_din_unplugged(void **state)
{
	const struct hal_gpio_line l[1] = { { .name = "estop", .active_low = true } };
	struct hal_fault f;
	struct hal_din *d;

	fake_lines();
	d = open_din(l, 1, 0);
	assert_int_equal(hal_din_start(d), 0);
	fake_unplug(0);
	assert_int_equal(wait_fault(d, &f), -EIO);
	hal_din_close(d);
}

/* ---- a chip that sleeps ---- */

/* Where each chip is, as sysfs says: the SoC's does not sleep, the I2C
 * expander and the SPI shift registers do, named by their device and
 * name or driver; a chip sysfs does not know cannot be told. */
static void test_chip_bus(void **state)
{
	struct hal_gpio_chip_bus b;
	struct sysfs_tree t;

	sysfs_tree_make(&t, "gpiochip0");
	assert_int_equal(hal_gpio_chip_bus(t.root, "gpiochip0", &b), 0);
	assert_false(b.sleeps);
	assert_int_equal(hal_gpio_chip_bus(t.root, "gpiochip2", &b), 1);
	assert_true(b.sleeps);
	assert_string_equal(b.bus, "i2c");
	assert_string_equal(b.device, "1-0020");
	assert_string_equal(b.what, "mcp23017");
	assert_int_equal(hal_gpio_chip_bus(t.root, "gpiochip3", &b), 1);
	assert_string_equal(b.bus, "spi");
	assert_string_equal(b.device, "spi0.1");
	assert_string_equal(b.what, "gpio-74x164");
	assert_int_equal(hal_gpio_chip_bus(t.root, "gpiochip9", &b), -ENOENT);
	assert_false(b.sleeps);
	assert_true(hal_gpio_chip_bus("/nonexistent", "gpiochip0", &b) < 0);
	sysfs_tree_free(&t);
}

static int open_dout_on(const char *sysfs, bool sleep_ok, char *warning, size_t size,
			struct hal_dout **d)
{
	const struct hal_gpio_line l[1] = { { .name = "cam", .active_low = true } };
	struct hal_gpio_cfg cfg = { .device = "io", .chip = "gpiochip7", .nlines = 1, .lines = l,
				    .sysfs = sysfs, .sleep_ok = sleep_ok, .warning = warning,
				    .warning_size = size };

	*d = NULL;
	return hal_gpio_dout_open(d, &cfg, err, sizeof(err));
}

/* A trigger on the I2C expander is refused, saying where the chip is,
 * what a set took and what to do; the line is released again. Allowed, it
 * opens with a warning, the lines where they were. On the SoC's chip, or
 * where sysfs cannot tell, nothing is said. */
static void test_dout_on_sleeping_chip(void **state)
{
	char warning[512];
	struct hal_dout *d;
	struct sysfs_tree t;

	fake_lines();
	sysfs_tree_make(&t, "gpiochip2");
	assert_int_equal(open_dout_on(t.root, false, warning, sizeof(warning), &d), -EOPNOTSUPP);
	assert_null(d);
	printf("%s\n", err);
	assert_non_null(strstr(err, "device 'io': chip gpiochip7 is on the i2c bus (1-0020, "
				    "mcp23017): the kernel sleeps in every set of its lines"));
	assert_non_null(strstr(err, "the longest of 4 sets at start: "));
	assert_non_null(strstr(err, "`allow_sleeping_chip: true`"));
	assert_null(fake_chip.holder[0]);

	fake_lines();
	assert_int_equal(open_dout_on(t.root, true, warning, sizeof(warning), &d), 0);
	printf("%s\n", warning);
	assert_non_null(strstr(warning, "device 'io': chip gpiochip7 is on the i2c bus (1-0020, "
					"mcp23017): every change of its trigger lines makes the "
					"loop wait for a bus transaction"));
	assert_int_equal(fake_chip.sets, 4); /* the probes, at the levels the lines had */
	assert_true(fake_chip.high[0]);      /* active low: deasserted high */
	hal_dout_close(d);
	sysfs_tree_free(&t);

	fake_lines();
	sysfs_tree_make(&t, "gpiochip0");
	strcpy(warning, "x");
	assert_int_equal(open_dout_on(t.root, false, warning, sizeof(warning), &d), 0);
	assert_string_equal(warning, "");
	assert_int_equal(fake_chip.sets, 0);
	hal_dout_close(d);
	sysfs_tree_free(&t);
	fake_lines();
	assert_int_equal(open_dout_on("/nonexistent", false, warning, sizeof(warning), &d), 0);
	assert_string_equal(warning, "");
	hal_dout_close(d);
}

/* Inputs on a chip that sleeps: opened, with a warning (the loop never
 * waits for them; their edges come late). */
static void test_din_on_sleeping_chip(void **state)
{
	const struct hal_gpio_line l[1] = { { .name = "estop", .active_low = true } };
	char warning[512] = "";
	struct sysfs_tree t;
	struct hal_gpio_cfg cfg = { .device = "io", .chip = "gpiochip7", .nlines = 1, .lines = l,
				    .warning = warning, .warning_size = sizeof(warning) };
	struct hal_din *d = NULL;

	fake_lines();
	sysfs_tree_make(&t, "gpiochip3");
	cfg.sysfs = t.root;
	assert_int_equal(hal_gpio_din_open(&d, &cfg, err, sizeof(err)), 0);
	printf("%s\n", warning);
	assert_non_null(strstr(warning, "device 'io': chip gpiochip7 is on the spi bus (spi0.1, "
					"gpio-74x164): the kernel reads such a chip in a thread"));
	assert_non_null(strstr(warning, "the longest of 4 reads at start: "));
	assert_non_null(strstr(warning, "The loop itself never waits for the chip"));
	hal_din_close(d);
	sysfs_tree_free(&t);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_dout_polarity),
		cmocka_unit_test(test_dout_one_set_per_change),
		cmocka_unit_test(test_dout_fault),
		cmocka_unit_test(test_open_errors),
		cmocka_unit_test(test_din_edges),
		cmocka_unit_test(test_din_read_back),
		cmocka_unit_test(test_din_level_ahead_of_poll),
		cmocka_unit_test(test_chip_bus),
		cmocka_unit_test(test_dout_on_sleeping_chip),
		cmocka_unit_test(test_din_on_sleeping_chip),
		cmocka_unit_test(test_din_lost_edges),
		cmocka_unit_test(test_din_unplugged),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
