/* SPDX-License-Identifier: MIT */
/* scenegen.c - random valid scenes (see scenegen.h). */
#include "scenegen.h"

#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testutil.h"

static void say(struct scenegen *g, const char *fmt, ...)
{
	va_list ap;
	int n;

	for (;;) {
		va_start(ap, fmt);
		n = vsnprintf(g->yaml + g->len, g->cap - g->len, fmt, ap);
		va_end(ap);
		if (n >= 0 && (size_t)n < g->cap - g->len)
			break;
		g->cap = g->cap * 2 + (size_t)n + 256;
		g->yaml = realloc(g->yaml, g->cap);
		if (!g->yaml)
			abort();
	}
	g->len += (size_t)n;
}

static bool chance(struct tu_rng *r, double p)
{
	return tu_uniform(r, 0, 1) < p;
}

static uint32_t pick(struct tu_rng *r, uint32_t n)
{
	return (uint32_t)(tu_u64(r) % n);
}

/* log-uniform in [lo, hi] */
static double logu(struct tu_rng *r, double lo, double hi)
{
	return exp(tu_uniform(r, log(lo), log(hi)));
}

/* n strictly increasing key frames over [a, b], a tenth of a frame apart
 * at least, at tenths of a frame. */
static void key_frames(struct tu_rng *r, double a, double b, uint32_t n, double *f)
{
	uint32_t i, j;

	for (i = 0; i < n; i++)
		f[i] = floor(tu_uniform(r, a, b) * 10) / 10;
	for (i = 1; i < n; i++)
		for (j = i; j > 0 && f[j] < f[j - 1]; j--) {
			double t = f[j];

			f[j] = f[j - 1];
			f[j - 1] = t;
		}
	for (i = 1; i < n; i++)
		if (f[i] < f[i - 1] + 0.1)
			f[i] = f[i - 1] + 0.1;
}

static const char *const interps[] = { "step", "linear", "hermite", "bspline", "beta", "bezier" };

/* interpolation, ease and beta of a strand; true when keys may carry
 * ease_in / ease_out */
static void strand_head(struct scenegen *g, struct tu_rng *r, const char *in, const char *interp,
			double span)
{
	say(g, "%sinterpolation: %s\n", in, interp);
	if (!strcmp(interp, "beta") && chance(r, 0.7))
		say(g, "%sbeta: {bias: %.3f, tension: %.3f}\n", in, tu_uniform(r, 0.3, 3),
		    tu_uniform(r, 0, 8));
	if (chance(r, 0.3))
		say(g, "%sease: {in: %.1f, out: %.1f}\n", in,
		    floor(tu_uniform(r, 0, span / 3) * 10) / 10,
		    floor(tu_uniform(r, 0, span / 3) * 10) / 10);
}

/* the ease_in / ease_out of a key (fractions summing to at most 1 per interval) */
static void key_ease(struct scenegen *g, struct tu_rng *r)
{
	if (chance(r, 0.2))
		say(g, ", ease_in: %.2f", tu_uniform(r, 0, 0.5));
	if (chance(r, 0.2))
		say(g, ", ease_out: %.2f", tu_uniform(r, 0, 0.5));
}

static void limits(struct scenegen *g, struct tu_rng *r, bool rev, double lo, double hi)
{
	double unit = rev ? 1 : 0.01, range = hi - lo + unit;
	bool any = false;

	if (!chance(r, 0.5))
		return;
	say(g, "    limits: {");
	if (chance(r, 0.5)) {
		/* around the keys' range: now and then inside it (a violation) */
		say(g, "min: %.4f, max: %.4f", lo - range * tu_uniform(r, -0.1, 0.6),
		    hi + range * tu_uniform(r, -0.1, 0.6));
		any = true;
	}
	if (chance(r, 0.7)) {
		say(g, "%svelocity: %.5g", any ? ", " : "", logu(r, 5, 3000) * unit);
		any = true;
	}
	if (chance(r, 0.7)) {
		say(g, "%sacceleration: %.5g", any ? ", " : "", logu(r, 20, 3e5) * unit);
		any = true;
	}
	if (!any)
		say(g, "velocity: %.5g", logu(r, 5, 3000) * unit);
	say(g, "}\n");
}

struct node {
	bool joint, rev, spin;
	double lo, hi;      /* the keys' values */
	uint32_t nkeys;
	double f[6], v[6];
	const char *interp;
};

static void timing(struct scenegen *g, struct tu_rng *r)
{
	static const uint32_t hz[] = { 100, 250, 500, 1000, 2000, 5000, 10000 };
	static const uint32_t fps[][2] = { { 24, 1 }, { 25, 1 }, { 30000, 1001 } };
	const uint32_t *f = fps[pick(r, 3)];
	double secs = logu(r, 1, 86400), frames;

	g->tick_hz = hz[pick(r, 7)];
	if (secs * g->tick_hz > (double)g->max_ticks)
		secs = (double)g->max_ticks / g->tick_hz;
	g->num = f[0];
	g->den = f[1];
	frames = floor(secs * f[0] / f[1]);
	if (frames < 1)
		frames = 1;
	g->first = (int64_t)pick(r, 100);
	g->last = g->first + (int64_t)frames;
	g->ticks = (int64_t)((double)(g->last - g->first) * g->tick_hz * f[1] / f[0]) + 1;
	if (f[1] == 1)
		say(g, "timing: {tick_hz: %u, frame_rate: %u, frames: [%lld, %lld]}\n", g->tick_hz,
		    f[0], (long long)g->first, (long long)g->last);
	else
		say(g, "timing: {tick_hz: %u, frame_rate: \"%u/%u\", frames: [%lld, %lld]}\n",
		    g->tick_hz, f[0], f[1], (long long)g->first, (long long)g->last);
}

static void nodes(struct scenegen *g, struct tu_rng *r, struct node *nd, uint32_t n)
{
	static const char *const axes[] = { "x", "y", "z" };
	double span = (double)(g->last - g->first);
	uint32_t i, k;

	say(g, "nodes:\n");
	for (i = 0; i < n; i++) {
		struct node *d = &nd[i];

		d->joint = !chance(r, 0.25);
		d->rev = d->joint && chance(r, 0.6);
		d->spin = d->rev && chance(r, 0.2);
		d->nkeys = 2 + pick(r, 5);
		key_frames(r, fmax(0, (double)g->first - span / 5), (double)g->last + span / 5,
			   d->nkeys, d->f);
		d->interp = d->spin ? interps[pick(r, 3)] : interps[pick(r, 6)];
		d->lo = 1e300;
		d->hi = -1e300;
		for (k = 0; k < d->nkeys; k++) {
			d->v[k] = d->spin ? floor(tu_uniform(r, -600, 600)) :
				  d->rev  ? tu_uniform(r, -360, 360) :
					    tu_uniform(r, -1, 1);
			d->lo = fmin(d->lo, d->v[k]);
			d->hi = fmax(d->hi, d->v[k]);
		}
		say(g, "  - name: n%u\n", i);
		if (i && chance(r, 0.5))
			say(g, "    parent: n%u\n", pick(r, i));
		if (chance(r, 0.5))
			say(g, "    pivot: [%.3f, %.3f, %.3f]\n", tu_uniform(r, -1, 1),
			    tu_uniform(r, -1, 1), tu_uniform(r, -1, 1));
		if (!d->joint)
			continue;
		if (chance(r, 0.7))
			say(g, "    joint: {type: %s, axis: %s}\n", d->rev ? "revolute" : "prismatic",
			    axes[pick(r, 3)]);
		else
			say(g, "    joint: {type: %s, axis: [%.3f, %.3f, %.3f]}\n",
			    d->rev ? "revolute" : "prismatic", tu_uniform(r, 0.1, 1),
			    tu_uniform(r, -1, 1), tu_uniform(r, -1, 1));
		if (chance(r, 0.2))
			say(g, "    rest: %.3f\n", d->rev ? tu_uniform(r, -90, 90) : tu_uniform(r, -1, 1));
		if (!d->spin)
			limits(g, r, d->rev, d->lo, d->hi);
	}
}

static void strands(struct scenegen *g, struct tu_rng *r, struct node *nd, uint32_t n)
{
	uint32_t i, k;
	bool any = false, rot4;

	for (i = 0; i < n; i++) {
		struct node *d = &nd[i];

		if (chance(r, 0.1))
			continue; /* a node no strand moves */
		if (!any)
			say(g, "strands:\n");
		any = true;
		say(g, "  - node: n%u\n", i);
		if (d->spin) {
			say(g, "    interpolation: %s\n    keys:\n", d->interp);
			for (k = 0; k < d->nkeys; k++)
				say(g, "      - {frame: %.1f, rpm: %.0f}\n", d->f[k], d->v[k]);
			continue;
		}
		strand_head(g, r, "    ", d->interp, d->f[d->nkeys - 1] - d->f[0]);
		rot4 = false;
		if (!d->joint && chance(r, 0.5)) {
			static const char *const rots[] = { "slerp", "squad", "cubic", "step" };
			uint32_t w = pick(r, 4);

			say(g, "    rotation: %s\n", rots[w]);
			/* cubic and step rotations are shaped by their keys alone */
			rot4 = w >= 2;
		}
		/* a storage choice: step and linear channels keep their keys alone */
		if (chance(r, 0.15))
			say(g, "    compact: true\n");
		say(g, "    keys:\n");
		for (k = 0; k < d->nkeys; k++) {
			say(g, "      - {frame: %.1f", d->f[k]);
			if (d->joint) {
				double slope = (d->hi - d->lo + 1) / (d->f[d->nkeys - 1] - d->f[0] + 1);

				say(g, d->rev ? ", angle: %.4f" : ", position: %.5f", d->v[k]);
				/* an animator's handles: a slope in the value's unit per
				 * frame, either side (hermite only) */
				if (!strcmp(d->interp, "hermite") && chance(r, 0.3))
					say(g, ", in: %.5f", tu_uniform(r, -3, 3) * slope);
				if (!strcmp(d->interp, "hermite") && chance(r, 0.3))
					say(g, ", out: %.5f", tu_uniform(r, -3, 3) * slope);
			} else {
				bool t = !k || chance(r, 0.7), rot = !k || !t || chance(r, 0.7);

				if (t)
					say(g, ", translate: [%.3f, %.3f, %.3f]", tu_uniform(r, -1, 1),
					    tu_uniform(r, -1, 1), tu_uniform(r, -1, 1));
				if (rot)
					say(g, ", rotate: [%.2f, %.2f, %.2f]", tu_uniform(r, -180, 180),
					    tu_uniform(r, -90, 90), tu_uniform(r, -180, 180));
				if (chance(r, 0.3))
					say(g, ", scale: [%.3f, %.3f, %.3f]", tu_uniform(r, 0.5, 2),
					    tu_uniform(r, 0.5, 2), tu_uniform(r, 0.5, 2));
			}
			if (!rot4)
				key_ease(g, r);
			say(g, "}\n");
		}
	}
}

static void camera(struct scenegen *g, struct tu_rng *r)
{
	double span = (double)(g->last - g->first), f[6];
	uint32_t n = 2 + pick(r, 4), k;

	double a = tu_uniform(r, -M_PI, M_PI);

	/* keys a few frames apart at least, the eye going round the subject by
	 * at most 30 degrees from one to the next: a camera the core's pan
	 * grid can follow (motion/camera.h) */
	key_frames(r, (double)g->first, (double)g->last + span / 10, n, f);
	for (k = 1; k < n; k++)
		if (f[k] < f[k - 1] + 4)
			f[k] = f[k - 1] + 4;
	say(g, "camera:\n");
	strand_head(g, r, "  ", interps[1 + pick(r, 5)], f[n - 1] - f[0]);
	say(g, "  keys:\n");
	for (k = 0; k < n; k++) {
		double d = tu_uniform(r, 3, 6);

		a += tu_uniform(r, -M_PI / 6, M_PI / 6);
		say(g, "    - {frame: %.1f, eye: [%.3f, %.3f, %.3f], look_at: [%.3f, %.3f, %.3f], "
		       "twist: %.2f}\n", f[k], d * cos(a), tu_uniform(r, 0.5, 2), d * sin(a),
		    tu_uniform(r, -0.2, 0.2), tu_uniform(r, 0, 1), tu_uniform(r, -0.2, 0.2),
		    tu_uniform(r, -10, 10));
	}
}

static void extras(struct scenegen *g, struct tu_rng *r)
{
	static const char *const modes[] = { "loop", "bounce", "growth" };
	double span = (double)(g->last - g->first), f[4];
	uint32_t first, k;

	if (chance(r, 0.3)) {
		first = pick(r, 5);
		say(g, "cycles:\n  - {name: c0, first: %u, last: %u, skip: %u, mode: %s, "
		       "frames_per_step: %u, start_frame: %u}\n", first, first + 1 + pick(r, 20),
		    1 + pick(r, 3), modes[pick(r, 3)], 1 + pick(r, 5), pick(r, 10));
	}
	if (chance(r, 0.3)) {
		key_frames(r, (double)g->first, (double)g->last + span / 10, 3, f);
		say(g, "attributes:\n  - name: a0\n    interpolation: %s\n    keys:\n",
		    interps[pick(r, 3)]);
		for (k = 0; k < 3; k++)
			say(g, "      - {frame: %.1f, value: %.4f}\n", f[k], tu_uniform(r, 0, 1));
	}
}

static void run_options(struct scenegen *g, struct tu_rng *r)
{
	int64_t span = g->last - g->first, a, b;
	uint32_t what = pick(r, 10);

	g->run[0] = '\0';
	if (what == 0 && span >= 2) {
		a = g->first + (int64_t)pick(r, (uint32_t)(span / 2 < 1000000 ? span / 2 : 1000000));
		b = a + 1 + (int64_t)pick(r, (uint32_t)(g->last - a < 1000000 ? g->last - a : 1000000));
		snprintf(g->run, sizeof(g->run), " --from %lld --to %lld", (long long)a,
			 (long long)(b > g->last ? g->last : b));
	} else if (what == 1 && span >= 1) {
		snprintf(g->run, sizeof(g->run), " --ping-pong --passes 3");
	} else if (what == 2) {
		snprintf(g->run, sizeof(g->run), " --loop --passes 2");
	} else if (what == 3) {
		/* go-motion over a few frames, with a shutter that opens for
		 * two ticks or more at the scene's rates */
		static const double angles[] = { 180, 360, 90, 270, 172.8 };
		double angle = angles[pick(r, 5)];
		double least = 720.0 * g->num / ((double)g->den * g->tick_hz) * 1.01;

		if (angle < least)
			angle = 360;
		if (angle < least)
			return;
		a = g->first + (int64_t)pick(r, (uint32_t)(span < 1000000 ? span + 1 : 1000000));
		b = a + (int64_t)pick(r, 8);
		snprintf(g->run, sizeof(g->run), " --mode step --shutter %g --from %lld --to %lld",
			 angle, (long long)a, (long long)(b > g->last ? g->last : b));
	}
}

/*
 * The seed's systems (issue 16), now and then: a surface, scripted or
 * Newtonian particles (emitted, or a small pinned lattice), a flock, maybe
 * a head aiming at an item, with limits on some channel that the run may or
 * may not keep. From a generator of their own, after everything else, so
 * that a seed's scene without them is what it was before they came.
 */
static void systems(struct scenegen *g, uint64_t seed)
{
	double secs = (double)(g->last - g->first) * g->den / g->num, f[3];
	const char *interp;
	struct tu_rng r;
	uint32_t kind, k, a, b, n;
	bool aim = false;
	char target[32] = "";

	tu_seed(&r, seed * 0xbf58476d1ce4e5b9ull + 16);
	if (secs > 60 || !chance(&r, 0.3))
		return;
	kind = pick(&r, 4);
	interp = interps[pick(&r, 6)];
	key_frames(&r, (double)g->first, (double)g->last, 3, f);
	if (kind == 0) {
		uint32_t cu = 2 + pick(&r, 3), cv = 2 + pick(&r, 3), su = 1 + pick(&r, 4),
			 sv = 1 + pick(&r, 4);

		say(g, "surfaces:\n  - name: gs0\n    control: [%u, %u]\n    samples: [%u, %u]\n"
		       "    origin: [-1, 2, -1]\n    size: [2, 2]\n    interpolation: %s\n"
		       "    keys:\n", cu, cv, su, sv, interp);
		for (k = 0; k < 3; k++) {
			say(g, "      - {frame: %.1f, heights: [", f[k]);
			for (a = 0; a < cu; a++) {
				say(g, "%s[", a ? ", " : "");
				for (b = 0; b < cv; b++)
					say(g, "%s%.3f", b ? ", " : "", tu_uniform(&r, -0.5, 0.5));
				say(g, "]");
			}
			say(g, "]}\n");
		}
		if (chance(&r, 0.5))
			say(g, "    limits: {y: {min: %.2f, max: %.2f, velocity: %.3f, "
			       "acceleration: %.3f}}\n", tu_uniform(&r, 1.3, 1.8),
			    tu_uniform(&r, 2.2, 2.7), logu(&r, 0.05, 5), logu(&r, 0.05, 50));
		aim = chance(&r, 0.5);
		snprintf(target, sizeof(target), "gs0.%u.%u", pick(&r, su), pick(&r, sv));
	} else if (kind == 1) {
		n = 1 + pick(&r, 8);
		say(g, "particles:\n  - name: gp0\n    pool: %u\n    motion: %s\n    step_hz: %u\n"
		       "    seed: %u\n    emit:\n      interpolation: %s\n      keys:\n"
		       "        - {frame: %.1f, rate: %.2f, spread: %.2f, velocity: [[-0.5, 1, -0.5], "
		       "[0.5, 3, 0.5]], lifetime: [0.2, %.2f], colour: [[0, 0, 0], [1, 1, 1]]}\n"
		       "        - {frame: %.1f, rate: %.2f}\n"
		       "    over_life: {interpolation: linear, keys: [{age: 0, alpha: 1}, "
		       "{age: 1, alpha: 0}]}\n    gravity: [0, -9.81, 0]\n", n,
		    chance(&r, 0.5) ? "newtonian" : "scripted", 10 + pick(&r, 91), pick(&r, 1000),
		    interps[pick(&r, 3)], f[0], tu_uniform(&r, 0, 10), tu_uniform(&r, 0, 5),
		    tu_uniform(&r, 0.3, 2), f[2], tu_uniform(&r, 0, 10));
	} else if (kind == 2) {
		a = 2 + pick(&r, 3);
		say(g, "particles:\n  - name: gc0\n    motion: newtonian\n    step_hz: 200\n"
		       "    lattice: {size: [%u, %u], spacing: [0.2, 0.2], origin: [0, 2, 0]}\n"
		       "    mass: 0.05\n    springs: {stiffness: %.2f, damping: 0.01}\n"
		       "    gravity: [0, -9.81, 0]\n    drag: 2\n    pins: [{at: [1, 1]}, "
		       "{at: [1, %u], keys: [{frame: %.1f, offset: [0, 0, 0]}, "
		       "{frame: %.1f, offset: [0, %.2f, 0]}]}]\n", a, a, tu_uniform(&r, 1, 20), a,
		    f[0], f[2], tu_uniform(&r, -0.3, 0.3));
		if (chance(&r, 0.5))
			say(g, "    limits: {y: {min: %.2f, velocity: %.3f, acceleration: %.3f}}\n",
			    tu_uniform(&r, 0.5, 1.9), logu(&r, 0.2, 10), logu(&r, 1, 200));
	} else {
		n = 1 + pick(&r, 8);
		say(g, "flocks:\n  - name: gb0\n    members: %u\n    step_hz: %u\n    seed: %u\n"
		       "    start: {centre: [0, 2, 0], spread: 1, velocity: [0.3, 0, 0]}\n"
		       "    separation: {distance: 0.4, weight: 2}\n    cohesion: 1\n"
		       "    alignment: 1\n    goal: {weight: 1, interpolation: %s, keys: "
		       "[{frame: %.1f, position: [1, 2, 0]}, {frame: %.1f, position: [-1, 2, 1]}]}\n"
		       "    speed: %.2f\n    acceleration: %.2f\n", n, 10 + pick(&r, 91),
		    pick(&r, 1000), interps[pick(&r, 3)], f[0], f[2], tu_uniform(&r, 0.2, 1),
		    tu_uniform(&r, 0.5, 3));
		aim = chance(&r, 0.5);
		snprintf(target, sizeof(target), "gb0.%u", pick(&r, n));
	}
	/* a head far enough for no target to sweep a quarter turn in a grid step */
	if (aim)
		say(g, "aims:\n  - {name: gh0, at: [0, 8, -6], target: %s%s}\n", target,
		    chance(&r, 0.5) ? ", limits: {pan: {velocity: 30, acceleration: 100}}" : "");
}

void scenegen_make(struct scenegen *g, uint64_t seed)
{
	struct tu_rng r;
	struct node nd[6];
	uint32_t n;

	tu_seed(&r, seed * 0x9e3779b97f4a7c15ull + 1);
	g->len = 0;
	if (!g->yaml) {
		g->cap = 4096;
		g->yaml = malloc(g->cap);
		if (!g->yaml)
			abort();
	}
	g->yaml[0] = '\0';
	say(g, "scene: gen-%llu\n", (unsigned long long)seed);
	timing(g, &r);
	n = 1 + pick(&r, 5);
	nodes(g, &r, nd, n);
	strands(g, &r, nd, n);
	if (chance(&r, 0.3))
		camera(g, &r);
	extras(g, &r);
	run_options(g, &r);
	systems(g, seed);
}

void scenegen_free(struct scenegen *g)
{
	free(g->yaml);
	g->yaml = NULL;
	g->len = g->cap = 0;
}
