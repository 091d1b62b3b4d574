/* SPDX-License-Identifier: MIT */
/*
 * test_limit_check.c - `strand check`'s limit verification (check/limit_check.c):
 * a scene that breaks each kind of limit (and where a controlled stop would
 * overrun one), caught at the right ticks, with the worst values and the
 * report lines of the command.
 *
 * The joint climbs linearly 0 -> 120 degrees over frames 0..24 (1 s at 24
 * fps, 120 deg/s), holds to frame 48 and comes back by frame 72. With 1000
 * ticks per second a tick is 0.024 frame and the value at tick k of the
 * climb is 0.12 k degrees, so everything below is exact arithmetic.
 */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check/channels.h"
#include "check/limit_check.h"
#include "cli/cli.h"
#include "cli/exitcode.h"
#include "cliutil.h"
#include "testutil.h"

static const char scene[] =
	"timing: {tick_hz: 1000, frame_rate: 24, frames: [0, 96]}\n"
	"nodes:\n"
	"  - name: arm\n"
	"    joint: {type: revolute, axis: z}\n"
	"    limits: {min: -10, max: 100, velocity: 100, acceleration: 50000}\n"
	"  - name: slide\n"
	"    joint: {type: prismatic, axis: x}\n"
	"    limits: {min: -0.2, max: 1}\n"
	"strands:\n"
	"  - node: arm\n"
	"    interpolation: linear\n"
	"    keys: [{frame: 0, angle: 0}, {frame: 24, angle: 120}, {frame: 48, angle: 120},\n"
	"           {frame: 72, angle: 0}]\n"
	"  - node: slide\n"
	"    interpolation: linear\n"
	"    keys: [{frame: 0, position: 0}, {frame: 96, position: -0.5}]\n";

#define MAXV 16

struct found {
	struct lim_violation v[MAXV];
	unsigned n;
};

static void collect(void *ctx, const struct lim_violation *v)
{
	struct found *f = ctx;

	assert_true(f->n < MAXV);
	f->v[f->n++] = *v;
}

static const struct lim_violation *find(const struct found *f, uint32_t node, enum lim_kind k,
					unsigned nth)
{
	unsigned i;

	for (i = 0; i < f->n; i++)
		if (f->v[i].channel == node && f->v[i].kind == k && f->v[i].seg == LIM_SEG_SCENE &&
		    nth-- == 0)
			return &f->v[i];
	fail_msg("no violation %u of %s on channel %u", nth, lim_kind_name(k), node);
	return NULL;
}

/* worst and limit in the file's units (degrees for an angle: turns /360). */
static void expect_in(const struct lim_violation *v, int64_t first, int64_t last, double worst,
		      double limit, double per_core)
{
	worst /= per_core;
	limit /= per_core;
	if (v->tick_first != first || v->tick_last != last ||
	    fabs(v->worst - worst) > 1e-5 * fabs(worst) || fabs(v->limit - limit) > 1e-15)
		fail_msg("%s: ticks %lld..%lld worst %.10g limit %g; want %lld..%lld %.10g %g",
			 lim_kind_name(v->kind), (long long)v->tick_first, (long long)v->tick_last,
			 v->worst, v->limit, (long long)first, (long long)last, worst, limit);
}

static void expect(const struct lim_violation *v, int64_t first, int64_t last, double worst,
		   double limit)
{
	expect_in(v, first, last, worst, limit, 360);
}

static void test_each_kind(void **state)
{
	struct scene_file sf;
	struct scene_built b;
	struct source_scene ss;
	struct load_err e;
	struct lim_result res;
	struct lim_channel *ch;
	struct lim_run run = { .from = 0, .to = 96 };
	struct found f = { .n = 0 };
	const struct lim_violation *v;
	uint32_t n;

	assert_int_equal(scene_file_parse(&sf, "limits.yaml", scene, strlen(scene), &e), 0);
	assert_int_equal(scene_file_build(&sf, &b, &e), 0);
	assert_int_equal(source_scene_init(&ss, &sf.desc, &b.sc), 0);
	assert_int_equal(lim_channels(&ss, NULL, &ch, &n), 0);
	assert_int_equal(n, 2);
	assert_string_equal(ch[0].name, "arm.angle");
	assert_string_equal(ch[1].name, "slide.position");
	assert_int_equal(lim_check(&ss.s, ch, n, &run, collect, &f, &res), 0);
	assert_int_equal(res.sat, 0);

	/* max 100: above from tick 834 (100.08 deg) to the descent's tick 2166 */
	v = find(&f, 0, LIM_MAX, 0);
	expect(v, 834, 2166, 120, 100);
	assert_true(fabs(v->frame_first - 20.016) < 1e-9 && fabs(v->frame_last - 51.984) < 1e-9);
	/* velocity 100 deg/s: 120 deg/s on the way up (ticks 0..1000: the run-up
	 * brings the arm to that speed at tick 0) and down */
	expect(find(&f, 0, LIM_VEL, 0), 0, 1000, 120, 100);
	expect(find(&f, 0, LIM_VEL, 1), 2001, 3000, -120, -100);
	/* acceleration: one tick at each corner of the linear path,
	 * 0.12 deg / (1 ms)^2 = 120000 deg/s^2 */
	expect(find(&f, 0, LIM_ACC, 0), 1000, 1000, -120000, -50000);
	expect(find(&f, 0, LIM_ACC, 1), 2000, 2000, -120000, -50000);
	expect(find(&f, 0, LIM_ACC, 2), 3000, 3000, 120000, 50000);
	/* prismatic min -0.2: -0.5 f / 96 < -0.2 after frame 38.4 = tick 1600 */
	v = find(&f, 1, LIM_MIN, 0);
	expect_in(v, 1601, 4000, -0.5, -0.2, 1);
	/* a controlled stop at 50000 deg/s^2 (50 deg/s less a tick) from 120
	 * deg/s goes on 0.07 + 0.02 = 0.09 deg: stopping at 0.12 k + 0.09 deg,
	 * past 100 from tick 833 up, through the hold (at rest: the value
	 * itself), and on the way down until 120 - 0.12 (k - 2000) - 0.09 <= 100 */
	expect(find(&f, 0, LIM_STOP, 0), 833, 2165, 120.09, 100);
	assert_int_equal(res.violations, 8);
	assert_int_equal(f.n, 8);
	free(ch);
	source_scene_free(&ss);
	scene_built_free(&b);
	scene_file_free(&sf);
}

/* The same through `strand check`: the report lines and exit code 1. */
static void test_command(void **state)
{
	char path[] = "/tmp/strand-limits-XXXXXX.yaml", *out = NULL, *err = NULL;
	char *argv[] = { "strand", "check", path, NULL };
	size_t out_len, err_len;
	FILE *fo, *fe;
	int fd = mkstemps(path, 5), rc;

	assert_true(fd >= 0);
	assert_int_equal(write(fd, scene, strlen(scene)), (ssize_t)strlen(scene));
	close(fd);
	fo = open_memstream(&out, &out_len);
	fe = open_memstream(&err, &err_len);
	rc = cli_main(3, argv, fo, fe);
	fclose(fo);
	fclose(fe);
	assert_int_equal(rc, STRAND_EXIT_VIOLATION);
	assert_int_equal(err_len, 0);
	assert_non_null(strstr(out, "arm.angle: max 120 deg beyond limit 100 deg, frames 20.016 to 51.984\n"));
	assert_non_null(strstr(out, "arm.angle: velocity -120 deg/s beyond limit -100 deg/s, frames 48.024 to 72\n"));
	assert_non_null(strstr(out, "arm.angle: acceleration 120000 deg/s^2 beyond limit 50000 deg/s^2, frames 72 to 72\n"));
	assert_non_null(strstr(out, "slide.position: min -0.5 units beyond limit -0.2 units, frames 38.424 to 96\n"));
	assert_non_null(strstr(out, "arm.angle: a controlled stop would end at 120.09 deg, beyond limit 100 deg, frames 19.992 to 51.96\n"));
	assert_non_null(strstr(out, ": 8 violations; 2 channels with limits, frames 0 to 96, 4001 ticks\n"));
	free(out);
	free(err);
	unlink(path);
}

/* A scene file made from an example with one line changed, for the tests
 * below: `from` replaced by `to` (which must be there). */
static void example_with(char *path, size_t size, const char *ex, const char *from,
			 const char *to)
{
	FILE *f = fopen(ex, "r");
	char text[16384];
	size_t n;
	char *at;

	assert_non_null(f);
	n = fread(text, 1, sizeof(text) - 1, f);
	fclose(f);
	text[n] = '\0';
	at = strstr(text, from);
	assert_non_null(at);
	snprintf(path, size, "/tmp/strand-limits-%d.yaml", (int)getpid());
	f = fopen(path, "w");
	assert_non_null(f);
	fprintf(f, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
	fclose(f);
}

/* strand check's first line is play's first reason, verbatim. */
static void same_first(const struct run *chk, const struct run *ply)
{
	char want[600];
	const char *nl = strchr(chk->out, '\n');

	assert_non_null(nl);
	snprintf(want, sizeof(want), "the first: %.*s.\n", (int)(nl - chk->out), chk->out);
	if (!strstr(ply->err, want))
		fail_msg("play says:\n%swant:\n%s", ply->err, want);
}

/*
 * An output's own limits replace its node's at run time, and check holds
 * the timeline to them (issue 12: the robot arm with {velocity: 20,
 * acceleration: 360} on base.angle's output passed check, then play stopped
 * at tick 561 with exit 7). Now check finds it and play refuses it, exit 1,
 * for the same first reason, before anything moves.
 */
static void test_output_limits(void **state)
{
	char path[256];
	struct run chk, ply;

	example_with(path, sizeof(path), "examples/robot_arm.yaml",
		     "axis: 0, counts_per_unit: 1000, ferror: 1, min_ferror: 0.1}",
		     "axis: 0, counts_per_unit: 1000, ferror: 1, min_ferror: 0.1,\n"
		     "     limits: {velocity: 20, acceleration: 360}}");
	{
		char args[300];

		snprintf(args, sizeof(args), "check %s", path);
		strand(&chk, args);
		snprintf(args, sizeof(args), "play %s --clock virtual --no-journal --quiet", path);
		strand(&ply, args);
	}
	assert_int_equal(chk.rc, STRAND_EXIT_VIOLATION);
	assert_non_null(strstr(chk.out, "base.angle: velocity 38.8889"));
	assert_non_null(strstr(chk.out, ": 3 violations; 3 channels with limits"));
	assert_int_equal(ply.rc, STRAND_EXIT_VIOLATION);
	same_first(&chk, &ply);
	run_free(&chk);
	run_free(&ply);
	unlink(path);
}

/*
 * A range that starts where the scene moves fast, next to a position limit
 * behind it: the run-up would have to start beyond the limit. check names
 * it (the frame and where the ramp would start), and play refuses it, exit
 * 1, for the same reason, instead of failing to plan after the devices
 * started (exit 2 before).
 */
static void test_runup_outside(void **state)
{
	static const char yaml[] =
		"timing: {tick_hz: 1000, frame_rate: 24, frames: [0, 48]}\n"
		"nodes: [{name: a, joint: {type: revolute, axis: z},\n"
		"         limits: {min: -1, max: 100, velocity: 200, acceleration: 100}}]\n"
		"strands: [{node: a, interpolation: linear,\n"
		"           keys: [{frame: 0, angle: 0}, {frame: 24, angle: 90}]}]\n";
	char path[] = "/tmp/strand-runup-XXXXXX.yaml", args[300];
	struct run chk, ply;
	int fd = mkstemps(path, 5);

	assert_true(fd >= 0);
	assert_int_equal(write(fd, yaml, strlen(yaml)), (ssize_t)strlen(yaml));
	close(fd);
	snprintf(args, sizeof(args), "check --sim %s --from 0 --to 20", path);
	strand(&chk, args);
	snprintf(args, sizeof(args), "play %s --sim --clock virtual --no-journal --quiet --from 0 "
		 "--to 20", path);
	strand(&ply, args);
	assert_int_equal(chk.rc, STRAND_EXIT_VIOLATION);
	/* 90 deg/s at 100 deg/s^2: 900 ticks of ramp, starting 40.5 deg back */
	assert_non_null(strstr(chk.out, "a.angle: the run-up into frame 0 starts at -40.5"));
	assert_int_equal(ply.rc, STRAND_EXIT_VIOLATION);
	same_first(&chk, &ply);
	run_free(&chk);
	run_free(&ply);
	unlink(path);
}

/*
 * Go-motion (--mode step --shutter): each frame runs up from rest to the
 * scene's speed where its exposure opens. At 48 deg/s and 100 deg/s^2 a
 * ramp takes 0.48 s and starts 11.5 deg behind: for frames 0 to 5 that is
 * behind the min of -1 deg. check names each frame's run-up, play refuses
 * the run for the same first reason; from frame 6 on check passes it, and
 * play plays it to its end (its own check at every tick never fires).
 */
static void test_gomo_runup_outside(void **state)
{
	static const char yaml[] =
		"timing: {tick_hz: 1000, frame_rate: 24, frames: [0, 24]}\n"
		"nodes: [{name: a, joint: {type: revolute, axis: z},\n"
		"         limits: {min: -1, max: 100, velocity: 200, acceleration: 100}}]\n"
		"strands: [{node: a, interpolation: linear,\n"
		"           keys: [{frame: 0, angle: 0}, {frame: 24, angle: 48}]}]\n";
	char path[] = "/tmp/strand-gomo-XXXXXX.yaml", args[300], want[128];
	struct run chk, ply;
	int fd = mkstemps(path, 5), f;

	assert_true(fd >= 0);
	assert_int_equal(write(fd, yaml, strlen(yaml)), (ssize_t)strlen(yaml));
	close(fd);
	snprintf(args, sizeof(args), "check --sim %s --mode step --shutter 180 --from 0 --to 10",
		 path);
	strand(&chk, args);
	snprintf(args, sizeof(args), "play %s --sim --clock virtual --no-journal --quiet "
		 "--mode step --shutter 180 --frames 0..10", path);
	strand(&ply, args);
	printf("%s", chk.out);
	assert_int_equal(chk.rc, STRAND_EXIT_VIOLATION);
	for (f = 0; f < 7; f++) {
		snprintf(want, sizeof(want), "a.angle: the go-motion run-up into frame %d starts at ",
			 f);
		assert_true(!strstr(chk.out, want) == (f == 6));
	}
	/* frame 0: from -0.48 deg (a quarter frame before 0, at the scene's
	 * speed) back 0.048 deg x 481 / 2 */
	assert_non_null(strstr(chk.out, "frame 0 starts at -12.02399 deg, beyond limit -1 deg;"));
	assert_non_null(strstr(chk.out, "frames 0 to 10, 418 ticks\n"));
	assert_int_equal(ply.rc, STRAND_EXIT_VIOLATION);
	same_first(&chk, &ply);
	run_free(&chk);
	run_free(&ply);

	snprintf(args, sizeof(args), "check --sim %s --mode step --shutter 180 --from 6 --to 24",
		 path);
	strand(&chk, args);
	snprintf(args, sizeof(args), "play %s --sim --clock virtual --no-journal --quiet "
		 "--mode step --shutter 180 --frames 6..24", path);
	strand(&ply, args);
	assert_int_equal(chk.rc, STRAND_EXIT_OK);
	assert_non_null(strstr(chk.out, ": 0 violations;"));
	assert_int_equal(ply.rc, STRAND_EXIT_OK);
	run_free(&chk);
	run_free(&ply);
	unlink(path);
}

/* A rig that stands outside an output's position limits is refused before
 * its first tick, naming the output (exit 7: the rig's state, not the
 * scene's), rather than faulting at tick 0. */
static void test_stands_outside(void **state)
{
	char path[256], args[300];
	struct run r;

	example_with(path, sizeof(path), "examples/robot_arm.yaml",
		     "axis: 0, counts_per_unit: 1000, ferror: 1, min_ferror: 0.1}",
		     "axis: 0, counts_per_unit: 1000, ferror: 1, min_ferror: 0.1, home: 200}");
	snprintf(args, sizeof(args), "play %s --clock virtual --no-journal --quiet", path);
	strand(&r, args);
	assert_int_equal(r.rc, STRAND_EXIT_FAULT);
	assert_non_null(strstr(r.err, "base.angle (device 'drives' axis 0) stands at 200 deg, "
				      "outside its limits -170 to 170 deg"));
	run_free(&r);
	unlink(path);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_each_kind),
		cmocka_unit_test(test_command),
		cmocka_unit_test(test_output_limits),
		cmocka_unit_test(test_runup_outside),
		cmocka_unit_test(test_gomo_runup_outside),
		cmocka_unit_test(test_stands_outside),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
