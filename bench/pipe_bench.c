/* SPDX-License-Identifier: MIT */
/*
 * pipe_bench.c - the seed paper's two-key matrix pipeline: decompose both
 * key matrices once (and prepare their slerp), then for each in-between
 * interpolate translation, scale and shear linearly and rotation by slerp,
 * and recompose. Fixed point (mot_mat_decompose, mot_slerp_prepare once;
 * mot_slerp_eval and mot_mat_compose per in-between) against the same
 * pipeline in double (dbl_mat.h), and the fixed pipeline's error against
 * the double one. The double pipeline is itself checked against the tests'
 * reference (ref_decompose, ref_slerp, ref_compose).
 *
 * Keys: S . H . R . T with scales log-uniform in [0.5, 2], shears in
 * [-0.2, 0.2], uniform random rotations and translations in [-100, 100]
 * (the paper's |t| <= 100), quantised to Q32.32 so that both pipelines start
 * from the same numbers.
 */
#include <math.h>
#include <stdio.h>

#include "bench.h"
#include "dbl_mat.h"
#include "motion/decomp.h"
#include "motion_bench.h"
#include "scene/scene_desc.h"
#include "tests/ref_mat.h"

#define NPAIR 256   /* key pairs */
#define NSTEP 64    /* in-betweens per pair, t = j / NSTEP */
#define TOL_REF 1e-9 /* double pipeline against ref_mat, per entry at |t| <= 100 */

struct fx_pair {
	struct mot_decomp a;
	mot_q32 dt[3], ds[3], dh[3]; /* b - a */
	struct mot_slerp rot;
};

struct db_pair {
	struct dbl_decomp a;
	double dt[3], ds[3], dh[3];
	struct dbl_slerp rot;
};

static struct fx_pair fx[NPAIR];
static struct db_pair db[NPAIR];
static struct mot_mat fx_out[NPAIR][NSTEP];
static struct dbl_mat db_out[NPAIR][NSTEP];
static struct mot_quat fx_q[NPAIR][NSTEP];
static struct dbl_quat db_q[NPAIR][NSTEP];

/* One in-between of pair p at t = j / NSTEP; q: the rotation, kept for the
 * error. */
static void fx_between(struct mot_mat *out, struct mot_quat *q, const struct fx_pair *p, int j)
{
	mot_q32 t = (mot_q32)j * (MOT_Q32_ONE / NSTEP);
	struct mot_decomp d;
	int k;

	for (k = 0; k < 3; k++) {
		d.translate[k] = p->a.translate[k] + mot_mul(p->dt[k], t, NULL);
		d.scale[k] = p->a.scale[k] + mot_mul(p->ds[k], t, NULL);
		d.shear[k] = p->a.shear[k] + mot_mul(p->dh[k], t, NULL);
	}
	mot_slerp_eval(&d.rot, &p->rot, t, NULL);
	mot_mat_compose(out, &d, NULL);
	*q = d.rot;
}

static void db_between(struct dbl_mat *out, struct dbl_quat *q, const struct db_pair *p, int j)
{
	double t = (double)j / NSTEP;
	struct dbl_decomp d;
	int k;

	for (k = 0; k < 3; k++) {
		d.translate[k] = p->a.translate[k] + p->dt[k] * t;
		d.scale[k] = p->a.scale[k] + p->ds[k] * t;
		d.shear[k] = p->a.shear[k] + p->dh[k] * t;
	}
	dbl_slerp_eval(&d.rot, &p->rot, t);
	dbl_mat_compose(out, &d);
	*q = d.rot;
}

static void batch_fixed(void *ctx)
{
	int p, j;

	for (p = 0; p < NPAIR; p++)
		for (j = 0; j < NSTEP; j++)
			fx_between(&fx_out[p][j], &fx_q[p][j], &fx[p], j);
}

static void batch_double(void *ctx)
{
	int p, j;

	for (p = 0; p < NPAIR; p++)
		for (j = 0; j < NSTEP; j++)
			db_between(&db_out[p][j], &db_q[p][j], &db[p], j);
}

/* A random key, the same matrix for both pipelines. */
static void rand_key(struct tu_rng *r, struct mot_mat *m, struct dbl_mat *dm)
{
	struct dbl_decomp d;
	double u1 = tu_uniform(r, 0, 1), u2 = tu_uniform(r, 0, 2 * M_PI);
	double u3 = tu_uniform(r, 0, 2 * M_PI);
	int i, k;

	d.rot = (struct dbl_quat){ sqrt(1 - u1) * sin(u2), sqrt(1 - u1) * cos(u2),
				   sqrt(u1) * sin(u3), sqrt(u1) * cos(u3) };
	for (k = 0; k < 3; k++) {
		d.scale[k] = exp(tu_uniform(r, log(0.5), log(2)));
		d.shear[k] = tu_uniform(r, -0.2, 0.2);
		d.translate[k] = tu_uniform(r, -100, 100);
	}
	dbl_mat_compose(dm, &d);
	for (i = 0; i < 4; i++)
		for (k = 0; k < 3; k++) {
			sd_to_q32(dm->m[i][k], &m->m[i][k]);
			dm->m[i][k] = q2d(m->m[i][k]);
		}
}

/* The same in-between by the tests' reference formulas, for the check. */
static void ref_between(struct ref_mat *out, const struct dbl_mat *ka, const struct dbl_mat *kb,
			double t)
{
	struct ref_mat ma, mb, r;
	struct ref_decomp a, b, d;
	struct ref_quat qa, qb, q;
	int i, k;

	for (i = 0; i < 4; i++)
		for (k = 0; k < 4; k++) {
			ma.m[i][k] = k < 3 ? ka->m[i][k] : i == 3;
			mb.m[i][k] = k < 3 ? kb->m[i][k] : i == 3;
		}
	ref_decompose(&a, &ma);
	ref_decompose(&b, &mb);
	for (i = 0; i < 4; i++)
		for (k = 0; k < 4; k++)
			ma.m[i][k] = mb.m[i][k] = i == k;
	for (i = 0; i < 3; i++)
		for (k = 0; k < 3; k++) {
			ma.m[i][k] = a.rot[i][k];
			mb.m[i][k] = b.rot[i][k];
		}
	ref_quat_from_mat(&qa, &ma);
	ref_quat_from_mat(&qb, &mb);
	ref_slerp(&q, &qa, &qb, t);
	ref_quat_to_mat(&r, &q);
	for (k = 0; k < 3; k++) {
		d.translate[k] = a.translate[k] + (b.translate[k] - a.translate[k]) * t;
		d.scale[k] = a.scale[k] + (b.scale[k] - a.scale[k]) * t;
		d.shear[k] = a.shear[k] + (b.shear[k] - a.shear[k]) * t;
		for (i = 0; i < 3; i++)
			d.rot[k][i] = r.m[k][i];
	}
	ref_compose(out, &d);
}

/* Angle between two rotations given as unit quaternions (q and -q equal). */
static double quat_angle(const struct mot_quat *a, const struct dbl_quat *b)
{
	double w = q2d(a->w), x = q2d(a->x), y = q2d(a->y), z = q2d(a->z);
	double s = w * b->w + x * b->x + y * b->y + z * b->z < 0 ? -1 : 1;
	double dw = w - s * b->w, dx = x - s * b->x, dy = y - s * b->y, dz = z - s * b->z;
	double pw = w + s * b->w, px = x + s * b->x, py = y + s * b->y, pz = z + s * b->z;

	return 4 * atan2(sqrt(dw * dw + dx * dx + dy * dy + dz * dz),
			 sqrt(pw * pw + px * px + py * py + pz * pz));
}

/* Errors of the fixed pipeline against the double one, and of the double
 * one against ref_mat. */
static int errors(const struct dbl_mat ka[NPAIR], const struct dbl_mat kb[NPAIR])
{
	double et = 0, ep = 0, er = 0, eref = 0;
	int p, j, i, k;

	for (p = 0; p < NPAIR; p++) {
		for (j = 0; j < NSTEP; j++) {
			const struct mot_mat *f = &fx_out[p][j];
			const struct dbl_mat *d = &db_out[p][j];
			struct ref_mat rr;

			for (k = 0; k < 3; k++) {
				/* worst displacement of a point of the cube |x| <= 100 */
				double disp = fabs(q2d(f->m[3][k]) - d->m[3][k]);

				et = fmax(et, disp);
				for (i = 0; i < 3; i++)
					disp += 100 * fabs(q2d(f->m[i][k]) - d->m[i][k]);
				ep = fmax(ep, disp);
			}
			er = fmax(er, quat_angle(&fx_q[p][j], &db_q[p][j]));
			if (j % 8)
				continue;
			ref_between(&rr, &ka[p], &kb[p], (double)j / NSTEP);
			for (i = 0; i < 4; i++)
				for (k = 0; k < 3; k++)
					eref = fmax(eref, fabs(rr.m[i][k] - d->m[i][k]) *
								  (i < 3 ? 100 : 1));
		}
	}
	bench_print("pipe_translation_err_fixed", et, "m");
	bench_print("pipe_point_err_fixed_at_100", ep, "m");
	bench_print("pipe_rotation_err_fixed", er, "rad");
	bench_print("pipe_double_vs_ref_at_100", eref, "m");
	if (eref <= TOL_REF)
		return 0;
	fprintf(stderr, "pipe_bench: the double pipeline is %.3g m from ref_mat's\n", eref);
	return -1;
}

int bench_pipeline(void)
{
	static struct dbl_mat ka[NPAIR], kb[NPAIR];
	struct tu_rng rng = { 0x70a1e5eedull };
	struct bench_pair t;
	int p, k;

	for (p = 0; p < NPAIR; p++) {
		struct mot_mat ma, mb;
		struct mot_decomp b;
		struct dbl_decomp dbb;

		rand_key(&rng, &ma, &ka[p]);
		rand_key(&rng, &mb, &kb[p]);
		if (mot_mat_decompose(&fx[p].a, NULL, &ma, NULL) ||
		    mot_mat_decompose(&b, NULL, &mb, NULL) || dbl_mat_decompose(&db[p].a, &ka[p]) ||
		    dbl_mat_decompose(&dbb, &kb[p]))
			return -1;
		for (k = 0; k < 3; k++) {
			fx[p].dt[k] = b.translate[k] - fx[p].a.translate[k];
			fx[p].ds[k] = b.scale[k] - fx[p].a.scale[k];
			fx[p].dh[k] = b.shear[k] - fx[p].a.shear[k];
			db[p].dt[k] = dbb.translate[k] - db[p].a.translate[k];
			db[p].ds[k] = dbb.scale[k] - db[p].a.scale[k];
			db[p].dh[k] = dbb.shear[k] - db[p].a.shear[k];
		}
		mot_slerp_prepare(&fx[p].rot, &fx[p].a.rot, &b.rot, NULL);
		dbl_slerp_prepare(&db[p].rot, &db[p].a.rot, &dbb.rot);
	}
	bench_run_pair(&t, batch_fixed, batch_double, NULL, NPAIR * NSTEP);
	bench_print("pipe_inbetween_fixed", t.fixed_ns, "ns/inbetween");
	bench_print("pipe_inbetween_double", t.double_ns, "ns/inbetween");
	bench_print("pipe_inbetween_ratio_fixed_over_double", t.ratio, "x");
	return errors(ka, kb);
}
