/* SPDX-License-Identifier: MIT */
/*
 * test_play_gpio.c - a run with a device of driver gpio (the fake chip,
 * tests/fake/gpio_line_fake.c) on a chip that sleeps, as sysfs says
 * (tests/fake/sysfs_tree.h): the camera trigger on an I2C expander is
 * refused at start (a device error, exit 7) unless the device allows it,
 * then said once at start; an e-stop on one is said; a rig-ready lamp
 * alone on one, or anything on the SoC's own chip, goes without a word.
 * On the virtual clock.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "cli/exitcode.h"
#include "playutil.h"
#include "rig/drv_gpio.h"
#include "tests/fake/gpio_line_fake.h"
#include "tests/fake/sysfs_tree.h"

struct setup {
	struct pu_source ps;
	struct pu_rig r;
	struct rig_gpio_desc gd;
	struct play_opts o;
	struct sysfs_tree t;
	char *warn;
	size_t warn_len;
	FILE *warn_f;
	char err[512];
};

/* The test arm on simulated drives; device io on gpiochip7 (where chip_at
 * is in the tree) with the camera trigger at offset 0 (triggers) and the
 * e-stop at offset 2 (estop), or the trigger on the simulated arm device
 * and only a rig-ready lamp at offset 1 on io (neither). */
static void setup(struct setup *s, const char *chip_at, bool triggers, bool estop, bool allow)
{
	memset(s, 0, sizeof(*s));
	pu_arm_source(&s->ps, 24, 1, 1000, 0, 48);
	pu_rig_init(&s->r, &s->ps, 1, estop ? PU_ESTOP : 0);
	s->gd = (struct rig_gpio_desc){ .chip = "gpiochip7", .allow_sleeping_chip = allow };
	s->r.dev[1].driver = &rig_drv_gpio;
	s->r.dev[1].priv = &s->gd;
	s->r.trig[0].line = 0;
	if (!triggers) {
		s->r.trig[0].device = "arm";
		s->r.dev[1].has_ready = true;
		s->r.dev[1].ready_line = 1;
	}
	if (estop)
		s->r.in[0].line = 2;
	pu_opts(&s->o, &s->ps);
	s->o.rig.sim = false;
	sysfs_tree_make(&s->t, chip_at);
	s->o.rig.gpio_sysfs = s->t.root;
	s->warn_f = open_memstream(&s->warn, &s->warn_len);
	assert_non_null(s->warn_f);
	s->o.rig.warn = s->warn_f;
	fake_reset();
	fake_chip.high[2] = true; /* the e-stop chain closed (active low) */
}

static int prepare(struct setup *s, struct play *p)
{
	int rc;

	pu_alloc_hook_install();
	rc = play_prepare(p, &s->r.d, &s->ps.s, &s->o, s->err, sizeof(s->err));
	fflush(s->warn_f);
	printf("warnings: '%s'%s%s\n", s->warn, rc ? "; error: " : "", rc ? s->err : "");
	return rc;
}

static void done(struct setup *s, struct play *p)
{
	play_free(p);
	fclose(s->warn_f);
	free(s->warn);
	sysfs_tree_free(&s->t);
}

/* The trigger on the I2C expander: refused at start, naming the chip, its
 * bus and what to do; nothing was held after. */
static void test_trigger_refused(void **state)
{
	struct setup s;
	struct play p;

	setup(&s, "gpiochip2", true, false, false);
	assert_int_equal(prepare(&s, &p), -EOPNOTSUPP);
	assert_int_equal(p.failed_at, PLAY_STAGE_START);
	assert_non_null(strstr(s.err, "device 'io': chip gpiochip7 is on the i2c bus (1-0020, "
				      "mcp23017): the kernel sleeps in every set of its lines"));
	assert_non_null(strstr(s.err, "allow_sleeping_chip: true"));
	assert_null(fake_chip.holder[0]);
	done(&s, &p);
}

/* Allowed: the run plays, and the start said what it costs, once, with
 * the e-stop's own warning. */
static void test_trigger_allowed(void **state)
{
	struct setup s;
	struct play p;

	setup(&s, "gpiochip2", true, true, true);
	assert_int_equal(prepare(&s, &p), 0);
	assert_non_null(strstr(s.warn, "strand: warning: device 'io': chip gpiochip7 is on the "
				       "i2c bus (1-0020, mcp23017): every change of its trigger "
				       "lines makes the loop wait for a bus transaction"));
	assert_non_null(strstr(s.warn, "strand: warning: device 'io': chip gpiochip7 is on the "
				       "i2c bus (1-0020, mcp23017): the kernel reads such a chip"));
	assert_int_equal(pu_play(&p), STRAND_EXIT_OK);
	assert_int_equal(loop_result(p.L)->frames_fired, 49);
	done(&s, &p);
}

/* A rig-ready lamp alone on the expander (set at start and at the end):
 * nothing to say. The SoC's own chip: nothing to say either. */
static void test_silent(void **state)
{
	struct setup s;
	struct play p;

	setup(&s, "gpiochip2", false, false, false);
	assert_int_equal(prepare(&s, &p), 0);
	assert_string_equal(s.warn, "");
	assert_int_equal(pu_play(&p), STRAND_EXIT_OK);
	done(&s, &p);
	setup(&s, "gpiochip0", true, true, false);
	assert_int_equal(prepare(&s, &p), 0);
	assert_string_equal(s.warn, "");
	assert_int_equal(pu_play(&p), STRAND_EXIT_OK);
	done(&s, &p);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_trigger_refused),
		cmocka_unit_test(test_trigger_allowed),
		cmocka_unit_test(test_silent),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
