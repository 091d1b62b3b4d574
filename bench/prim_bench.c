/* SPDX-License-Identifier: MIT */
/*
 * prim_bench.c - ns per call of the operations a tick is made of, fixed
 * point against double (libm for the elementary functions, dbl_mat.h and
 * dbl_curve.h for the rest): where a scene's ratio comes from.
 *
 * "thru": one call per element of arrays of 1024 random inputs, results
 * stored, calls independent (the nodes of one level of a hierarchy).
 * mat_mul_chain: a 1000-node chain W(i) = L(i) . W(i-1), every product
 * waiting for the one before (the worst case of a tick). Curves: one curve
 * of 10 keys at uneven frames, played at 1 kHz and 24 fps with a cursor,
 * per kind, as curve.h states its costs.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "dbl_curve.h"
#include "dbl_mat.h"
#include "motion/decomp.h"
#include "motion/trig.h"
#include "motion_bench.h"
#include "scene/scene_desc.h"

#define NIN 1024
#define ROUNDS 64 /* trig batches: NIN * ROUNDS calls */
/* Each round moves the inputs a little (an LSB in fixed point, about as
 * little in double) so that no round can reuse the one before. */
#define NUDGE 1e-9

static struct {
	mot_q32 turns[NIN], y[NIN], x[NIN], c[NIN], pos[NIN], out[NIN], out2[NIN];
	double drad[NIN], dy[NIN], dx[NIN], dc[NIN], dpos[NIN], dout[NIN], dout2[NIN];
	struct mot_mat ma[NIN], mb[NIN], mo[NIN];
	struct dbl_mat da[NIN], dbm[NIN], dmo[NIN];
	struct mot_quat qa[NIN], qb[NIN], qo[NIN];
	struct dbl_quat dqa[NIN], dqb[NIN], dqo[NIN];
	struct mot_slerp sl[NIN];
	struct dbl_slerp dsl[NIN];
	struct mot_decomp dc_[NIN];
	struct dbl_decomp ddc[NIN];
	mot_q32 pt[NIN][3], po[NIN][3], tt[NIN];
	double dpt[NIN][3], dpo[NIN][3], dtt[NIN];
} in;

/* ---- batches: one macro per shape, the body inlined into its loop ---------------- */

#define TRIG_BATCH(name, body)                                                 \
	static void name(void *ctx)                                            \
	{                                                                      \
		int r, i;                                                      \
                                                                               \
		for (r = 0; r < ROUNDS; r++)                                   \
			for (i = 0; i < NIN; i++) {                            \
				body;                                          \
			}                                                      \
	}

TRIG_BATCH(fx_sincos, mot_sincos(in.turns[i] + r, &in.out[i], &in.out2[i]))
TRIG_BATCH(db_sincos, sincos(in.drad[i] + r * NUDGE, &in.dout[i], &in.dout2[i]))
TRIG_BATCH(fx_atan2, in.out[i] = mot_atan2(in.y[i] + r, in.x[i]))
TRIG_BATCH(db_atan2, in.dout[i] = atan2(in.dy[i] + r * NUDGE, in.dx[i]))
TRIG_BATCH(fx_acos, in.out[i] = mot_acos(in.c[i] - r, NULL))
TRIG_BATCH(db_acos, in.dout[i] = acos(in.dc[i] - r * NUDGE))
TRIG_BATCH(fx_sqrt, in.out[i] = mot_sqrt(in.pos[i] + r, NULL))
TRIG_BATCH(db_sqrt, in.dout[i] = sqrt(in.dpos[i] + r * NUDGE))
TRIG_BATCH(fx_rsqrt, in.out[i] = mot_rsqrt(in.pos[i] + r, NULL))
TRIG_BATCH(db_rsqrt, in.dout[i] = 1 / sqrt(in.dpos[i] + r * NUDGE))

#define THRU_BATCH(name, reps, body)                                           \
	static void name(void *ctx)                                            \
	{                                                                      \
		int r, i;                                                      \
                                                                               \
		for (r = 0; r < (reps); r++)                                   \
			for (i = 0; i < NIN; i++) {                            \
				body;                                          \
			}                                                      \
	}

THRU_BATCH(fx_mul, 16, mot_mat_mul(&in.mo[i], &in.ma[i], &in.mb[i], NULL))
THRU_BATCH(db_mul, 16, dbl_mat_mul(&in.dmo[i], &in.da[i], &in.dbm[i]))
THRU_BATCH(fx_apply, 16, mot_mat_apply(in.po[i], in.pt[i], &in.ma[i], NULL))
THRU_BATCH(db_apply, 16, dbl_mat_apply(in.dpo[i], in.dpt[i], &in.da[i]))
THRU_BATCH(fx_to_mat, 16, mot_quat_to_mat(&in.mo[i], &in.qa[i], NULL))
THRU_BATCH(db_to_mat, 16, dbl_quat_to_mat(&in.dmo[i], &in.dqa[i]))
THRU_BATCH(fx_slerp_prep, 4, mot_slerp_prepare(&in.sl[i], &in.qa[i], &in.qb[i], NULL))
THRU_BATCH(db_slerp_prep, 4, dbl_slerp_prepare(&in.dsl[i], &in.dqa[i], &in.dqb[i]))
THRU_BATCH(fx_slerp_eval, 16, mot_slerp_eval(&in.qo[i], &in.sl[i], in.tt[i], NULL))
THRU_BATCH(db_slerp_eval, 16, dbl_slerp_eval(&in.dqo[i], &in.dsl[i], in.dtt[i]))
THRU_BATCH(fx_decompose, 2, mot_mat_decompose(&in.dc_[i], NULL, &in.ma[i], NULL))
THRU_BATCH(db_decompose, 2, dbl_mat_decompose(&in.ddc[i], &in.da[i]))
THRU_BATCH(fx_inverse, 2, mot_mat_inverse(&in.mo[i], &in.ma[i], NULL))
THRU_BATCH(fx_compose, 8, mot_mat_compose(&in.mo[i], &in.dc_[i], NULL))
THRU_BATCH(db_compose, 8, dbl_mat_compose(&in.dmo[i], &in.ddc[i]))

/* the chain: rigid links (rotation, translation within 1 m) stay in range */
#define CHAIN 1000
static struct mot_mat link_f[CHAIN], chain_f[CHAIN];
static struct dbl_mat link_d[CHAIN], chain_d[CHAIN];

static void fx_chain(void *ctx)
{
	int r, i;

	for (r = 0; r < 16; r++) {
		chain_f[0] = link_f[0];
		for (i = 1; i < CHAIN; i++)
			mot_mat_mul(&chain_f[i], &link_f[i], &chain_f[i - 1], NULL);
	}
}

static void db_chain(void *ctx)
{
	int r, i;

	for (r = 0; r < 16; r++) {
		chain_d[0] = link_d[0];
		for (i = 1; i < CHAIN; i++)
			dbl_mat_mul(&chain_d[i], &link_d[i], &chain_d[i - 1]);
	}
}

/* ---- inputs ------------------------------------------------------------------------ */

static void rand_quat(struct tu_rng *r, struct mot_quat *q, struct dbl_quat *dq)
{
	double u1 = tu_uniform(r, 0, 1), u2 = tu_uniform(r, 0, 2 * M_PI);
	double u3 = tu_uniform(r, 0, 2 * M_PI);

	*q = (struct mot_quat){ d2q(sqrt(1 - u1) * sin(u2)), d2q(sqrt(1 - u1) * cos(u2)),
				d2q(sqrt(u1) * sin(u3)), d2q(sqrt(u1) * cos(u3)) };
	*dq = (struct dbl_quat){ q2d(q->w), q2d(q->x), q2d(q->y), q2d(q->z) };
}

/* S . H . R . T, the same matrix in both formats */
static void rand_mat(struct tu_rng *r, struct mot_mat *m, struct dbl_mat *dm)
{
	struct mot_decomp d;
	struct dbl_quat dq;
	int i, k;

	rand_quat(r, &d.rot, &dq);
	mot_quat_normalize(&d.rot, &d.rot, NULL);
	if (d.rot.w < 0)
		d.rot = (struct mot_quat){ -d.rot.w, -d.rot.x, -d.rot.y, -d.rot.z };
	for (k = 0; k < 3; k++) {
		d.scale[k] = d2q(exp(tu_uniform(r, log(0.5), log(2))));
		d.shear[k] = d2q(tu_uniform(r, -0.2, 0.2));
		d.translate[k] = d2q(tu_uniform(r, -100, 100));
	}
	mot_mat_compose(m, &d, NULL);
	for (i = 0; i < 4; i++)
		for (k = 0; k < 3; k++)
			dm->m[i][k] = q2d(m->m[i][k]);
}

static void inputs(void)
{
	struct tu_rng r = { 0x9e3779b97f4a7c15ull };
	int i, k;

	for (i = 0; i < NIN; i++) {
		double t = tu_uniform(&r, -4, 4);

		in.turns[i] = d2q(t);
		in.drad[i] = 2 * M_PI * q2d(in.turns[i]);
		in.y[i] = d2q(tu_uniform(&r, -100, 100));
		in.x[i] = d2q(tu_uniform(&r, -100, 100));
		in.c[i] = d2q(tu_uniform(&r, -0.99, 0.99));
		in.pos[i] = d2q(tu_uniform(&r, 1e-3, 1e4));
		in.dy[i] = q2d(in.y[i]);
		in.dx[i] = q2d(in.x[i]);
		in.dc[i] = q2d(in.c[i]);
		in.dpos[i] = q2d(in.pos[i]);
		rand_mat(&r, &in.ma[i], &in.da[i]);
		rand_mat(&r, &in.mb[i], &in.dbm[i]);
		rand_quat(&r, &in.qa[i], &in.dqa[i]);
		rand_quat(&r, &in.qb[i], &in.dqb[i]);
		for (k = 0; k < 3; k++) {
			in.pt[i][k] = d2q(tu_uniform(&r, -100, 100));
			in.dpt[i][k] = q2d(in.pt[i][k]);
		}
		in.tt[i] = (mot_q32)(tu_u64(&r) >> 32);
		in.dtt[i] = q2d(in.tt[i]);
	}
	for (i = 0; i < NIN; i++) {
		mot_slerp_prepare(&in.sl[i], &in.qa[i], &in.qb[i], NULL);
		dbl_slerp_prepare(&in.dsl[i], &in.dqa[i], &in.dqb[i]);
		mot_mat_decompose(&in.dc_[i], NULL, &in.ma[i], NULL);
		dbl_mat_decompose(&in.ddc[i], &in.da[i]);
	}
	for (i = 0; i < CHAIN; i++) {
		int j;

		mot_quat_to_mat(&link_f[i], &in.qa[i], NULL);
		for (k = 0; k < 3; k++)
			link_f[i].m[3][k] = d2q(tu_uniform(&r, -1, 1));
		for (k = 0; k < 4; k++)
			for (j = 0; j < 3; j++)
				link_d[i].m[k][j] = q2d(link_f[i].m[k][j]);
	}
}

/* ---- curves ------------------------------------------------------------------------ */

#define CURVE_KEYS 10

struct curve_run {
	struct scene_built b; /* one prismatic joint carrying the curve */
	struct mot_cursor cur;
	struct dbl_curve dc;
	struct dbl_cursor dcur;
	void *dmem;
	mot_q32 *frame;
	double *dframe;
	uint32_t n;
};

static void fx_curve(void *ctx)
{
	struct curve_run *c = ctx;
	const struct mot_curve *cv = &c->b.sc.curves[0];
	mot_q32 acc = 0;
	uint32_t k;

	for (k = 0; k < c->n; k++)
		acc += mot_curve_eval(cv, &c->cur, c->frame[k], NULL);
	bench_sink += (uint64_t)(int64_t)acc;
}

static void db_curve(void *ctx)
{
	struct curve_run *c = ctx;
	double acc = 0;
	uint32_t k;

	for (k = 0; k < c->n; k++)
		acc += dbl_curve_eval(&c->dc, &c->dcur, c->dframe[k]);
	bench_sink += (uint64_t)(int64_t)acc;
}

static int bench_curve(enum mot_interp kind, const char *name)
{
	struct tu_rng r = { 0xc0ffee + (uint64_t)kind };
	struct sd_key keys[CURVE_KEYS];
	struct sd_node node = { 0 };
	struct scene_desc d = { 0 };
	struct scene_build_err e;
	struct curve_run c = { 0 };
	struct bench_pair p;
	double f = 0, fps_per_tick = 24.0 / 1000;
	char pre[48];
	uint32_t i;

	for (i = 0; i < CURVE_KEYS; i++) {
		keys[i] = (struct sd_key){ .frame = f, .value = tu_uniform(&r, -100, 100) };
		f += tu_uniform(&r, 6, 40);
	}
	node = (struct sd_node){ .name = "c", .parent = -1, .kind = MOT_NODE_PRISMATIC,
				 .axis_id = MOT_AXIS_X, .axis = { 1, 0, 0 } };
	node.value = (struct sd_curve){ .interp = kind, .nkeys = CURVE_KEYS, .keys = keys,
					.beta1 = 1.5, .beta2 = 2 };
	d = (struct scene_desc){ .name = name, .rate_num = 24, .rate_den = 1, .tick_hz = 1000,
				 .nnodes = 1, .nodes = &node };
	c.dmem = malloc(dbl_curve_size(&node.value));
	c.n = (uint32_t)(keys[CURVE_KEYS - 1].frame / fps_per_tick);
	c.frame = calloc(c.n, sizeof(*c.frame));
	c.dframe = calloc(c.n, sizeof(*c.dframe));
	if (!c.dmem || !c.frame || !c.dframe || scene_build(&c.b, &d, &e) ||
	    dbl_curve_init(&c.dc, &node.value, 1, false, c.dmem))
		return -1;
	for (i = 0; i < c.n; i++) {
		c.frame[i] = mot_timing_tick_frame(&c.b.sc.timing, i);
		c.dframe[i] = q2d(c.frame[i]);
	}
	bench_run_pair(&p, fx_curve, db_curve, &c, c.n);
	snprintf(pre, sizeof(pre), "prim_curve_%s", name);
	bench_printf(pre, "_fixed", p.fixed_ns, "ns/call");
	bench_printf(pre, "_double", p.double_ns, "ns/call");
	if (kind >= MOT_INTERP_BSPLINE) {
		double itf = 0, itd = 0;

		for (i = 0; i < c.n; i++) {
			itf += mot_curve_newton_iterations(&c.b.sc.curves[0], c.frame[i]);
			itd += dbl_curve_newton_iterations(&c.dc, c.dframe[i]);
		}
		bench_printf(pre, "_newton_it_fixed", itf / c.n, "iterations/call");
		bench_printf(pre, "_newton_it_double", itd / c.n, "iterations/call");
	}
	scene_built_free(&c.b);
	free(c.dmem);
	free(c.frame);
	free(c.dframe);
	return 0;
}

/* ---- the table ----------------------------------------------------------------------- */

static void pair(const char *name, bench_batch_fn fx, bench_batch_fn db, double calls)
{
	struct bench_pair p;
	char pre[48];

	bench_run_pair(&p, fx, db, NULL, calls);
	snprintf(pre, sizeof(pre), "prim_%s", name);
	bench_printf(pre, "_fixed", p.fixed_ns, "ns/call");
	bench_printf(pre, "_double", p.double_ns, "ns/call");
}

int bench_primitives(void)
{
	static const char *const kind[] = { "step", "linear", "hermite", "bspline", "beta",
					    "bezier" };
	int bad = 0;
	unsigned k;

	inputs();
	pair("sincos", fx_sincos, db_sincos, NIN * ROUNDS);
	pair("atan2", fx_atan2, db_atan2, NIN * ROUNDS);
	pair("acos", fx_acos, db_acos, NIN * ROUNDS);
	pair("sqrt", fx_sqrt, db_sqrt, NIN * ROUNDS);
	pair("rsqrt", fx_rsqrt, db_rsqrt, NIN * ROUNDS);
	pair("mat_mul", fx_mul, db_mul, NIN * 16);
	pair("mat_mul_chain", fx_chain, db_chain, (CHAIN - 1) * 16);
	pair("mat_apply", fx_apply, db_apply, NIN * 16);
	pair("quat_to_mat", fx_to_mat, db_to_mat, NIN * 16);
	pair("slerp_prepare", fx_slerp_prep, db_slerp_prep, NIN * 4);
	pair("slerp_eval", fx_slerp_eval, db_slerp_eval, NIN * 16);
	pair("mat_decompose", fx_decompose, db_decompose, NIN * 2);
	/* prepared, never per tick: no double twin */
	bench_print("prim_mat_inverse_fixed", bench_run_one(fx_inverse, NULL, NIN * 2), "ns/call");
	pair("mat_compose", fx_compose, db_compose, NIN * 8);
	for (k = 0; k < sizeof(kind) / sizeof(kind[0]); k++)
		bad |= bench_curve((enum mot_interp)k, kind[k]);
	return bad;
}
