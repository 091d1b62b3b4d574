/* SPDX-License-Identifier: MIT */
/*
 * test_chase.c - strand play --chase on the virtual clock (play/chase.h,
 * play/loop_chase.c): LTC made by libltc's encoder behind the simulated
 * capture device (sim/sim_ltc.h) and a frame pulse on a simulated input,
 * each fired frame's due time held against the instant the source began
 * that frame (the simulation's log):
 *
 *   - the card's clock 0, +-100, +-1000 ppm off, the source's 1000 ppm
 *     fast, stamps up to 1 ms late: lock within 5 frames of the first mark,
 *     every trigger within 1 ms of its source frame's start, the source's
 *     rate within 10 ppm after 10 s;
 *   - a dropout shorter than --freewheel: no stop, the triggers still
 *     within 1 ms; a longer one: a controlled stop after the freewheel
 *     time, a new cue when the source is back, the run finished;
 *   - a jump, reverse play, a held frame: a controlled stop and a new cue;
 *   - a signal 40 dB down; drop-frame labels across minute boundaries at
 *     30000/1001 (the journal's source_tc the label the source sent);
 *   - genlock: pulses with 1 ms of jitter and some missing.
 *
 * Every run is also held to what pu_finish checks of every run: no
 * allocation in the loop, every command the drives saw within its
 * output's speed and acceleration limits (so no axis jumped), no trigger
 * the camera missed.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "playutil.h"
#include "testutil.h"
#include "play/chase.h"
#include "scene/timecode.h"
#include "sim/sim_gpio.h"
#include "sim/sim_ltc.h"

#define LOG_CAP 8192

static struct sim_ltc_frame g_log[LOG_CAP];
static size_t g_nlog;

struct outcome {
	int code;
	struct chase_stats st;
	int64_t recues;
	struct tu_worst phase;   /* due - the source frame's start, us */
	struct tu_worst stretch; /* frame interval against the source's, relative */
	int64_t fired, matched;
	int64_t unplayed;        /* fired while the source played no such frame then */
	int64_t first_frame, last_frame;
	double lock_frames;      /* the lock, in frames after the first mark */
};

/* The source frame a label names, in the source's rules. */
static int64_t label_frame(const struct timecode *tc, const struct sim_ltc_frame *f)
{
	return timecode_frame(tc, f->hh, f->mm, f->ss, f->ff);
}

/* Play the arm (frames 0..last at num/den, 1 kHz) chasing spec. */
static void run(struct outcome *oc, const char *spec, struct sim_ltc_cfg *sc,
		struct hal_din *din, uint32_t num, uint32_t den, int64_t last,
		const char *tc_offset, double freewheel_ms, const int64_t *truth_ns,
		size_t ntruth)
{
	static struct pu_source ps;
	static struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct pu_csv csv;
	struct timecode tc;
	char path[256];
	int64_t off = 0, prev_due = -1, prev_t = -1;
	uint32_t i;
	int cf, cd, cs;

	memset(oc, 0, sizeof(*oc));
	oc->first_frame = -1;
	g_nlog = 0;
	if (sc) {
		sc->log = g_log;
		sc->log_cap = LOG_CAP;
		sc->log_n = &g_nlog;
	}
	pu_arm_source(&ps, num, den, 1000, 0, last);
	pu_rig_init(&r, &ps, 1, 0);
	pu_opts(&o, &ps);
	pu_tmpname(path, sizeof(path), "chase");
	o.journal_path = path;
	o.chase.spec = spec;
	o.chase.sim = sc;
	o.chase.sim_din = din;
	o.chase.tc_offset = tc_offset;
	o.chase.freewheel_ms = freewheel_ms;
	oc->code = pu_run(&p, &r, &ps, &o);
	oc->st = p.chase.st;
	oc->recues = p.chase.recues;
	if (oc->st.lock_ns >= 0)
		oc->lock_frames = (double)(oc->st.lock_ns - oc->st.first_mark_ns) / p.chase.frame_ns;
	timecode_init(&tc, num / p.chase.cfg.mult, den);
	off = p.chase.cfg.offset;
	play_free(&p);
	assert_int_equal(pu_csv_read(&csv, path), 0);
	cf = pu_csv_col(&csv, "frame");
	cd = pu_csv_col(&csv, "due_ns");
	cs = pu_csv_col(&csv, "source_tc");
	for (i = 1; i < csv.nrows; i++) {
		int64_t f = atoll(csv.cell[i][cf]), due = atoll(csv.cell[i][cd]), t = -1;
		int64_t want = off + f; /* the source frame the scene's frame is */
		double quant;
		size_t j;

		oc->fired++;
		if (oc->first_frame < 0)
			oc->first_frame = f;
		oc->last_frame = f;
		if (truth_ns) { /* pulses: the pulse that is this frame */
			if (want >= 0 && (size_t)want < ntruth)
				t = truth_ns[want];
		} else {
			char lbl[24];

			/* the label nearest in time (reverse play repeats labels) */
			for (j = 0; j < g_nlog && j < LOG_CAP; j++)
				if (!g_log[j].reverse &&
				    label_frame(&tc, &g_log[j]) == want % timecode_day(&tc) &&
				    (t < 0 || llabs(g_log[j].t_ns - due) < llabs(t - due)))
					t = g_log[j].t_ns;
			/* the journal names the label the source sent then */
			timecode_format(&tc, want, lbl, sizeof(lbl));
			assert_string_equal(csv.cell[i][cs], lbl);
		}
		if (t < 0 || llabs(due - t) > 20000000) {
			/* between a reverse or a stop of the source and the mark
			 * that shows it (LTC is decoded a frame late), the
			 * schedule freewheels on frames the source never played */
			oc->unplayed++;
			continue;
		}
		/* the scene's trigger tick is on the frame's start or up to a
		 * tick after it (FORMULAS.md 5): that much is the scene's */
		quant = ceil((double)f * den * 1000 / num - 1e-9) - (double)f * den * 1000 / num;
		tu_worst_add(&oc->phase, ((double)(due - t) - quant * 1e6) / 1000.0, (double)f);
		oc->matched++;
		if (prev_due >= 0 && prev_t >= 0 && t > prev_t)
			tu_worst_add(&oc->stretch, (double)(due - prev_due) / (double)(t - prev_t) - 1,
				     (double)f);
		prev_due = due;
		prev_t = t;
	}
	pu_csv_free(&csv);
	remove(path);
}

static struct sim_ltc_cfg ltc25(double cap_ppm, double src_ppm)
{
	struct sim_ltc_cfg c;

	memset(&c, 0, sizeof(c));
	c.rate = 48000;
	c.period = 480;
	c.fps_num = 25;
	c.fps_den = 1;
	c.ss = 1; /* 00:00:01:00: the scene's frame 25 */
	c.begin_s = 0.1;
	c.end_s = 12;
	c.cap_ppm = cap_ppm;
	c.src_ppm = src_ppm;
	c.jitter_ns = 1000000;
	c.seed = 5;
	return c;
}

static void test_clock_errors(void **state)
{
	static const double cap[] = { 0, 100, -100, 1000, -1000, 0 };
	static const double src[] = { 0, 0, 0, 0, 0, 1000 };
	char name[64];
	unsigned i;

	(void)state;
	for (i = 0; i < sizeof(cap) / sizeof(cap[0]); i++) {
		struct sim_ltc_cfg c = ltc25(cap[i], src[i]);
		struct tu_worst lock = { 0 }, rate = { 0 };
		struct outcome oc;

		run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
		assert_int_equal(oc.code, 0);
		assert_true(oc.matched > 150 && oc.matched == oc.fired && !oc.unplayed);
		assert_int_equal(oc.last_frame, 240);
		snprintf(name, sizeof(name), "chase_trigger_card%+.0f_src%+.0fppm", cap[i], src[i]);
		tu_bound(name, &oc.phase, 1000, "us");
		tu_worst_add(&lock, oc.lock_frames, 0);
		snprintf(name, sizeof(name), "chase_lock_card%+.0f_src%+.0fppm", cap[i], src[i]);
		tu_bound(name, &lock, 5, "frames");
		tu_worst_add(&rate, (oc.st.rate - (1 + src[i] * 1e-6)) * 1e6, 0);
		snprintf(name, sizeof(name), "chase_rate_card%+.0f_src%+.0fppm", cap[i], src[i]);
		tu_bound(name, &rate, 10, "ppm");
		/* the motion stretched by the source's rate and the schedule's
		 * slew at most */
		tu_bound("chase_frame_interval_vs_source", &oc.stretch,
			 src[i] * 1e-6 + CHASE_SLEW + 1e-3, "relative");
	}
}

static void test_dropouts(void **state)
{
	struct sim_ltc_event ev[1] = { { .at_s = 3.0, .ev = SIM_LTC_SILENCE, .until_s = 3.3 } };
	struct sim_ltc_cfg c = ltc25(100, 0);
	struct tu_worst fw = { 0 };
	struct outcome oc;

	(void)state;
	/* 300 ms of silence, freewheel 500: played through */
	c.events = ev;
	c.nevents = 1;
	run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.recues, 0);
	assert_int_equal(oc.st.events[CHASE_EV_LOST], 0);
	tu_bound("chase_trigger_after_300ms_dropout", &oc.phase, 1000, "us");
	/* 1.5 s of silence, freewheel 500: a stop after 500 ms without a
	 * mark, a new cue once it is back, the scene played to its end */
	ev[0].until_s = 4.5;
	run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.st.events[CHASE_EV_LOST], 1);
	assert_int_equal(oc.recues, 1);
	assert_int_equal(oc.last_frame, 240);
	tu_worst_add(&fw, (double)oc.st.freewheel_max_ns / 1e6 - 500, 0);
	/* the stop comes in the first tick past the freewheel time */
	tu_bound("chase_freewheel_stop_after_ms", &fw, 1.5, "ms beyond 500");
	tu_bound("chase_trigger_after_recue", &oc.phase, 1000, "us");
}

static void test_jump_reverse_hold(void **state)
{
	static const struct sim_ltc_event jump[] = {
		{ .at_s = 3.0, .ev = SIM_LTC_JUMP, .ss = 6, .ff = 0 } };
	static const struct sim_ltc_event rev[] = {
		{ .at_s = 3.0, .ev = SIM_LTC_REVERSE }, { .at_s = 3.5, .ev = SIM_LTC_FORWARD } };
	static const struct sim_ltc_event hold[] = {
		{ .at_s = 3.0, .ev = SIM_LTC_HOLD, .until_s = 3.6 } };
	struct sim_ltc_cfg c = ltc25(0, 0);
	struct outcome oc;

	(void)state;
	c.events = jump;
	c.nevents = 1;
	run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.st.events[CHASE_EV_JUMP], 1);
	assert_int_equal(oc.recues, 1);
	assert_true(oc.unplayed <= 2);
	tu_bound("chase_trigger_after_jump", &oc.phase, 1000, "us");
	c.events = rev;
	c.nevents = 2;
	run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_true(oc.st.events[CHASE_EV_REVERSE] >= 1);
	assert_true(oc.recues >= 1);
	assert_true(oc.unplayed <= 2);
	tu_bound("chase_trigger_after_reverse", &oc.phase, 1000, "us");
	c.events = hold;
	c.nevents = 1;
	run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_true(oc.st.events[CHASE_EV_STOPPED] >= 1);
	assert_true(oc.recues >= 1);
	assert_true(oc.unplayed <= 2);
	tu_bound("chase_trigger_after_hold", &oc.phase, 1000, "us");
}

static void test_quiet(void **state)
{
	struct sim_ltc_cfg c = ltc25(-100, 0);
	struct outcome oc;

	(void)state;
	c.volume_db = -40;
	run(&oc, "ltc:sim", &c, NULL, 25, 1, 240, NULL, 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_true(oc.st.level_dbfs < -39 && oc.st.level_dbfs > -42);
	tu_bound("chase_trigger_quiet_-40dBFS", &oc.phase, 1000, "us");
}

/* 30000/1001, drop-frame: from 00:00:58;00 over the minute boundary (no
 * labels ;00 and ;01 at 00:01:00) and the scene's frame 0 at 00:00:57;00. */
static void test_drop_frame(void **state)
{
	struct sim_ltc_cfg c = ltc25(200, 0);
	struct outcome oc;

	(void)state;
	c.fps_num = 30000;
	c.fps_den = 1001;
	c.ss = 58;
	c.end_s = 8;
	run(&oc, "ltc:sim", &c, NULL, 30000, 1001, 200, "00:00:57;00", 500, NULL, 0);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.last_frame, 200);
	/* frame 200 is 00:01:03;22: past the boundary, two labels dropped */
	assert_true(oc.matched > 100 && oc.matched == oc.fired);
	tu_bound("chase_trigger_drop_frame_29.97", &oc.phase, 1000, "us");
}

/* Label -> frame -> label over the first 20 minutes at every rule. */
static void test_timecode_frames(void **state)
{
	static const uint32_t rates[][2] = { { 24, 1 }, { 25, 1 }, { 30000, 1001 },
					     { 60000, 1001 }, { 30, 1 } };
	unsigned r;

	(void)state;
	for (r = 0; r < 5; r++) {
		struct timecode tc;
		int64_t f, g;
		char s[24];

		timecode_init(&tc, rates[r][0], rates[r][1]);
		for (f = 0; f < 20 * 60 * 60; f++) {
			timecode_format(&tc, f, s, sizeof(s));
			assert_int_equal(timecode_parse(&tc, s, &g), 0);
			assert_int_equal(g, f);
		}
		if (tc.drop) {
			assert_int_equal(timecode_parse(&tc, "00:01:00;00", &g), -EINVAL);
			assert_int_equal(timecode_parse(&tc, "00:10:00;00", &g), 0);
		}
		assert_int_equal(timecode_day(&tc), (int64_t)tc.nominal * 86400 -
						     (int64_t)tc.drop * 1296);
	}
}

/* A frame pulse (a camera's sync out) on a simulated input: 25 pulses a
 * second from 0.2 s, +-0.5 ms of jitter, pulses 100-102 missing (freewheel),
 * then none from pulse 200 on (a stop after the freewheel time). */
static void test_genlock(void **state)
{
	static int64_t truth[400];
	struct sim_gpio *g;
	struct hal_clock clk;
	struct tu_rng rng;
	struct outcome oc;
	char err[128];
	int i;

	(void)state;
	hal_clock_init(&clk, true);
	tu_seed(&rng, 3);
	assert_int_equal(sim_gpio_new(&g, "sync", 0, 1, &clk, 1024, err, sizeof(err)), 0);
	for (i = 0; i < 400; i++) {
		/* the true pulse, and its edge as the generator's jitter puts it */
		truth[i] = 200000000 + (int64_t)i * 40000000;
		if ((i >= 100 && i <= 102) || i >= 300)
			continue;
		int64_t at = truth[i] + (int64_t)tu_uniform(&rng, -5e5, 5e5);

		assert_int_equal(sim_gpio_schedule(g, 0, at, true), 0);
		assert_int_equal(sim_gpio_schedule(g, 0, at + 2000000, false), 0);
	}
	/* truth is by pulse count from the first: offset chosen at the cue */
	run(&oc, "gpio:sim", NULL, sim_gpio_din(g), 25, 1, 240, NULL, 500, truth, 400);
	sim_gpio_free(g);
	assert_int_equal(oc.code, 0);
	assert_int_equal(oc.last_frame, 240);
	tu_bound("genlock_trigger_vs_pulse", &oc.phase, 1000, "us");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_timecode_frames),
		cmocka_unit_test(test_clock_errors),
		cmocka_unit_test(test_dropouts),
		cmocka_unit_test(test_jump_reverse_hold),
		cmocka_unit_test(test_quiet),
		cmocka_unit_test(test_drop_frame),
		cmocka_unit_test(test_genlock),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
