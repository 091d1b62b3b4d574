/* SPDX-License-Identifier: MIT */
/*
 * test_cli.c - the strand command in-process: --version, --help on every
 * subcommand, usage and scene errors with their exit codes, and every
 * example checked, exported (csv, jsonl, ticks), plotted and described.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/exitcode.h"
#include "cliutil.h"
#include "testutil.h"

static size_t lines(const char *s)
{
	size_t n = 0;

	for (; *s; s++)
		n += *s == '\n';
	return n;
}

static void test_version_help(void **state)
{
	static const char *const cmds[] = { "check", "export", "plot", "info", "play", "journal" };
	struct run r;
	char args[64], want[64];
	size_t i;

	strand(&r, "--version");
	assert_int_equal(r.rc, STRAND_EXIT_OK);
	/* and the libgpiod it was built with, which tells two builds apart */
	assert_int_equal(strncmp(r.out, "strand " STRAND_VERSION " (libgpiod ",
				 strlen("strand " STRAND_VERSION " (libgpiod ")), 0);
	assert_non_null(strstr(r.out, ")\n"));
	run_free(&r);
	strand(&r, "--help");
	assert_int_equal(r.rc, STRAND_EXIT_OK);
	for (i = 0; i < 6; i++)
		assert_non_null(strstr(r.out, cmds[i]));
	run_free(&r);
	for (i = 0; i < 6; i++) {
		snprintf(args, sizeof(args), "%s --help", cmds[i]);
		snprintf(want, sizeof(want), "usage: strand %s", cmds[i]);
		strand(&r, args);
		assert_int_equal(r.rc, STRAND_EXIT_OK);
		assert_memory_equal(r.out, want, strlen(want));
		assert_non_null(strstr(r.out, "exit codes"));
		run_free(&r);
	}
}

static void expect(const char *args, int rc, const char *err_line)
{
	struct run r;

	strand(&r, args);
	if (r.rc != rc || (err_line && strcmp(r.err, err_line)))
		fail_msg("strand %s: rc %d, stderr '%s'; want rc %d, '%s'", args, r.rc, r.err, rc,
			 err_line ? err_line : "");
	run_free(&r);
}

static void test_usage(void **state)
{
	expect("", STRAND_EXIT_USAGE, NULL);
	expect("fly", STRAND_EXIT_USAGE, "strand: unknown command 'fly' (try 'strand --help')\n");
	expect("check", STRAND_EXIT_USAGE,
	       "strand check: expected one scene file\nTry 'strand check --help'.\n");
	expect("check a.yaml b.yaml", STRAND_EXIT_USAGE, NULL);
	expect("export examples/robot_arm.yaml --at seconds", STRAND_EXIT_USAGE,
	       "strand export: --at takes frames or ticks, not 'seconds'\nTry 'strand export --help'.\n");
	expect("export examples/robot_arm.yaml --every 0", STRAND_EXIT_USAGE, NULL);
	expect("export examples/robot_arm.yaml --from 10 --to 5", STRAND_EXIT_USAGE, NULL);
	expect("export examples/robot_arm.yaml --format xml", STRAND_EXIT_USAGE, NULL);
	expect("export examples/robot_arm.yaml --to", STRAND_EXIT_USAGE,
	       "strand export: option '--to' needs a value\nTry 'strand export --help'.\n");
	expect("info --verbose examples/robot_arm.yaml", STRAND_EXIT_USAGE,
	       "strand info: unknown option '--verbose'\nTry 'strand info --help'.\n");
	expect("plot examples/robot_arm.yaml", STRAND_EXIT_USAGE,
	       "strand plot: -o FILE.svg is required\nTry 'strand plot --help'.\n");
	expect("plot examples/robot_arm.yaml -o /tmp/x.svg --compare nobody", STRAND_EXIT_USAGE,
	       NULL);
	expect("check /nonexistent/scene.yaml", STRAND_EXIT_IO,
	       "/nonexistent/scene.yaml: cannot open: No such file or directory\n");
}

/* Every number of strand play's options in range where it enters, the
 * option named (issue 12: --duration 1e16 ended a run at tick 0 with exit
 * 0, --timeout 1e17 failed at once; a duration below a tick ran forever). */
static void test_play_ranges(void **state)
{
	static const struct {
		const char *args, *err;
	} cases[] = {
		{ "--duration 1e16", "--duration 1e16: at most 1e9 seconds (31 years)" },
		{ "--duration 0.0001", "--duration 0.0001: shorter than a tick (1 ms at tick_hz 1000)" },
		{ "--duration -1", "--duration -1: a non-negative number" },
		{ "--mode step --timeout 1e17", "--timeout 1e17: at most 1e9 seconds (31 years)" },
		{ "--mode step --timeout 0.0004",
		  "--timeout 0.0004: shorter than a tick (1 ms at tick_hz 1000)" },
		{ "--mode step --settle 1e300", "--settle 1e300: at most 1e12 ms (31 years)" },
		{ "--mode step --exposure 2e12", "--exposure 2e12: at most 1e12 ms (31 years)" },
		{ "--mode step --exposure nan", "--exposure nan: a non-negative number" },
		{ "--from 2147483648", "--from 2147483648: a frame number" },
		{ "--loop --passes 0", "--passes 0: a count of 1 or more" },
		{ "--priority 100", "--priority 100: 0 to 99" },
		{ "--cpu 1024", "--cpu 1024: a CPU number" },
	};
	char args[256], want[256];
	size_t i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		snprintf(args, sizeof(args), "play examples/robot_arm.yaml --sim --clock virtual "
			 "--no-journal --quiet %s", cases[i].args);
		snprintf(want, sizeof(want), "strand play: %s\nTry 'strand play --help'.\n",
			 cases[i].err);
		expect(args, STRAND_EXIT_USAGE, want);
	}
	expect("play examples/robot_arm.yaml --sim --clock virtual --no-journal --quiet --mode "
	       "step --frames 0..99999999999", STRAND_EXIT_USAGE,
	       "strand play: --frames '0..99999999999': frame numbers and repeats go up to "
	       "2147483647, at column 4\n");
	expect("play examples/robot_arm.yaml --sim --clock virtual --no-journal --quiet --mode "
	       "step --frames 3x9999999999", STRAND_EXIT_USAGE,
	       "strand play: --frames '3x9999999999': frame numbers and repeats go up to "
	       "2147483647, at column 3\n");
	/* in range: a short run, and one of a tick */
	expect("play examples/robot_arm.yaml --sim --clock virtual --no-journal --quiet "
	       "--duration 0.5", STRAND_EXIT_OK, "");
	expect("play examples/robot_arm.yaml --sim --clock virtual --no-journal --quiet "
	       "--duration 0.0006", STRAND_EXIT_OK, "");
}

/* A scene error is one line on stderr and exit 2, from every subcommand. */
static void test_scene_error(void **state)
{
	static const char *const cmds[] = { "check", "export", "info", "plot -o /dev/null" };
	char path[] = "/tmp/strand-test-XXXXXX.yaml", args[128];
	const char *yaml = "timing: {frame_rate: 24, frames: [0, 10]}\n"
			   "nodes:\n  - {name: base, joint: {type: revolute, axis: y}}\n"
			   "strands:\n  - node: base\n    keys: [{frame: 0, angel: 3}]\n";
	char want[256];
	struct run r;
	size_t i;
	int fd = mkstemps(path, 5);

	assert_true(fd >= 0);
	assert_int_equal(write(fd, yaml, strlen(yaml)), (ssize_t)strlen(yaml));
	close(fd);
	snprintf(want, sizeof(want), "%s:6:23: unknown key 'angel' in key (did you mean 'angle'?)\n",
		 path);
	for (i = 0; i < 4; i++) {
		snprintf(args, sizeof(args), "%s %s", cmds[i], path);
		strand(&r, args);
		assert_int_equal(r.rc, STRAND_EXIT_SCENE);
		assert_string_equal(r.err, want);
		assert_int_equal(r.out_len, 0);
		run_free(&r);
	}
	unlink(path);
}

static void test_examples(void **state)
{
	char args[256], svg[] = "/tmp/strand-test-XXXXXX.svg";
	size_t i;
	int fd = mkstemps(svg, 4);

	assert_true(fd >= 0);
	close(fd);
	for (i = 0; i < NEXAMPLES; i++) {
		struct run r;
		FILE *f;
		char head[6] = { 0 };

		snprintf(args, sizeof(args), "check %s", cli_examples[i]);
		strand(&r, args);
		if (r.rc != STRAND_EXIT_OK)
			fail_msg("%s: %s%s", args, r.out, r.err);
		assert_non_null(strstr(r.out, " 0 violations"));
		run_free(&r);

		snprintf(args, sizeof(args), "info %s", cli_examples[i]);
		strand(&r, args);
		assert_int_equal(r.rc, STRAND_EXIT_OK);
		assert_non_null(strstr(r.out, "bytes in one block"));
		run_free(&r);

		snprintf(args, sizeof(args), "export %s", cli_examples[i]);
		strand(&r, args);
		assert_int_equal(r.rc, STRAND_EXIT_OK);
		assert_int_equal(r.err_len, 0);
		assert_memory_equal(r.out, "tick,frame,", 11);
		run_free(&r);

		snprintf(args, sizeof(args), "plot %s -o %s", cli_examples[i], svg);
		strand(&r, args);
		assert_int_equal(r.rc, STRAND_EXIT_OK);
		f = fopen(svg, "r");
		assert_non_null(f);
		assert_int_equal(fread(head, 1, 5, f), 5);
		fclose(f);
		assert_string_equal(head, "<?xml");
		run_free(&r);
	}
	unlink(svg);
}

/* Rows, columns and sample times of the three kinds of export. */
static void test_export(void **state)
{
	struct run r;
	const char *row2;

	strand(&r, "export examples/robot_arm.yaml");
	assert_int_equal(lines(r.out), 1 + 241);
	assert_memory_equal(r.out, "tick,frame,base.x,base.y,base.z,arm1.x,arm1.y,arm1.z,"
				   "arm2.x,arm2.y,arm2.z,claw.x,claw.y,claw.z,"
				   "base.angle,arm1.angle,arm2.angle\n", 117);
	/* frame 1 fires at tick ceil(1000 / 24) = 42, frame time 42 * 24 / 1000 */
	row2 = strchr(strchr(r.out, '\n') + 1, '\n') + 1;
	assert_memory_equal(row2, "42,1.008,", 9);
	run_free(&r);

	strand(&r, "export examples/camera_move.yaml --at ticks --from 0 --to 3 --every 10");
	/* frame 3 at 30000/1001 fps fires at tick ceil(3 * 1001 / 30) = 101: ticks 0..100 */
	assert_int_equal(lines(r.out), 1 + 11);
	assert_non_null(strstr(r.out, "\n100,2.997002997,"));
	run_free(&r);

	strand(&r, "export examples/propeller.yaml --format jsonl --from 250 --to 500 --every 125");
	assert_int_equal(lines(r.out), 1 + 3);
	assert_memory_equal(r.out, "[\"tick\",\"frame\",", 16);
	assert_non_null(strstr(r.out, "\"propeller.rpm\"]\n[10000,250,"));
	assert_non_null(strstr(r.out, ",2400]\n"));
	run_free(&r);

	strand(&r, "export examples/cycled_data.yaml --from 0 --to 0");
	assert_string_equal(strchr(r.out, '\n') + 1, "0,0,0,0,0,1,0,0,0,1,0,1,0\n");
	run_free(&r);
}

/* Saturated arithmetic is reported, never passed off as a result. */
static void test_saturation(void **state)
{
	expect("check tests/scenes/saturates.yaml", STRAND_EXIT_INTERNAL,
	       "tests/scenes/saturates.yaml: the core's arithmetic saturated at frame 0: "
	       "values too large for its Q32.32 format\n");
	expect("export tests/scenes/saturates.yaml", STRAND_EXIT_INTERNAL,
	       "tests/scenes/saturates.yaml: the core's arithmetic saturated: "
	       "values too large for its Q32.32 format\n");
}

/* Rows depend only on their sample time: every 7th frame exported alone
 * equals the same rows of the full export (the core's cursors make
 * sequential playback fast, never different), for a scene with every kind
 * of key. */
static void test_export_random_access(void **state)
{
	struct run all, some;
	const char *p, *q;
	size_t row = 0, matched = 0;

	strand(&all, "export tests/scenes/every_key.yaml --at ticks");
	strand(&some, "export tests/scenes/every_key.yaml --at ticks --every 7");
	assert_int_equal(all.rc, STRAND_EXIT_OK);
	assert_int_equal(some.rc, STRAND_EXIT_OK);
	assert_int_equal(all.err_len + some.err_len, 0);
	q = some.out;
	for (p = all.out; *p; row++) {
		const char *end = strchr(p, '\n') + 1;

		/* the header, then rows 0, 7, 14, ... of the samples */
		if (row == 0 || (row - 1) % 7 == 0) {
			assert_memory_equal(p, q, (size_t)(end - p));
			q += end - p;
			matched++;
		}
		p = end;
	}
	assert_int_equal(*q, '\0');
	assert_true(matched > 600);
	run_free(&all);
	run_free(&some);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_version_help), cmocka_unit_test(test_usage),
		cmocka_unit_test(test_play_ranges),
		cmocka_unit_test(test_scene_error),  cmocka_unit_test(test_examples),
		cmocka_unit_test(test_export),	     cmocka_unit_test(test_export_random_access),
		cmocka_unit_test(test_saturation),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
