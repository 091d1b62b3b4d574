/* SPDX-License-Identifier: MIT */
/*
 * test_play.c - whole runs of the loop on the virtual clock: trigger ticks
 * exactly as FORMULAS.md section 5 says, the journal equal to what the
 * simulated camera saw, every commanded move within the limits, loops and
 * ping-pong, offsets and pulse widths, bit-reproducible runs, and not one
 * allocation by the loop thread.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/exitcode.h"
#include "playutil.h"
#include "sim/sim_camera.h"
#include "sim/sim_drive.h"
#include "sim/sim_gpio.h"
#include "testutil.h"

/* Every frame from..to fired once, at FORMULAS section 5's tick after the
 * pre-roll (the first frame fired at tick0; -1: take it from the camera).
 * Returns tick0. */
static int64_t check_frames(const struct play *p, const struct sim_camera *cam, int64_t from,
			    int64_t to, int64_t tick0)
{
	const struct mot_timing *t = p->tm;
	int64_t f, t_from = mot_timing_trigger_tick(t, from);

	assert_int_equal(sim_camera_count(cam), to - from + 1);
	if (tick0 < 0)
		tick0 = sim_camera_exposure(cam, 0)->tick;
	for (f = from; f <= to; f++) {
		const struct sim_exposure *e = sim_camera_exposure(cam, (uint64_t)(f - from));
		int64_t want = tick0 + mot_timing_trigger_tick(t, f) - t_from;

		if (e->tick != want)
			fail_msg("frame %lld: exposed at tick %lld, want %lld", (long long)f,
				 (long long)e->tick, (long long)want);
		/* virtual time: the edge's time is its tick's, exactly */
		assert_int_equal(e->ts_ns, loop_due(p->L, e->tick));
	}
	return tick0;
}

static void test_whole_run(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;

	pu_arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 1, PU_ESTOP);
	pu_opts(&o, &ps);
	assert_int_equal(pu_run(&p, &r, &ps, &o), STRAND_EXIT_OK);
	assert_int_equal(loop_result(p.L)->rep.cause, LOOP_CAUSE_FINISHED);
	/* the rig stood at the first pose, where b is just starting to move:
	 * a one-tick move to the start of b's one-tick run-up, a tick at rest
	 * there, then frame 0 */
	assert_int_equal(check_frames(&p, rig_sim_camera(&p.rig, 0), 0, 240, -1), 2);
	assert_int_equal(loop_result(p.L)->frames_fired, 241);
	/* the drive followed: worst following error seen, and within bound */
	assert_true(loop_result(p.L)->ferr_worst > 0);
	play_free(&p);
}

/* Values each in range that together would overflow: refused before the
 * rig moves, with a message naming what to change (issue 12). */
static void test_edges(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	char err[256];

	/* total frames: passes times frames times triggers beyond int64_t */
	pu_arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 2, 0);
	pu_opts(&o, &ps);
	o.loop.loop = true;
	o.loop.passes = INT64_MAX / 100;
	assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), -EINVAL);
	printf("%s\n", err);
	assert_non_null(strstr(err, "more frames than a run counts"));
	assert_int_equal(p.failed_at, PLAY_STAGE_OPTIONS);
	play_free(&p);
	o.loop.loop = false;
	o.loop.ping_pong = true;
	o.loop.passes = INT64_MAX / 100;
	assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "more frames than a run counts"));
	play_free(&p);

	/* a pre-roll of 1e11 degrees at the least velocity limit: 3e20 ticks */
	pu_arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 1, 0);
	pu_opts(&o, &ps);
	r.out[0].home = 1e11;
	r.out[0].limits.has_vel = true;
	r.out[0].limits.vel = RIG_LIMIT_RATE_MIN;
	assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), -ERANGE);
	printf("%s\n", err);
	assert_non_null(strstr(err, "the pre-roll to frame 0 would take more than 2^53 ticks"));
	play_free(&p);
	/* below the least: refused as the loader refuses it */
	r.out[0].home = 0;
	r.out[0].limits.vel = 1e-300;
	assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), -ERANGE);
	printf("%s\n", err);
	assert_string_equal(err, "outputs[0] (a.angle): velocity limit 1e-300 is below 1e-06 a "
			    "second (too slow to plan a move with)");
	play_free(&p);
	/* a simulated camera's exposure beyond a day */
	pu_rig_init(&r, &ps, 1, 0);
	r.dev[1].sim.exposure_ms = 1e300;
	assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), -ERANGE);
	printf("%s\n", err);
	assert_non_null(strstr(err, "devices[1] (io): sim: exposure_ms 1e+300 is above"));
	play_free(&p);
}

/* A rig standing elsewhere: the pre-roll brings it to the first pose within
 * the limits, then the frames follow at their exact ticks. */
static void test_preroll(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	int64_t t0;

	pu_arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 1, 0);
	r.out[0].home = -45; /* degrees away from the first pose */
	r.out[1].home = 0.3;
	pu_opts(&o, &ps);
	assert_int_equal(pu_run(&p, &r, &ps, &o), STRAND_EXIT_OK);
	t0 = sim_camera_exposure(rig_sim_camera(&p.rig, 0), 0)->tick;
	printf("pre-roll %lld ticks\n", (long long)t0);
	assert_true(t0 > 0);
	/* 45 deg at 60 deg/s and 120 deg/s^2 takes at least 1.25 s from the
	 * last tick at rest (tick -1, where the rig stood) */
	assert_true(t0 + 1 >= 1250);
	check_frames(&p, rig_sim_camera(&p.rig, 0), 0, 240, t0);
	play_free(&p);
}

/* Trigger ticks exactly per section 5 at rates that do and do not divide
 * the tick rate, over a span that starts after frame 0. */
static void test_rates(void **state)
{
	static const uint32_t rates[][3] = {
		{ 24, 1, 1000 }, { 25, 1, 1000 }, { 30000, 1001, 1000 }, { 60, 1, 1000 },
		{ 24000, 1001, 997 }, { 30, 1, 250 }, { 60000, 1001, 240 },
	};
	size_t i;

	for (i = 0; i < sizeof(rates) / sizeof(rates[0]); i++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;

		pu_arm_source(&ps, rates[i][0], rates[i][1], rates[i][2], 17, 230);
		pu_rig_init(&r, &ps, 1, 0);
		r.trig[0].pulse_ms = 1000.0 / rates[i][2]; /* one tick */
		pu_opts(&o, &ps);
		assert_int_equal(pu_run(&p, &r, &ps, &o), STRAND_EXIT_OK);
		/* frame 17 is in the middle of a's move: a run-up first */
		assert_true(check_frames(&p, rig_sim_camera(&p.rig, 0), 17, 230, -1) > 2);
		play_free(&p);
	}
}

/* A day at 1 kHz and 30000/1001 fps: frames 0..2589410 begin within 24 h;
 * the last fires at tick ceil(2589410 * 1001 * 1000 / 30000) = 86399981.
 * Every trigger tick is checked. Triggers only, so the run measures the
 * loop itself. */
static void test_24h(void **state)
{
	const int64_t last = 2589410;
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	char err[256];
	uint64_t n;
	int64_t f;
	const struct loop_result *res;

	pu_source_init(&ps, "day", 30000, 1001, 1000, 0, last);
	pu_rig_init(&r, &ps, 1, 0);
	pu_opts(&o, &ps);
	o.rig.camera_cap = (uint64_t)last + 1;
	pu_alloc_hook_install();
	assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), 0);
	assert_int_equal(pu_play(&p), STRAND_EXIT_OK);
	res = loop_result(p.L);
	n = sim_camera_count(rig_sim_camera(&p.rig, 0));
	assert_int_equal(n, (uint64_t)last + 1);
	assert_int_equal(sim_camera_exposure(rig_sim_camera(&p.rig, 0), n - 1)->tick, 86399981);
	for (f = 0; f <= last; f++)
		if (sim_camera_exposure(rig_sim_camera(&p.rig, 0), (uint64_t)f)->tick !=
		    mot_timing_trigger_tick(p.tm, f))
			fail_msg("frame %lld at the wrong tick", (long long)f);
	printf("24 h: %lld ticks in %.2f s wall, %.1f ns cpu per tick\n",
	       (long long)res->ticks_run, p.wall_ns / 1e9, (double)res->cpu_ns / res->ticks_run);
	play_free(&p);
}


/* The journal holds exactly what the camera saw: one fired row per
 * exposure, same frame order, same tick and time, and every output's
 * setpoint equal to the source at that tick's frame time. */
static void test_journal_matches_camera(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct pu_csv c;
	char path[256];
	int cf, ct, cs, cm, ca, cb, cd, ctc;
	uint32_t i;

	pu_arm_source(&ps, 30000, 1001, 1000, 0, 240);
	pu_rig_init(&r, &ps, 1, PU_ESTOP);
	pu_opts(&o, &ps);
	pu_tmpname(path, sizeof(path), "journal");
	o.journal_path = path;
	assert_int_equal(pu_run(&p, &r, &ps, &o), STRAND_EXIT_OK);
	assert_int_equal(pu_csv_read(&c, path), 0);
	cf = pu_csv_col(&c, "frame");
	ct = pu_csv_col(&c, "tick");
	cs = pu_csv_col(&c, "state");
	cm = pu_csv_col(&c, "mono_ns");
	cd = pu_csv_col(&c, "due_ns");
	ca = pu_csv_col(&c, "a.angle");
	cb = pu_csv_col(&c, "b.position");
	ctc = pu_csv_col(&c, "timecode");
	assert_string_equal(c.cell[0][0], "frame");
	assert_int_equal(c.nrows - 1, sim_camera_count(rig_sim_camera(&p.rig, 0)));
	for (i = 1; i < c.nrows; i++) {
		const struct sim_exposure *e = sim_camera_exposure(rig_sim_camera(&p.rig, 0), i - 1);
		int64_t tick = atoll(c.cell[i][ct]);
		mot_q32 fr = mot_timing_tick_frame(p.tm, tick - e->tick +
						   mot_timing_trigger_tick(p.tm, i - 1));

		assert_int_equal(atoll(c.cell[i][cf]), i - 1);
		assert_string_equal(c.cell[i][cs], "fired");
		assert_int_equal(tick, e->tick);
		assert_int_equal(atoll(c.cell[i][cm]), e->ts_ns);
		assert_int_equal(atoll(c.cell[i][cd]), e->ts_ns);
		/* the scene tick of this frame's edge is its trigger tick */
		assert_true(fabs(atof(c.cell[i][ca]) - q2d(pu_value(&ps, 0, fr)) * 360) < 1e-7);
		assert_true(fabs(atof(c.cell[i][cb]) - q2d(pu_value(&ps, 1, fr))) < 1e-9);
	}
	/* drop-frame timecode at 29.97: frame 30 is 00:00:01;00 */
	assert_string_equal(c.cell[31][ctc], "00:00:01;00");
	pu_csv_free(&c);
	play_free(&p);
	unlink(path);
}

static int slurp(const char *path, char **buf, size_t *len)
{
	FILE *f = fopen(path, "rb");

	if (!f)
		return -1;
	fseek(f, 0, SEEK_END);
	*len = (size_t)ftell(f);
	rewind(f);
	*buf = malloc(*len ? *len : 1);
	if (fread(*buf, 1, *len, f) != *len) {
		fclose(f);
		return -1;
	}
	fclose(f);
	return 0;
}

/* The virtual clock is bit-reproducible: two runs, identical journals. */
static void test_reproducible(void **state)
{
	char path[2][256], *buf[2];
	size_t len[2];
	int k;

	for (k = 0; k < 2; k++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;

		pu_arm_source(&ps, 24, 1, 1000, 0, 240);
		pu_rig_init(&r, &ps, 1, 0);
		r.out[0].home = 10;
		pu_opts(&o, &ps);
		pu_tmpname(path[k], sizeof(path[k]), "repro");
		o.journal_path = path[k];
		assert_int_equal(pu_run(&p, &r, &ps, &o), STRAND_EXIT_OK);
		play_free(&p);
		assert_int_equal(slurp(path[k], &buf[k], &len[k]), 0);
		unlink(path[k]);
	}
	assert_int_equal(len[0], len[1]);
	assert_true(len[0] > 241 * sizeof(struct journal_rec));
	assert_memory_equal(buf[0], buf[1], len[0]);
	free(buf[0]);
	free(buf[1]);
}

/* --loop and --ping-pong: the frames each pass fires, in order, with the
 * ticks between them as section 5 says in either direction; bridges
 * within the limits between passes (pu_run checks the drive's commands).
 * The range ends in the middle of a's move, so every pass ends moving. */
static void test_loop_and_ping_pong(void **state)
{
	int mode;

	for (mode = 0; mode < 2; mode++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;
		struct pu_csv c;
		char path[256];
		int64_t want[3 * 41], n = 0, f, pass_end[3];
		int cf, ct;
		uint32_t i;

		pu_arm_source(&ps, 24, 1, 1000, 20, 60);
		pu_rig_init(&r, &ps, 1, 0);
		pu_opts(&o, &ps);
		o.loop.loop = mode == 0;
		o.loop.ping_pong = mode == 1;
		o.loop.passes = 3;
		pu_tmpname(path, sizeof(path), "passes");
		o.journal_path = path;
		assert_int_equal(pu_run(&p, &r, &ps, &o), STRAND_EXIT_OK);
		if (mode == 0) {
			for (i = 0; i < 3; i++) {
				for (f = 20; f <= 60; f++)
					want[n++] = f;
				pass_end[i] = n;
			}
		} else {
			for (f = 20; f <= 60; f++)
				want[n++] = f;
			pass_end[0] = n;
			for (f = 59; f >= 20; f--)
				want[n++] = f;
			pass_end[1] = n;
			for (f = 21; f <= 60; f++)
				want[n++] = f;
			pass_end[2] = n;
		}
		assert_int_equal(sim_camera_count(rig_sim_camera(&p.rig, 0)), n);
		assert_int_equal(pu_csv_read(&c, path), 0);
		assert_int_equal(c.nrows - 1, n);
		cf = pu_csv_col(&c, "frame");
		ct = pu_csv_col(&c, "tick");
		for (i = 0; i < (uint32_t)n; i++) {
			int64_t tick = atoll(c.cell[i + 1][ct]);

			assert_int_equal(atoll(c.cell[i + 1][cf]), want[i]);
			assert_int_equal(tick, sim_camera_exposure(rig_sim_camera(&p.rig, 0), i)->tick);
			/* within a pass, the gap is the difference of trigger ticks */
			if (i > 0 && i != pass_end[0] && i != pass_end[1]) {
				int64_t gap = llabs(mot_timing_trigger_tick(p.tm, want[i]) -
						    mot_timing_trigger_tick(p.tm, want[i - 1]));

				assert_int_equal(tick - atoll(c.cell[i][ct]), gap);
			} else if (i > 0) {
				/* a bridge: the rig stops and comes back */
				assert_true(tick - atoll(c.cell[i][ct]) > 100);
			}
		}
		pu_csv_free(&c);
		play_free(&p);
		unlink(path);
	}
}

/* A negative offset fires before the frame's tick, by exactly the offset;
 * the pulse lasts its width; both from the loop's own schedule. */
static void test_offset_and_width(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct sim_gpio_edge edges[1024];
	int64_t tick0;
	uint64_t i, n;

	pu_arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 2, 0);
	r.trig[0].offset_ms = -8;
	r.trig[0].pulse_ms = 3;
	r.trig[1].offset_ms = 5;
	r.trig[1].pulse_ms = 1;
	pu_opts(&o, &ps);
	{
		char err[256];

		pu_alloc_hook_install();
		assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), 0);
	}
	sim_gpio_record(rig_sim_gpio(&p.rig, "io"), edges, 1024);
	assert_int_equal(pu_play(&p), STRAND_EXIT_OK);
	n = sim_gpio_edges(rig_sim_gpio(&p.rig, "io"));
	assert_int_equal(n, 4 * 241);
	/* the camera on line 1 fires 13 ticks after the one on line 0 */
	tick0 = sim_camera_exposure(rig_sim_camera(&p.rig, 0), 0)->tick + 8;
	for (i = 0; i < 241; i++) {
		int64_t t = tick0 + mot_timing_trigger_tick(p.tm, (int64_t)i);

		assert_int_equal(sim_camera_exposure(rig_sim_camera(&p.rig, 0), i)->tick, t - 8);
		assert_int_equal(sim_camera_exposure(rig_sim_camera(&p.rig, 1), i)->tick, t + 5);
	}
	for (i = 0; i < n; i++) {
		uint64_t k;

		if (!edges[i].asserted)
			continue;
		/* the matching falling edge of the same line */
		for (k = i + 1; k < n && edges[k].line != edges[i].line; k++)
			;
		assert_true(k < n);
		assert_false(edges[k].asserted);
		assert_int_equal(edges[k].tick - edges[i].tick, edges[i].line == 0 ? 3 : 1);
	}
	play_free(&p);
}

/* In the loop thread, at frame 50's edge: the machine stalls for 100.5 ms,
 * two and a half frames at 24 fps. */
static void stall_at_50(void *ctx, const struct sim_exposure *e)
{
	struct play *p = ctx;

	if (loop_result(p->L)->last_frame == 50)
		p->clk.vnow += 100500000;
}

/* A stall: the loop wakes late, runs the 100 missed ticks back to back
 * (counted as catch-up, not as wake-ups), and still fires every frame once,
 * in order, at its own tick; frames 51 and 52 go out late in time and the
 * journal says by how much; frame 53 is on time again. */
static void test_stall_catch_up(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct pu_csv c;
	static struct sim_gpio_edge edges[1024];
	char err[256], path[256];
	int64_t t0, f, k50;
	int cl, ct;
	const struct lat_stats *lat;

	pu_arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 1, 0);
	pu_opts(&o, &ps);
	pu_tmpname(path, sizeof(path), "stall");
	o.journal_path = path;
	pu_alloc_hook_install();
	assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), 0);
	sim_camera_on_exposure(rig_sim_camera(&p.rig, 0), stall_at_50, &p);
	sim_gpio_record(rig_sim_gpio(&p.rig, "io"), edges, 1024);
	assert_int_equal(pu_finish(&p, false), STRAND_EXIT_OK);
	lat = &loop_result(p.L)->lat;
	/* 51 and 52 went out back to back: the camera, busy with 51 for half
	 * a frame, could not take 52 (a real camera would not either) */
	assert_int_equal(sim_camera_missed(rig_sim_camera(&p.rig, 0)), 1);
	assert_int_equal(sim_camera_count(rig_sim_camera(&p.rig, 0)), 240);
	/* every trigger went out once, at its own tick */
	assert_int_equal(sim_gpio_edges(rig_sim_gpio(&p.rig, "io")), 2 * 241);
	t0 = edges[0].tick;
	for (f = 0; f <= 240; f++) {
		assert_true(edges[2 * f].asserted);
		assert_int_equal(edges[2 * f].tick, t0 + mot_timing_trigger_tick(p.tm, f));
	}
	k50 = t0 + mot_timing_trigger_tick(p.tm, 50);
	/* the stalled tick and the 99 catch-up ticks after it that still
	 * ended after their successor was due; the 100th was back on time */
	assert_int_equal(lat->overruns, 100);
	assert_int_equal(lat->catchup, 100);
	assert_int_equal(lat->late_max_ns, 100500000 - 1000000);
	/* one wake-up sample per sleep: the catch-up ticks have none */
	assert_int_equal(lat->n + lat->catchup, loop_result(p.L)->ticks_run);
	assert_int_equal(pu_csv_read(&c, path), 0);
	cl = pu_csv_col(&c, "late_us");
	ct = pu_csv_col(&c, "tick");
	for (f = 51; f <= 52; f++) {
		int64_t k = atoll(c.cell[f + 1][ct]);

		assert_true(fabs(atof(c.cell[f + 1][cl]) -
				 (100500.0 - 1000.0 * (double)(k - k50))) < 1e-6);
	}
	/* frame 50's edge: the stall struck while it went out, and the clock
	 * read right after it says so */
	assert_true(atof(c.cell[50 + 1][cl]) == 100500.0);
	assert_true(atof(c.cell[49 + 1][cl]) == 0);
	assert_true(atof(c.cell[53 + 1][cl]) == 0);
	pu_csv_free(&c);
	play_free(&p);
	unlink(path);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_whole_run),
		cmocka_unit_test(test_edges),
		cmocka_unit_test(test_preroll),
		cmocka_unit_test(test_rates),
		cmocka_unit_test(test_24h),
		cmocka_unit_test(test_journal_matches_camera),
		cmocka_unit_test(test_reproducible),
		cmocka_unit_test(test_loop_and_ping_pong),
		cmocka_unit_test(test_offset_and_width),
		cmocka_unit_test(test_stall_catch_up),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
