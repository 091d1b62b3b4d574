/* SPDX-License-Identifier: MIT */
/* synth.c - scene descriptions built in code (see synth.h). */
#include "synth.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void *s_alloc(struct synth *s, size_t n)
{
	void *p = calloc(1, n ? n : 1);

	if (!p) {
		fprintf(stderr, "synth: out of memory\n");
		abort();
	}
	if (s->nmem == s->capmem) {
		s->capmem = s->capmem ? 2 * s->capmem : 64;
		s->mem = realloc(s->mem, s->capmem * sizeof(*s->mem));
		if (!s->mem)
			abort();
	}
	s->mem[s->nmem++] = p;
	return p;
}

void synth_free(struct synth *s)
{
	size_t i;

	for (i = 0; i < s->nmem; i++)
		free(s->mem[i]);
	free(s->mem);
	memset(s, 0, sizeof(*s));
}

/* xorshift64*, private so that synth needs no test framework */
static uint64_t rnd(uint64_t *st)
{
	*st ^= *st >> 12;
	*st ^= *st << 25;
	*st ^= *st >> 27;
	return *st * 2685821657736338717ull;
}

static double uni(uint64_t *st, double lo, double hi)
{
	return lo + (hi - lo) * (double)(rnd(st) >> 11) * (1.0 / 9007199254740992.0);
}

static void timing(struct scene_desc *d, double frames)
{
	d->rate_num = 24;
	d->rate_den = 1;
	d->tick_hz = 1000;
	d->frame_first = 0;
	d->frame_last = frames;
}

void synth_robot_arm(struct synth *s, double scale, double frames)
{
	/* pivots in rest coordinates (the arm standing up along +y) */
	static const double pivot[5][3] = {
		{ 0, 0, 0 }, { 0, 0.3, 0 }, { 0, 0.9, 0 }, { 0, 1.35, 0 }, { 0, 1.5, 0.02 },
	};
	static const enum mot_axis axis_id[5] = { MOT_AXIS_Y, MOT_AXIS_Z, MOT_AXIS_Z, MOT_AXIS_X,
						  MOT_AXIS_VEC };
	static const char *const names[5] = { "base", "arm1", "arm2", "wrist", "claw" };
	/* angles (degrees) at five uneven key frames, per joint */
	static const double ang[5][5] = {
		{ 0, 120, 400, 250, -30 }, { 0, 35, -20, 60, 10 }, { 0, -70, 45, -90, 0 },
		{ 0, 90, 180, 45, -45 },   { 0, 30, 0, 30, 0 },
	};
	static const double at[5] = { 0, 0.17, 0.45, 0.71, 1.0 };
	struct sd_node *n;
	int i, k;

	memset(s, 0, sizeof(*s));
	n = s_alloc(s, 5 * sizeof(*n));
	for (i = 0; i < 5; i++) {
		struct sd_key *keys = s_alloc(s, 5 * sizeof(*keys));

		n[i].name = names[i];
		n[i].parent = i - 1;
		n[i].kind = MOT_NODE_REVOLUTE;
		n[i].axis_id = axis_id[i];
		for (k = 0; k < 3; k++) {
			n[i].pivot[k] = pivot[i][k] * scale;
			n[i].axis[k] = axis_id[i] == MOT_AXIS_VEC ? (k == 1 ? 0.0 : 1.0) :
								   (k == (int)axis_id[i]);
		}
		for (k = 0; k < 5; k++) {
			keys[k].frame = at[k] * frames + (k > 0 && k < 4 ? i * 1.5 : 0);
			keys[k].value = ang[i][k];
		}
		n[i].value.interp = MOT_INTERP_HERMITE;
		n[i].value.nkeys = 5;
		n[i].value.keys = keys;
	}
	s->d.name = "robot-arm";
	timing(&s->d, frames);
	s->d.nnodes = 5;
	s->d.nodes = n;
}

static void rand_curve(struct synth *s, uint64_t *st, struct sd_curve *c, enum mot_interp kind,
		       double lo, double hi, double frames)
{
	uint32_t n = 2 + (uint32_t)(rnd(st) % 7), i;
	struct sd_key *k = s_alloc(s, n * sizeof(*k));
	double f = uni(st, -0.1, 0.1) * frames;

	for (i = 0; i < n; i++) {
		k[i].frame = f;
		k[i].value = uni(st, lo, hi);
		f += uni(st, 0.05, 0.4) * frames;
		if (kind <= MOT_INTERP_HERMITE && rnd(st) % 4 == 0) {
			k[i].ease_out = uni(st, 0, 0.4);
			k[i].ease_in = uni(st, 0, 0.4);
		}
	}
	c->interp = kind;
	c->nkeys = n;
	c->keys = k;
	c->beta1 = uni(st, 0.5, 3);
	c->beta2 = uni(st, 0, 5);
	if (rnd(st) % 5 == 0) {
		double span = k[n - 1].frame - k[0].frame;

		c->ease_out = span * uni(st, 0, 0.3);
		c->ease_in = span * uni(st, 0, 0.3);
	}
}

/* Node i of a random forest: its name, a parent among the few nodes before
 * it (keeping the depth bounded; now and then none) and a pivot. Returns the
 * roll in [0, 100) that picks its kind. */
static uint32_t rand_node(struct synth *s, uint64_t *st, struct sd_node *nd, int *depth,
			  uint32_t i, const char *prefix)
{
	uint32_t roll = (uint32_t)(rnd(st) % 100), k;
	char *name = s_alloc(s, 16);

	snprintf(name, 16, "%s%u", prefix, i);
	nd->name = name;
	nd->parent = -1;
	depth[i] = 0;
	if (i > 0 && roll % 50 != 0) {
		uint32_t j = i - 1 - (uint32_t)(rnd(st) % (i < 8 ? i : 8));

		if (depth[j] < 12) {
			nd->parent = (int32_t)j;
			depth[i] = depth[j] + 1;
		}
	}
	for (k = 0; k < 3; k++)
		nd->pivot[k] = uni(st, -1, 1);
	return roll;
}

/* A joint's axis: x, y, z or a tilted one (normalised by the builder). */
static void rand_axis(uint64_t *st, struct sd_node *nd)
{
	uint32_t k;

	nd->axis_id = (enum mot_axis)(rnd(st) % 4);
	for (k = 0; k < 3; k++)
		nd->axis[k] = nd->axis_id == MOT_AXIS_VEC ? uni(st, -1, 1) + 0.1 :
							    (k == (uint32_t)nd->axis_id);
}

static void rand_quat(uint64_t *st, double q[4])
{
	double n;
	int i;

	do {
		n = 0;
		for (i = 0; i < 4; i++) {
			q[i] = uni(st, -1, 1);
			n += q[i] * q[i];
		}
	} while (n < 0.01 || n > 1);
	for (i = 0; i < 4; i++)
		q[i] /= sqrt(n);
}

void synth_random(struct synth *s, uint64_t seed, uint32_t n, double frames)
{
	uint64_t st = seed * 0x9e3779b97f4a7c15ull + 1;
	struct sd_node *nodes;
	int *depth;
	uint32_t i, k;

	memset(s, 0, sizeof(*s));
	nodes = s_alloc(s, n * sizeof(*nodes));
	depth = s_alloc(s, n * sizeof(*depth));
	for (i = 0; i < n; i++) {
		struct sd_node *nd = &nodes[i];
		uint32_t roll = rand_node(s, &st, nd, depth, i, "n");
		enum mot_interp kind = (enum mot_interp)(i % 6);

		if (roll < 60) {
			nd->kind = MOT_NODE_REVOLUTE;
			rand_axis(&st, nd);
			if (roll < 8) {
				rand_curve(s, &st, &nd->spin, (enum mot_interp)(rnd(&st) % 3), -600,
					   2400, frames);
				nd->spin.ease_in = nd->spin.ease_out = 0;
				for (k = 0; k < nd->spin.nkeys; k++)
					((struct sd_key *)nd->spin.keys)[k].ease_in =
						((struct sd_key *)nd->spin.keys)[k].ease_out = 0;
			} else {
				rand_curve(s, &st, &nd->value, kind, -400, 400, frames);
			}
		} else if (roll < 72) {
			nd->kind = MOT_NODE_PRISMATIC;
			rand_axis(&st, nd);
			rand_curve(s, &st, &nd->value, kind, -1, 1, frames);
		} else {
			struct sd_free *f = &nd->free;
			uint32_t nr;

			nd->kind = MOT_NODE_FREE;
			nd->has_free = true;
			for (k = 0; k < MOT_FREE_NCHANNELS; k++) {
				double lo = -1, hi = 1;

				if (rnd(&st) % 3 == 0)
					continue;
				if (k >= MOT_FREE_SX && k <= MOT_FREE_SZ) {
					lo = 0.7;
					hi = 1.4;
				} else if (k >= MOT_FREE_HXY) {
					lo = -0.3;
					hi = 0.3;
				}
				rand_curve(s, &st, &f->ch[k], (enum mot_interp)((i + k) % 6), lo, hi,
					   frames);
				/* a free strand's ease is strand-wide, not per channel */
				f->ch[k].ease_in = f->ch[k].ease_out = 0;
			}
			nr = (uint32_t)(rnd(&st) % 6);
			if (nr) {
				struct sd_rot_key *rk = s_alloc(s, nr * sizeof(*rk));
				double fr = uni(&st, -0.1, 0.1) * frames;

				for (k = 0; k < nr; k++) {
					rk[k].frame = fr;
					rand_quat(&st, rk[k].q);
					fr += uni(&st, 0.05, 0.4) * frames;
				}
				f->nrot = nr;
				f->rot = rk;
				f->squad = rnd(&st) % 2;
			}
		}
	}
	s->d.name = "synthetic";
	timing(&s->d, frames);
	s->d.nnodes = n;
	s->d.nodes = nodes;
}

/* The joint's form forced: its kind, and its axis a coordinate one (i mod
 * 3) or a tilted one drawn as rand_axis() draws them. */
static void force_form(uint64_t *st, struct sd_node *nd, uint32_t i, enum synth_form form)
{
	const bool tilt = form == SYNTH_REV_TILT || form == SYNTH_PRI_TILT;
	uint32_t k;

	nd->kind = form <= SYNTH_REV_TILT ? MOT_NODE_REVOLUTE : MOT_NODE_PRISMATIC;
	if (tilt == (nd->axis_id == MOT_AXIS_VEC))
		return;
	nd->axis_id = tilt ? MOT_AXIS_VEC : (enum mot_axis)(i % 3);
	for (k = 0; k < 3; k++)
		nd->axis[k] = tilt ? uni(st, -1, 1) + 0.1 : (k == (uint32_t)nd->axis_id);
}

void synth_joints(struct synth *s, uint64_t seed, uint32_t n, double frames, unsigned kinds)
{
	synth_joints_of(s, seed, n, frames, kinds, SYNTH_ANY);
}

void synth_joints_of(struct synth *s, uint64_t seed, uint32_t n, double frames, unsigned kinds,
		     enum synth_form form)
{
	uint64_t st = seed * 0x9e3779b97f4a7c15ull + 1;
	enum mot_interp kind[MOT_INTERP_BEZIER + 1];
	uint32_t nkinds = 0, i, k;
	struct sd_node *nodes;
	int *depth;

	for (k = 0; k <= MOT_INTERP_BEZIER; k++)
		if (!kinds || (kinds >> k & 1))
			kind[nkinds++] = (enum mot_interp)k;
	memset(s, 0, sizeof(*s));
	nodes = s_alloc(s, n * sizeof(*nodes));
	depth = s_alloc(s, n * sizeof(*depth));
	for (i = 0; i < n; i++) {
		struct sd_node *nd = &nodes[i];
		uint32_t roll = rand_node(s, &st, nd, depth, i, "j");
		double range;

		nd->kind = roll < 80 ? MOT_NODE_REVOLUTE : MOT_NODE_PRISMATIC;
		rand_axis(&st, nd);
		if (form != SYNTH_ANY)
			force_form(&st, nd, i, form);
		range = nd->kind == MOT_NODE_REVOLUTE ? 400 : 1; /* degrees or units */
		rand_curve(s, &st, &nd->value, kind[i % nkinds], -range, range, frames);
	}
	s->d.name = "joints";
	timing(&s->d, frames);
	s->d.nnodes = n;
	s->d.nodes = nodes;
}
