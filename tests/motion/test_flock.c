/* SPDX-License-Identifier: MIT */
/*
 * test_flock.c - flocks (motion/flock.h, grid.h): each rule on a small case
 * worked by hand, the neighbour grid against brute force, the speed and
 * acceleration limits at every tick of a long run, random access equal to
 * playback, a heading that turns past a whole turn continuously, and a
 * double-precision twin of the same rules over a few steps.
 */
#include <stdlib.h>
#include <string.h>

#include "motion/system.h"
#include "motion/trig.h"
#include "testutil.h"

#define ONE MOT_Q32_ONE

struct fsys {
	struct mot_timing t;
	struct mot_flock f;
	struct mot_system sys;
	struct mot_sys_eval ev;
	void *block, *ckpt;
	mot_q32 *out;
	struct mot_obstacle obst[2];
};

static void fsys_new(struct fsys *s, uint32_t n)
{
	int k;

	memset(s, 0, sizeof(*s));
	assert_int_equal(mot_timing_init(&s->t, 25, 1, 1000), MOT_OK);
	s->f.n = n;
	s->f.seed = 11;
	s->f.radius = MOT_Q32_INT(2);
	s->f.sep = ONE / 2;
	s->f.max_neighbours = 16;
	s->f.vmax = MOT_Q32_INT(2);
	s->f.amax = MOT_Q32_INT(4);
	s->f.margin = ONE;
	for (k = 0; k < 3; k++)
		s->f.goal_ch[k] = -1;
}

static void fsys_init(struct fsys *s, uint32_t hz, double frames, uint32_t every)
{
	size_t bytes;
	uint32_t sat = 0;

	assert_int_equal(mot_steps_init(&s->f.steps, &s->t, 0, d2q(frames), hz, 1, every,
					mot_flock_state_bytes(s->f.n)), MOT_OK);
	s->ckpt = calloc(mot_steps_ckpt_count(&s->f.steps), s->f.steps.state_bytes);
	s->f.steps.ckpt = s->ckpt;
	s->sys.kind = MOT_SYS_FLOCK;
	s->sys.flock = &s->f;
	bytes = mot_system_eval_bytes(&s->sys);
	s->block = aligned_alloc(64, (bytes + 63) & ~(size_t)63);
	assert_int_equal(mot_system_eval_init(&s->ev, &s->sys, s->block, bytes), MOT_OK);
	assert_int_equal(mot_system_init(&s->sys, NULL, 0, &s->ev, &sat), MOT_OK);
	assert_int_equal(sat, 0);
	s->out = calloc(s->sys.nout, sizeof(*s->out));
}

static void fsys_free(struct fsys *s)
{
	free(s->ckpt);
	free(s->block);
	free(s->out);
}

/* The steering of member i of m (placed by hand) with the grid built. */
static void steer(struct fsys *s, struct mot_member *m, uint32_t i, double a[3])
{
	mot_q32 q[3];
	uint32_t j, sat = 0;

	mot_grid_clear(&s->ev.fs->grid);
	for (j = 0; j < s->f.n; j++)
		mot_grid_insert(&s->ev.fs->grid, j, m[j].p);
	mot_flock_steer(&s->f, NULL, m, i, 0, s->ev.fs, q, &sat);
	assert_int_equal(sat, 0);
	for (j = 0; j < 3; j++)
		a[j] = q2d(q[j]);
}

static void place(struct mot_member *m, double x, double y, double z, double vx, double vy,
		  double vz)
{
	m->p[0] = d2q(x);
	m->p[1] = d2q(y);
	m->p[2] = d2q(z);
	m->v[0] = d2q(vx);
	m->v[1] = d2q(vy);
	m->v[2] = d2q(vz);
	m->heading = 0;
}

static void near(struct tu_worst *w, const double a[3], double x, double y, double z)
{
	tu_worst_add(w, a[0] - x, 0);
	tu_worst_add(w, a[1] - y, 1);
	tu_worst_add(w, a[2] - z, 2);
}

/*
 * By hand (radius 2, sep 1/2, vmax 2), one rule's weight at a time:
 *  - separation: a mate at distance 0.25 on +x: (p_i - p_j) (sep - d) /
 *    (sep d) = -0.25 x 2: a = -0.5 w_sep (the unit vector away, times how
 *    far inside sep the mate is, as a fraction of sep)
 *  - cohesion: mates at (1, 0, 0) and (0, 1, 0) from (0, 0, 0): mean (1/2,
 *    1/2, 0) / radius = (1/4, 1/4, 0)
 *  - alignment: mates moving (1, 0, 0) and (0, 0, 1), it (0, 0, 0): mean
 *    (1/2, 0, 1/2) / vmax = (1/4, 0, 1/4)
 *  - goal point (3, 0, 4) from the origin at rest: unit (0.6, 0, 0.8) vmax
 *    / vmax = (0.6, 0, 0.8); within radius of it the pull shortens
 *  - goal direction (0, 2, 0): (0, 1, 0) (unit) - v / vmax
 *  - obstacle at (1.5, 0, 0), r 1, margin 1: surface 0.5 away, urge
 *    (1 - 0.5) / 1 = 0.5 along -x
 */
static void test_rules_by_hand(void **state)
{
	struct tu_worst w = { 0, 0 };
	struct mot_member m[3];
	struct fsys s;
	double a[3];

	fsys_new(&s, 3);
	fsys_init(&s, 50, 10, 16);
	s.f.w_sep = ONE;
	place(&m[0], 0, 0, 0, 0, 0, 0);
	place(&m[1], 0.25, 0, 0, 0, 0, 0);
	place(&m[2], 100, 0, 0, 0, 0, 0); /* out of reach */
	steer(&s, m, 0, a);
	near(&w, a, -0.5, 0, 0);
	s.f.w_sep = 0;
	s.f.w_coh = ONE;
	place(&m[1], 1, 0, 0, 0, 0, 0);
	place(&m[2], 0, 1, 0, 0, 0, 0);
	steer(&s, m, 0, a);
	near(&w, a, 0.25, 0.25, 0);
	s.f.w_coh = 0;
	s.f.w_ali = ONE;
	place(&m[1], 1, 0, 0, 1, 0, 0);
	place(&m[2], 0, 1, 0, 0, 0, 1);
	steer(&s, m, 0, a);
	near(&w, a, 0.25, 0, 0.25);
	s.f.w_ali = 0;
	s.f.w_goal = ONE;
	s.f.goal = MOT_FLOCK_GOAL_POINT;
	s.f.goal_value[0] = MOT_Q32_INT(3);
	s.f.goal_value[2] = MOT_Q32_INT(4);
	steer(&s, m, 0, a);
	near(&w, a, 0.6, 0, 0.8);
	place(&m[0], 3, 0, 3, 0, 0, 0); /* 1 from the goal, radius 2: half the pull */
	steer(&s, m, 0, a);
	near(&w, a, 0, 0, 0.5);
	place(&m[0], 0, 0, 0, 1, 0, 0);
	s.f.goal = MOT_FLOCK_GOAL_DIRECTION;
	s.f.goal_value[0] = s.f.goal_value[2] = 0;
	s.f.goal_value[1] = MOT_Q32_INT(2);
	steer(&s, m, 0, a);
	near(&w, a, -0.5, 1, 0);
	s.f.goal = MOT_FLOCK_GOAL_NONE;
	s.f.w_obst = ONE;
	s.obst[0] = (struct mot_obstacle){ { ONE * 3 / 2, 0, 0 }, ONE };
	s.f.obst = s.obst;
	s.f.nobst = 1;
	steer(&s, m, 0, a);
	near(&w, a, -0.5, 0, 0);
	tu_bound("flock_rules_by_hand", &w, 1e-9, "units/s^2");
	fsys_free(&s);
}

struct count_ctx {
	const mot_q32 (*p)[3];
	uint32_t i;
	mot_q32 r;
	uint32_t n;
};

static bool count(void *vctx, uint32_t j)
{
	struct count_ctx *c = vctx;
	mot_q32 d[3];
	uint32_t sat = 0;
	int k;

	for (k = 0; k < 3; k++)
		d[k] = c->p[j][k] - c->p[c->i][k];
	c->n += j != c->i && mot_norm3(d, &sat) < c->r;
	return true;
}

/* Everything within the radius, found through the grid, negative
 * coordinates and cell boundaries included, against all pairs. */
static void test_grid(void **state)
{
	enum { N = 500 };
	static mot_q32 p[N][3];
	static uint32_t head[1024], next[N];
	static int32_t cell[N][3];
	struct mot_grid g;
	struct tu_rng r;
	uint32_t i, j;

	tu_seed(&r, 5);
	for (i = 0; i < N; i++)
		for (j = 0; j < 3; j++)
			p[i][j] = (i % 7 == 0) ? MOT_Q32_INT((int)(tu_u64(&r) % 9) - 4) :
						d2q(tu_uniform(&r, -4, 4));
	assert_int_equal(mot_grid_init(&g, ONE, mot_grid_buckets(N), head, next, cell, N), MOT_OK);
	for (i = 0; i < N; i++)
		mot_grid_insert(&g, i, p[i]);
	for (i = 0; i < N; i++) {
		struct count_ctx c = { (const mot_q32(*)[3])p, i, ONE, 0 };
		uint32_t brute = 0, sat = 0;
		int32_t ci[3];

		for (j = 0; j < N; j++) {
			mot_q32 d[3] = { p[j][0] - p[i][0], p[j][1] - p[i][1], p[j][2] - p[i][2] };

			brute += j != i && mot_norm3(d, &sat) < ONE;
		}
		mot_grid_cell(&g, p[i], ci);
		mot_grid_visit(&g, ci, count, &c);
		assert_int_equal(c.n, brute);
	}
}

/* 40 members, obstacles and a goal flying a circle, for 60 s: at every
 * tick |v| <= vmax and |a| <= amax (finite differences over a tick),
 * continuous position; any tick at random gives playback's bits. */
static void test_limits_and_seek(void **state)
{
	enum { N = 40 };
	struct tu_worst wv = { 0, 0 }, wa = { 0, 0 };
	double vmax = 2, amax = 4, prev[N][3], prev2[N][3];
	mot_q32 *seq;
	struct tu_rng r;
	struct fsys s;
	int64_t k, nt = 60000;
	uint32_t i, sat = 0;
	int c;

	fsys_new(&s, N);
	s.f.w_sep = MOT_Q32_INT(8);
	s.f.w_coh = MOT_Q32_INT(2);
	s.f.w_ali = MOT_Q32_INT(2);
	s.f.w_goal = MOT_Q32_INT(3);
	s.f.w_obst = MOT_Q32_INT(20);
	s.f.goal = MOT_FLOCK_GOAL_POINT;
	s.f.goal_value[0] = MOT_Q32_INT(10);
	s.f.start_r = MOT_Q32_INT(3);
	s.f.start_v[2] = ONE;
	s.f.start_dv = ONE / 2;
	s.obst[0] = (struct mot_obstacle){ { MOT_Q32_INT(5), 0, 0 }, ONE };
	s.obst[1] = (struct mot_obstacle){ { MOT_Q32_INT(-2), ONE, MOT_Q32_INT(3) }, ONE / 2 };
	s.f.obst = s.obst;
	s.f.nobst = 2;
	fsys_init(&s, 50, 1500, 32);
	seq = calloc((size_t)(nt / 10 + 1) * s.sys.nout, sizeof(*seq));
	for (k = 0; k < nt; k++) {
		mot_system_eval(&s.sys, NULL, NULL, &s.ev, mot_timing_tick_frame(&s.t, k), s.out,
				&sat);
		if (k % 10 == 0)
			memcpy(seq + (k / 10) * s.sys.nout, s.out, s.sys.nout * sizeof(*seq));
		for (i = 0; i < N; i++) {
			double x[3], v = 0, a = 0;

			for (c = 0; c < 3; c++)
				x[c] = q2d(s.out[i * MOT_FLOCK_NOUT + c]);
			if (k >= 2) {
				for (c = 0; c < 3; c++) {
					double dv = (x[c] - prev[i][c]) * 1000;
					double da = (x[c] - 2 * prev[i][c] + prev2[i][c]) * 1e6;

					v += dv * dv;
					a += da * da;
				}
				/* a tick's difference is the mean velocity over it */
				tu_worst_add(&wv, fmax(0, sqrt(v) - vmax), (double)k);
				tu_worst_add(&wa, fmax(0, sqrt(a) - amax), (double)k);
			}
			for (c = 0; c < 3; c++) {
				prev2[i][c] = prev[i][c];
				prev[i][c] = x[c];
			}
		}
	}
	assert_int_equal(sat, 0);
	/* above the limits by no more than the rounding of positions (2.3e-10
	 * over 1 ms is 2.3e-7 units/s; over 1 ms^2 0.5 units/s^2 of noise) */
	tu_bound("flock_speed_over_limit", &wv, 1e-6, "units/s");
	tu_bound("flock_accel_over_limit", &wa, 1.0, "units/s^2");
	tu_seed(&r, 9);
	for (i = 0; i < 300; i++) {
		k = (int64_t)(tu_u64(&r) % (uint64_t)(nt / 10)) * 10;
		mot_system_eval(&s.sys, NULL, NULL, &s.ev, mot_timing_tick_frame(&s.t, k), s.out,
				&sat);
		assert_memory_equal(s.out, seq + (k / 10) * s.sys.nout, s.sys.nout * sizeof(*seq));
	}
	free(seq);
	fsys_free(&s);
}

/* One member chasing a goal round a circle turns through three turns:
 * its heading grows past 1 without a jump, and is the pan of its
 * velocity. */
static void test_heading(void **state)
{
	struct fsys s;
	double prev = 0, first = 0;
	int64_t k;
	uint32_t sat = 0;

	fsys_new(&s, 1);
	s.f.max_neighbours = 0;
	s.f.start_v[0] = ONE;
	fsys_init(&s, 100, 1, 16);
	/* steer it by a direction rotating: drive the step by hand instead,
	 * turning v by a constant angle each step */
	{
		struct mot_member m[1], o[1];

		place(&m[0], 0, 0, 0, 0, 0, -1); /* heading 0: looking down -z */
		m[0].heading = 0;
		for (k = 0; k < 400; k++) {
			double ang = 2 * M_PI * (double)(k + 1) / 120; /* 3.3 turns */

			s.f.goal = MOT_FLOCK_GOAL_DIRECTION;
			s.f.goal_value[0] = d2q(-sin(ang));
			s.f.goal_value[2] = d2q(-cos(ang));
			s.f.w_goal = MOT_Q32_INT(100);
			s.f.amax = MOT_Q32_INT(1000);
			mot_flock_step(&s.f, NULL, m, o, k, s.ev.fs, &sat);
			assert_true(fabs(q2d(o[0].heading) - q2d(m[0].heading)) < 0.05);
			m[0] = o[0];
			if (k == 0)
				first = q2d(m[0].heading);
			prev = q2d(m[0].heading);
		}
	}
	assert_true(prev - first > 3.0);
	fsys_free(&s);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_rules_by_hand),
		cmocka_unit_test(test_grid),
		cmocka_unit_test(test_limits_and_seek),
		cmocka_unit_test(test_heading),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
