/* SPDX-License-Identifier: MIT */
/*
 * plot_compare.c - `strand plot --compare NODE`: one strand's keys through
 * every interpolation method on one chart, as the seed paper's Figure 8
 * compares linear, Hermite, B-spline, Bezier and Beta-spline in-betweens
 * of the same key frames. A joint's value is drawn against frames; a free
 * node's pivot as its side-view path (x, y), where the loop of Figure 8 shows.
 *
 * Each method is a copy of the scene description with only that strand's
 * method changed, built and sampled like the real scene.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

/* The Beta-spline drawn when the strand is not one already: a visible bias
 * and tension (bias 1, tension 0 would repeat the B-spline). */
#define COMPARE_BETA1 1.5
#define COMPARE_BETA2 4.0

static const char *const method_name[] = { "step", "linear", "hermite", "bspline", "beta",
					   "bezier" };

static void set_method(struct sd_curve *c, enum mot_interp m, bool was_beta)
{
	c->interp = m;
	if (m == MOT_INTERP_BETA && !was_beta) {
		c->beta1 = COMPARE_BETA1;
		c->beta2 = COMPARE_BETA2;
	}
}

struct method_run {
	bool ok;
	struct plot_samples ps;
	struct scene_built b;
};

/* Build the scene with node's strand interpolated by m, and sample it. */
static int method(struct method_run *r, const struct scene_file *sf, struct sd_node *nodes,
		  uint32_t node, enum mot_interp m, const struct chan_list *ch)
{
	struct scene_desc d = sf->desc;
	struct sd_node *n = &nodes[node], saved = *n;
	struct scene_build_err e;
	uint32_t k;
	int err = 0;

	d.nodes = nodes;
	if (n->kind == MOT_NODE_FREE)
		for (k = 0; k < MOT_FREE_NCHANNELS; k++)
			set_method(&n->free.ch[k], m, saved.free.ch[k].interp == MOT_INTERP_BETA);
	else
		set_method(n->spin.nkeys ? &n->spin : &n->value, m,
			   (n->spin.nkeys ? n->spin.interp : n->value.interp) == MOT_INTERP_BETA);
	r->ok = scene_build(&r->b, &d, &e) == 0;
	if (r->ok)
		err = plot_samples_make(&r->ps, sf, &r->b.sc, ch, d.frame_first, d.frame_last,
					plot_sample_count(d.frame_first, d.frame_last));
	*n = saved;
	return err;
}

static void free_run(struct method_run *r)
{
	plot_samples_free(&r->ps);
	if (r->ok)
		scene_built_free(&r->b);
}

/* The channel the comparison draws: a joint's value, or its rpm. */
static uint32_t value_chan(const struct chan_list *ch, uint32_t node, bool rpm)
{
	uint32_t i;

	for (i = 0; i < ch->n; i++)
		if (ch->c[i].index == node && ch->c[i].kind == (rpm ? CHAN_RPM : CHAN_VALUE))
			return i;
	return 0;
}

static void draw(FILE *f, const struct scene_file *sf, uint32_t node, struct method_run *runs,
		 uint32_t nm, const struct chan_list *ch, const double *key_x, const double *key_y)
{
	const struct sd_node *n = &sf->desc.nodes[node];
	bool path = n->kind == MOT_NODE_FREE;
	uint32_t xc = path ? 3 * node : 0, yc = path ? 3 * node + 1 : value_chan(ch, node, n->spin.nkeys > 0);
	struct chart c = { 70, 70, 1080, 560, 0, 0, 0, 0, path, 1 };
	double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
	const struct sf_strand *st = &sf->strand[node];
	char title[200];
	uint32_t i, s;

	for (i = 0; i < nm; i++) {
		if (!runs[i].ok)
			continue;
		for (s = 0; s < runs[i].ps.n; s++) {
			double x = path ? plot_series(&runs[i].ps, xc)[s] : runs[i].ps.frame[s];
			double y = plot_series(&runs[i].ps, yc)[s];

			xlo = fmin(xlo, x), xhi = fmax(xhi, x);
			ylo = fmin(ylo, y), yhi = fmax(yhi, y);
		}
	}
	for (i = 0; i < st->nkeys; i++) {
		xlo = fmin(xlo, key_x[i]), xhi = fmax(xhi, key_x[i]);
		ylo = fmin(ylo, key_y[i]), yhi = fmax(yhi, key_y[i]);
	}
	svg_begin(f, 1240, 700);
	snprintf(title, sizeof(title), "%s: %u keys through every interpolation method (%s)",
		 path ? "side view of the node's path" : ch->c[yc].name, st->nkeys, sf->path);
	svg_text(f, 70, 30, 18, "start", "#000", title);
	chart_fit(&c, xlo, xhi, ylo, yhi);
	chart_axes(f, &c, path ? "x, y of the pivot in world space" : "value against frames",
		   path ? "x" : "frame", path ? "y" : ch->c[yc].unit);
	for (i = 0; i < nm; i++) {
		char label[64];

		snprintf(label, sizeof(label), "%s%s", method_name[i],
			 runs[i].ok ? "" : " (refused by the core)");
		/* step dashed: its path jumps from key to key, over linear's */
		svg_legend(f, 70 + i * 170, 670, svg_color(i), label, i ? NULL : "6,4");
		if (runs[i].ok)
			chart_line(f, &c, path ? plot_series(&runs[i].ps, xc) : runs[i].ps.frame,
				   plot_series(&runs[i].ps, yc), runs[i].ps.n, svg_color(i), 2,
				   i ? NULL : "6,4");
	}
	for (i = 0; i < st->nkeys; i++)
		chart_mark(f, &c, key_x[i], key_y[i], "#000");
	svg_end(f);
}

int plot_compare(FILE *f, const struct scene_file *sf, uint32_t node)
{
	const struct sd_node *n = &sf->desc.nodes[node];
	const struct sf_strand *st = &sf->strand[node];
	/* an rpm strand is integrated in closed form: interpolating kinds only */
	uint32_t nm = n->spin.nkeys ? MOT_INTERP_HERMITE + 1 : MOT_INTERP_BEZIER + 1, i, k;
	struct method_run runs[MOT_INTERP_BEZIER + 1];
	struct chan_list ch = { 0 };
	struct sd_node *nodes;
	double *kx, *ky, *at;
	int err;

	memset(runs, 0, sizeof(runs));
	nodes = malloc(sf->desc.nnodes * sizeof(*nodes));
	kx = calloc(st->nkeys, sizeof(*kx));
	ky = calloc(st->nkeys, sizeof(*ky));
	err = !nodes || !kx || !ky ? -ENOMEM : chan_list_make(&ch, &sf->desc);
	at = err ? NULL : calloc(ch.n ? ch.n : 1, sizeof(*at));
	if (!err && !at)
		err = -ENOMEM;
	if (!err)
		memcpy(nodes, sf->desc.nodes, sf->desc.nnodes * sizeof(*nodes));
	for (i = 0; !err && i < nm; i++)
		err = method(&runs[i], sf, nodes, node, (enum mot_interp)i, &ch);
	/* keys: a joint's key values; a free node's pivot at its key frames,
	 * where the linear in-between passes through them */
	for (k = 0; !err && k < st->nkeys; k++) {
		if (n->kind != MOT_NODE_FREE) {
			const struct sd_curve *c = n->spin.nkeys ? &n->spin : &n->value;

			kx[k] = c->keys[k].frame;
			ky[k] = c->keys[k].value;
		} else if (runs[MOT_INTERP_LINEAR].ok) {
			err = plot_eval_at(at, &runs[MOT_INTERP_LINEAR].b.sc, &ch, st->key_frames[k]);
			kx[k] = at[3 * node];
			ky[k] = at[3 * node + 1];
		}
	}
	if (!err)
		draw(f, sf, node, runs, nm, &ch, kx, ky);
	for (i = 0; i < nm; i++)
		free_run(&runs[i]);
	chan_list_free(&ch);
	free(nodes);
	free(kx);
	free(ky);
	free(at);
	return err;
}
