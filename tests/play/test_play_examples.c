/* SPDX-License-Identifier: MIT */
/*
 * test_play_examples.c - `strand play` in-process, as a user runs it: every
 * example played whole on the simulated rig in virtual time (every frame of
 * the span fired once, in order, at its section 5 tick, nothing allocated by
 * the loop thread), the robot arm's journal equal to the scene evaluated at
 * each trigger tick, a scene that `strand check` rejects refused unless
 * --force, and the command's usage errors.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/exitcode.h"
#include "cliutil.h"
#include "load/load.h"
#include "playutil.h"
#include "scene/source_scene.h"
#include "testutil.h"

/* `strand ARGS` (a format with up to two strings) with its output
 * captured, the loop's allocations counted. */
static void play(struct run *r, const char *fmt, const char *a, const char *b)
{
	char args[1024];

	snprintf(args, sizeof(args), fmt, a, b);
	pu_alloc_hook_install();
	strand(r, args);
}

/* The scene's timing and span, read the way play reads it. */
static void scene_timing(const char *path, struct mot_timing *t, int64_t *from, int64_t *to)
{
	struct scene_file sf;
	struct load_err e;

	assert_int_equal(scene_file_load(&sf, path, &e), 0);
	assert_int_equal(mot_timing_init(t, sf.desc.rate_num, sf.desc.rate_den, sf.desc.tick_hz), 0);
	*from = (int64_t)sf.desc.frame_first;
	*to = (int64_t)sf.desc.frame_last;
	scene_file_free(&sf);
}

static void test_examples_played_whole(void **state)
{
	size_t i;

	for (i = 0; i < NEXAMPLES; i++) {
		struct mot_timing t;
		struct run r;
		struct pu_csv c;
		char path[256];
		int64_t from, to, f, t0;
		uint64_t before = pu_loop_allocations();
		int cf, ct, cs;

		pu_tmpname(path, sizeof(path), "example");
		play(&r, "play %s --sim --clock virtual --quiet --journal %s", cli_examples[i],
		       path);
		if (r.rc)
			fail_msg("%s: exit %d: %s", cli_examples[i], r.rc, r.err);
		assert_int_equal(pu_loop_allocations() - before, 0);
		scene_timing(cli_examples[i], &t, &from, &to);
		assert_int_equal(pu_csv_read(&c, path), 0);
		assert_int_equal(c.nrows - 1, to - from + 1);
		cf = pu_csv_col(&c, "frame");
		ct = pu_csv_col(&c, "tick");
		cs = pu_csv_col(&c, "state");
		t0 = atoll(c.cell[1][ct]) - mot_timing_trigger_tick(&t, from);
		for (f = from; f <= to; f++) {
			char **row = c.cell[f - from + 1];

			assert_int_equal(atoll(row[cf]), f);
			assert_string_equal(row[cs], "fired");
			assert_int_equal(atoll(row[ct]), t0 + mot_timing_trigger_tick(&t, f));
		}
		printf("%s: %u frames, first at tick %lld\n", cli_examples[i], c.nrows - 1,
		       (long long)atoll(c.cell[1][ct]));
		pu_csv_free(&c);
		run_free(&r);
		unlink(path);
	}
}

/* The robot arm on its own (simulated) rig: each journal row's setpoints
 * are the scene evaluated at that row's scene tick, to the 10 digits the
 * journal prints. */
static void test_robot_arm_setpoints(void **state)
{
	const char *ex = "examples/robot_arm.yaml";
	static const char *const names[] = { "base.angle", "arm1.angle", "arm2.angle" };
	struct scene_file sf;
	struct scene_built b;
	struct source_scene ss;
	struct load_err e;
	struct run r;
	struct pu_csv c;
	char path[256];
	uint32_t idx[3], k, row;
	int col[3], ct, cf;
	int64_t t0;

	pu_tmpname(path, sizeof(path), "arm");
	/* the example has its own rig (driver: sim): no --sim needed */
	play(&r, "play %s --clock virtual --quiet --journal %s", ex, path);
	assert_int_equal(r.rc, STRAND_EXIT_OK);
	assert_int_equal(scene_file_load(&sf, ex, &e), 0);
	assert_int_equal(scene_file_build(&sf, &b, &e), 0);
	assert_int_equal(source_scene_init(&ss, &sf.desc, &b.sc), 0);
	for (k = 0; k < 3; k++) {
		struct src_channel info;

		idx[k] = (uint32_t)src_lookup(&ss.s, names[k], &info);
		assert_int_equal(info.unit, SRC_UNIT_TURNS);
	}
	assert_int_equal(src_select(&ss.s, idx, 3), 0);
	assert_int_equal(pu_csv_read(&c, path), 0);
	assert_int_equal(c.nrows - 1, 241);
	for (k = 0; k < 3; k++)
		col[k] = pu_csv_col(&c, names[k]);
	ct = pu_csv_col(&c, "tick");
	cf = pu_csv_col(&c, "frame");
	t0 = atoll(c.cell[1][ct]);
	for (row = 1; row < c.nrows; row++) {
		int64_t f = atoll(c.cell[row][cf]);
		int64_t scene_tick = atoll(c.cell[row][ct]) - t0;
		mot_q32 v[3];
		uint32_t sat = 0;

		assert_int_equal(scene_tick, mot_timing_trigger_tick(&b.sc.timing, f));
		src_eval(&ss.s, mot_timing_tick_frame(&b.sc.timing, scene_tick), v, &sat);
		assert_int_equal(sat, 0);
		for (k = 0; k < 3; k++) {
			double want = q2d(v[k]) * 360, got = atof(c.cell[row][col[k]]);

			if (fabs(got - want) > 1e-9 * fmax(1, fabs(want)))
				fail_msg("frame %lld %s: journal %.12g, scene %.12g", (long long)f,
					 names[k], got, want);
		}
	}
	pu_csv_free(&c);
	source_scene_free(&ss);
	scene_built_free(&b);
	scene_file_free(&sf);
	run_free(&r);
	unlink(path);
}

/* A scene whose arm is too fast for its limits: refused with the first
 * violation named (exit 1), played with --force (setpoints clamped). */
static void test_refuses_what_check_rejects(void **state)
{
	static const char yaml[] =
		"scene: too-fast\n"
		"timing: {tick_hz: 1000, frame_rate: 24, frames: [0, 48]}\n"
		"nodes: [{name: a, joint: {type: revolute, axis: z},\n"
		"         limits: {velocity: 30, acceleration: 100}}]\n"
		"strands: [{node: a, interpolation: linear,\n"
		"           keys: [{frame: 0, angle: 0}, {frame: 24, angle: 90}]}]\n";
	char path[256];
	struct run r;
	FILE *f;

	pu_tmpname(path, sizeof(path), "fast.yaml");
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(yaml, f);
	fclose(f);
	play(&r, "play %s --sim --clock virtual --no-journal%s", path, "");
	assert_int_equal(r.rc, STRAND_EXIT_VIOLATION);
	assert_non_null(strstr(r.err, "strand check finds"));
	/* (90.00001: the run-up's last step, rounded to the core's step) */
	assert_non_null(strstr(r.err, "the first: a.angle: velocity 90.0000"));
	assert_non_null(strstr(r.err, " deg/s beyond limit 30 deg/s, frames 0 to 24."));
	run_free(&r);
	play(&r, "play %s --sim --clock virtual --no-journal --force%s", path, "");
	assert_int_equal(r.rc, STRAND_EXIT_OK);
	assert_non_null(strstr(r.out, "--force: a.angle clamped to its limits"));
	run_free(&r);
	unlink(path);
}

static void test_usage(void **state)
{
	static const struct {
		const char *args;
		int rc;
		const char *says;
	} cases[] = {
		{ "--frames 1,2", STRAND_EXIT_USAGE, "--frames is for --mode step" },
		{ "--mode fast", STRAND_EXIT_USAGE, "continuous or step" },
		{ "--loop --ping-pong", STRAND_EXIT_USAGE, "not both" },
		{ "--passes 3", STRAND_EXIT_USAGE, "--passes goes with" },
		{ "--clock sundial", STRAND_EXIT_USAGE, "real or virtual" },
		{ "--priority 120", STRAND_EXIT_USAGE, "0 to 99" },
		{ "--from 100 --to 50", STRAND_EXIT_USAGE, "--from 100 is after --to 50" },
		{ "--mode step --frames 3,,4", STRAND_EXIT_USAGE, "column 3" },
	};
	size_t i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		struct run r;

		play(&r, "play examples/robot_arm.yaml --clock virtual --no-journal %s%s",
		       cases[i].args, "");
		if (r.rc != cases[i].rc || !strstr(r.err, cases[i].says))
			fail_msg("'%s': exit %d, said: %s", cases[i].args, r.rc, r.err);
		run_free(&r);
	}
	{
		struct run r;

		/* a scene without a rig plays only on a simulated one */
		play(&r, "play %s --clock virtual --no-journal%s", "examples/curves.yaml",
		       "");
		assert_int_equal(r.rc, STRAND_EXIT_SCENE);
		assert_non_null(strstr(r.err, "--sim"));
		run_free(&r);
		play(&r, "journal %s%s", "/nonexistent/journal", "");
		assert_int_equal(r.rc, STRAND_EXIT_IO);
		run_free(&r);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_examples_played_whole),
		cmocka_unit_test(test_robot_arm_setpoints),
		cmocka_unit_test(test_refuses_what_check_rejects),
		cmocka_unit_test(test_usage),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
