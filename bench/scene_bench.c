/* SPDX-License-Identifier: MIT */
/*
 * scene_bench.c - whole scenes: ns per tick of mot_scene_eval() against the
 * double twin (dbl_scene.h) on the same scene and the same ticks, and the
 * core's worst errors against tests/ref_scene.c.
 *
 * Scenes (tests/synth.c):
 *   arm         the paper's 5-joint robot arm, 1.5 m, hermite keys, 240
 *               frames at 24 fps played at 1 kHz, every tick;
 *   random1000  1,000 nodes: joints (revolute x/y/z/tilted, prismatic,
 *               spin) and free nodes (translate/scale/shear channels, slerp
 *               and squad tracks), every curve kind, some ease;
 *   joints1000  1,000 joints with linear and hermite keys: a rig's case;
 *   kind_<k>    1,000 joints all keyed with curve kind k: the cost of each.
 * The 1,000-node scenes play 96 frames at 1 kHz, every TICK_STRIDE-th tick
 * (cursors still move to the same or the next segment, as in playback).
 * "Per joint" divides a tick by the number of nodes, free nodes included.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "dbl_scene.h"
#include "motion_bench.h"
#include "scene/scene_desc.h"
#include "tests/ref_scene.h"
#include "tests/synth.h"

#define NODES 1000
#define FRAMES_1000 96
#define TICK_STRIDE 16 /* 1,000-node scenes: 250 ticks a repeat */
#define ERR_STRIDE 13  /* ticks between accuracy samples: ~300 of the span */
#define AGREE_TOL 1e-9 /* double twin against ref_scene, units and entries */
#define AGREE_TOL_ROTKEYS 2e-8 /* the same under a rotation track (struct errs) */

struct run {
	struct scene_built b;
	struct mot_eval ev;
	struct mot_pose pose;
	struct dbl_scene ds;
	struct dbl_eval dev;
	struct dbl_pose dp;
	mot_q32 *frame;  /* the ticks played, as the core sees them */
	double *dframe;  /* the same instants, exactly, for the twin */
	uint32_t nticks;
};

static int run_open(struct run *r, const struct scene_desc *d, int64_t stride)
{
	struct scene_build_err e;
	const struct mot_timing *t;
	int64_t k0, k1, k;

	if (scene_build(&r->b, d, &e)) {
		fprintf(stderr, "scene_bench: %s: scene_build: %d at node %d %s\n", d->name, e.code,
			e.node, e.what ? e.what : "");
		return -1;
	}
	if (scene_eval_new(&r->ev, &r->b.sc) || scene_pose_new(&r->pose, &r->b.sc) ||
	    dbl_scene_new(&r->ds, d) || dbl_eval_new(&r->dev, &r->ds) ||
	    dbl_pose_new(&r->dp, &r->ds)) {
		fprintf(stderr, "scene_bench: %s: cannot set up the scene\n", d->name);
		return -1;
	}
	t = &r->b.sc.timing;
	k0 = mot_timing_trigger_tick(t, (int64_t)d->frame_first);
	k1 = mot_timing_trigger_tick(t, (int64_t)d->frame_last);
	r->nticks = (uint32_t)((k1 - k0) / stride + 1);
	r->frame = calloc(r->nticks, sizeof(*r->frame));
	r->dframe = calloc(r->nticks, sizeof(*r->dframe));
	if (!r->frame || !r->dframe)
		return -1;
	for (k = 0; k < r->nticks; k++) {
		r->frame[k] = mot_timing_tick_frame(t, k0 + k * stride);
		r->dframe[k] = q2d(r->frame[k]);
	}
	return 0;
}

static void run_close(struct run *r)
{
	free(r->frame);
	free(r->dframe);
	dbl_pose_free(&r->dp);
	dbl_eval_free(&r->dev);
	dbl_scene_free(&r->ds);
	scene_pose_free(&r->pose);
	scene_eval_free(&r->ev);
	scene_built_free(&r->b);
}

static void play_fixed(void *ctx)
{
	struct run *r = ctx;
	uint32_t k;

	for (k = 0; k < r->nticks; k++)
		mot_scene_eval(&r->b.sc, &r->ev, r->frame[k], &r->pose);
	bench_sink += (uint64_t)r->pose.pos[r->b.sc.nnodes - 1][0];
}

static void play_double(void *ctx)
{
	struct run *r = ctx;
	uint32_t k;

	for (k = 0; k < r->nticks; k++)
		dbl_scene_eval(&r->ds, &r->dev, r->dframe[k], &r->dp);
	bench_sink += (uint64_t)(int64_t)r->dp.pos[r->ds.nnodes - 1][0];
}

/* Time one scene; per_node: divide by the node count too. */
static void time_scene(const char *name, struct run *r, bool per_node)
{
	double units = r->nticks * (per_node ? (double)r->b.sc.nnodes : 1.0);
	const char *unit = per_node ? "ns/joint/tick" : "ns/tick";
	struct bench_pair p;
	char pre[64];

	bench_run_pair(&p, play_fixed, play_double, r, units);
	snprintf(pre, sizeof(pre), "%s_%s", name, per_node ? "joint_tick" : "tick");
	bench_printf(pre, "_fixed", p.fixed_ns, unit);
	bench_printf(pre, "_double", p.double_ns, unit);
	bench_printf(pre, "_ratio_fixed_over_double", p.ratio, "x");
	if (r->ev.sat)
		printf("# %s: the core saturated (status %#x)\n", name, r->ev.sat);
}

/* ---- accuracy --------------------------------------------------------------------- */

/*
 * The twin's agreement with ref_scene is kept apart for nodes under a
 * rotation track. Quantised rotation keys are unit only to about 2^-32, and
 * ref_slerp (textbook: acos of the keys' dot product, sine weights) and the
 * core's slerp (atan2 of the Gram-Schmidt component, a cos + c sin), which
 * the twin follows, part on such keys by up to ~2^-32 / (arc angle) per
 * matrix entry: the reference's own uncertainty there, not different work.
 * Measured: with ref_slerp's formula in the twin the difference falls from
 * ~5e-9 to ~1e-10 m, what remains being acos(d) of non-unit keys.
 */
struct errs {
	double pos, rot, lin, joint;  /* fixed core against ref_scene */
	double pos_out;               /* ... outside rotation tracks */
	double dbl_pos, dbl_lin;      /* double twin against ref_scene ... */
	double dbl_pos_rk, dbl_lin_rk; /* ... under a rotation track */
};

static void from_dbl(struct ref_mat *out, const struct dbl_mat *m)
{
	int i, j;

	for (i = 0; i < 4; i++) {
		for (j = 0; j < 3; j++)
			out->m[i][j] = m->m[i][j];
		out->m[i][3] = i == 3;
	}
}

static double dist3(const double a[3], const double b[3])
{
	return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
		    (a[2] - b[2]) * (a[2] - b[2]));
}

static void worst(double *w, double e)
{
	if (e > *w || isnan(e))
		*w = e;
}

/* Every ERR_STRIDE-th tick of the scene's span (every tick with stride 1). */
static int measure(struct errs *e, const struct scene_desc *d, int64_t stride, bool rigid)
{
	struct ref_scene *ref = ref_scene_new(d);
	struct ref_pose rp;
	struct run r = { 0 };
	bool *rk = calloc(d->nnodes, sizeof(*rk));
	uint32_t k, i;

	*e = (struct errs){ 0 };
	if (!rk || !ref || ref_pose_new(&rp, d) || run_open(&r, d, stride))
		return -1;
	for (i = 0; i < d->nnodes; i++) {
		const struct sd_node *n = &d->nodes[i];

		rk[i] = (n->kind == MOT_NODE_FREE && n->has_free && n->free.nrot) ||
			(n->parent >= 0 && rk[n->parent]);
	}
	for (k = 0; k < r.nticks; k++) {
		mot_scene_eval(&r.b.sc, &r.ev, r.frame[k], &r.pose);
		dbl_scene_eval(&r.ds, &r.dev, r.dframe[k], &r.dp);
		ref_scene_eval(ref, r.frame[k], &rp);
		for (i = 0; i < d->nnodes; i++) {
			struct ref_mat wf, wd;
			double pf[3] = { q2d(r.pose.pos[i][0]), q2d(r.pose.pos[i][1]),
					 q2d(r.pose.pos[i][2]) };
			double dv = q2d(r.pose.value[i]) - rp.value[i];

			ref_from_mat(&wf, &r.pose.world[i]);
			from_dbl(&wd, &r.dp.world[i]);
			worst(&e->pos, dist3(pf, rp.pos[i]));
			if (!rk[i])
				worst(&e->pos_out, dist3(pf, rp.pos[i]));
			worst(&e->lin, ref_lin_diff(&wf, &rp.world[i]));
			if (rigid)
				worst(&e->rot, ref_rot_angle_diff(&wf, &rp.world[i]));
			if (d->nodes[i].kind == MOT_NODE_REVOLUTE)
				worst(&e->joint, fabs(dv) * 2 * M_PI);
			worst(rk[i] ? &e->dbl_pos_rk : &e->dbl_pos, dist3(r.dp.pos[i], rp.pos[i]));
			worst(rk[i] ? &e->dbl_lin_rk : &e->dbl_lin,
			      ref_lin_diff(&wd, &rp.world[i]));
		}
	}
	if (r.ev.sat)
		printf("# %s: the core saturated (status %#x)\n", d->name, r.ev.sat);
	run_close(&r);
	ref_pose_free(&rp);
	ref_scene_free(ref);
	free(rk);
	return 0;
}

/* Print the core's errors and the twin's agreement; -1 when the twin
 * disagrees with the reference (then its timings compare nothing). */
static int report(const char *name, const struct errs *e, bool rigid)
{
	bench_printf(name, "_pos_err_fixed", e->pos, "m");
	if (rigid)
		bench_printf(name, "_rot_err_fixed", e->rot, "rad");
	else
		bench_printf(name, "_lin_err_fixed", e->lin, "entry");
	bench_printf(name, "_joint_err_fixed", e->joint, "rad");
	bench_printf(name, "_double_vs_ref_pos", e->dbl_pos, "m");
	bench_printf(name, "_double_vs_ref_lin", e->dbl_lin, "entry");
	if (e->dbl_pos_rk > 0 || e->dbl_lin_rk > 0) {
		bench_printf(name, "_pos_err_fixed_outside_rotkeys", e->pos_out, "m");
		bench_printf(name, "_double_vs_ref_pos_rotkeys", e->dbl_pos_rk, "m");
		bench_printf(name, "_double_vs_ref_lin_rotkeys", e->dbl_lin_rk, "entry");
	}
	if (e->dbl_pos <= AGREE_TOL && e->dbl_lin <= AGREE_TOL &&
	    e->dbl_pos_rk <= AGREE_TOL_ROTKEYS && e->dbl_lin_rk <= AGREE_TOL_ROTKEYS)
		return 0;
	fprintf(stderr, "scene_bench: %s: the double twin is %.3g m / %.3g (%.3g m / %.3g under "
		"rotation tracks) from ref_scene, above %g (%g): its timings are not of the same "
		"work\n", name, e->dbl_pos, e->dbl_lin, e->dbl_pos_rk, e->dbl_lin_rk, AGREE_TOL,
		AGREE_TOL_ROTKEYS);
	return -1;
}

/* ---- the scenes --------------------------------------------------------------------- */

static int bench_arm(void)
{
	static const double scale[2] = { 1, 60 };
	struct synth sy;
	struct errs e;
	struct run r = { 0 };
	int bad = 0, s;

	synth_robot_arm(&sy, 1, 240);
	if (run_open(&r, &sy.d, 1))
		return -1;
	time_scene("arm", &r, false);
	run_close(&r);
	synth_free(&sy);
	for (s = 0; s < 2; s++) {
		char name[32];

		synth_robot_arm(&sy, scale[s], 240);
		if (measure(&e, &sy.d, 1, true))
			return -1;
		snprintf(name, sizeof(name), "arm_x%g", scale[s]);
		bad |= report(name, &e, true);
		synth_free(&sy);
	}
	return bad;
}

static int bench_1000(const char *name, struct synth *sy, bool rigid, bool errors)
{
	struct run r = { 0 };
	struct errs e;
	int bad = 0;

	if (run_open(&r, &sy->d, TICK_STRIDE))
		return -1;
	time_scene(name, &r, true);
	run_close(&r);
	if (errors) {
		if (measure(&e, &sy->d, ERR_STRIDE, rigid))
			return -1;
		bad = report(name, &e, rigid);
	}
	synth_free(sy);
	return bad;
}

int bench_scenes(void)
{
	static const char *const kind[] = { "step", "linear", "hermite", "bspline", "beta",
					    "bezier" };
	struct synth sy;
	int bad = 0;
	unsigned k;

	bad |= bench_arm();
	synth_random(&sy, 1, NODES, FRAMES_1000);
	bad |= bench_1000("random1000", &sy, false, true);
	synth_joints(&sy, 1, NODES, FRAMES_1000,
		     1u << MOT_INTERP_LINEAR | 1u << MOT_INTERP_HERMITE);
	bad |= bench_1000("joints1000", &sy, true, true);
	for (k = 0; k < sizeof(kind) / sizeof(kind[0]); k++) {
		char name[32];

		snprintf(name, sizeof(name), "kind_%s1000", kind[k]);
		synth_joints(&sy, 1, NODES, FRAMES_1000, 1u << k);
		bad |= bench_1000(name, &sy, true, false);
	}
	return bad;
}
