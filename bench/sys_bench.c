/* SPDX-License-Identifier: MIT */
/*
 * sys_bench.c - the seed's advanced systems against double-precision twins
 * doing the same work, side by side in one run (bench.h), as BENCH lines:
 *
 *   surface    a 64 x 64 sampled B-spline surface (4,096 actuators) on an
 *              8 x 8 net whose heights are keyed (Hermite): ns per actuator
 *              per tick at 1 kHz, and the share of one core it takes
 *   particles  a fountain of 10,000 Newtonian particles (gravity, drag, a
 *              ground plane, 100 steps a second, the pool full): ns per
 *              particle per tick at 1 kHz, the steps included
 *   flock      1,000 members (separation, cohesion, alignment, a goal, a
 *              neighbour grid, 50 steps a second): ns per member per tick
 *
 * The twins (below) follow the core's algorithms step for step in double
 * precision: the same bases and separable sum, the same emission, Verlet,
 * deaths and Hermite in-betweens, the same rules and cuts; their results
 * are compared with the core's so that they are known to do the same work.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "dbl_curve.h"
#include "motion/rng.h"
#include "motion/system.h"
#include "scene/scene_desc.h"

#define TICKS 1000 /* one second at 1 kHz */

static struct mot_timing tm;

static double tick_frame(int64_t k)
{
	return q2d(mot_timing_tick_frame(&tm, k));
}

/* ---- surface ------------------------------------------------------------------------ */

#define NC 8
#define NS 64
#define NK 6

struct surf {
	struct mot_surface s;
	struct mot_curve curves[NC * NC];
	struct mot_key keys[NC * NC][NK];
	struct mot_curve_seg seg[NC * NC][NK];
	struct mot_cursor cur[NC * NC];
	int32_t idx[NC * NC * 3];
	mot_q32 rest[NC * NC * 3], fixed[NS * NS * 3], out[NS * NS * 3], scratch[NC * NC * 3 + NC];
	struct mot_surface_w wu[NS], wv[NS];
	/* the twin */
	struct dbl_curve dc[NC * NC];
	struct dbl_cursor dcur[NC * NC];
	double dwu[NS][4], dwv[NS][4];
	uint32_t diu[NS][4], div[NS][4];
	double dctl[NC * NC], drow[NC], dout[NS * NS * 3], drest[NC * NC * 3];
	int64_t t0;
};

static void surf_fixed(void *ctx)
{
	struct surf *s = ctx;
	uint32_t sat = 0;
	int64_t k;

	for (k = 0; k < TICKS; k++)
		mot_surface_eval(&s->s, s->curves, s->cur, mot_timing_tick_frame(&tm, s->t0 + k),
				 s->scratch, s->out, &sat);
	bench_sink += (uint64_t)s->out[NS * NS];
}

static void surf_double(void *ctx)
{
	struct surf *s = ctx;
	int64_t k;
	int i, j, b, a;

	for (k = 0; k < TICKS; k++) {
		double f = tick_frame(s->t0 + k);

		for (i = 0; i < NC * NC; i++)
			s->dctl[i] = dbl_curve_eval(&s->dc[i], &s->dcur[i], f);
		/* y moves: along u for each row and control column, then along v */
		for (i = 0; i < NS; i++) {
			for (b = 0; b < NC; b++) {
				double x = 0;

				for (a = 0; a < 4; a++)
					x += s->dwu[i][a] * s->dctl[s->diu[i][a] * NC + b];
				s->drow[b] = x;
			}
			for (j = 0; j < NS; j++) {
				double y = 0;

				for (a = 0; a < 4; a++)
					y += s->dwv[j][a] * s->drow[s->div[j][a]];
				s->dout[(i * NS + j) * 3 + 1] = y;
			}
		}
		/* x and z stand still: copied, as the core copies its fixed samples */
		for (i = 0; i < NS * NS; i++) {
			s->dout[i * 3] = s->drest[0];
			s->dout[i * 3 + 2] = s->drest[2];
		}
	}
	bench_sink += (uint64_t)(int64_t)(s->dout[NS * NS] * 1e6);
}

static int bench_surface(void)
{
	struct surf *s = calloc(1, sizeof(*s));
	struct sd_key sk[NK];
	struct sd_curve sc = { MOT_INTERP_HERMITE, NK, sk, 1, 0, 0, 0 };
	struct bench_pair p;
	struct tu_rng r;
	double worst = 0;
	uint32_t i, k, sat = 0;

	tu_seed(&r, 64);
	for (i = 0; i < NC * NC; i++) {
		for (k = 0; k < NK; k++) {
			sk[k] = (struct sd_key){ 20.0 * k, tu_uniform(&r, -0.3, 0.3), 0, 0 };
			s->keys[i][k] = (struct mot_key){ d2q(sk[k].frame), d2q(sk[k].value), 0, 0 };
			sk[k].value = q2d(s->keys[i][k].value);
		}
		mot_curve_init(&s->curves[i], MOT_INTERP_HERMITE, s->keys[i], NK, NULL, s->seg[i], NK,
			       &sat);
		dbl_curve_init(&s->dc[i], &sc, 1.0, false, malloc(dbl_curve_size(&sc)));
		s->idx[i * 3] = s->idx[i * 3 + 2] = -1;
		s->idx[i * 3 + 1] = (int32_t)i;
	}
	s->s = (struct mot_surface){ .basis = MOT_SURFACE_BSPLINE, .ncu = NC, .ncv = NC, .nsu = NS,
				     .nsv = NS, .curve = s->idx, .rest = s->rest, .wu = s->wu,
				     .wv = s->wv, .fixed = s->fixed };
	if (mot_surface_init(&s->s, NC * NC, &sat))
		return 1;
	for (i = 0; i < NS; i++)
		for (k = 0; k < 4; k++) {
			s->dwu[i][k] = (double)s->wu[i].w[k] / 4611686018427387904.0;
			s->dwv[i][k] = (double)s->wv[i].w[k] / 4611686018427387904.0;
			s->diu[i][k] = s->wu[i].idx[k];
			s->div[i][k] = s->wv[i].idx[k];
		}
	s->t0 = 1500;
	bench_run_pair(&p, surf_fixed, surf_double, s, (double)TICKS * NS * NS);
	bench_print("surface64_actuator_tick_fixed", p.fixed_ns, "ns/actuator/tick");
	bench_print("surface64_actuator_tick_double", p.double_ns, "ns/actuator/tick");
	bench_print("surface64_ratio_fixed_over_double", p.ratio, "x");
	/* 4,096 actuators at 1 kHz: the share of one core */
	bench_print("surface64_core_share_at_1khz", p.fixed_ns * NS * NS * 1000 / 1e9 * 100, "%");
	for (i = 0; i < NS * NS; i++)
		worst = fmax(worst, fabs(q2d(s->out[i * 3 + 1]) - s->dout[i * 3 + 1]));
	bench_print("surface64_fixed_vs_double", worst, "units");
	return worst > 1e-6;
}

/* ---- particles ------------------------------------------------------------------------ */

#define NP 10000
#define P_HZ 100

struct dpart {
	double p[3], v[3], a[3], p0[3], v0[3], birth, death, inv_life, size, col[3], alpha;
	bool used;
};

/* A state of the twin: its generator and carry travel with it, as the
 * core's head does, so that a step computed again gives the same. */
struct dstate {
	uint64_t rng;
	double carry;
	struct dpart p[NP];
};

struct part {
	struct mot_particles ps;
	struct mot_system sys;
	struct mot_sys_eval ev;
	void *block;
	mot_q32 *out;
	int64_t tf, td; /* the next tick of each side: every batch moves forward */
	/* the twin: states at step n and n + 1, and its output */
	struct dstate *da, *db;
	int64_t dn;
	bool db_ok;
	double g[3], drag, vlo[3], vhi[3], life_lo, life_hi, rate, spread, h;
	double *dout;
};

static double du(uint64_t *s)
{
	struct mot_rng r = { *s };
	double u = (double)(mot_rng_u64(&r) >> 32) / 4294967296.0;

	*s = r.s;
	return u;
}

/* The twin's step n -> n + 1 (particles.c's, in double) */
static void dpart_step(struct part *P, const struct dstate *as, struct dstate *bs, int64_t n)
{
	const struct dpart *a = as->p;
	struct dpart *b = bs->p;
	double t0 = (double)n, t1 = n + 1.0, h = P->h;
	int64_t count, i;
	uint32_t s = 0;
	int k;

	memcpy(bs, as, sizeof(*as));
	for (i = 0; i < NP; i++) {
		struct dpart *q = &b[i];
		double vp[3];

		if (!(a[i].used && a[i].birth <= t0 && t0 < a[i].death))
			continue;
		for (k = 0; k < 3; k++) {
			q->v[k] = a[i].v[k] + a[i].a[k] * h / 2;
			q->p[k] = a[i].p[k] + q->v[k] * h;
			vp[k] = q->v[k] + a[i].a[k] * h / 2;
		}
		if (q->p[1] < 0) {
			q->p[1] = -q->p[1] * 0.5;
			if (q->v[1] < 0)
				q->v[1] = -q->v[1] * 0.5;
			if (vp[1] < 0)
				vp[1] = -vp[1] * 0.5;
		}
		for (k = 0; k < 3; k++) {
			q->a[k] = P->g[k] - P->drag * vp[k];
			q->v[k] += q->a[k] * h / 2;
		}
		if (q->death <= t1) {
			/* its state at death on the step's Hermite curve */
			double s1 = q->death - t0, s2 = s1 * s1, s3 = s2 * s1;

			for (k = 0; k < 3; k++)
				q->p[k] = (2 * s3 - 3 * s2 + 1) * a[i].p[k] + (s3 - 2 * s2 + s1) * h * a[i].v[k] +
					  (3 * s2 - 2 * s3) * q->p[k] + (s3 - s2) * h * q->v[k];
		}
	}
	{
		struct mot_rng r = { bs->rng };
		double rate;

		rate = P->rate + ((double)(mot_rng_u64(&r) >> 31) / 4294967296.0 - 1) * P->spread;
		bs->rng = r.s;
		if (rate > 0)
			bs->carry += rate * h;
	}
	count = (int64_t)floor(bs->carry);
	bs->carry -= (double)count;
	for (i = 0; i < count; i++) {
		double birth = n + (double)(i + 1) / count, d[12], life, dt;
		struct dpart *q;

		for (k = 0; k < 12; k++)
			d[k] = du(&bs->rng);
		while (s < NP && b[s].used && b[s].death > birth)
			s++;
		if (s == NP)
			continue;
		q = &b[s];
		life = P->life_lo + (P->life_hi - P->life_lo) * d[6];
		for (k = 0; k < 3; k++) {
			q->p0[k] = 0;
			q->v0[k] = P->vlo[k] + (P->vhi[k] - P->vlo[k]) * d[3 + k];
			q->col[k] = 1;
		}
		q->used = true;
		q->birth = birth;
		q->death = birth + life * P_HZ;
		q->inv_life = 1 / life;
		dt = ((q->death < t1 ? q->death : t1) - birth) * h;
		for (k = 0; k < 3; k++) {
			q->a[k] = P->g[k] - P->drag * q->v0[k];
			q->p[k] = q->p0[k] + (q->v0[k] + q->a[k] * dt / 2) * dt;
			q->v[k] = q->v0[k] + q->a[k] * dt;
		}
		s++;
	}
}

/* The twin's in-betweens: particles.c's slot() in double */
static void dpart_eval(struct part *P, double frame)
{
	double t = frame / 25.0 * P_HZ, h = P->h, t0;
	int64_t n = (int64_t)floor(t), i;
	int k;

	while (P->dn < n) { /* forward one step at a time, as the cache does */
		struct dstate *x = P->da;

		if (!P->db_ok)
			dpart_step(P, P->da, P->db, P->dn);
		P->da = P->db;
		P->db = x;
		P->dn++;
		P->db_ok = false;
	}
	if (!P->db_ok) {
		dpart_step(P, P->da, P->db, n); /* b: step n + 1 */
		P->db_ok = true;
	}
	t0 = (double)n;
	for (i = 0; i < NP; i++) {
		const struct dpart *a = &P->da->p[i], *b = &P->db->p[i];
		const struct dpart *q = b->used && b->birth <= t ? b : a;
		double *o = P->dout + i * 8, age;

		if (!q->used) {
			for (k = 0; k < 8; k++)
				o[k] = k < 3 ? q->p[k] : 0;
			continue;
		}
		if (q == a && b->used && b->birth != a->birth && a->death > t0) {
			/* the particle b replaced, on to its death under its acceleration */
			double dt = ((t < a->death ? t : a->death) - t0) * h;

			for (k = 0; k < 3; k++)
				o[k] = a->p[k] + a->v[k] * dt + a->a[k] / 2 * dt * dt;
		} else if (q->death <= t0 || q == a) {
			for (k = 0; k < 3; k++)
				o[k] = q->p[k];
		} else {
			bool born = q->birth > t0;
			double s0 = born ? q->birth : t0, s1 = q->death < t0 + 1 ? q->death : t0 + 1;
			double tt = t < s1 ? t : s1, s = (tt - s0) / (s1 - s0), H = (s1 - s0) * h;
			double s2 = s * s, s3 = s2 * s;

			for (k = 0; k < 3; k++)
				o[k] = (2 * s3 - 3 * s2 + 1) * (born ? q->p0[k] : a->p[k]) +
				       (s3 - 2 * s2 + s) * H * (born ? q->v0[k] : a->v[k]) +
				       (3 * s2 - 2 * s3) * b->p[k] + (s3 - s2) * H * b->v[k];
		}
		age = (t - q->birth) * h;
		for (k = 0; k < 3; k++)
			o[3 + k] = q->col[k];
		o[6] = t < q->death ? 1.0 * fmin(1, age * q->inv_life) : 0;
		o[7] = 0;
	}
}

/* Each batch plays the next second: playback, one step a step, as the
 * loop plays (a batch that went back would time the seeks instead). */
static void part_fixed(void *ctx)
{
	struct part *P = ctx;
	uint32_t sat = 0;
	int64_t k;

	for (k = 0; k < TICKS; k++, P->tf++)
		mot_system_eval(&P->sys, NULL, NULL, &P->ev, mot_timing_tick_frame(&tm, P->tf),
				P->out, &sat);
	bench_sink += (uint64_t)P->out[1];
}

static void part_double(void *ctx)
{
	struct part *P = ctx;
	int64_t k;

	for (k = 0; k < TICKS; k++, P->td++)
		dpart_eval(P, tick_frame(P->td));
	bench_sink += (uint64_t)(int64_t)(P->dout[1] * 1e6);
}

static int bench_particles(void)
{
	struct part *P = calloc(1, sizeof(*P));
	struct mot_particles *ps = &P->ps;
	struct bench_pair p;
	size_t bytes;
	uint32_t sat = 0, i;
	int k;

	for (k = 0; k < MOT_PC_COUNT; k++)
		ps->curve[k] = -1;
	ps->motion = MOT_PARTICLES_NEWTON;
	ps->npool = NP;
	ps->emit = true;
	ps->seed = 10000;
	ps->value[MOT_PC_RATE] = MOT_Q32_INT(9000);
	ps->value[MOT_PC_SPREAD] = MOT_Q32_INT(500);
	ps->value[MOT_PC_LIFE_LO] = MOT_Q32_ONE * 8 / 10;
	ps->value[MOT_PC_LIFE_HI] = MOT_Q32_ONE;
	for (k = 0; k < 3; k++) {
		ps->value[MOT_PC_VEL_LO + k] = k == 1 ? MOT_Q32_INT(4) : -MOT_Q32_ONE / 2;
		ps->value[MOT_PC_VEL_HI + k] = k == 1 ? MOT_Q32_INT(6) : MOT_Q32_ONE / 2;
		ps->value[MOT_PC_COL_LO + k] = ps->value[MOT_PC_COL_HI + k] = MOT_Q32_ONE;
	}
	ps->value[MOT_PC_ALPHA_LO] = ps->value[MOT_PC_ALPHA_HI] = MOT_Q32_ONE;
	for (k = MOT_PC_AGE_R; k <= MOT_PC_AGE_ALPHA; k++)
		ps->value[k] = MOT_Q32_ONE;
	ps->gravity[1] = -d2q(9.81);
	ps->drag = MOT_Q32_ONE / 10;
	ps->ground = true;
	ps->restitution = MOT_Q32_ONE / 2;
	/* 2 s to fill the pool, then 1 + 2 x BENCH_REPEATS batches a side, a second each */
	if (mot_steps_init(&ps->steps, &tm, 0, MOT_Q32_INT(25 * (4 + 2 * BENCH_REPEATS)), P_HZ, 1,
			   16, mot_particles_state_bytes(NP)))
		return 1;
	ps->steps.ckpt = malloc((size_t)mot_steps_ckpt_count(&ps->steps) * ps->steps.state_bytes);
	P->sys.kind = MOT_SYS_PARTICLES;
	P->sys.particles = ps;
	bytes = mot_system_eval_bytes(&P->sys);
	P->block = aligned_alloc(64, (bytes + 63) & ~(size_t)63);
	mot_system_eval_init(&P->ev, &P->sys, P->block, bytes);
	if (mot_system_init(&P->sys, NULL, 0, &P->ev, &sat))
		return 1;
	P->out = calloc(P->sys.nout, sizeof(*P->out));
	/* the twin, run from the start to where the timing begins (2 s) */
	P->da = calloc(1, sizeof(*P->da));
	P->db = calloc(1, sizeof(*P->db));
	P->dout = calloc((size_t)NP * 8, sizeof(*P->dout));
	P->da->rng = 10000;
	P->h = 1.0 / P_HZ;
	P->g[1] = q2d(ps->gravity[1]);
	P->drag = 0.1;
	P->rate = 9000;
	P->spread = 500;
	P->life_lo = q2d(ps->value[MOT_PC_LIFE_LO]);
	P->life_hi = 1;
	for (k = 0; k < 3; k++) {
		P->vlo[k] = q2d(ps->value[MOT_PC_VEL_LO + k]);
		P->vhi[k] = q2d(ps->value[MOT_PC_VEL_HI + k]);
	}
	P->tf = P->td = 2000;
	bench_run_pair(&p, part_fixed, part_double, P, (double)TICKS * NP);
	printf("# particles: %lld alive at most of %u, %lld dropped\n", (long long)ps->peak, NP,
	       (long long)ps->dropped);
	bench_print("particles10k_particle_tick_fixed", p.fixed_ns, "ns/particle/tick");
	bench_print("particles10k_particle_tick_double", p.double_ns, "ns/particle/tick");
	bench_print("particles10k_ratio_fixed_over_double", p.ratio, "x");
	{
		double worst = 0;

		/* the twin does the core's work: the same particles in the same
		 * slots, on the same paths, until a rounding of a birth or death
		 * time first sends a particle to another slot (then the two
		 * pools go their own ways, each right); 0.3 s in they agree */
		mot_system_eval(&P->sys, NULL, NULL, &P->ev, mot_timing_tick_frame(&tm, 300), P->out,
				&sat);
		P->dn = 0;
		P->db_ok = false;
		memset(P->da, 0, sizeof(*P->da));
		P->da->rng = 10000;
		dpart_eval(P, tick_frame(300));
		for (i = 0; i < NP; i++)
			for (k = 0; k < 3; k++) {
				double e = fabs(q2d(P->out[i * 8 + k]) - P->dout[i * 8 + k]);

				if (e > worst && getenv("SYS_BENCH_DEBUG"))
					printf("# slot %u.%d: fixed %.9g double %.9g\n", i, k,
					       q2d(P->out[i * 8 + k]), P->dout[i * 8 + k]);
				worst = fmax(worst, e);
			}
		bench_print("particles10k_fixed_vs_double_at_0.3s", worst, "units");
		return worst > 1e-6;
	}
}

/* ---- flock ---------------------------------------------------------------------------- */

#define NF 1000
#define F_HZ 50

struct dmem {
	double p[3], v[3];
};

struct flk {
	struct mot_flock f;
	struct mot_system sys;
	struct mot_sys_eval ev;
	void *block;
	mot_q32 *out;
	int64_t tf, td;
	/* the twin */
	struct dmem *da, *db;
	int64_t dn;
	bool db_ok;
	uint32_t *head, *next, mask;
	int32_t (*cell)[3];
	double *dout;
};

static uint32_t dhash(const int32_t c[3])
{
	return ((uint32_t)c[0] * 73856093u) ^ ((uint32_t)c[1] * 19349663u) ^
	       ((uint32_t)c[2] * 83492791u);
}

static void dcut(double v[3], double lim)
{
	double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);

	if (n > lim)
		for (int k = 0; k < 3; k++)
			v[k] *= lim / n;
}

/* flock.c's rules in double, on the same kind of grid */
static void dflock_step(struct flk *F, const struct dmem *m, struct dmem *o)
{
	const double R = 2, sep = 0.8, ws = 6, wc = 1, wa = 2, wg = 2, vmax = 3, amax = 5,
		     h = 1.0 / F_HZ;
	uint32_t i;
	int k;

	memset(F->head, 0, sizeof(*F->head) * (F->mask + 1));
	for (i = 0; i < NF; i++) {
		uint32_t b;

		for (k = 0; k < 3; k++)
			F->cell[i][k] = (int32_t)floor(m[i].p[k] / R);
		b = dhash(F->cell[i]) & F->mask;
		F->next[i] = F->head[b];
		F->head[b] = i + 1;
	}
	for (i = 0; i < NF; i++) {
		double a[3] = { 0, 0, 0 }, sp[3] = { 0, 0, 0 }, dp[3] = { 0, 0, 0 }, dv[3] = { 0, 0, 0 };
		double u[3], len, dvv[3];
		uint32_t count = 0;
		int dx, dy, dz;

		for (dx = -1; dx <= 1 && count < 8; dx++)
			for (dy = -1; dy <= 1 && count < 8; dy++)
				for (dz = -1; dz <= 1 && count < 8; dz++) {
					int32_t q[3] = { F->cell[i][0] + dx, F->cell[i][1] + dy,
							 F->cell[i][2] + dz };
					uint32_t it = F->head[dhash(q) & F->mask];

					for (; it && count < 8; it = F->next[it - 1]) {
						uint32_t j = it - 1;
						double d[3], dl;

						if (j == i || memcmp(F->cell[j], q, sizeof(q)))
							continue;
						for (k = 0; k < 3; k++)
							d[k] = m[i].p[k] - m[j].p[k];
						dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
						if (dl >= R)
							continue;
						for (k = 0; k < 3; k++) {
							dp[k] -= d[k];
							dv[k] += m[j].v[k] - m[i].v[k];
							if (dl < sep && dl > 0)
								sp[k] += d[k] * (sep - dl) / (sep * dl);
						}
						count++;
					}
				}
		for (k = 0; k < 3; k++) {
			a[k] = ws * sp[k];
			if (count)
				a[k] += wc * dp[k] / count / R + wa * dv[k] / count / vmax;
			u[k] = (k == 1 ? 3.0 : 0.0) - m[i].p[k];
		}
		len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
		for (k = 0; k < 3; k++)
			a[k] += wg * ((len ? u[k] / (len < R ? R : len) : 0) * vmax - m[i].v[k]) / vmax;
		dcut(a, amax);
		for (k = 0; k < 3; k++)
			o[i].v[k] = m[i].v[k] + a[k] * h;
		dcut(o[i].v, vmax);
		for (k = 0; k < 3; k++) {
			dvv[k] = o[i].v[k] - m[i].v[k];
			o[i].p[k] = m[i].p[k] + (m[i].v[k] + dvv[k] / 2) * h;
		}
	}
}

static void dflock_eval(struct flk *F, double frame)
{
	double t = frame / 25.0 * F_HZ, tau;
	int64_t n = (int64_t)floor(t);
	uint32_t i;
	int k;

	while (F->dn < n) {
		struct dmem *x = F->da;

		if (!F->db_ok)
			dflock_step(F, F->da, F->db);
		F->da = F->db;
		F->db = x;
		F->dn++;
		F->db_ok = false;
	}
	if (!F->db_ok) {
		dflock_step(F, F->da, F->db);
		F->db_ok = true;
	}
	tau = t - n;
	for (i = 0; i < NF; i++) {
		double *o = F->dout + i * 4, v[3];

		for (k = 0; k < 3; k++) {
			double dv = F->db[i].v[k] - F->da[i].v[k];

			o[k] = F->da[i].p[k] + (F->da[i].v[k] * tau + dv * tau * tau / 2) / F_HZ;
			v[k] = F->da[i].v[k] + dv * tau;
		}
		o[3] = atan2(-v[0], -v[2]) / (2 * M_PI);
	}
}

static void flock_fixed(void *ctx)
{
	struct flk *F = ctx;
	uint32_t sat = 0;
	int64_t k;

	for (k = 0; k < TICKS; k++, F->tf++)
		mot_system_eval(&F->sys, NULL, NULL, &F->ev, mot_timing_tick_frame(&tm, F->tf),
				F->out, &sat);
	bench_sink += (uint64_t)F->out[1];
}

static void flock_double(void *ctx)
{
	struct flk *F = ctx;
	int64_t k;

	for (k = 0; k < TICKS; k++, F->td++)
		dflock_eval(F, tick_frame(F->td));
	bench_sink += (uint64_t)(int64_t)(F->dout[1] * 1e6);
}

static int bench_flock(void)
{
	struct flk *F = calloc(1, sizeof(*F));
	struct mot_flock *f = &F->f;
	struct bench_pair p;
	size_t bytes;
	uint32_t sat = 0, i;
	int k;

	f->n = NF;
	f->seed = 1000;
	f->start_r = MOT_Q32_INT(12);
	f->start_v[0] = MOT_Q32_ONE;
	f->start_dv = MOT_Q32_ONE;
	f->radius = MOT_Q32_INT(2);
	f->sep = MOT_Q32_ONE * 8 / 10;
	f->max_neighbours = 8;
	f->w_sep = MOT_Q32_INT(6);
	f->w_coh = MOT_Q32_ONE;
	f->w_ali = MOT_Q32_INT(2);
	f->w_goal = MOT_Q32_INT(2);
	f->goal = MOT_FLOCK_GOAL_POINT;
	for (k = 0; k < 3; k++)
		f->goal_ch[k] = -1;
	f->goal_value[1] = MOT_Q32_INT(3);
	f->vmax = MOT_Q32_INT(3);
	f->amax = MOT_Q32_INT(5);
	f->margin = MOT_Q32_ONE;
	if (mot_steps_init(&f->steps, &tm, 0, MOT_Q32_INT(25 * (4 + 2 * BENCH_REPEATS)), F_HZ, 1,
			   16, mot_flock_state_bytes(NF)))
		return 1;
	f->steps.ckpt = malloc((size_t)mot_steps_ckpt_count(&f->steps) * f->steps.state_bytes);
	F->sys.kind = MOT_SYS_FLOCK;
	F->sys.flock = f;
	bytes = mot_system_eval_bytes(&F->sys);
	F->block = aligned_alloc(64, (bytes + 63) & ~(size_t)63);
	mot_system_eval_init(&F->ev, &F->sys, F->block, bytes);
	if (mot_system_init(&F->sys, NULL, 0, &F->ev, &sat))
		return 1;
	F->out = calloc(F->sys.nout, sizeof(*F->out));
	/* the twin starts from the core's members at step 0 */
	F->da = calloc(NF, sizeof(*F->da));
	F->db = calloc(NF, sizeof(*F->db));
	for (i = 0; i < NF; i++) {
		const struct mot_member *mm = (const struct mot_member *)(const void *)f->steps.ckpt;

		for (k = 0; k < 3; k++) {
			F->da[i].p[k] = q2d(mm[i].p[k]);
			F->da[i].v[k] = q2d(mm[i].v[k]);
		}
	}
	F->mask = mot_grid_buckets(NF) - 1;
	F->head = calloc(F->mask + 1, sizeof(*F->head));
	F->next = calloc(NF, sizeof(*F->next));
	F->cell = calloc(NF, sizeof(*F->cell));
	F->dout = calloc((size_t)NF * 4, sizeof(*F->dout));
	F->tf = F->td = 2000;
	bench_run_pair(&p, flock_fixed, flock_double, F, (double)TICKS * NF);
	bench_print("flock1k_member_tick_fixed", p.fixed_ns, "ns/member/tick");
	bench_print("flock1k_member_tick_double", p.double_ns, "ns/member/tick");
	bench_print("flock1k_ratio_fixed_over_double", p.ratio, "x");
	{
		/* a flock is chaotic: the twin's rounding parts from the core's
		 * over the steps; one step after the start they agree */
		double worst = 0;

		mot_system_eval(&F->sys, NULL, NULL, &F->ev, mot_timing_tick_frame(&tm, 10), F->out,
				&sat);
		F->dn = 0;
		F->db_ok = false;
		for (i = 0; i < NF; i++) {
			const struct mot_member *mm =
				(const struct mot_member *)(const void *)f->steps.ckpt;

			for (k = 0; k < 3; k++) {
				F->da[i].p[k] = q2d(mm[i].p[k]);
				F->da[i].v[k] = q2d(mm[i].v[k]);
			}
		}
		dflock_eval(F, tick_frame(10));
		for (i = 0; i < NF; i++)
			for (k = 0; k < 3; k++)
				worst = fmax(worst, fabs(q2d(F->out[i * 4 + k]) - F->dout[i * 4 + k]));
		bench_print("flock1k_fixed_vs_double_after_a_step", worst, "units");
		return worst > 1e-6;
	}
}

int main(int argc, char **argv)
{
	int bad = 0;

	(void)argc;
	(void)argv;
	mot_timing_init(&tm, 25, 1, 1000);
	printf("# systems: the core against double twins, %d ticks at 1 kHz a timing, medians "
	       "of %d\n", TICKS, BENCH_REPEATS);
	bad |= bench_surface();
	bad |= bench_particles();
	bad |= bench_flock();
	return bad;
}
