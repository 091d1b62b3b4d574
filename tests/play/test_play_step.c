/* SPDX-License-Identifier: MIT */
/*
 * test_play_step.c - step mode (shoot-move-shoot) on the virtual clock:
 * every frame of a range, a list and a reshoot lands at its exact pose,
 * the drives are in position when the shutter fires, and a camera-ready
 * input paces the shots.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/exitcode.h"
#include "play/frames.h"
#include "playutil.h"
#include "sim/sim_camera.h"
#include "sim/sim_drive.h"
#include "testutil.h"

#define SHOTS_MAX 64

struct shot {
	int64_t target[2]; /* counts the drives were told */
	double actual[2];  /* where they were */
};

static struct shot shots[SHOTS_MAX];
static uint32_t nshots;

/* At each exposure, in the loop thread: where the drives stand. */
static void on_exposure(void *ctx, const struct sim_exposure *e)
{
	struct play *p = ctx;
	uint32_t i;

	if (nshots >= SHOTS_MAX)
		return;
	for (i = 0; i < 2; i++) {
		const struct rig_out *o = &p->rig.out[i];
		const struct sim_drive_watch *w = sim_drive_watch(sim_drive_of(p->rig.axes[o->dev]), o->ch);

		shots[nshots].target[i] = w->target;
		shots[nshots].actual[i] = w->x;
	}
	nshots++;
}

static void prepare(struct play *p, struct pu_rig *r, struct pu_source *ps,
		    struct play_opts *o, struct frame_list *fl, const char *spec, unsigned inputs)
{
	char err[256];

	pu_arm_source(ps, 24, 1, 1000, 0, 240);
	pu_rig_init(r, ps, 1, inputs);
	pu_opts(o, ps);
	assert_int_equal(frames_parse(fl, spec, err, sizeof(err)), 0);
	o->loop.mode = LOOP_MODE_STEP;
	o->loop.frames = fl;
	pu_alloc_hook_install();
	if (play_prepare(p, &r->d, &ps->s, o, err, sizeof(err)))
		fail_msg("play_prepare: %s", err);
	nshots = 0;
	sim_camera_on_exposure(rig_sim_camera(&p->rig, 0), on_exposure, p);
}

/* Every shot at the frame's exact pose (the counts of the source's value
 * at the integer frame), the drives within their in-position tolerance,
 * and the journal saying the same, in the order asked for. */
static void test_step_lands_exactly(void **state)
{
	static const int64_t want[] = { 0,  1,  2,  3,  4,  5,  6,  7,  8,  9,	10, 11,
					12, 13, 14, 15, 16, 17, 18, 19, 20, 55, 55, 55,
					130, 129, 128, 127, 126, 125 };
	const uint32_t n = sizeof(want) / sizeof(want[0]);
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct frame_list fl;
	struct pu_csv c;
	char path[256];
	int cf, cs;
	uint32_t i, k;

	prepare(&p, &r, &ps, &o, &fl, "0..20,55x3,130..125", 0);
	assert_int_equal(pu_finish(&p, true), STRAND_EXIT_OK);
	assert_int_equal(nshots, n);
	for (i = 0; i < n; i++)
		for (k = 0; k < 2; k++) {
			const struct rig_out *ro = &p.rig.out[k];
			int64_t exact = hal_scale_counts(&ro->scale,
							 pu_value(&ps, k, want[i] * MOT_Q32_ONE), NULL);

			assert_int_equal(shots[i].target[k], exact);
			if (fabs(shots[i].actual[k] - (double)exact) >
			    ro->in_position * fabs(ro->scale.per_unit_d))
				fail_msg("frame %lld: %s %g counts from its pose", (long long)want[i],
					 ro->channel, shots[i].actual[k] - (double)exact);
		}
	play_free(&p);
	frames_free(&fl);

	/* the same with a journal: frames in order, setpoints at the poses */
	pu_arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 1, 0);
	pu_opts(&o, &ps);
	assert_int_equal(frames_parse(&fl, "0..20,55x3,130..125", path, sizeof(path)), 0);
	pu_tmpname(path, sizeof(path), "step");
	o.loop.mode = LOOP_MODE_STEP;
	o.loop.frames = &fl;
	o.journal_path = path;
	assert_int_equal(pu_run(&p, &r, &ps, &o), STRAND_EXIT_OK);
	assert_int_equal(pu_csv_read(&c, path), 0);
	assert_int_equal(c.nrows - 1, n);
	cf = pu_csv_col(&c, "frame");
	cs = pu_csv_col(&c, "a.angle");
	for (i = 0; i < n; i++) {
		assert_int_equal(atoll(c.cell[i + 1][cf]), want[i]);
		assert_true(fabs(atof(c.cell[i + 1][cs]) -
				 q2d(pu_value(&ps, 0, want[i] * MOT_Q32_ONE)) * 360) < 1e-7);
	}
	pu_csv_free(&c);
	play_free(&p);
	frames_free(&fl);
	unlink(path);
}

/* A reshoot without a camera-ready input and no settle time fires faster
 * than the simulated camera can take pictures (it misses some); with the
 * camera-ready input wired, no shot is missed. */
static void test_step_camera_ready(void **state)
{
	int wired;

	for (wired = 0; wired < 2; wired++) {
		struct pu_source ps;
		struct pu_rig r;
		struct play_opts o;
		struct play p;
		struct frame_list fl;
		char err[256];
		uint64_t i;

		pu_arm_source(&ps, 24, 1, 1000, 0, 240);
		pu_rig_init(&r, &ps, 1, wired ? PU_READY : 0);
		pu_opts(&o, &ps);
		assert_int_equal(frames_parse(&fl, "100x10", err, sizeof(err)), 0);
		o.loop.mode = LOOP_MODE_STEP;
		o.loop.frames = &fl;
		o.loop.settle_ticks = 0;
		o.loop.exposure_ticks = 2;
		pu_alloc_hook_install();
		assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), 0);
		assert_int_equal(pu_finish(&p, false), STRAND_EXIT_OK);
		assert_int_equal(loop_result(p.L)->frames_fired, 10);
		if (!wired) {
			assert_true(sim_camera_missed(rig_sim_camera(&p.rig, 0)) > 0);
		} else {
			assert_int_equal(sim_camera_missed(rig_sim_camera(&p.rig, 0)), 0);
			assert_int_equal(sim_camera_count(rig_sim_camera(&p.rig, 0)), 10);
			/* paced by the camera: exposure plus readout apart */
			for (i = 1; i < 10; i++)
				assert_true(sim_camera_exposure(rig_sim_camera(&p.rig, 0), i)->tick -
						    sim_camera_exposure(rig_sim_camera(&p.rig, 0), i - 1)->tick >=
					    (int64_t)(0.5 * 1000 / 24));
		}
		play_free(&p);
		frames_free(&fl);
	}
}

/* Frame lists as the command line gives them. */
static void test_frames_parse(void **state)
{
	struct frame_list fl;
	struct frame_iter it = { 0 };
	char err[256];
	int64_t f, got[16], n = 0;
	static const int64_t want[] = { 3, 7, 6, 5, 9, 9, 1, 1, 2, 2 };

	assert_int_equal(frames_parse(&fl, "3,7..5,9x2,1..2x2", err, sizeof(err)), 0);
	assert_int_equal(frames_count(&fl), 10);
	while (frames_next(&fl, &it, &f))
		got[n++] = f;
	assert_int_equal(n, 10);
	assert_memory_equal(got, want, sizeof(want));
	frames_free(&fl);
	assert_int_equal(frames_parse(&fl, "3,,4", err, sizeof(err)), -EINVAL);
	assert_non_null(strstr(err, "column 3"));
	assert_int_equal(frames_parse(&fl, "5x0", err, sizeof(err)), -EINVAL);
	assert_int_equal(frames_parse(&fl, "-1", err, sizeof(err)), -EINVAL);
	assert_int_equal(frames_parse(&fl, "1..", err, sizeof(err)), -EINVAL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_frames_parse),
		cmocka_unit_test(test_step_lands_exactly),
		cmocka_unit_test(test_step_camera_ready),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
