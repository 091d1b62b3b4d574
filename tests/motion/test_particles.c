/* SPDX-License-Identifier: MIT */
/*
 * test_particles.c - particle systems (motion/particles.h, steps.h, rng.h):
 * a projectile's exact parabola (Newtonian and scripted), an undamped
 * spring against the exact solution of velocity Verlet and its energy, the
 * emission N = M + rV counted against a reference with the same draws, the
 * pool bound found at the right step, random access equal to playback
 * (checkpoints), a bounce, a colour fading with age, and the stability
 * bound refusing a stiff system.
 */
#include <stdlib.h>
#include <string.h>

#include "motion/rng.h"
#include "motion/system.h"
#include "testutil.h"

#define ONE MOT_Q32_ONE

struct psys {
	struct mot_timing t;
	struct mot_particles ps;
	struct mot_system sys;
	struct mot_sys_eval ev;
	void *block, *ckpt;
	mot_q32 *out;
	struct mot_curve curves[8];
	struct mot_key keys[8][4];
	struct mot_curve_seg seg[8][4];
	uint32_t ncurves;
};

/* A constant-valued system at 25 fps, 1 kHz ticks, stepping at hz. */
static void psys_new(struct psys *s, uint32_t motion, uint32_t npool, bool emit, uint32_t hz)
{
	int k;

	memset(s, 0, sizeof(*s));
	assert_int_equal(mot_timing_init(&s->t, 25, 1, 1000), MOT_OK);
	s->ps.motion = motion;
	s->ps.npool = npool;
	s->ps.emit = emit;
	for (k = 0; k < MOT_PC_COUNT; k++)
		s->ps.curve[k] = -1;
	for (k = MOT_PC_AGE_R; k <= MOT_PC_AGE_SIZE; k++)
		s->ps.value[k] = ONE;
	s->ps.value[MOT_PC_LIFE_LO] = s->ps.value[MOT_PC_LIFE_HI] = MOT_Q32_INT(100);
	s->ps.seed = 7;
	(void)hz;
}

/* A curve of n (frame, value) keys. */
static int32_t psys_curve(struct psys *s, enum mot_interp kind, const double (*kv)[2], int n)
{
	uint32_t c = s->ncurves++, sat = 0;
	int i;

	for (i = 0; i < n; i++)
		s->keys[c][i] = (struct mot_key){ d2q(kv[i][0]), d2q(kv[i][1]), 0, 0 };
	assert_int_equal(mot_curve_init(&s->curves[c], kind, s->keys[c], (uint32_t)n, NULL,
					s->seg[c], 4, &sat), MOT_OK);
	return (int32_t)c;
}

static int psys_init(struct psys *s, uint32_t hz, double frames, uint32_t every)
{
	size_t bytes;
	uint32_t sat = 0;
	int err;

	assert_int_equal(mot_steps_init(&s->ps.steps, &s->t, 0, d2q(frames), hz, 1, every,
					mot_particles_state_bytes(s->ps.npool)), MOT_OK);
	s->ckpt = calloc(mot_steps_ckpt_count(&s->ps.steps), s->ps.steps.state_bytes);
	s->ps.steps.ckpt = s->ckpt;
	s->sys.kind = MOT_SYS_PARTICLES;
	s->sys.particles = &s->ps;
	bytes = mot_system_eval_bytes(&s->sys);
	s->block = aligned_alloc(64, (bytes + 63) & ~(size_t)63);
	assert_int_equal(mot_system_eval_init(&s->ev, &s->sys, s->block, bytes), MOT_OK);
	err = mot_system_init(&s->sys, s->curves, s->ncurves, &s->ev, &sat);
	s->out = calloc(s->sys.nout ? s->sys.nout : 1, sizeof(*s->out));
	assert_int_equal(sat, 0);
	return err;
}

static void psys_free(struct psys *s)
{
	free(s->ckpt);
	free(s->block);
	free(s->out);
}

static void psys_eval(struct psys *s, int64_t tick)
{
	uint32_t sat = 0;

	mot_system_eval(&s->sys, s->curves, NULL, &s->ev, mot_timing_tick_frame(&s->t, tick),
			s->out, &sat);
	assert_int_equal(sat, 0);
}

/* One particle released at step 1 (the rate keyed to one a step, then
 * none), flying for 10 s: x = p0 + v0 a + g a^2 / 2 at every tick. */
static void projectile(uint32_t motion, const char *name, double bound)
{
	static const double rate[2][2] = { { 0, 50 }, { 0.6, 0 } };
	const double v0[3] = { 3, 10, -2 }, p0[3] = { 0, 1, 0.5 }, g[3] = { 0.25, -9.81, 0 };
	struct tu_worst w = { 0, 0 };
	struct psys s;
	int64_t k;
	int c;

	psys_new(&s, motion, 1, true, 50);
	s.ps.curve[MOT_PC_RATE] = psys_curve(&s, MOT_INTERP_STEP, rate, 2);
	for (c = 0; c < 3; c++) {
		s.ps.value[MOT_PC_POS_LO + c] = s.ps.value[MOT_PC_POS_HI + c] = d2q(p0[c]);
		s.ps.value[MOT_PC_VEL_LO + c] = s.ps.value[MOT_PC_VEL_HI + c] = d2q(v0[c]);
		s.ps.gravity[c] = d2q(g[c]);
	}
	assert_int_equal(psys_init(&s, 50, 250, 16), MOT_OK);
	assert_int_equal(s.ps.dropped, 0);
	for (k = 20; k <= 10000; k++) {
		/* born at step 1: 1/50 s */
		double a = q2d(mot_timing_tick_frame(&s.t, k)) / 25.0 - 0.02;

		psys_eval(&s, k);
		for (c = 0; c < 3; c++) {
			double ref = q2d(d2q(p0[c])) + q2d(d2q(v0[c])) * a +
				     0.5 * q2d(d2q(g[c])) * a * a;

			tu_worst_add(&w, q2d(s.out[c]) - ref, (double)k);
		}
		assert_true(s.out[MOT_PART_ALPHA] == 0); /* alpha keyed 0 (lo = hi = 0) */
	}
	tu_bound(name, &w, bound, "units");
	psys_free(&s);
}

static void test_projectile(void **state)
{
	/* Verlet is exact on a parabola but for rounding, and the rounding
	 * of g h/2 is the same every step: a velocity error growing with the
	 * steps, a position error with their square (0.86 um after 500) */
	projectile(MOT_PARTICLES_NEWTON, "particles_projectile_newton", 1.5e-6);
	/* the script is the closed form itself: the age's rounding (1 LSB of
	 * seconds) times the speed (100 units/s at 10 s) */
	projectile(MOT_PARTICLES_SCRIPTED, "particles_projectile_scripted", 3e-8);
}

/*
 * One spring, one end pinned: x'' = -k (x - L) from x = 3/4, at rest. Velocity
 * Verlet's positions at the steps are exactly L + A cos(w~ n h) with
 * cos(w~ h) = 1 - (w h)^2 / 2 (Stormer's recurrence), so the fixed-point
 * run is compared with that, and its energy with the start's: it
 * oscillates by O((w h)^2) and does not drift.
 */
static void test_spring(void **state)
{
	const double k = 400, L = 0.5, A = 0.25, h = 1.0 / 1000;
	static const mot_q32 rest[2][3] = { { 0, 0, 0 }, { 3 * ONE / 4, 0, 0 } };
	struct mot_spring sp = { 0, 1, ONE / 2 };
	struct mot_pin pin = { 0, { -1, -1, -1 } };
	struct tu_worst w = { 0, 0 }, we = { 0, 0 };
	double wt = acos(1 - k * h * h / 2) / h, e0 = 0.5 * k * A * A, emax_first = 0, emax_last = 0;
	struct psys s;
	int64_t n;

	psys_new(&s, MOT_PARTICLES_NEWTON, 2, false, 1000);
	s.ps.rest = rest;
	s.ps.springs = &sp;
	s.ps.nsprings = 1;
	s.ps.pins = &pin;
	s.ps.npins = 1;
	s.ps.spring_k = MOT_Q32_INT(400);
	assert_int_equal(psys_init(&s, 1000, 500, 64), MOT_OK); /* 20 s */
	for (n = 0; n <= 20000; n++) {
		/* step n is tick n (1 kHz both) */
		double x, v, e;

		psys_eval(&s, n);
		x = q2d(s.out[3]);
		tu_worst_add(&w, x - (L + A * cos(wt * (double)n * h)), (double)n);
		assert_int_equal(s.out[0], 0); /* the pinned end */
		/* energy from the state's velocity */
		{
			const struct mot_particle *p = (const struct mot_particle *)(const void *)(
				(const char *)s.ev.cache.a + sizeof(struct mot_particles_head));

			v = q2d(p[1].v[0]);
			if (s.ev.cache.n != n)
				continue;
			x = q2d(p[1].p[0]);
		}
		e = 0.5 * v * v + 0.5 * k * (x - L) * (x - L);
		tu_worst_add(&we, (e - e0) / e0, (double)n);
		if (n < 2000)
			emax_first = fmax(emax_first, fabs(e - e0) / e0);
		if (n > 18000)
			emax_last = fmax(emax_last, fabs(e - e0) / e0);
	}
	tu_bound("particles_spring_verlet_exact", &w, 5e-8, "units");
	/* Verlet's energy swings by (w h)^2 / 4 = 1e-4 of itself, every period */
	tu_bound("particles_spring_energy_rel", &we, 1.1e-4, "");
	/* no drift: the last 2 s swing no wider than the first 2 s (+1%) */
	assert_true(emax_last <= emax_first * 1.01);
	psys_free(&s);
}

/* The number released each step against N = M + rV computed from the same
 * draws (r = mot_rng_sym), in exact arithmetic: with M, V multiples of
 * the step rate every carry is exact. Twelve draws follow r for each
 * particle, whether it finds a slot or not. */
static void test_emission(void **state)
{
	struct psys s;
	struct mot_rng r;
	int64_t n, total = 0, ref_total = 0;
	double carry = 0;
	void *a, *b;
	uint32_t sat = 0;

	psys_new(&s, MOT_PARTICLES_SCRIPTED, 4096, true, 50);
	s.ps.value[MOT_PC_RATE] = MOT_Q32_INT(100);
	s.ps.value[MOT_PC_SPREAD] = MOT_Q32_INT(50);
	s.ps.value[MOT_PC_LIFE_LO] = s.ps.value[MOT_PC_LIFE_HI] = ONE / 2;
	assert_int_equal(psys_init(&s, 50, 250, 32), MOT_OK);
	assert_int_equal(s.ps.dropped, 0);
	a = malloc(s.ps.steps.state_bytes);
	b = malloc(s.ps.steps.state_bytes);
	memcpy(a, s.ckpt, s.ps.steps.state_bytes);
	mot_rng_seed(&r, 7);
	for (n = 0; n < s.ps.steps.nsteps; n++) {
		const struct mot_particle *q = (const void *)((char *)b +
							      sizeof(struct mot_particles_head));
		double rate;
		int64_t born = 0, i, kref;

		mot_particles_step(&s.ps, s.curves, a, b, n, s.ev.ps, &sat);
		for (i = 0; i < 4096; i++)
			born += q[i].used && q[i].birth > n * ONE && q[i].birth <= (n + 1) * ONE;
		rate = 100 + q2d(mot_rng_sym(&r)) * 50;
		carry += rate / 50;
		kref = (int64_t)floor(carry);
		carry -= (double)kref;
		for (i = 0; i < 12 * kref; i++)
			mot_rng_u64(&r);
		assert_int_equal(born, kref);
		total += born;
		ref_total += kref;
		memcpy(a, b, s.ps.steps.state_bytes);
	}
	/* the mean rate over 10 s: M within the draws' spread */
	assert_true(llabs(total - 1000) < 60);
	assert_int_equal(total, ref_total);
	assert_int_equal(sat, 0);
	free(a);
	free(b);
	psys_free(&s);
}

/* One a step, living 1 s (50 steps): 50 slots are exactly enough (a slot
 * freed at the step a new particle is born is taken), 49 drop the 50th. */
static void test_pool(void **state)
{
	uint32_t pool;

	for (pool = 4; pool <= 51; pool++) {
		struct psys s;

		if (pool > 5 && pool < 49)
			continue;
		psys_new(&s, MOT_PARTICLES_SCRIPTED, pool, true, 50);
		s.ps.value[MOT_PC_RATE] = MOT_Q32_INT(50);
		s.ps.value[MOT_PC_LIFE_LO] = s.ps.value[MOT_PC_LIFE_HI] = ONE;
		assert_int_equal(psys_init(&s, 50, 100, 16), MOT_OK);
		if (pool >= 50) {
			assert_int_equal(s.ps.dropped, 0);
			assert_int_equal(s.ps.first_drop, -1);
			assert_int_equal(s.ps.peak, 50);
		} else {
			/* particle pool + 1 is born at step pool + 1 */
			assert_int_equal(s.ps.first_drop, pool + 1);
			assert_true(s.ps.dropped > 0);
		}
		psys_free(&s);
	}
}

/* A Newtonian fountain with every force: evaluated at random ticks from
 * its checkpoints it gives the bits of playing it tick by tick, forwards
 * and backwards. */
static void test_seek(void **state)
{
	struct psys s;
	mot_q32 *seq;
	struct tu_rng r;
	int64_t k, nt = 4000;
	uint32_t nout;
	int c, i;

	psys_new(&s, MOT_PARTICLES_NEWTON, 64, true, 100);
	s.ps.value[MOT_PC_RATE] = MOT_Q32_INT(60);
	s.ps.value[MOT_PC_SPREAD] = MOT_Q32_INT(30);
	for (c = 0; c < 3; c++) {
		s.ps.value[MOT_PC_VEL_LO + c] = c == 1 ? MOT_Q32_INT(4) : -ONE;
		s.ps.value[MOT_PC_VEL_HI + c] = c == 1 ? MOT_Q32_INT(6) : ONE;
		s.ps.value[MOT_PC_COL_LO + c] = ONE / 2;
		s.ps.value[MOT_PC_COL_HI + c] = ONE;
	}
	s.ps.value[MOT_PC_LIFE_LO] = ONE / 2;
	s.ps.value[MOT_PC_LIFE_HI] = ONE;
	s.ps.value[MOT_PC_ALPHA_LO] = s.ps.value[MOT_PC_ALPHA_HI] = ONE;
	s.ps.gravity[1] = -d2q(9.81);
	s.ps.drag = ONE / 10;
	s.ps.ground = true;
	s.ps.restitution = ONE / 2;
	s.ps.pair_radius = ONE / 4;
	s.ps.pair_strength = MOT_Q32_INT(2);
	assert_int_equal(psys_init(&s, 100, 100, 8), MOT_OK);
	nout = s.sys.nout;
	seq = calloc((size_t)nt * nout, sizeof(*seq));
	for (k = 0; k < nt; k++) {
		psys_eval(&s, k);
		memcpy(seq + k * nout, s.out, nout * sizeof(*seq));
	}
	/* backwards, then at random */
	for (k = nt - 1; k >= 0; k -= 7) {
		psys_eval(&s, k);
		assert_memory_equal(s.out, seq + k * nout, nout * sizeof(*seq));
	}
	tu_seed(&r, 3);
	for (i = 0; i < 400; i++) {
		k = (int64_t)(tu_u64(&r) % (uint64_t)nt);
		psys_eval(&s, k);
		assert_memory_equal(s.out, seq + k * nout, nout * sizeof(*seq));
	}
	free(seq);
	psys_free(&s);
}

/* Dropped from 1 unit onto a ground at 0 with restitution 1/2: the next
 * apex at e^2 h = 0.25 (within the step's bounce error). */
static void test_bounce(void **state)
{
	static const double rate[2][2] = { { 0, 100 }, { 0.3, 0 } };
	struct tu_worst w = { 0, 0 };
	double apex = 0;
	bool rising = false;
	struct psys s;
	int64_t k;

	psys_new(&s, MOT_PARTICLES_NEWTON, 1, true, 100);
	s.ps.curve[MOT_PC_RATE] = psys_curve(&s, MOT_INTERP_STEP, rate, 2);
	s.ps.value[MOT_PC_POS_LO + 1] = s.ps.value[MOT_PC_POS_HI + 1] = ONE;
	s.ps.gravity[1] = -d2q(9.81);
	s.ps.ground = true;
	s.ps.restitution = ONE / 2;
	assert_int_equal(psys_init(&s, 100, 50, 16), MOT_OK);
	for (k = 10; k < 1500; k++) {
		double y;

		psys_eval(&s, k);
		y = q2d(s.out[1]);
		assert_true(y >= -1e-3);
		if (y < 0.01)
			rising = true;
		if (rising)
			apex = fmax(apex, y);
		if (rising && y < apex - 0.05)
			break;
	}
	/* the bounce is taken at the first step below the plane, with the
	 * step's half velocity: an energy error up to g h |v| at impact (1.2
	 * cm of the 25 cm here at 100 steps a second) */
	tu_worst_add(&w, apex - 0.25, 0);
	tu_bound("particles_bounce_apex", &w, 0.015, "units");
	psys_free(&s);
}

/* Alpha keyed 1 -> 0 over the life: half at half life; colour times its
 * curve; dead: alpha 0, position held. */
static void test_fade(void **state)
{
	static const double rate[2][2] = { { 0, 50 }, { 0.6, 0 } };
	static const double fade[2][2] = { { 0, 1 }, { 1, 0 } };
	struct tu_worst w = { 0, 0 };
	struct psys s;
	int64_t k;

	psys_new(&s, MOT_PARTICLES_SCRIPTED, 1, true, 50);
	s.ps.curve[MOT_PC_RATE] = psys_curve(&s, MOT_INTERP_STEP, rate, 2);
	s.ps.curve[MOT_PC_AGE_ALPHA] = psys_curve(&s, MOT_INTERP_LINEAR, fade, 2);
	s.ps.value[MOT_PC_ALPHA_LO] = s.ps.value[MOT_PC_ALPHA_HI] = ONE;
	s.ps.value[MOT_PC_LIFE_LO] = s.ps.value[MOT_PC_LIFE_HI] = MOT_Q32_INT(2);
	s.ps.value[MOT_PC_VEL_LO] = s.ps.value[MOT_PC_VEL_HI] = ONE;
	s.ps.value[MOT_PC_COL_LO + 1] = s.ps.value[MOT_PC_COL_HI + 1] = ONE / 4;
	assert_int_equal(psys_init(&s, 50, 100, 16), MOT_OK);
	for (k = 20; k < 4000; k++) {
		double age = q2d(mot_timing_tick_frame(&s.t, k)) / 25.0 - 0.02;

		psys_eval(&s, k);
		if (age < 2) {
			tu_worst_add(&w, q2d(s.out[MOT_PART_ALPHA]) - (1 - age / 2), (double)k);
			assert_int_equal(s.out[MOT_PART_G], ONE / 4);
		} else {
			assert_int_equal(s.out[MOT_PART_ALPHA], 0);
			tu_worst_add(&w, q2d(s.out[0]) - 2.0, (double)k); /* held where it died */
		}
	}
	tu_bound("particles_fade", &w, 1e-8, "");
	psys_free(&s);
}

/* A lattice too stiff for its step is refused: w h = 2 sqrt(k) h with
 * two springs at the middle particle. */
static void test_stability(void **state)
{
	static const mot_q32 rest[3][3] = { { 0, 0, 0 }, { ONE, 0, 0 }, { 2 * ONE, 0, 0 } };
	struct mot_spring sp[2] = { { 0, 1, ONE }, { 1, 2, ONE } };
	struct psys s;

	/* 2 deg k h^2 = 4 k / 100^2 < 3.24: k < 8100 */
	psys_new(&s, MOT_PARTICLES_NEWTON, 3, false, 100);
	s.ps.rest = rest;
	s.ps.springs = sp;
	s.ps.nsprings = 2;
	s.ps.spring_k = MOT_Q32_INT(8000);
	assert_int_equal(psys_init(&s, 100, 10, 16), MOT_OK);
	psys_free(&s);
	psys_new(&s, MOT_PARTICLES_NEWTON, 3, false, 100);
	s.ps.rest = rest;
	s.ps.springs = sp;
	s.ps.nsprings = 2;
	s.ps.spring_k = MOT_Q32_INT(8200);
	assert_int_equal(psys_init(&s, 100, 10, 16), MOT_E_RANGE);
	psys_free(&s);
}

/* The generator: splitmix64's published first outputs for seed 0, and
 * the Q32.32 draws' ranges. */
static void test_rng(void **state)
{
	struct mot_rng r;
	int i;

	mot_rng_seed(&r, 0);
	assert_true(mot_rng_u64(&r) == 0xe220a8397b1dcdafull);
	assert_true(mot_rng_u64(&r) == 0x6e789e6aa1b965f4ull);
	for (i = 0; i < 10000; i++) {
		mot_q32 u = mot_rng_unit(&r), v = mot_rng_sym(&r);

		assert_true(u >= 0 && u < ONE);
		assert_true(v >= -ONE && v < ONE);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_rng),
		cmocka_unit_test(test_projectile),
		cmocka_unit_test(test_spring),
		cmocka_unit_test(test_emission),
		cmocka_unit_test(test_pool),
		cmocka_unit_test(test_seek),
		cmocka_unit_test(test_bounce),
		cmocka_unit_test(test_fade),
		cmocka_unit_test(test_stability),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
