/* SPDX-License-Identifier: MIT */
/*
 * test_play_gomo.c - go-motion (step mode with a shutter, plan/gomo.h) on
 * the virtual clock: for each frame the drives are sent the scene's own
 * setpoints, to the bit, at every tick of the exposure f - s/2 .. f + s/2;
 * the simulated camera exposes while they run, and where the drives stood
 * during each exposure is the scene's motion within the drive model's
 * following error; the run-up and run-out stay within the limits (every
 * command the drives saw, pu_finish); the journal records each exposure's
 * ticks and poses; a trigger that fires early rises during the run-up.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/exitcode.h"
#include "plan/gomo.h"
#include "plan/timeline.h"
#include "play/frames.h"
#include "playutil.h"
#include "sim/sim_camera.h"
#include "sim/sim_drive.h"
#include "testutil.h"

#define TRACE 200000

static int64_t targets[TRACE * 2];
static double actual[TRACE * 2];

/* The journal's 10 significant digits. */
static void near10(double got, double want)
{
	if (fabs(got - want) > 1e-9 * fmax(fabs(want), 1e-3))
		fail_msg("journal %.12g, want %.12g", got, want);
}

struct gomo_run {
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct frame_list fl;
	char journal[256];
};

/* The arm of playutil on a rig whose simulated camera exposes for the
 * shutter's time, go-motion over `spec` with shutter s, trigger offset
 * offset_ms; played to its end. */
static void gomo_play(struct gomo_run *g, const char *spec, mot_q32 s, double offset_ms)
{
	char err[256];
	struct sim_drive *d;

	pu_arm_source(&g->ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&g->r, &g->ps, 1, 0);
	g->r.dev[1].sim.exposure_ms = q2d(s) * 1000.0 / 24;
	g->r.dev[1].sim.readout_ms = 5;
	g->r.trig[0].offset_ms = offset_ms;
	pu_opts(&g->o, &g->ps);
	assert_int_equal(frames_parse(&g->fl, spec, err, sizeof(err)), 0);
	g->o.loop.mode = LOOP_MODE_STEP;
	g->o.loop.frames = &g->fl;
	g->o.loop.shutter = s;
	/* the scene's own motion over its span (strand play's range) */
	g->o.loop.from = 0;
	g->o.loop.to = 240;
	pu_tmpname(g->journal, sizeof(g->journal), "gomo");
	g->o.journal_path = g->journal;
	pu_alloc_hook_install();
	if (play_prepare(&g->p, &g->r.d, &g->ps.s, &g->o, err, sizeof(err)))
		fail_msg("play_prepare: %s", err);
	d = sim_drive_of(g->p.rig.axes[g->p.rig.out[0].dev]);
	sim_drive_trace(d, targets, TRACE);
	sim_drive_trace_actual(d, actual);
	assert_int_equal(pu_finish(&g->p, true), STRAND_EXIT_OK);
}

static void gomo_free(struct gomo_run *g)
{
	play_free(&g->p);
	frames_free(&g->fl);
	unlink(g->journal);
}

/* Every exposure: the scene's setpoints exactly, the drives' positions
 * within their following error, the journal's ticks and poses. */
static void check_exposures(struct gomo_run *g, const int64_t *want, uint32_t nwant, mot_q32 s,
			    int64_t lead)
{
	const struct mot_timing *t = &g->ps.s.timing;
	struct sim_camera *cam = rig_sim_camera(&g->p.rig, 0);
	const struct sim_drive_channel *m = NULL;
	double worst_rel = 0, worst[2] = { 0, 0 };
	static const bool extend[2] = { true, true };
	mot_q32 tl_mem[TIMELINE_WORDS(2)], x[2];
	struct timeline tl;
	struct pu_csv c;
	int cf, ct, co, cc, cs[2], cso[2], csc[2];
	uint32_t i, k, sat = 0;

	(void)m;
	/* the scene's motion as the run takes it: its own within the span,
	 * going on at the speed of its ends beyond (plan/timeline.h) */
	timeline_init(&tl, &g->ps.s, 2, extend, 0, 240, tl_mem, &sat);
	assert_int_equal(sim_camera_count(cam), nwant);
	assert_int_equal(sim_camera_missed(cam), 0);
	assert_int_equal(pu_csv_read(&c, g->journal), 0);
	assert_int_equal(c.nrows - 1, nwant);
	cf = pu_csv_col(&c, "frame");
	ct = pu_csv_col(&c, "tick");
	co = pu_csv_col(&c, "open_tick");
	cc = pu_csv_col(&c, "close_tick");
	cs[0] = pu_csv_col(&c, "a.angle");
	cs[1] = pu_csv_col(&c, "b.position");
	cso[0] = pu_csv_col(&c, "a.angle@open");
	cso[1] = pu_csv_col(&c, "b.position@open");
	csc[0] = pu_csv_col(&c, "a.angle@close");
	csc[1] = pu_csv_col(&c, "b.position@close");
	for (i = 0; i < nwant; i++) {
		const struct sim_exposure *e = sim_camera_exposure(cam, i);
		int64_t f = atoll(c.cell[i + 1][cf]), edge = atoll(c.cell[i + 1][ct]);
		int64_t open = atoll(c.cell[i + 1][co]), close = atoll(c.cell[i + 1][cc]);
		int64_t ka, kb, j, exp_ticks;

		assert_int_equal(f, want[i]);
		if (getenv("GOMO_DEBUG")) {
			for (k = 0; k < c.ncols; k++)
				printf("%s=%s ", c.cell[0][k], c.cell[i + 1][k]);
			printf("\n");
		}
		assert_int_equal(gomo_window(t, f, s, &ka, &kb), 0);
		/* the exposure is the window's ticks, the edge moved by its offset */
		assert_int_equal(close - open, kb - ka);
		assert_int_equal(edge, open - lead);
		assert_int_equal(e->tick, edge);
		for (k = 0; k < 2; k++) {
			const struct rig_out *ro = &g->p.rig.out[k];
			double file = k ? 1 : 360;

			timeline_eval(&tl, ka, x, &sat);
			near10(atof(c.cell[i + 1][cso[k]]), q2d(x[k]) * file);
			timeline_eval(&tl, kb, x, &sat);
			near10(atof(c.cell[i + 1][csc[k]]), q2d(x[k]) * file);
			(void)cs;
			/* what the drive was sent over the exposure: the scene */
			for (j = open; j <= close; j++) {
				int64_t exact;

				timeline_eval(&tl, ka + j - open, x, &sat);
				exact = hal_scale_counts(&ro->scale, x[k], NULL);

				if (targets[j * 2 + k] != exact)
					fail_msg("frame %lld tick %lld: %s sent %lld, the scene %lld",
						 (long long)f, (long long)j, ro->channel,
						 (long long)targets[j * 2 + k], (long long)exact);
			}
			/* where it stood while the camera exposed: the scene's
			 * motion, within the following error of the drive model
			 * (2 zeta (1 - kff) v / w at the speed v there, sim_drive.h)
			 * plus a tick of that motion, since a position is read
			 * before its tick's setpoint is sent */
			exp_ticks = (int64_t)ceil(q2d(s) * 1000.0 / 24);
			for (j = e->tick; j <= e->tick + exp_ticks && j + 1 <= close; j++) {
				double sp = (double)targets[j * 2 + k];
				double v = (double)(targets[(j + 1) * 2 + k] - targets[j * 2 + k]) * 1000;
				double w = 2 * M_PI * SIM_DRIVE_DEFAULT_BANDWIDTH_HZ;
				double bound = 2 * SIM_DRIVE_DEFAULT_DAMPING *
						       (1 - SIM_DRIVE_DEFAULT_FEEDFORWARD) * fabs(v) / w +
					       fabs(v) / 1000 + 1;
				double err = fabs(actual[(j + 1) * 2 + k] - sp);

				if (err > bound)
					fail_msg("frame %lld tick %lld: %s %.3f counts from the scene, "
						 "bound %.3f", (long long)f, (long long)j, ro->channel,
						 err, bound);
				if (err > worst[k])
					worst[k] = err;
				if (bound > 0 && err / bound > worst_rel)
					worst_rel = err / bound;
			}
		}
	}
	assert_int_equal(sat, 0);
	printf("BOUND go-motion exposure: worst %.3f counts a.angle, %.3f counts b.position; "
	       "%.2f of the following-error bound\n", worst[0], worst[1], worst_rel);
	pu_csv_free(&c);
}

/* 180 degrees at 24 fps, forwards, a jump and backwards, and the span's
 * ends (beyond which the exposure goes on at their speed, timeline.h):
 * each frame's exposure half a frame long, centred on it. */
static void test_gomo_exposures(void **state)
{
	static const int64_t want[] = { 20, 21, 22, 23, 24, 25, 100, 180, 179, 178, 0, 240 };
	struct gomo_run g;

	memset(&g, 0, sizeof(g));
	gomo_play(&g, "20..25,100,180..178,0,240", MOT_Q32_ONE / 2, 0);
	check_exposures(&g, want, sizeof(want) / sizeof(want[0]), MOT_Q32_ONE / 2, 0);
	gomo_free(&g);
}

/* A trigger 8 ms early (shutter lag) rises in the run-up, 8 ticks before
 * the exposure's first; a full 360 degree shutter exposes a whole frame. */
static void test_gomo_early_trigger(void **state)
{
	static const int64_t want[] = { 60, 61, 62 };
	struct gomo_run g;

	memset(&g, 0, sizeof(g));
	gomo_play(&g, "60..62", MOT_Q32_ONE, -8);
	check_exposures(&g, want, 3, MOT_Q32_ONE, 8);
	gomo_free(&g);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_gomo_exposures),
		cmocka_unit_test(test_gomo_early_trigger),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
