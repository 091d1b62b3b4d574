/* SPDX-License-Identifier: MIT */
/*
 * test_live.c - a live session on the simulated robot arm in virtual time
 * (live/live.h): the machine states, jog (dead-man, a position limit),
 * move to a frame (its exact pose), a play segment, the e-stop latch and
 * its reset, teach (the file edited in place, a refused teach leaves it
 * unchanged), disable.
 */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "live/live.h"
#include "load/load.h"
#include "mbpeer.h"
#include "scene/source_scene.h"
#include "testutil.h"

struct fixture {
	struct live *lv;
	pthread_t svc;
	volatile int stop;
	char dir[64], path[128];
};

static void *service(void *arg)
{
	struct fixture *f = arg;

	while (!f->stop) {
		int ms = live_service(f->lv);

		nanosleep(&(struct timespec){ .tv_nsec = ms * 1000000L }, NULL);
	}
	return NULL;
}

static char *slurp(const char *path, size_t *len)
{
	FILE *fp = fopen(path, "rb");
	char *buf;
	long n;

	assert_non_null(fp);
	fseek(fp, 0, SEEK_END);
	n = ftell(fp);
	fseek(fp, 0, SEEK_SET);
	buf = malloc((size_t)n + 1);
	assert_int_equal(fread(buf, 1, (size_t)n, fp), (size_t)n);
	buf[n] = 0;
	fclose(fp);
	if (len)
		*len = (size_t)n;
	return buf;
}

/* A live session on a copy of the scene (its own devices unless sim). */
static void open_scene(struct fixture *f, const char *scene, bool sim, double deadman_ms)
{
	struct live_opts o = { .sim = sim, .virtual_clock = true, .deadman_ms = deadman_ms };
	char err[512], *text;
	size_t len;
	FILE *fp;

	memset(f, 0, sizeof(*f));
	snprintf(f->dir, sizeof(f->dir), "/tmp/strand-live-XXXXXX");
	assert_non_null(mkdtemp(f->dir));
	snprintf(f->path, sizeof(f->path), "%s/arm.yaml", f->dir);
	text = slurp(scene, &len);
	fp = fopen(f->path, "wb");
	fwrite(text, 1, len, fp);
	fclose(fp);
	free(text);
	o.rt.cpu = -1;
	o.rt.name = "strand-rt";
	if (live_open(&f->lv, f->path, &o, err, sizeof(err))) {
		print_error("live_open: %s\n", err);
		fail();
	}
	pthread_create(&f->svc, NULL, service, f);
}

static void open_fixture(struct fixture *f, double deadman_ms)
{
	open_scene(f, "examples/robot_arm.yaml", true, deadman_ms);
}

static void close_fixture(struct fixture *f)
{
	char cmd[160];

	f->stop = 1;
	pthread_join(f->svc, NULL);
	live_close(f->lv);
	snprintf(cmd, sizeof(cmd), "rm -rf %s", f->dir);
	assert_int_equal(system(cmd), 0);
}

/* Wait (at most 20 s of wall time) for a snapshot that pred accepts. */
static void wait_for(struct fixture *f, bool (*pred)(const struct live_snap *, const void *),
		     const void *arg, struct live_snap *s, const char *what)
{
	int i;

	for (i = 0; i < 20000; i++) {
		live_snapshot(f->lv, s);
		if (pred(s, arg))
			return;
		nanosleep(&(struct timespec){ .tv_nsec = 1000000 }, NULL);
	}
	print_error("timed out waiting for %s (state %s, loop %s)\n", what,
		    live_state_name(s->state), s->loop_state);
	fail();
}

static bool is_state(const struct live_snap *s, const void *arg)
{
	return s->state == *(const enum live_state *)arg;
}

static bool at_rest(const struct live_snap *s, const void *arg)
{
	(void)arg;
	return s->cmd_seen == s->cmd_sent && s->state == LIVE_ENABLED &&
	       !strcmp(s->loop_state, "hold");
}

static void expect_state(struct fixture *f, enum live_state st, struct live_snap *s)
{
	wait_for(f, is_state, &st, s, live_state_name(st));
}

static void rest(struct fixture *f, struct live_snap *s)
{
	wait_for(f, at_rest, NULL, s, "the rig at rest");
}

/* A channel of a scene at a frame, as the session's source evaluates it,
 * in the file's units. */
static double channel_at(const char *path, const char *channel, int64_t frame);

static double scene_at(const char *path, const char *channel, int64_t frame)
{
	return channel_at(path, channel, frame);
}

static double channel_at(const char *path, const char *channel, int64_t frame)
{
	struct scene_file sf;
	struct scene_built b;
	struct source_scene ss;
	struct src_channel info;
	struct load_err e;
	uint32_t idx, sat = 0;
	mot_q32 v;
	int i;

	assert_int_equal(scene_file_load(&sf, path, &e), 0);
	assert_int_equal(scene_file_build(&sf, &b, &e), 0);
	assert_int_equal(source_scene_init(&ss, &sf.desc, &b.sc), 0);
	i = src_lookup(&ss.s, channel, &info);
	assert_true(i >= 0);
	idx = (uint32_t)i;
	assert_int_equal(src_select(&ss.s, &idx, 1), 0);
	src_eval(&ss.s, (mot_q32)frame * MOT_Q32_ONE, &v, &sat);
	source_scene_free(&ss);
	scene_built_free(&b);
	scene_file_free(&sf);
	return (double)v * ((info.unit == SRC_UNIT_TURNS ? 360.0 : 1.0) / 4294967296.0);
}

static void ok(int rc, const char *msg)
{
	if (rc)
		fprintf(stderr, "error: %s\n", msg);
	assert_int_equal(rc, 0);
}

/* base.angle is output 0 of the simulated rig: its limits are the node's,
 * -170..170 deg, 90 deg/s, 360 deg/s^2. */
static void test_states_jog_goto_play(void **state)
{
	struct fixture f;
	struct live_snap s;
	char msg[512];
	double moved;
	int64_t lat;

	open_fixture(&f, 250);
	live_snapshot(f.lv, &s);
	assert_int_equal(s.state, LIVE_DISABLED);
	/* disabled: no command reaches the loop */
	assert_int_equal(live_goto(f.lv, 10, msg, sizeof(msg)), -EPERM);
	assert_non_null(strstr(msg, "enable"));
	ok(live_enable(f.lv, msg, sizeof(msg)), msg);
	expect_state(&f, LIVE_ENABLED, &s);
	ok(live_ping(f.lv, 0, &lat, msg, sizeof(msg)), msg);

	/* one jog command and no refresh: the dead-man ends it; the axis
	 * comes to rest having ramped for at most 250 ms (+ a tick) and
	 * braked at the limit deceleration: v = a t = 90 at most, so it
	 * moved at most a t^2 = 360 * 0.251^2 deg */
	ok(live_jog(f.lv, 1, 0, 1.0, 1, msg, sizeof(msg)), msg);
	/* a doubled command is ignored (answered 0, nothing done) */
	ok(live_jog(f.lv, 1, 0, 1.0, 1, msg, sizeof(msg)), msg);
	rest(&f, &s);
	moved = s.out[0].sp;
	printf("BOUND dead-man jog moved %.4f deg <= %.4f deg, then rest (v %.3g)\n", moved,
	       360 * 0.251 * 0.251, s.out[0].vel);
	assert_true(moved > 0);
	assert_true(moved <= 360 * 0.251 * 0.251 + 1e-9);
	assert_true(s.out[0].vel == 0);
	assert_true(s.frame == -1);

	/* move to frame 48: its exact pose, as step mode lands on it */
	ok(live_goto(f.lv, 48, msg, sizeof(msg)), msg);
	rest(&f, &s);
	assert_int_equal(s.frame, 48);
	{
		double want = scene_at("examples/robot_arm.yaml", "base.angle", 48);

		printf("BOUND goto 48: base %.12g deg == the scene's %.12g (exact)\n",
		       s.out[0].sp, want);
		assert_true(s.out[0].sp == want);
	}
	/* a frame whose pose is outside a limit is refused (none here): a
	 * pose beyond base's limit is */
	{
		double pose[4] = { 200, NAN, NAN, NAN };

		assert_int_equal(live_move(f.lv, pose, s.nout, msg, sizeof(msg)), -ERANGE);
		assert_non_null(strstr(msg, "base.angle"));
	}

	/* a segment of play: frames 0..24, back to rest holding the last pose */
	{
		struct live_play p = { .has_from = true, .from = 0, .has_to = true, .to = 24,
				       .settle_ms = 200, .exposure_ms = 100, .timeout_s = 10 };

		struct live_play endless = p;

		/* a looped segment without an end: busy until a stop */
		endless.loop = true;
		ok(live_play(f.lv, &endless, msg, sizeof(msg)), msg);
		assert_int_equal(live_play(f.lv, &p, msg, sizeof(msg)), -EBUSY);
		assert_int_equal(live_goto(f.lv, 3, msg, sizeof(msg)), -EBUSY);
		ok(live_stop(f.lv, msg, sizeof(msg)), msg);
		rest(&f, &s);
		ok(live_play(f.lv, &p, msg, sizeof(msg)), msg);
		rest(&f, &s);
		assert_int_equal(s.fired, 25);
		assert_int_equal(s.frame, 24);
		assert_non_null(strstr(s.reason, "finished"));
	}

	/* e-stop: latched; enable refused until reset */
	live_estop(f.lv);
	expect_state(&f, LIVE_ESTOPPED, &s);
	assert_non_null(strstr(s.reason, "e-stop"));
	assert_int_equal(live_enable(f.lv, msg, sizeof(msg)), -EPERM);
	ok(live_reset(f.lv, msg, sizeof(msg)), msg);
	expect_state(&f, LIVE_DISABLED, &s);
	ok(live_enable(f.lv, msg, sizeof(msg)), msg);
	expect_state(&f, LIVE_ENABLED, &s);
	ok(live_disable(f.lv, msg, sizeof(msg)), msg);
	expect_state(&f, LIVE_DISABLED, &s);
	close_fixture(&f);
}

/* A jog held on (a dead-man longer than the test) into base's +170 limit:
 * it arrives on the limit and never passes it. */
static void test_jog_limit(void **state)
{
	struct fixture f;
	struct live_snap s;
	char msg[512];
	double top = -1e9;
	uint64_t last = 0;
	int i;

	open_fixture(&f, 1e9);
	ok(live_enable(f.lv, msg, sizeof(msg)), msg);
	expect_state(&f, LIVE_ENABLED, &s);
	ok(live_jog(f.lv, 7, 0, 1.0, 1, msg, sizeof(msg)), msg);
	/* 170 deg at 90 deg/s: ~2.2 s of virtual time, paced at the wall's */
	for (i = 0; i < 10000; i++) {
		live_snapshot(f.lv, &s);
		if (s.serial != last) {
			last = s.serial;
			if (s.out[0].sp > top)
				top = s.out[0].sp;
			if (fabs(s.out[0].sp - 170) < 1e-7 && s.out[0].vel == 0)
				break;
		}
		nanosleep(&(struct timespec){ .tv_nsec = 1000000 }, NULL);
	}
	/* on it: within a step of Q32.32 turns (8.4e-8 deg), never above */
	printf("BOUND jog into the +170 limit: highest setpoint %.12g <= 170 + 1e-9 deg, at "
	       "rest within 1e-7 deg of it\n", top);
	assert_true(top <= 170 + 1e-9);
	assert_true(fabs(s.out[0].sp - 170) < 1e-7);
	assert_int_equal(s.state, LIVE_MOVING); /* still jogging, no fault: limits kept */
	ok(live_jog(f.lv, 7, 0, 0, 2, msg, sizeof(msg)), msg);
	rest(&f, &s);
	assert_true(fabs(s.out[0].sp - 170) < 1e-7);
	close_fixture(&f);
}

/* Teach: a key where the rig stands; a refused teach (a limit broken)
 * leaves the file as it was; delete and move. */
static void test_teach(void **state)
{
	struct fixture f;
	struct live_snap s;
	char msg[512], *before, *after, bak[160];
	const char *base = "base";

	open_fixture(&f, 250);
	ok(live_enable(f.lv, msg, sizeof(msg)), msg);
	expect_state(&f, LIVE_ENABLED, &s);
	ok(live_goto(f.lv, 48, msg, sizeof(msg)), msg);
	rest(&f, &s);
	/* key base's 60 deg at frame 72 (between 48 and 96, both 60) */
	before = slurp(f.path, NULL);
	ok(live_teach(f.lv, 72, &base, 1, msg, sizeof(msg)), msg);
	after = slurp(f.path, NULL);
	{
		char line[96];

		/* where the rig stands, between the keys at 48 and 96, in their style */
		snprintf(line, sizeof(line), "      - {frame: 48, angle: 60}\n"
			 "      - {frame: 72, angle: %.10g}\n      - {frame: 96,", s.out[0].sp);
		assert_non_null(strstr(after, line));
	}
	/* the comments stay */
	assert_non_null(strstr(after, "# turns about y on the floor"));
	snprintf(bak, sizeof(bak), "%s.bak", f.path);
	{
		char *b = slurp(bak, NULL);

		assert_string_equal(b, before);
		free(b);
	}
	free(before);
	/* 60 deg at frame 1 next to 0 deg at frame 0 breaks base's speed
	 * limit: refused, file unchanged */
	assert_int_equal(live_teach(f.lv, 1, &base, 1, msg, sizeof(msg)), -EDOM);
	assert_non_null(strstr(msg, "violation"));
	before = slurp(f.path, NULL);
	assert_string_equal(before, after);
	free(before);
	free(after);
	/* move it to 70, then delete it */
	ok(live_teach_move(f.lv, "base", 72, 70, msg, sizeof(msg)), msg);
	after = slurp(f.path, NULL);
	assert_non_null(strstr(after, "{frame: 70, angle: 53.47"));
	free(after);
	ok(live_teach_delete(f.lv, "base", 70, msg, sizeof(msg)), msg);
	after = slurp(f.path, NULL);
	assert_null(strstr(after, "frame: 70"));
	free(after);
	ok(live_disable(f.lv, msg, sizeof(msg)), msg);
	close_fixture(&f);
}

/*
 * Drives stopped and started again, as a live session does between runs of
 * the loop (a disable, an e-stop and its reset): each device must report
 * where it stands when it starts again and follow from there. Every
 * output has a following error bound (0.2 degrees at rest, 1 at speed): a
 * device that stood still while the new run's setpoints moved, or pulled
 * towards an old target, faults the run.
 */
static void restart_cycles(struct fixture *f, const char *what)
{
	struct live_snap s;
	char msg[512];
	uint32_t i;
	int cycle;

	ok(live_enable(f->lv, msg, sizeof(msg)), msg);
	expect_state(f, LIVE_ENABLED, &s);
	for (cycle = 0; cycle < 2; cycle++) {
		ok(live_goto(f->lv, 36, msg, sizeof(msg)), msg);
		rest(f, &s);
		if (cycle == 0) {
			live_estop(f->lv);
			expect_state(f, LIVE_ESTOPPED, &s);
			ok(live_reset(f->lv, msg, sizeof(msg)), msg);
		} else {
			ok(live_disable(f->lv, msg, sizeof(msg)), msg);
		}
		expect_state(f, LIVE_DISABLED, &s);
		ok(live_enable(f->lv, msg, sizeof(msg)), msg);
		expect_state(f, LIVE_ENABLED, &s);
		rest(f, &s);
		/* started again where the drives stood when they stopped: frame
		 * 36's pose, give or take what a servo had still to settle (an
		 * e-stop or a disable takes the power at once) */
		for (i = 0; i < s.nout; i++) {
			printf("BOUND %s restart %d: %s stands at %.6f, held at %.6f (|fe| %.2e <= "
			       "0.05 deg)\n", what, cycle, i ? "b" : "a", s.out[i].act, s.out[i].sp,
			       fabs(s.out[i].fe));
			assert_true(s.out[i].has_act);
			assert_true(fabs(s.out[i].fe) <= 0.05);
		}
		assert_true(fabs(s.out[0].sp - 40) < 0.01);
		/* and follows from there: a move and a segment of play */
		ok(live_goto(f->lv, 0, msg, sizeof(msg)), msg);
		rest(f, &s);
		{
			struct live_play p = { .has_from = true, .from = 24, .has_to = true,
					       .to = 48, .timeout_s = 10 };

			ok(live_play(f->lv, &p, msg, sizeof(msg)), msg);
			rest(f, &s);
			assert_int_equal(s.state, LIVE_ENABLED);
			assert_non_null(strstr(s.reason, "finished"));
		}
	}
	ok(live_disable(f->lv, msg, sizeof(msg)), msg);
	expect_state(f, LIVE_DISABLED, &s);
}

/* Two revolute joints a and b over frames 0..72 (tests/mbpeer.h's), on the
 * rig of devices (a YAML text) with the outputs given. */
static void two_joint_scene(const char *path, const char *devices, const char *outputs)
{
	FILE *fp = fopen(path, "w");

	assert_non_null(fp);
	fprintf(fp,
		"scene: restart\n"
		"timing: {tick_hz: 1000, frame_rate: 24, frames: [0, 72]}\n"
		"nodes:\n"
		"  - {name: a, joint: {type: revolute, axis: y},\n"
		"     limits: {min: -170, max: 170, velocity: 90, acceleration: 360}}\n"
		"  - {name: b, parent: a, pivot: [0, 0.3, 0], joint: {type: revolute, axis: z},\n"
		"     limits: {min: -90, max: 90, velocity: 60, acceleration: 240}}\n"
		"strands:\n"
		"  - {node: a, interpolation: hermite, ease: {in: 12, out: 12},\n"
		"     keys: [{frame: 0, angle: 0}, {frame: 36, angle: 40},\n"
		"            {frame: 72, angle: 0}]}\n"
		"  - {node: b, interpolation: hermite, ease: {in: 12, out: 12},\n"
		"     keys: [{frame: 0, angle: 0}, {frame: 48, angle: -20},\n"
		"            {frame: 72, angle: 0}]}\n"
		"devices:\n%s  - {name: io, driver: sim}\n"
		"outputs:\n%s"
		"triggers:\n"
		"  - {name: camera, device: io, line: 0, pulse_ms: 2}\n", devices, outputs);
	fclose(fp);
}

static void test_restart_sim(void **state)
{
	struct fixture f;
	char path[160];

	snprintf(path, sizeof(path), "/tmp/strand-live-sim-%d.yaml", (int)getpid());
	two_joint_scene(path, "  - {name: drives, driver: sim}\n",
			"  - {channel: a.angle, device: drives, axis: 0, counts_per_unit: 1000,\n"
			"     ferror: 1, min_ferror: 0.2}\n"
			"  - {channel: b.angle, device: drives, axis: 1, counts_per_unit: 1000,\n"
			"     ferror: 1, min_ferror: 0.2}\n");
	open_scene(&f, path, false, 250);
	unlink(path);
	restart_cycles(&f, "sim");
	close_fixture(&f);
}

/* A rig found outside a position limit (a's 10..170, the twin at 0): it
 * holds, a jog further out does not move it, a jog back in does, and
 * nothing faults. */
static void test_outside_limits(void **state)
{
	struct fixture f;
	struct live_snap s;
	char path[160], msg[512];
	int i;

	snprintf(path, sizeof(path), "/tmp/strand-live-out-%d.yaml", (int)getpid());
	two_joint_scene(path, "  - {name: drives, driver: sim}\n",
			"  - {channel: a.angle, device: drives, axis: 0, counts_per_unit: 1000,\n"
			"     limits: {min: 10, max: 170, velocity: 90, acceleration: 360}}\n"
			"  - {channel: b.angle, device: drives, axis: 1, counts_per_unit: 1000}\n");
	open_scene(&f, path, false, 250);
	unlink(path);
	ok(live_enable(f.lv, msg, sizeof(msg)), msg);
	expect_state(&f, LIVE_ENABLED, &s);
	for (i = 0; i < 6; i++) { /* outwards, 300 ms */
		ok(live_jog(f.lv, 3, 0, -0.5, i + 1, msg, sizeof(msg)), msg);
		nanosleep(&(struct timespec){ .tv_nsec = 50000000 }, NULL);
	}
	rest(&f, &s);
	printf("BOUND outside the limit: a jogged outwards stays at %.9f deg (0)\n", s.out[0].sp);
	assert_int_equal(s.state, LIVE_ENABLED);
	assert_true(s.out[0].sp == 0);
	for (i = 0; i < 6; i++) { /* back in */
		ok(live_jog(f.lv, 3, 0, 0.5, i + 7, msg, sizeof(msg)), msg);
		nanosleep(&(struct timespec){ .tv_nsec = 50000000 }, NULL);
	}
	rest(&f, &s);
	printf("BOUND outside the limit: a jogged back in to %.3f deg, no fault\n", s.out[0].sp);
	assert_int_equal(s.state, LIVE_ENABLED);
	assert_true(s.out[0].sp > 1);
	ok(live_disable(f.lv, msg, sizeof(msg)), msg);
	close_fixture(&f);
}

/* CiA 402 drives on the simulated bus (interface sim: the master, the
 * protocol and the drives in-process): the drives' NMT and 402 states
 * through a stop and a start. */
static void test_restart_canopen(void **state)
{
	struct fixture f;
	char path[160];

	snprintf(path, sizeof(path), "/tmp/strand-live-co-%d.yaml", (int)getpid());
	two_joint_scene(path, "  - {name: arm, driver: canopen,\n"
			"     canopen: {interface: sim, bitrate: 1000000, heartbeat_ms: 20}}\n",
			"  - {channel: a.angle, device: arm, node: 3, counts_per_unit: 1000,\n"
			"     ferror: 1, min_ferror: 0.2}\n"
			"  - {channel: b.angle, device: arm, node: 7, counts_per_unit: 1000,\n"
			"     ferror: 1, min_ferror: 0.2}\n");
	open_scene(&f, path, false, 250);
	unlink(path);
	restart_cycles(&f, "canopen");
	close_fixture(&f);
}

/* A Modbus drive: strand-simdrive, a server in a process of its own,
 * whose enable coil is cleared and set again. */
static struct mbp_peer peer = { .pid = -1 };

/* The server goes whatever the test came to (it holds the test's output). */
static int stop_peer(void **state)
{
	if (peer.pid > 0)
		mbp_stop(&peer);
	peer.pid = -1;
	return 0;
}

static void test_restart_modbus(void **state)
{
	struct fixture f;
	char path[160], conn[96];
	int port = mbp_free_port();

	assert_true(port > 0);
	snprintf(path, sizeof(path), "/tmp/strand-live-mb-%d.yaml", (int)getpid());
	snprintf(conn, sizeof(conn), "tcp: {host: 127.0.0.1, port: %d}", port);
	mbp_scene(path, 1000, conn, NULL, ", ferror: 1, min_ferror: 0.2");
	if (mbp_start(&peer, path, ""))
		fail_msg("strand-simdrive did not start: '%s'", peer.line);
	open_scene(&f, path, false, 250);
	unlink(path);
	restart_cycles(&f, "modbus");
	close_fixture(&f);
	assert_int_equal(mbp_stop(&peer), 0);
	peer.pid = -1;
}

/* The camera on a six-axis rig (slider x, y, z; a pan/tilt/roll head) and
 * a free node, a crane turned 30 degrees about y, whose tip's pivot three
 * more outputs follow. */
static const char space_scene[] =
	"scene: space\n"
	"timing: {tick_hz: 1000, frame_rate: 24, frames: [0, 48]}\n"
	"nodes:\n"
	"  - {name: crane, pivot: [0, 1, 0]}\n"
	"  - {name: tip, parent: crane, pivot: [0.5, 1, 0]}\n"
	"strands:\n"
	"  - {node: crane, keys: [{frame: 0, rotate: [0, 30, 0]},\n"
	"                        {frame: 48, rotate: [0, 30, 0]}]}\n"
	"camera:\n"
	"  keys:\n"
	"    - {frame: 0, eye: [1, 1.5, 3], look_at: [0, 0.5, 0], twist: 10}\n"
	"    - {frame: 48, eye: [1, 1.5, 3], look_at: [0, 0.5, 0], twist: 10}\n"
	"devices:\n"
	"  - {name: drives, driver: sim}\n"
	"  - {name: io, driver: sim}\n"
	"outputs:\n"
	"  - {channel: camera.x, device: drives, axis: 0, counts_per_unit: 10000,\n"
	"     limits: {min: -5, max: 5, velocity: 0.5, acceleration: 2}}\n"
	"  - {channel: camera.y, device: drives, axis: 1, counts_per_unit: 10000,\n"
	"     limits: {min: -5, max: 5, velocity: 0.4, acceleration: 2}}\n"
	"  - {channel: camera.z, device: drives, axis: 2, counts_per_unit: 10000,\n"
	"     limits: {min: -5, max: 5, velocity: 0.5, acceleration: 1}}\n"
	"  - {channel: camera.pan, device: drives, axis: 3, counts_per_unit: 100,\n"
	"     limits: {velocity: 30, acceleration: 120}}\n"
	"  - {channel: camera.tilt, device: drives, axis: 4, counts_per_unit: 100,\n"
	"     limits: {min: -80, max: 80, velocity: 30, acceleration: 120}}\n"
	"  - {channel: camera.roll, device: drives, axis: 5, counts_per_unit: 100,\n"
	"     limits: {min: -90, max: 90, velocity: 30, acceleration: 120}}\n"
	"  - {channel: tip.x, device: drives, axis: 6, counts_per_unit: 10000,\n"
	"     limits: {min: -5, max: 5, velocity: 0.5, acceleration: 2}}\n"
	"  - {channel: tip.y, device: drives, axis: 7, counts_per_unit: 10000,\n"
	"     limits: {min: -5, max: 5, velocity: 0.5, acceleration: 2}}\n"
	"  - {channel: tip.z, device: drives, axis: 8, counts_per_unit: 10000,\n"
	"     limits: {min: -5, max: 5, velocity: 0.5, acceleration: 2}}\n"
	"triggers:\n"
	"  - {name: camera, device: io, line: 0, pulse_ms: 2}\n";

/* Jog for about ms of wall time (refreshed every 50 ms), then let the
 * dead-man end it; the rig at rest again into *s. */
static void space_jog(struct fixture *f, const char *node, const char *space, const char *axis,
		      double speed, int ms, uint64_t *seq, struct live_snap *s)
{
	char msg[512];
	int t;

	for (t = 0; t < ms; t += 50) {
		ok(live_jog_space(f->lv, 9, node, space, axis, speed, ++*seq, msg, sizeof(msg)),
		   msg);
		nanosleep(&(struct timespec){ .tv_nsec = 50000000 }, NULL);
	}
	rest(f, s);
}

/* The camera's axes in the world, from pan, tilt and roll (degrees): rows
 * of Rz(roll) . Rx(tilt) . Ry(pan) (motion/camera.h). */
static void cam_axes(const struct live_snap *s, double r[3][3])
{
	double p = s->out[3].sp * M_PI / 180, t = s->out[4].sp * M_PI / 180;
	double o = s->out[5].sp * M_PI / 180;
	double a0[3] = { cos(p), 0, -sin(p) }, a1[3] = { sin(t) * sin(p), cos(t), sin(t) * cos(p) };
	int k;

	for (k = 0; k < 3; k++) {
		r[0][k] = cos(o) * a0[k] + sin(o) * a1[k];
		r[1][k] = -sin(o) * a0[k] + cos(o) * a1[k];
	}
	r[2][0] = cos(t) * sin(p);
	r[2][1] = -sin(t);
	r[2][2] = cos(t) * cos(p);
}

static double moved(const struct live_snap *a, const struct live_snap *b, uint32_t i)
{
	return b->out[i].sp - a->out[i].sp;
}

/*
 * Jog the camera and a free node in their own space and the world's
 * (live_space.c): what the motion must keep, it keeps. Bounds: directions
 * within 1e-6 (a cosine), what must not move within 1e-6 units or degrees
 * (the outputs run at rates a finite difference gave, each tick's step
 * rounded to the core's 2^-32).
 */
static void test_space_jog(void **state)
{
	struct fixture f;
	struct live_snap a, b;
	char path[160], msg[512];
	double r0[3][3], r1[3][3], d[3], n = 0, c = 0, tip0, tip1;
	uint64_t seq = 0;
	uint32_t i;
	FILE *fp;

	snprintf(path, sizeof(path), "/tmp/strand-live-space-%d.yaml", (int)getpid());
	fp = fopen(path, "w");
	fputs(space_scene, fp);
	fclose(fp);
	open_scene(&f, path, false, 250);
	unlink(path);
	ok(live_enable(f.lv, msg, sizeof(msg)), msg);
	expect_state(&f, LIVE_ENABLED, &a);
	ok(live_goto(f.lv, 0, msg, sizeof(msg)), msg);
	rest(&f, &a);

	/* dolly: along where the camera looks (its -z), nothing turns */
	space_jog(&f, "camera", "local", "dolly", 0.5, 300, &seq, &b);
	cam_axes(&a, r0);
	for (i = 0; i < 3; i++) {
		d[i] = moved(&a, &b, i);
		n += d[i] * d[i];
		c -= d[i] * r0[2][i];
	}
	c /= sqrt(n);
	printf("BOUND dolly %.4f units: along the view, cos %.12f >= 1 - 1e-6; pan, tilt, roll "
	       "moved %.1e %.1e %.1e deg <= 1e-6\n", sqrt(n), c, moved(&a, &b, 3), moved(&a, &b, 4),
	       moved(&a, &b, 5));
	assert_true(sqrt(n) > 0.05 && c >= 1 - 1e-6);
	for (i = 3; i < 9; i++)
		assert_true(fabs(moved(&a, &b, i)) <= 1e-6);

	/* tilt in the camera's space, rolled 10 degrees: about its own x,
	 * which stays where it points; the eye stays. The channels' rates are
	 * made again every few milliseconds and held between: the axis
	 * wanders by the second-order term, about (w T)^2 / 2 each (w the rate,
	 * 0.26 rad/s here, T 10 ms: live_space_follow): 1e-5 a turn of the
	 * direction; 2e-3 in all, what a braking along its last tangent
	 * adds included */
	a = b;
	space_jog(&f, "camera", "local", "tilt", 0.5, 300, &seq, &b);
	cam_axes(&a, r0);
	cam_axes(&b, r1);
	for (i = 0, n = 0; i < 3; i++)
		n = fmax(n, fabs(r1[0][i] - r0[0][i]));
	printf("BOUND local tilt %.3f deg (tilt channel %.3f, pan %.3f): the camera's x axis "
	       "moved %.1e <= 2e-3, the eye %.1e <= 1e-6\n",
	       acos(fmin(1, r0[2][0] * r1[2][0] + r0[2][1] * r1[2][1] + r0[2][2] * r1[2][2])) *
		       180 / M_PI, moved(&a, &b, 4), moved(&a, &b, 3), n,
	       fmax(fabs(moved(&a, &b, 0)), fmax(fabs(moved(&a, &b, 1)), fabs(moved(&a, &b, 2)))));
	assert_true(fabs(moved(&a, &b, 3)) > 0.01); /* rolled: pan moves too */
	assert_true(n <= 2e-3);
	for (i = 0; i < 3; i++)
		assert_true(fabs(moved(&a, &b, i)) <= 1e-6);

	/* pan about the world's vertical through the eye: pan alone */
	a = b;
	space_jog(&f, "camera", "world", "pan", -0.5, 300, &seq, &b);
	printf("BOUND world pan %.3f deg; tilt, roll moved %.1e %.1e deg <= 1e-6\n",
	       moved(&a, &b, 3), moved(&a, &b, 4), moved(&a, &b, 5));
	assert_true(moved(&a, &b, 3) < -1);
	for (i = 0; i < 9; i++)
		if (i != 3)
			assert_true(fabs(moved(&a, &b, i)) <= 1e-6);

	/* the crane about its own y through its pivot (0, 1, 0): its tip
	 * keeps its height exactly and its distance from the pivot within
	 * 3e-3 units: its outputs go along the tangent of the circle that a
	 * direction made every 10 ms gives, from samples up to 4 ms old, and
	 * brake along the last (s^2 / 2r: 2.4e-4 from 0.25 units/s at 2) */
	a = b;
	space_jog(&f, "crane", "local", "ry", 0.5, 300, &seq, &b);
	tip0 = hypot(a.out[6].sp, a.out[8].sp);
	tip1 = hypot(b.out[6].sp, b.out[8].sp);
	printf("BOUND crane local ry: tip (%.4f %.4f %.4f) -> (%.4f %.4f %.4f), radius %.9f -> "
	       "%.9f (3e-3), height moved %.1e <= 1e-6\n", a.out[6].sp, a.out[7].sp, a.out[8].sp,
	       b.out[6].sp, b.out[7].sp, b.out[8].sp, tip0, tip1, moved(&a, &b, 7));
	assert_true(fabs(moved(&a, &b, 6)) > 0.01);
	assert_true(fabs(tip1 - tip0) <= 3e-3 && fabs(moved(&a, &b, 7)) <= 1e-6);
	for (i = 0; i < 6; i++)
		assert_true(moved(&a, &b, i) == 0);

	/* and along the world's z: the tip alone, along z */
	a = b;
	space_jog(&f, "crane", "world", "z", -0.5, 300, &seq, &b);
	printf("BOUND crane world z: tip moved %.4f along z, %.1e %.1e across <= 1e-6\n",
	       moved(&a, &b, 8), moved(&a, &b, 6), moved(&a, &b, 7));
	assert_true(moved(&a, &b, 8) < -0.05);
	assert_true(fabs(moved(&a, &b, 6)) <= 1e-6 && fabs(moved(&a, &b, 7)) <= 1e-6);

	/* the camera keyed where the rig holds it: at frame 24 the scene's
	 * camera is there (the eye exactly, its angles through look_at within
	 * 1e-5 deg), the file's comments and other keys as they were */
	{
		static const char *const cam[6] = { "camera.x", "camera.y", "camera.z",
						     "camera.pan", "camera.tilt", "camera.roll" };
		const char *camera = "camera";
		char *text;

		ok(live_teach(f.lv, 24, &camera, 1, msg, sizeof(msg)), msg);
		text = slurp(f.path, NULL);
		assert_non_null(strstr(text, "{frame: 24, eye: ["));
		assert_non_null(strstr(text, "{frame: 48, eye: [1, 1.5, 3]"));
		free(text);
		for (i = 0; i < 6; i++) {
			double v = channel_at(f.path, cam[i], 24);

			printf("BOUND taught %s at 24: %.9f, the rig's %.9f (1e-5)\n", cam[i], v,
			       b.out[i].sp);
			assert_true(fabs(v - b.out[i].sp) <= 1e-5);
		}
	}

	/* a jog of the camera whose client goes ends at once, not at the
	 * dead-man's time */
	{
		int64_t lat, t0;

		ok(live_jog_space(f.lv, 9, "camera", "world", "x", 0.3, ++seq, msg, sizeof(msg)),
		   msg);
		nanosleep(&(struct timespec){ .tv_nsec = 100000000 }, NULL);
		live_client_gone(f.lv, 9);
		ok(live_ping(f.lv, 0, &lat, msg, sizeof(msg)), msg);
		live_snapshot(f.lv, &b);
		t0 = b.tick;
		rest(&f, &b);
		/* 0.15 units/s braked at 2 units/s^2: 75 ticks; the dead-man
		 * alone would take 250 more */
		printf("BOUND a client gone: at rest %lld ticks later (< 200)\n",
		       (long long)(b.tick - t0));
		assert_true(b.tick - t0 < 200);
	}

	/* what is not the camera or a free node is refused, by name */
	assert_int_equal(live_jog_space(f.lv, 9, "nothing", "local", "x", 0.5, ++seq, msg,
					sizeof(msg)), -ENOENT);
	ok(live_disable(f.lv, msg, sizeof(msg)), msg);
	close_fixture(&f);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_states_jog_goto_play),
		cmocka_unit_test(test_jog_limit),
		cmocka_unit_test(test_teach),
		cmocka_unit_test(test_space_jog),
		cmocka_unit_test(test_outside_limits),
		cmocka_unit_test(test_restart_sim),
		cmocka_unit_test(test_restart_canopen),
		cmocka_unit_test_teardown(test_restart_modbus, stop_peer),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
