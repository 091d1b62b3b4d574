/* SPDX-License-Identifier: MIT */
/*
 * plot.c - `strand plot`'s overview page: top and side views of every
 * node's world path, then each channel against frames with its keys
 * marked, and the sampling of a built scene that it and the method
 * comparison (plot_compare.c) share.
 */
#include "plot.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define VIEW_W 540
#define VIEW_H 360
#define CHART_W 540
#define CHART_H 150
#define PAGE_W 1300
#define LEFT 70
#define GAP_X 90
#define GAP_Y 70

int plot_samples_make(struct plot_samples *ps, const struct scene_file *sf,
		      const struct mot_scene *sc, const struct chan_list *ch, double first,
		      double last, uint32_t n)
{
	struct mot_eval ev;
	struct mot_pose pose;
	uint32_t s, c;

	ps->n = n;
	ps->frame = calloc(n, sizeof(*ps->frame));
	ps->val = calloc((size_t)n * (ch->n ? ch->n : 1), sizeof(*ps->val));
	if (!ps->frame || !ps->val || scene_eval_new(&ev, sc)) {
		plot_samples_free(ps);
		return -ENOMEM;
	}
	if (scene_pose_new(&pose, sc)) {
		scene_eval_free(&ev);
		plot_samples_free(ps);
		return -ENOMEM;
	}
	for (s = 0; s < n; s++) {
		double f = n > 1 ? first + (last - first) * s / (n - 1) : first;

		ps->frame[s] = f;
		mot_scene_eval(sc, &ev, (mot_q32)llround(f * 4294967296.0), &pose);
		for (c = 0; c < ch->n; c++)
			ps->val[(size_t)c * n + s] = chan_value(&ch->c[c], &pose);
	}
	ps->sat = ev.sat;
	scene_pose_free(&pose);
	scene_eval_free(&ev);
	return 0;
}

void plot_samples_free(struct plot_samples *ps)
{
	free(ps->frame);
	free(ps->val);
	ps->frame = ps->val = NULL;
}

int plot_eval_at(double *out, const struct mot_scene *sc, const struct chan_list *ch,
		 double frame)
{
	struct mot_eval ev;
	struct mot_pose pose;
	uint32_t c;

	if (scene_eval_new(&ev, sc))
		return -ENOMEM;
	if (scene_pose_new(&pose, sc)) {
		scene_eval_free(&ev);
		return -ENOMEM;
	}
	mot_scene_eval(sc, &ev, (mot_q32)llround(frame * 4294967296.0), &pose);
	for (c = 0; c < ch->n; c++)
		out[c] = chan_value(&ch->c[c], &pose);
	scene_pose_free(&pose);
	scene_eval_free(&ev);
	return 0;
}

/* Sample count: a few per frame, at most enough for a smooth line. */
uint32_t plot_sample_count(double first, double last)
{
	double n = (last - first) * 4 + 1;

	return n < 2 ? 2 : n > 2001 ? 2001 : (uint32_t)n;
}

static void range_of(const double *v, uint32_t n, double *lo, double *hi)
{
	uint32_t i;

	for (i = 0; i < n; i++) {
		*lo = fmin(*lo, v[i]);
		*hi = fmax(*hi, v[i]);
	}
}

/* ---- the overview ------------------------------------------------------------ */

struct page {
	FILE *f;
	const struct scene_file *sf;
	const struct mot_scene *sc;
	const struct chan_list *ch;
	const struct plot_samples *ps;
	double *at_key;   /* scratch: every channel at one key frame */
	uint32_t next_id;
};

/* Top (x, z) or side (x, y) view of every node's path, keys marked. */
static int view(struct page *p, double x, double y, uint32_t vaxis, const char *title)
{
	const struct scene_desc *d = &p->sf->desc;
	struct chart c = { x, y, VIEW_W, VIEW_H, 0, 0, 0, 0, true, p->next_id++ };
	double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
	uint32_t i, k, n = p->ps->n;

	for (i = 0; i < d->nnodes; i++) {
		range_of(plot_series(p->ps, 3 * i), n, &xlo, &xhi);
		range_of(plot_series(p->ps, 3 * i + vaxis), n, &ylo, &yhi);
	}
	if (!d->nnodes)
		xlo = xhi = ylo = yhi = 0;
	chart_fit(&c, xlo, xhi, ylo, yhi);
	chart_axes(p->f, &c, title, "x", vaxis == 1 ? "y" : "z");
	for (i = 0; i < d->nnodes; i++) {
		const struct sf_strand *st = &p->sf->strand[i];

		chart_line(p->f, &c, plot_series(p->ps, 3 * i), plot_series(p->ps, 3 * i + vaxis),
			   n, svg_color(i), 2, NULL);
		for (k = 0; st->present && k < st->nkeys; k++) {
			if (plot_eval_at(p->at_key, p->sc, p->ch, st->key_frames[k]))
				return -ENOMEM;
			chart_mark(p->f, &c, p->at_key[3 * i], p->at_key[3 * i + vaxis],
				   svg_color(i));
		}
	}
	return 0;
}

/* Key marks: points in data coordinates. */
struct marks {
	double *x, *y;
	uint32_t n;
};

/* The key marks of one channel: its keys' values where the file gives
 * them (an approximating curve need not pass through them), else the
 * evaluated value at each key frame. */
static int channel_keys(struct page *p, uint32_t chan, struct marks *m)
{
	const struct scene_desc *d = &p->sf->desc;
	const struct chan *ch = &p->ch->c[chan];
	const struct sd_curve *curve = NULL;
	const double *frames = NULL;
	uint32_t n = 0, k;
	bool given = true;

	switch (ch->kind) {
	case CHAN_VALUE:
		curve = &d->nodes[ch->index].value;
		break;
	case CHAN_RPM:
		curve = &d->nodes[ch->index].spin;
		break;
	case CHAN_ATTR:
		curve = &d->attrs[ch->index].curve;
		break;
	case CHAN_CAMERA:
		curve = &d->camera.ch[ch->comp < 3 ? ch->comp : 0];
		given = ch->comp < 3; /* pan, tilt, roll: evaluated at the camera's keys */
		break;
	case CHAN_POS:
		if (p->sf->strand[ch->index].present) {
			frames = p->sf->strand[ch->index].key_frames;
			n = p->sf->strand[ch->index].nkeys;
		}
		given = false;
		break;
	default:
		break;
	}
	if (curve)
		n = curve->nkeys;
	m->n = 0;
	m->x = calloc(n ? n : 1, sizeof(*m->x));
	m->y = calloc(n ? n : 1, sizeof(*m->y));
	if (!m->x || !m->y)
		return -ENOMEM;
	for (k = 0; k < n; k++) {
		m->x[k] = curve ? curve->keys[k].frame : frames[k];
		if (given) {
			m->y[k] = curve->keys[k].value;
		} else {
			if (plot_eval_at(p->at_key, p->sc, p->ch, m->x[k]))
				return -ENOMEM;
			m->y[k] = p->at_key[chan];
		}
	}
	m->n = n;
	return 0;
}

static void marks_free(struct marks *m, uint32_t count)
{
	uint32_t i;

	for (i = 0; i < count; i++) {
		free(m[i].x);
		free(m[i].y);
	}
}

/* One chart of `count` (at most 3) consecutive channels from `chan`; the
 * range holds the lines and the key marks. */
static int channel_chart(struct page *p, double x, double y, uint32_t chan, uint32_t count,
			 const char *title)
{
	const struct plot_samples *ps = p->ps;
	struct chart c = { x, y, CHART_W, CHART_H, 0, 0, 0, 0, false, p->next_id++ };
	double lo = INFINITY, hi = -INFINITY, lx = x + CHART_W - 10;
	struct marks m[3];
	uint32_t i, k;
	int err = 0;

	memset(m, 0, sizeof(m));
	for (i = 0; i < count && !err; i++) {
		range_of(plot_series(ps, chan + i), ps->n, &lo, &hi);
		err = channel_keys(p, chan + i, &m[i]);
		range_of(m[i].y, m[i].n, &lo, &hi);
	}
	if (err) {
		marks_free(m, count);
		return err;
	}
	chart_fit(&c, ps->frame[0], ps->frame[ps->n - 1], lo, hi);
	chart_axes(p->f, &c, title, "frame", p->ch->c[chan].unit);
	for (i = 0; i < count; i++) {
		const char *color = svg_color(count == 1 ? chan : i);

		chart_line(p->f, &c, ps->frame, plot_series(ps, chan + i), ps->n, color, 1.8, NULL);
		for (k = 0; k < m[i].n; k++)
			chart_mark(p->f, &c, m[i].x[k], m[i].y[k], color);
		if (count > 1) {
			const char *dot = strrchr(p->ch->c[chan + i].name, '.');

			svg_legend(p->f, lx - 50 * (count - i), y + 14, color, dot ? dot + 1 : "",
				   NULL);
		}
	}
	marks_free(m, count);
	return 0;
}

/* Charts: a node's three position channels together, the camera's eye and
 * its angles together, every other channel alone. */
static uint32_t chart_group(const struct chan_list *ch, uint32_t i, char *title, size_t size)
{
	const struct chan *c = &ch->c[i];

	if (c->kind == CHAN_POS) {
		snprintf(title, size, "%.*s position (.x .y .z)",
			 (int)(strrchr(c->name, '.') - c->name), c->name);
		return 3;
	}
	if (c->kind == CHAN_CAMERA) {
		snprintf(title, size, c->comp == 0 ? "camera eye (.x .y .z)" :
						     "camera angles (.pan .tilt .roll, degrees)");
		return 3;
	}
	snprintf(title, size, "%s%s%s", c->name, c->unit[0] ? ", " : "",
		 !strcmp(c->unit, "deg") ? "degrees" : c->unit);
	return 1;
}

int plot_overview(FILE *f, const struct scene_file *sf, const struct mot_scene *sc,
		  const struct chan_list *ch, const struct plot_samples *ps)
{
	struct page p = { f, sf, sc, ch, ps, NULL, 0 };
	uint32_t i, groups = 0, n, col = 0;
	double y, height;
	char title[160];
	int err = 0;

	for (i = 0; i < ch->n; i += n, groups++)
		n = chart_group(ch, i, title, sizeof(title));
	height = 90 + VIEW_H + 90 + ((groups + 1) / 2) * (CHART_H + GAP_Y) + 20;
	p.at_key = calloc(ch->n ? ch->n : 1, sizeof(*p.at_key));
	if (!p.at_key)
		return -ENOMEM;
	svg_begin(f, PAGE_W, height);
	snprintf(title, sizeof(title), "%s - %s", sf->desc.name[0] ? sf->desc.name : "scene",
		 sf->path);
	svg_text(f, LEFT, 30, 18, "start", "#000", title);
	err = view(&p, LEFT, 80, 2, "top view (x, z): node paths, keys ringed");
	if (!err)
		err = view(&p, LEFT + VIEW_W + GAP_X, 80, 1, "side view (x, y): node paths, keys ringed");
	y = 80 + VIEW_H + 40;
	for (i = 0; i < sf->desc.nnodes; i++)
		svg_legend(f, LEFT + (i % 8) * 140, y + (i / 8) * 16, svg_color(i),
			   sf->desc.nodes[i].name, NULL);
	y += ((sf->desc.nnodes + 7) / 8) * 16 + 40;
	for (i = 0; !err && i < ch->n; i += n) {
		n = chart_group(ch, i, title, sizeof(title));
		err = channel_chart(&p, LEFT + col * (CHART_W + GAP_X), y, i, n, title);
		if (++col == 2) {
			col = 0;
			y += CHART_H + GAP_Y;
		}
	}
	svg_end(f);
	free(p.at_key);
	return err;
}
