/* SPDX-License-Identifier: MIT */
/*
 * test_scene.c - whole scenes end to end against the floating-point
 * reference (ref_scene.c): the paper's 5-joint robot arm at 1.5 m and at
 * 90 m, random hierarchies with every node, key and curve kind, a spin after
 * 24 hours, a camera panning through +-180 degrees, sequential against
 * random access, and the API's answers to bad input.
 */
#include "testutil.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "motion/arena.h"
#include "ref_scene.h"
#include "scene/scene_desc.h"
#include "synth.h"

struct run {
	struct scene_built b;
	struct mot_eval ev;
	struct mot_pose pose;
	struct ref_scene *ref;
	struct ref_pose rp;
};

static void run_open(struct run *r, const struct scene_desc *d)
{
	struct scene_build_err e;
	int err = scene_build(&r->b, d, &e);

	if (err)
		fail_msg("scene_build: %d at node %d %s key %u", err, e.node, e.what ? e.what : "",
			 e.key);
	assert_int_equal(scene_eval_new(&r->ev, &r->b.sc), 0);
	assert_int_equal(scene_pose_new(&r->pose, &r->b.sc), 0);
	r->ref = ref_scene_new(d);
	assert_non_null(r->ref);
	assert_int_equal(ref_pose_new(&r->rp, d), 0);
}

static void run_close(struct run *r)
{
	ref_pose_free(&r->rp);
	ref_scene_free(r->ref);
	scene_pose_free(&r->pose);
	scene_eval_free(&r->ev);
	scene_built_free(&r->b);
}

static void mat_from_fixed(struct ref_mat *out, const struct mot_mat *m)
{
	ref_from_mat(out, m);
}

/*
 * Every tick (or every `step` ticks) of the scene's span: world pivot
 * positions (m), world rotations (rad, joint-only scenes) or linear-part
 * entries (scenes with scale and shear), joint values (turns).
 */
static void compare(struct run *r, const struct scene_desc *d, int64_t step, bool rigid,
		    struct tu_worst *wpos, struct tu_worst *wrot, struct tu_worst *wval)
{
	const struct mot_timing *t = &r->b.sc.timing;
	int64_t k0 = mot_timing_trigger_tick(t, (int64_t)d->frame_first);
	int64_t k1 = mot_timing_trigger_tick(t, (int64_t)d->frame_last);
	int64_t k;
	uint32_t i, j;

	for (k = k0; k <= k1; k += step) {
		mot_q32 f = mot_timing_tick_frame(t, k);

		mot_scene_eval(&r->b.sc, &r->ev, f, &r->pose);
		ref_scene_eval(r->ref, f, &r->rp);
		for (i = 0; i < d->nnodes; i++) {
			struct ref_mat w;

			mat_from_fixed(&w, &r->pose.world[i]);
			for (j = 0; j < 3; j++)
				tu_worst_add(wpos, q2d(r->pose.pos[i][j]) - r->rp.pos[i][j],
					     (double)k);
			if (rigid)
				tu_worst_add(wrot, ref_rot_angle_diff(&w, &r->rp.world[i]), (double)k);
			else
				tu_worst_add(wrot, ref_lin_diff(&w, &r->rp.world[i]), (double)k);
			if (d->nodes[i].kind != MOT_NODE_FREE) {
				double v = q2d(r->pose.value[i]), rv = r->rp.value[i];

				/* revolute values in turns: compare as angles (rad) */
				if (d->nodes[i].kind == MOT_NODE_REVOLUTE)
					tu_worst_add(wval, (v - rv) * 2 * M_PI, (double)k);
				else
					tu_worst_add(wval, v - rv, (double)k);
			}
		}
	}
	assert_int_equal(r->ev.sat, 0);
}

/* The precision goal: a 5-joint chain within 1e-6 rad and 1 um of a
 * double reference over a +-100 m workspace. */
static void test_robot_arm(void **state)
{
	static const double scales[] = { 1.0, 60.0 };
	size_t s;

	for (s = 0; s < 2; s++) {
		struct synth sy;
		struct run r;
		struct tu_worst wp = { 0, 0 }, wr = { 0, 0 }, wv = { 0, 0 };
		char name[64];

		synth_robot_arm(&sy, scales[s], 240);
		run_open(&r, &sy.d);
		compare(&r, &sy.d, 1, true, &wp, &wr, &wv);
		snprintf(name, sizeof(name), "scene.robot_arm_x%g.position", scales[s]);
		tu_bound(name, &wp, 1e-6, "m");
		snprintf(name, sizeof(name), "scene.robot_arm_x%g.rotation", scales[s]);
		tu_bound(name, &wr, 1e-6, "rad");
		snprintf(name, sizeof(name), "scene.robot_arm_x%g.joint", scales[s]);
		tu_bound(name, &wv, 1e-8, "rad");
		run_close(&r);
		synth_free(&sy);
	}
}

/* Random hierarchies: every node kind, every key and curve kind, slerp and
 * squad, ease. Scale and shear make rotation angles meaningless for free
 * nodes, so the linear part is compared entry by entry. */
static void test_random(void **state)
{
	struct tu_worst wp = { 0, 0 }, wl = { 0, 0 }, wv = { 0, 0 };
	uint64_t seed;

	for (seed = 1; seed <= 6; seed++) {
		struct synth sy;
		struct run r;

		synth_random(&sy, seed, 120, 96);
		run_open(&r, &sy.d);
		compare(&r, &sy.d, 7, false, &wp, &wl, &wv);
		run_close(&r);
		synth_free(&sy);
	}
	tu_bound("scene.random.position", &wp, 1e-6, "units");
	tu_bound("scene.random.linear", &wl, 1e-7, "entry");
	tu_bound("scene.random.joint", &wv, 1e-8, "rad or units");
}

/* Playback with cursors and random access give the same bits. */
static void test_random_access(void **state)
{
	struct synth sy;
	struct scene_built b;
	struct mot_eval seq, rnd;
	struct mot_pose p1, p2;
	struct tu_rng rng;
	struct scene_build_err e;
	const struct mot_timing *t;
	int64_t k, n;
	uint32_t i, j;

	synth_random(&sy, 42, 200, 120);
	assert_int_equal(scene_build(&b, &sy.d, &e), 0);
	t = &b.sc.timing;
	assert_int_equal(scene_eval_new(&seq, &b.sc), 0);
	assert_int_equal(scene_eval_new(&rnd, &b.sc), 0);
	assert_int_equal(scene_pose_new(&p1, &b.sc), 0);
	assert_int_equal(scene_pose_new(&p2, &b.sc), 0);
	tu_seed(&rng, 7);
	n = mot_timing_trigger_tick(t, 130);
	for (k = -200; k < n; k++) {
		mot_q32 f = mot_timing_tick_frame(t, k);
		mot_q32 g = mot_timing_tick_frame(t, (int64_t)(tu_u64(&rng) % (uint64_t)n));

		mot_scene_eval(&b.sc, &seq, f, &p1);
		/* the random evaluator jumps somewhere else first */
		mot_scene_eval(&b.sc, &rnd, g, &p2);
		mot_scene_eval(&b.sc, &rnd, f, &p2);
		for (i = 0; i < b.sc.nnodes; i++) {
			for (j = 0; j < 3; j++)
				assert_int_equal(p1.pos[i][j], p2.pos[i][j]);
			assert_memory_equal(&p1.world[i], &p2.world[i], sizeof(p1.world[i]));
			assert_int_equal(p1.value[i], p2.value[i]);
		}
	}
	scene_pose_free(&p1);
	scene_pose_free(&p2);
	scene_eval_free(&seq);
	scene_eval_free(&rnd);
	scene_built_free(&b);
	synth_free(&sy);
}

static void assert_same_pose(const struct mot_scene *sc, const struct mot_pose *a,
			     const struct mot_pose *b)
{
	uint32_t i;

	for (i = 0; i < sc->nnodes; i++) {
		assert_memory_equal(a->pos[i], b->pos[i], sizeof(a->pos[i]));
		assert_memory_equal(&a->world[i], &b->world[i], sizeof(a->world[i]));
		assert_int_equal(a->value[i], b->value[i]);
		assert_int_equal(a->rpm[i], b->rpm[i]);
	}
}

/*
 * The evaluation's shortcuts give the bits of the long way (scene.c): a
 * warm memo that keeps the matrices of nodes that did not move and the
 * sines of joints whose value did not, and the kernels without overflow
 * tests of the small case, against an evaluation reset before every tick
 * (cold) with the small case switched off, and a joint's curve from the
 * memo's piece, learnt at another frame, and a free node's channels on
 * their own way (MOT_MEMO_FREE_OWN), against the cold evaluation's
 * mot_curve_eval(). Two evaluations taking turns at one pose must not
 * trust each other's work. Every scene kind, every tick of a third, then
 * ticks in a scrambled order (random access); the shortcuts must be taken,
 * or this tests nothing.
 */
/* Every pivot of a synthetic scene moved onto a coordinate line (a rig's
 * links along an axis), every fifth to the origin: the revolute joints'
 * kernel for a pivot on one line (scene.c's revolute_line()). */
static void pivots_on_lines(struct synth *sy)
{
	uint32_t i, k;

	for (i = 0; i < sy->d.nnodes; i++) {
		/* synth's own allocation: writable */
		struct sd_node *nd = (struct sd_node *)&sy->d.nodes[i];

		for (k = 0; k < 3; k++)
			if (k != i % 3 || i % 5 == 0)
				nd->pivot[k] = 0;
	}
}

/*
 * The pivot's pre-scale at its edge (scene.c's PRE_SHIFT, x86-64): a pivot
 * component of 2 - 2^-32 units (raw 2^33 - 1) takes it, one of 2 units
 * does not; on a line and off one, the same bits as the tested kernels
 * and as the small kernels without it.
 */
static void test_pre_edge(void **state)
{
	static const double edge[4][3] = {
		{ 2 - 0x1p-32, -(2 - 0x1p-32), 0.5 }, /* pre */
		{ 2, 0.25, 0 },                        /* not */
		{ 0, -2, 0 },                          /* not, on a line */
		{ 0, 0, 2 - 0x1p-32 },                 /* pre, on a line */
	};
	struct synth sy;
	struct scene_built b;
	struct scene_build_err e;
	struct mot_eval warm, cold, plain;
	struct mot_pose pw, pc;
	uint32_t i, k, pre[4] = { 0 }, small[4] = { 0 };
	int64_t tk, n;

	(void)state;
	synth_joints(&sy, 21, 200, 96, 0);
	for (i = 0; i < sy.d.nnodes; i++) {
		struct sd_node *nd = (struct sd_node *)&sy.d.nodes[i];

		for (k = 0; k < 3; k++)
			nd->pivot[k] = edge[i % 4][k];
	}
	assert_int_equal(scene_build(&b, &sy.d, &e), 0);
	assert_int_equal(scene_eval_new(&warm, &b.sc), 0);
	assert_int_equal(scene_eval_new(&cold, &b.sc), 0);
	assert_int_equal(scene_eval_new(&plain, &b.sc), 0);
	assert_int_equal(scene_pose_new(&pw, &b.sc), 0);
	assert_int_equal(scene_pose_new(&pc, &b.sc), 0);
	for (i = 0; i < b.sc.nnodes; i++) {
		pre[i % 4] += warm.memo[i].pre;
		small[i % 4] += warm.memo[i].small;
	}
#if defined(__x86_64__)
	assert_true(pre[0] > 0 && pre[0] == small[0]);
	assert_true(pre[3] > 0 && pre[3] == small[3]);
#else
	assert_int_equal(pre[0] + pre[3], 0);
#endif
	assert_int_equal(pre[1] + pre[2], 0);
	assert_true(small[1] > 0 && small[2] > 0);
	n = mot_timing_trigger_tick(&b.sc.timing, 100);
	for (tk = -5; tk < n; tk += 7) {
		mot_q32 f = mot_timing_tick_frame(&b.sc.timing, tk);

		mot_scene_eval(&b.sc, &warm, f, &pw);
		assert_int_equal(mot_eval_reset(&cold, &b.sc), MOT_OK);
		assert_int_equal(mot_eval_reset(&plain, &b.sc), MOT_OK);
		for (i = 0; i < b.sc.nnodes; i++) {
			cold.memo[i].small = 0;
			cold.memo[i].pre = 0;
			plain.memo[i].pre = 0;
		}
		mot_scene_eval(&b.sc, &cold, f, &pc);
		assert_same_pose(&b.sc, &pw, &pc);
		mot_scene_eval(&b.sc, &plain, f, &pc);
		assert_same_pose(&b.sc, &pw, &pc);
	}
	assert_int_equal(warm.sat, 0);
	scene_pose_free(&pw);
	scene_pose_free(&pc);
	scene_eval_free(&warm);
	scene_eval_free(&cold);
	scene_eval_free(&plain);
	scene_built_free(&b);
	synth_free(&sy);
}

/* A free node with scale or shear channels and no rotation: S . H is
 * lower-triangular (scene.c's node_world_in(), tri). */
static bool free_scales_only(const struct mot_scene *sc, const struct mot_node *n)
{
	const struct mot_free_strand *fs;
	uint32_t k;

	if (n->kind != MOT_NODE_FREE || n->strand < 0)
		return false;
	fs = &sc->free[n->strand];
	if (fs->rot >= 0 || fs->quat[0] >= 0)
		return false;
	for (k = MOT_FREE_SX; k < MOT_FREE_NCHANNELS; k++)
		if (fs->channel[k] >= 0)
			return true;
	return false;
}

static void test_shortcuts(void **state)
{
	struct synth sy;
	uint32_t kind;

	for (kind = 0; kind < 4; kind++) {
		struct scene_built b;
		struct scene_build_err e;
		struct mot_eval warm, cold, one, other, plain;
		struct mot_pose pw, pc, shared;
		const struct mot_timing *t;
		uint32_t i, kept = 0, small = 0, total = 0, pieces = 0, line = 0, tri = 0, own = 0;
		uint32_t pre = 0;
		int64_t k, n;

		if (kind == 0)
			synth_random(&sy, 3, 300, 96);
		else if (kind == 1)
			synth_joints(&sy, 5, 300, 96, 0);
		else if (kind == 2)
			synth_joints(&sy, 9, 300, 96, 1u << MOT_INTERP_STEP);
		else
			synth_joints(&sy, 13, 300, 96, 0);
		if (kind == 3)
			pivots_on_lines(&sy);
		assert_int_equal(scene_build(&b, &sy.d, &e), 0);
		t = &b.sc.timing;
		assert_int_equal(scene_eval_new(&warm, &b.sc), 0);
		assert_int_equal(scene_eval_new(&cold, &b.sc), 0);
		assert_int_equal(scene_eval_new(&one, &b.sc), 0);
		assert_int_equal(scene_eval_new(&other, &b.sc), 0);
		assert_int_equal(scene_eval_new(&plain, &b.sc), 0);
		assert_int_equal(scene_pose_new(&pw, &b.sc), 0);
		assert_int_equal(scene_pose_new(&pc, &b.sc), 0);
		assert_int_equal(scene_pose_new(&shared, &b.sc), 0);
		for (i = 0; i < b.sc.nnodes; i++) {
			small += warm.memo[i].small;
			pre += warm.memo[i].pre;
			assert_true(!warm.memo[i].pre || warm.memo[i].small);
			line += warm.memo[i].small && warm.memo[i].prow < 3 &&
				b.sc.nodes[i].kind == MOT_NODE_REVOLUTE &&
				b.sc.nodes[i].axis_id != MOT_AXIS_VEC;
			tri += warm.memo[i].small && free_scales_only(&b.sc, &b.sc.nodes[i]);
			own += !!(warm.memo[i].free & MOT_MEMO_FREE_OWN);
		}
		n = mot_timing_trigger_tick(t, 100);
		for (k = -5; k < n; k += 3) {
			mot_q32 f = mot_timing_tick_frame(t, k);

			mot_scene_eval(&b.sc, &warm, f, &pw);
			for (i = 0; i < b.sc.nnodes; i++) {
				kept += !warm.memo[i].moved;
				pieces += warm.memo[i].lo < warm.memo[i].hi;
			}
			total += b.sc.nnodes;
			assert_int_equal(mot_eval_reset(&cold, &b.sc), MOT_OK);
			for (i = 0; i < b.sc.nnodes; i++) {
				cold.memo[i].small = 0;
				/* a free node's channels by mot_curve_eval() */
				cold.memo[i].free &= (uint8_t)~MOT_MEMO_FREE_OWN;
			}
			mot_scene_eval(&b.sc, &cold, f, &pc);
			assert_same_pose(&b.sc, &pw, &pc);
			/* the small kernels without the pivot's pre-scale */
			assert_int_equal(mot_eval_reset(&plain, &b.sc), MOT_OK);
			for (i = 0; i < b.sc.nnodes; i++)
				plain.memo[i].pre = 0;
			mot_scene_eval(&b.sc, &plain, f, &pc);
			assert_same_pose(&b.sc, &pw, &pc);
			/* a memo follows its own pose: another evaluation
			 * writing it in between (at another frame) is noticed */
			mot_scene_eval(&b.sc, &one, f, &shared);
			mot_scene_eval(&b.sc, &other, mot_timing_tick_frame(t, k / 2), &shared);
			mot_scene_eval(&b.sc, &one, f, &shared);
			assert_same_pose(&b.sc, &pw, &shared);
		}
		for (k = 0; k < 300; k++) {
			/* back and forth: every span the memo learnt is the curve's */
			mot_q32 f = mot_timing_tick_frame(t, (k * 7919) % n - 5);

			mot_scene_eval(&b.sc, &warm, f, &pw);
			assert_int_equal(mot_eval_reset(&cold, &b.sc), MOT_OK);
			for (i = 0; i < b.sc.nnodes; i++)
				cold.memo[i].free &= (uint8_t)~MOT_MEMO_FREE_OWN;
			mot_scene_eval(&b.sc, &cold, f, &pc);
			assert_same_pose(&b.sc, &pw, &pc);
		}
		assert_int_equal(warm.sat, 0);
		assert_int_equal(cold.sat, 0);
		/* the small case covers most nodes; the memo keeps some */
		assert_true(small > b.sc.nnodes / 2 || kind == 0);
		assert_true(small > 0);
#if defined(__x86_64__)
		/* pivots within 2 units (every synthetic scene's): pre-scaled */
		assert_true(pre > small / 2);
#else
		assert_int_equal(pre, 0);
#endif
		/* the pivots on a line take their own kernel */
		assert_true(kind < 3 || line > b.sc.nnodes / 4);
		/* and free nodes that scale or shear without turning theirs */
		assert_true(kind > 0 || tri > 4);
		assert_true(kept > total / 50);
		/* the free nodes' channels take their own way (random scenes) */
		assert_true(own > b.sc.nnodes / 8 || kind > 0 || !MOT_HAVE_INT128);
		assert_true(pieces > total / 8);
		scene_pose_free(&pw);
		scene_pose_free(&pc);
		scene_pose_free(&shared);
		scene_eval_free(&warm);
		scene_eval_free(&cold);
		scene_eval_free(&one);
		scene_eval_free(&other);
		scene_eval_free(&plain);
		scene_built_free(&b);
		synth_free(&sy);
	}
}

/* A scene of `n` nodes at 24 frames a second and 1 kHz, frames 0 to
 * frame_last: what the small scenes of these tests share. */
static void desc_small(struct scene_desc *d, const struct sd_node *nodes, uint32_t n,
		       double frame_last)
{
	memset(d, 0, sizeof(*d));
	d->rate_num = 24;
	d->rate_den = 1;
	d->tick_hz = 1000;
	d->frame_last = frame_last;
	d->nnodes = n;
	d->nodes = nodes;
}

/* A propeller spun up to 1200 rpm over 48 frames and held for a day: the
 * angle is the exact value for the tick's Q32.32 frame time, rounded once,
 * to the last bit; nothing accumulates. */
static void test_spin_day(void **state)
{
	static const struct sd_key rpm[] = { { 0, 0, 0, 0, 0, 0, 0 }, { 48, 1200, 0, 0, 0, 0, 0 } };
	struct sd_node n;
	struct scene_desc d;
	struct scene_built b;
	struct mot_eval ev;
	struct mot_pose p;
	struct scene_build_err e;
	const int64_t day = 86400LL * 1000;
	int64_t k;

	memset(&n, 0, sizeof(n));
	n.name = "propeller";
	n.parent = -1;
	n.kind = MOT_NODE_REVOLUTE;
	n.axis_id = MOT_AXIS_Z;
	n.axis[2] = 1;
	n.spin.interp = MOT_INTERP_LINEAR;
	n.spin.nkeys = 2;
	n.spin.keys = rpm;
	desc_small(&d, &n, 1, 48);
	assert_int_equal(scene_build(&b, &d, &e), 0);
	assert_int_equal(scene_eval_new(&ev, &b.sc), 0);
	assert_int_equal(scene_pose_new(&p, &b.sc), 0);
	/* after the ramp: turns = (1200*48/2 + 1200 (f - 48)) / (60 * 24) */
	for (k = day - 5; k <= day + 5; k++) {
		mot_q32 f = mot_timing_tick_frame(&b.sc.timing, k);
		/* turns(f) = (28800 + 1200 (f - 48)) / 1440 = 5 f / 6 - 20, from the
		 * frame time the core sees (f in Q32.32), rounded half up */
		mot_q32 want = (mot_q32)(((__int128)5 * f + 3) / 6) - ((mot_q32)20 << 32);

		mot_scene_eval(&b.sc, &ev, f, &p);
		assert_int_equal(p.value[0], want);
		assert_int_equal(p.rpm[0], MOT_Q32_INT(1200));
	}
	/* at exactly 24 h the propeller has made 1727980 turns */
	mot_scene_eval(&b.sc, &ev, mot_timing_tick_frame(&b.sc.timing, day), &p);
	assert_int_equal(p.value[0], (mot_q32)1727980 << 32);
	assert_int_equal(ev.sat, 0);
	scene_pose_free(&p);
	scene_eval_free(&ev);
	scene_built_free(&b);
}

/* A camera circling a model twice: pan runs continuously through +-180
 * degrees (no jump back through a full turn), equals the principal value
 * modulo a turn, and tilt and the eye match the reference. */
static void test_camera_pan(void **state)
{
	enum { NK = 17 };
	static struct sd_key keys[MOT_CAM_NCHANNELS][NK];
	struct scene_desc d;
	struct scene_built b;
	struct mot_eval ev;
	struct mot_pose p;
	struct ref_scene *ref;
	struct ref_pose rp;
	struct scene_build_err e;
	struct tu_worst wpan = { 0, 0 }, wtilt = { 0, 0 }, weye = { 0, 0 };
	double prev = 0, total;
	int i, c;
	int64_t k, k1;

	memset(&d, 0, sizeof(d));
	for (i = 0; i < NK; i++) {
		double a = 2 * M_PI * i / 8.0; /* 8 keys per turn, two turns */

		for (c = 0; c < MOT_CAM_NCHANNELS; c++)
			keys[c][i].frame = i * 12;
		keys[MOT_CAM_EYE_X][i].value = 6 * sin(a);
		keys[MOT_CAM_EYE_Y][i].value = 1.6 + 0.3 * sin(3 * a);
		keys[MOT_CAM_EYE_Z][i].value = 6 * cos(a);
		keys[MOT_CAM_LOOK_Y][i].value = 1;
		keys[MOT_CAM_TWIST][i].value = 5 * sin(a);
	}
	for (c = 0; c < MOT_CAM_NCHANNELS; c++) {
		d.camera.ch[c].interp = MOT_INTERP_HERMITE;
		d.camera.ch[c].nkeys = NK;
		d.camera.ch[c].keys = keys[c];
	}
	d.camera.ease_in = d.camera.ease_out = 24;
	d.has_camera = true;
	d.rate_num = 24;
	d.rate_den = 1;
	d.tick_hz = 1000;
	d.frame_last = 12 * (NK - 1);
	assert_int_equal(scene_build(&b, &d, &e), 0);
	assert_int_equal(scene_eval_new(&ev, &b.sc), 0);
	assert_int_equal(scene_pose_new(&p, &b.sc), 0);
	ref = ref_scene_new(&d);
	assert_non_null(ref);
	assert_int_equal(ref_pose_new(&rp, &d), 0);
	k1 = mot_timing_trigger_tick(&b.sc.timing, 12 * (NK - 1));
	for (k = 0; k <= k1; k++) {
		mot_q32 f = mot_timing_tick_frame(&b.sc.timing, k);
		double pan, diff;

		mot_scene_eval(&b.sc, &ev, f, &p);
		ref_scene_eval(ref, f, &rp);
		pan = q2d(p.cam.pan);
		/* continuous: no tick moves the head by more than a degree */
		if (k > 0 && fabs(pan - prev) > 1.0 / 360)
			fail_msg("pan jumps %.6f turn at tick %lld", pan - prev, (long long)k);
		prev = pan;
		diff = pan - rp.pan;
		diff -= nearbyint(diff);
		tu_worst_add(&wpan, diff * 2 * M_PI, (double)k);
		tu_worst_add(&wtilt, (q2d(p.cam.tilt) - rp.tilt) * 2 * M_PI, (double)k);
		for (c = 0; c < 3; c++)
			tu_worst_add(&weye, q2d(p.cam.eye[c]) - rp.eye[c], (double)k);
	}
	/* the eye goes round twice counter-clockwise seen from above: pan has
	 * turned through two full turns, and crossed +-180 degrees on the way */
	total = q2d(p.cam.pan) - q2d(b.sc.camera->pan_ref[0]);
	assert_true(fabs(fabs(total) - 2.0) < 1e-9);
	tu_bound("scene.camera.pan", &wpan, 1e-8, "rad");
	tu_bound("scene.camera.tilt", &wtilt, 1e-8, "rad");
	tu_bound("scene.camera.eye", &weye, 1e-9, "m");
	assert_int_equal(ev.sat, 0);
	ref_pose_free(&rp);
	ref_scene_free(ref);
	scene_pose_free(&p);
	scene_eval_free(&ev);
	scene_built_free(&b);
}

/* Bad input to the API gets an error code, never a trap. */
static void test_bad_input(void **state)
{
	static const struct sd_key rev[] = { { 0, 0, 0, 0, 0, 0, 0 }, { 10, 5, 0, 0, 0, 0, 0 },
					     { 10, 6, 0, 0, 0, 0, 0 } };
	static const struct sd_key ok[] = { { 0, 0, 0, 0, 0, 0, 0 }, { 10, 5, 0, 0, 0, 0, 0 } };
	struct synth sy;
	struct sd_node *n;
	struct scene_built b;
	struct scene_build_err e;
	struct mot_eval ev;
	struct mot_cursor cur[2];
	struct mot_arena a;
	unsigned char small[64] __attribute__((aligned(64)));

	synth_robot_arm(&sy, 1, 96);
	n = (struct sd_node *)sy.d.nodes;

	/* keys out of order */
	n[2].value.keys = rev;
	n[2].value.nkeys = 3;
	assert_int_equal(scene_build(&b, &sy.d, &e), MOT_E_ORDER);
	assert_int_equal(e.node, 2);
	n[2].value.keys = ok;
	n[2].value.nkeys = 2;
	assert_int_equal(scene_build(&b, &sy.d, &e), 0);

	/* a parent after its child, and a parent that is the node itself */
	{
		struct mot_node *nodes = (struct mot_node *)b.sc.nodes;

		nodes[1].parent = 3;
		assert_int_equal(mot_scene_validate(&b.sc), MOT_E_PARENT);
		nodes[1].parent = 1;
		assert_int_equal(mot_scene_validate(&b.sc), MOT_E_PARENT);
		nodes[1].parent = 0;
		assert_int_equal(mot_scene_validate(&b.sc), MOT_OK);
		/* the claw's tilted axis with derived fields that do not match it
		 * (an axis edited without mot_node_prepare), then prepared again */
		nodes[4].axis[0] = nodes[4].axis[2];
		nodes[4].axis[2] = -nodes[4].axis[0];
		assert_int_equal(mot_scene_validate(&b.sc), MOT_E_INVAL);
		mot_node_prepare(&nodes[4]);
		assert_int_equal(mot_scene_validate(&b.sc), MOT_OK);
		/* derived fields on a node that has none */
		nodes[1].rot_pr[0] = 1;
		assert_int_equal(mot_scene_validate(&b.sc), MOT_E_INVAL);
		mot_node_prepare(&nodes[1]);
		assert_int_equal(mot_scene_validate(&b.sc), MOT_OK);
	}
	/* too few cursors for the scene */
	ev.cursors = cur;
	ev.ncursors = 2;
	assert_int_equal(mot_eval_reset(&ev, &b.sc), MOT_E_CAPACITY);
	scene_built_free(&b);

	/* a value outside the core's range */
	{
		static const struct sd_key huge[] = { { 0, 0, 0, 0, 0, 0, 0 },
						      { 10, 1e12, 0, 0, 0, 0, 0 } }; /* deg */

		n[0].value.keys = huge;
		n[0].value.nkeys = 2;
		assert_int_equal(scene_build(&b, &sy.d, &e), MOT_E_RANGE);
		assert_int_equal(e.node, 0);
		n[0].value.keys = ok;
	}
	/* a frame rate above the tick rate */
	sy.d.rate_num = 2000;
	assert_int_equal(scene_build(&b, &sy.d, &e), MOT_E_INVAL);
	sy.d.rate_num = 24;

	/* a full arena refuses, and a sealed one too */
	mot_arena_init(&a, small, sizeof(small));
	assert_non_null(mot_arena_alloc(&a, 32, 8));
	assert_null(mot_arena_alloc(&a, 64, 8));
	assert_true(a.failed);
	mot_arena_init(&a, small, sizeof(small));
	mot_arena_seal(&a);
	assert_null(mot_arena_alloc(&a, 8, 8));
	assert_true(a.failed);
	synth_free(&sy);
}

/* A strand without keys is refused by every prepare function. */
/* Build a small scene and evaluate it once at frame 0; the nodes may be
 * patched in between (values the loader would refuse). */
static void eval_once(struct scene_built *b, struct mot_eval *ev, struct mot_pose *p,
		      const struct sd_node *nodes, uint32_t n,
		      void (*patch)(struct mot_node *nodes))
{
	struct scene_desc d;
	struct scene_build_err e;

	desc_small(&d, nodes, n, 1);
	assert_int_equal(scene_build(b, &d, &e), 0);
	patch((struct mot_node *)b->sc.nodes);
	assert_int_equal(scene_eval_new(ev, &b->sc), 0);
	assert_int_equal(scene_pose_new(p, &b->sc), 0);
	mot_scene_eval(&b->sc, ev, 0, p);
}

static void patch_prismatic(struct mot_node *nodes)
{
	nodes[1].pivot[0] = INT64_MAX - ((int64_t)1 << 60);
}

static void patch_revolute(struct mot_node *nodes)
{
	nodes[0].pivot[0] = (int64_t)1 << 62;
}

/*
 * The hot path sums products in 128 bits and checks the results once per
 * node; what does not fit is redone with the saturating sums. A pivot plus
 * an offset beyond int64 whose image does fit (under a parent scaled by
 * 1/2) comes out exact and unflagged; a translation that cannot fit
 * saturates with its sign and is flagged, next to exact entries.
 */
static void test_wide_sums(void **state)
{
	static const struct sd_key half[] = { { 0, 0.5, 0, 0, 0, 0, 0 } };
	static const struct sd_key far[] = { { 0, 536870912, 0, 0, 0, 0, 0 } }; /* 2^29 units */
	struct sd_node n[2];
	struct scene_built b;
	struct mot_eval ev;
	struct mot_pose p;
	__int128 want;
	int k;

	memset(n, 0, sizeof(n));
	n[0].name = "half";
	n[0].parent = -1;
	n[0].kind = MOT_NODE_FREE;
	n[0].has_free = true;
	for (k = MOT_FREE_SX; k <= MOT_FREE_SZ; k++)
		n[0].free.ch[k] = (struct sd_curve){ MOT_INTERP_LINEAR, 1, half, 1, 0, 0, 0,
						     false };
	n[1].name = "slide";
	n[1].parent = 0;
	n[1].kind = MOT_NODE_PRISMATIC;
	n[1].axis_id = MOT_AXIS_X;
	n[1].axis[0] = 1;
	n[1].value = (struct sd_curve){ MOT_INTERP_LINEAR, 1, far, 1, 0, 0, 0, false };
	eval_once(&b, &ev, &p, n, 2, patch_prismatic);
	/* pos = (p + t) / 2, rounded half up; W_t = t / 2 */
	want = ((__int128)b.sc.nodes[1].pivot[0] + ((int64_t)1 << 61) + 1) >> 1;
	assert_true(p.pos[1][0] == (int64_t)want);
	assert_int_equal(p.world[1].m[3][0], (int64_t)1 << 60);
	assert_int_equal(p.world[1].m[0][0], MOT_Q32_HALF);
	assert_int_equal(ev.sat, 0);
	scene_pose_free(&p);
	scene_eval_free(&ev);
	scene_built_free(&b);

	/* half a turn about z at (2^30 units, 0, 0): W_t = 2 p does not fit */
	memset(n, 0, sizeof(n));
	n[0].name = "turn";
	n[0].parent = -1;
	n[0].kind = MOT_NODE_REVOLUTE;
	n[0].axis_id = MOT_AXIS_Z;
	n[0].axis[2] = 1;
	n[0].rest = 180;
	eval_once(&b, &ev, &p, n, 1, patch_revolute);
	assert_true(ev.sat & MOT_SAT_OVERFLOW);
	assert_int_equal(p.world[0].m[3][0], MOT_Q32_MAX);
	assert_int_equal(p.world[0].m[3][1], 0);
	assert_int_equal(p.pos[0][0], (int64_t)1 << 62);
	assert_int_equal(p.world[0].m[0][0], -MOT_Q32_ONE);
	assert_int_equal(p.world[0].m[1][1], -MOT_Q32_ONE);
	scene_pose_free(&p);
	scene_eval_free(&ev);
	scene_built_free(&b);
}

/*
 * The small case under scale and shear (scene.c, memo_prepare()): a chain
 * of free nodes that scale by up to 1.5 and shear by up to 0.2, each with a
 * joint turning below it, is small all the way down; one that scales by
 * up to 1030 without shear (three levels: 1030^3 is above 2^30, and every
 * result still fits) is small while the bounds stay below 2^30 (the first
 * two free nodes and their joints) and not from the third free node down.
 * Either way the bits are the tested kernels' (an evaluation reset before
 * every tick with the small case switched off).
 */
#define SCALED_LEVELS 6

static void test_scaled_small(void **state)
{
	static const struct sd_key up15[] = { { 0, 1, 0, 0, 0, 0, 0 }, { 24, 1.5, 0, 0, 0, 0, 0 } };
	static const struct sd_key up1030[] = { { 0, 1, 0, 0, 0, 0, 0 },
						 { 24, 1030, 0, 0, 0, 0, 0 } };
	static const struct sd_key shear[] = { { 0, 0, 0, 0, 0, 0, 0 }, { 24, 0.2, 0, 0, 0, 0, 0 } };
	static const struct sd_key turn[] = { { 0, 0, 0, 0, 0, 0, 0 }, { 24, 90, 0, 0, 0, 0, 0 } };
	static const char *const names[2 * SCALED_LEVELS] = { "f0", "j0", "f1", "j1", "f2", "j2",
							      "f3", "j3", "f4", "j4", "f5", "j5" };
	uint32_t s, i, k;

	for (s = 0; s < 2; s++) {
		struct sd_node n[2 * SCALED_LEVELS];
		struct scene_desc d;
		struct scene_build_err e;
		struct scene_built b;
		struct mot_eval warm, cold;
		struct mot_pose pw, pc;
		const struct mot_timing *t;
		int64_t tk, n1;

		memset(n, 0, sizeof(n));
		for (i = 0; i < 2 * SCALED_LEVELS; i++) {
			n[i].name = names[i];
			n[i].parent = (int32_t)i - 1;
			n[i].pivot[0] = 1;
			n[i].pivot[1] = 0.25;
			if (i % 2 == 0) {
				n[i].kind = MOT_NODE_FREE;
				n[i].has_free = true;
				for (k = MOT_FREE_SX; k <= MOT_FREE_SZ; k++)
					n[i].free.ch[k] = (struct sd_curve){ MOT_INTERP_LINEAR, 2,
									     s ? up1030 : up15, 1, 0,
									     0, 0, false };
				for (k = MOT_FREE_HXY; k <= MOT_FREE_HYZ && !s; k++)
					n[i].free.ch[k] = (struct sd_curve){ MOT_INTERP_LINEAR, 2,
									     shear, 1, 0, 0, 0,
									     false };
			} else {
				n[i].kind = MOT_NODE_REVOLUTE;
				n[i].axis_id = MOT_AXIS_Z;
				n[i].axis[2] = 1;
				n[i].value = (struct sd_curve){ MOT_INTERP_LINEAR, 2, turn, 1, 0, 0, 0,
								false };
			}
		}
		desc_small(&d, n, s ? SCALED_LEVELS : 2 * SCALED_LEVELS, 24);
		assert_int_equal(scene_build(&b, &d, &e), 0);
		assert_int_equal(scene_eval_new(&warm, &b.sc), 0);
		assert_int_equal(scene_eval_new(&cold, &b.sc), 0);
		assert_int_equal(scene_pose_new(&pw, &b.sc), 0);
		assert_int_equal(scene_pose_new(&pc, &b.sc), 0);
		for (i = 0; i < b.sc.nnodes; i++)
			assert_int_equal(warm.memo[i].small, s == 0 || i < 4);
		t = &b.sc.timing;
		n1 = mot_timing_trigger_tick(t, 25);
		for (tk = -3; tk < n1; tk += 7) {
			mot_q32 f = mot_timing_tick_frame(t, tk);

			mot_scene_eval(&b.sc, &warm, f, &pw);
			assert_int_equal(mot_eval_reset(&cold, &b.sc), MOT_OK);
			for (i = 0; i < b.sc.nnodes; i++) {
				cold.memo[i].small = 0;
				/* a free node's channels by mot_curve_eval() */
				cold.memo[i].free &= (uint8_t)~MOT_MEMO_FREE_OWN;
			}
			mot_scene_eval(&b.sc, &cold, f, &pc);
			assert_same_pose(&b.sc, &pw, &pc);
		}
		assert_int_equal(warm.sat, 0);
		assert_int_equal(cold.sat, 0);
		scene_pose_free(&pw);
		scene_pose_free(&pc);
		scene_eval_free(&warm);
		scene_eval_free(&cold);
		scene_built_free(&b);
	}
}

/*
 * A free node's rotation track by scene.c's memo (the key interval it
 * learnt, or the held end's matrix) against mot_rot_track_eval() at the
 * same frame with a cursor of its own (the matrix made from its quaternion,
 * or the end's made at init) and mot_node_local()'s (a memo of its own,
 * learnt every call), and the whole pose against an evaluation reset
 * before every frame: squad and slerp, eased keys, an interval three
 * LSB wide and one of a million frames, a compact track, a single key, a
 * strand-wide ease, a scale too large for the untested sums. Frames on
 * either side of every key by one LSB and on it, then a dense sweep forward
 * and in a scrambled order; the memo must hold intervals and ends.
 */
#define MEMO_NODES 8
#define MEMO_SWEEP 601

static void test_rot_memo(void **state)
{
	static const struct sd_rot_key keys[] = {
		{ 0, { 1, 0, 0, 0 }, 0, 0.3 },           { 3.25, { 0.8, 0.5, -0.2, 0.1 }, 0.2, 0 },
		{ 10, { -0.3, 0.6, 0.7, -0.1 }, 0.1, 0.4 },
		{ 10 + 3.0 / 4294967296.0, { -0.2, 0.7, 0.6, 0.1 }, 0.5, 0.5 },
		{ 17.5, { 0.1, -0.2, 0.3, 0.9 }, 0, 0 }, { 24, { 0.5, 0.5, 0.5, 0.5 }, 0.6, 0 },
	};
	static const struct sd_rot_key plain[] = {
		{ -1, { 1, 0, 0, 0 }, 0, 0 },          { 2.5, { 0.6, 0, 0.8, 0 }, 0, 0 },
		{ 9, { -0.5, 0.5, -0.5, 0.5 }, 0, 0 }, { 20, { 0, 0, 0, 1 }, 0, 0 },
		{ 1e6, { 0.9, -0.1, 0.1, 0.3 }, 0, 0 },
	};
	static const struct sd_key big[] = { { 0, 1, 0, 0, 0, 0, 0 }, { 24, 300, 0, 0, 0, 0, 0 } };
	struct sd_node n[MEMO_NODES];
	struct scene_desc d;
	struct scene_build_err e;
	struct scene_built b;
	struct mot_eval warm, cold;
	struct mot_pose pw, pc;
	mot_q32 fr[MEMO_SWEEP + 64];
	struct mot_mat loc;
	uint32_t i, j, k, nf = 0, arcs = 0, ends = 0;

	memset(n, 0, sizeof(n));
	for (i = 0; i < MEMO_NODES; i++) {
		static const char *const names[MEMO_NODES] = { "squad",  "slerp", "plain", "far",
							       "compact", "one",  "warp",  "big" };

		n[i].name = names[i];
		n[i].parent = -1;
		n[i].kind = MOT_NODE_FREE;
		n[i].has_free = true;
		n[i].free.rot = i == 2 || i == 4 ? plain : keys;
		n[i].free.nrot = i == 5 ? 1 : i == 2 || i == 4 ? 4 : 6;
		n[i].free.squad = i != 1 && i != 2 && i != 4;
	}
	n[3].free.rot = plain; /* a million frames from 20: the sweep inside */
	n[3].free.nrot = 5;
	n[4].free.rot_compact = true;
	n[6].free.ease_out = 4;
	n[6].free.ease_in = 6;
	for (k = MOT_FREE_SX; k <= MOT_FREE_SZ; k++)
		n[7].free.ch[k] = (struct sd_curve){ MOT_INTERP_LINEAR, 2, big, 1, 0, 0, 0, false };
	desc_small(&d, n, MEMO_NODES, 24);
	assert_int_equal(scene_build(&b, &d, &e), 0);
	assert_int_equal(scene_eval_new(&warm, &b.sc), 0);
	assert_int_equal(scene_eval_new(&cold, &b.sc), 0);
	assert_int_equal(scene_pose_new(&pw, &b.sc), 0);
	assert_int_equal(scene_pose_new(&pc, &b.sc), 0);
	/* every key of the first track (the others share most), +-1 LSB */
	for (k = 0; k < 6; k++)
		for (j = 0; j < 3; j++)
			fr[nf++] = b.sc.rot[b.sc.free[b.sc.nodes[0].strand].rot].keys[k].frame +
				   (mot_q32)j - 1;
	for (k = 0; k < 5; k++)
		for (j = 0; j < 3; j++)
			fr[nf++] = b.sc.rot[b.sc.free[b.sc.nodes[2].strand].rot].keys[k].frame +
				   (mot_q32)j - 1;
	for (k = 0; k < MEMO_SWEEP; k++) /* -2 .. 27 frames, not on a grid */
		fr[nf++] = -2 * MOT_Q32_ONE + (mot_q32)k * (MOT_Q32_ONE / 20 + 12345);
	for (k = 0; k < 2 * nf; k++) {
		mot_q32 f = k < nf ? fr[k] : fr[(k * 7919) % nf];

		mot_scene_eval(&b.sc, &warm, f, &pw);
		assert_int_equal(mot_eval_reset(&cold, &b.sc), MOT_OK);
		mot_scene_eval(&b.sc, &cold, f, &pc);
		assert_same_pose(&b.sc, &pw, &pc);
		for (i = 0; i < 6; i++) { /* no warp, no scale: R rounded from Q2.62 */
			const struct mot_rot_track *r =
				&b.sc.rot[b.sc.free[b.sc.nodes[i].strand].rot];
			struct mot_cursor cur = { 0, 0 };
			const struct mot_rot_q62 *held;
			struct mot_rot_q62 own;
			struct mot_quat q;
			uint32_t sat = 0;

			held = mot_rot_track_eval(&q, r, &cur, f, &sat);
			if (!held) {
				assert_int_equal(mot_quat_to_rot_q62(own.r, &q, &sat), MOT_OK);
				held = &own;
			}
			assert_int_equal(sat, 0);
			for (j = 0; j < 9; j++) {
				mot_acc x = mot_acc_from(held->r[j / 3][j % 3], 0);

				assert_int_equal(pw.world[i].m[j / 3][j % 3],
						 mot_acc_round(x, 30, NULL));
			}
			/* a root's local matrix, pivot 0: its world one */
			mot_node_local(&loc, &b.sc, &cold, i, f, NULL, NULL);
			assert_memory_equal(&loc, &pw.world[i], sizeof(loc));
			arcs += warm.memo[i].arc != NULL && warm.memo[i].lo <= f &&
				f < warm.memo[i].hi;
			ends += warm.memo[i].end != NULL && warm.memo[i].lo <= f &&
				f < warm.memo[i].hi;
		}
	}
	assert_int_equal(warm.sat, 0);
	assert_int_equal(cold.sat, 0);
	assert_true(arcs > nf);
	assert_true(ends > nf);
	scene_pose_free(&pw);
	scene_pose_free(&pc);
	scene_eval_free(&warm);
	scene_eval_free(&cold);
	scene_built_free(&b);
}

static void test_no_keys(void **state)
{
	struct mot_rot_track rt;
	struct mot_rot_seg seg[1];
	struct mot_curve c;
	struct mot_curve_seg cs[4];
	struct mot_key k[1] = { { 0, 0, 0, 0 } };

	assert_int_equal(mot_rot_track_init(&rt, NULL, 0, false, seg, 1, NULL), MOT_E_NOKEYS);
	assert_int_equal(mot_curve_init(&c, MOT_INTERP_LINEAR, k, 0, NULL, cs, 4, NULL),
			 MOT_E_NOKEYS);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_robot_arm),   cmocka_unit_test(test_random),
		cmocka_unit_test(test_random_access), cmocka_unit_test(test_spin_day),
		cmocka_unit_test(test_camera_pan),  cmocka_unit_test(test_bad_input),
		cmocka_unit_test(test_no_keys),     cmocka_unit_test(test_wide_sums),
		cmocka_unit_test(test_shortcuts),   cmocka_unit_test(test_scaled_small),
		cmocka_unit_test(test_rot_memo),    cmocka_unit_test(test_pre_edge),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
