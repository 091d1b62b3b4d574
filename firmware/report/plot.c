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
/* The most values sampled (channels x samples): a 64 x 64 surface's 12288
 * channels get fewer samples, not a 200 MB table. */
#define PLOT_VALUES_MAX (4u << 20)
/* The most items of a system drawn (paths, lines on a chart), evenly
 * chosen among them. */
#define PLOT_ITEMS_MAX 64u

int plot_samples_make(struct plot_samples *ps, const struct scene_file *sf,
		      const struct mot_scene *sc, const struct chan_list *ch, double first,
		      double last, uint32_t n)
{
	struct mot_eval ev;
	struct mot_pose pose;
	uint32_t s, c;

	if ((uint64_t)n * ch->n > PLOT_VALUES_MAX)
		n = PLOT_VALUES_MAX / ch->n > 2 ? PLOT_VALUES_MAX / ch->n : 2;
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

/* The first channel of system s's item `item` (its x), or of the first
 * system channel when item is UINT32_MAX. */
static uint32_t sys_chan(const struct chan_list *ch, const struct scene_desc *d, uint32_t s,
			 uint32_t item)
{
	uint32_t i, base = 0;

	for (i = 0; i < ch->n && ch->c[i].kind != CHAN_SYS; i++)
		;
	for (base = 0; base < s; base++)
		i += sd_sys_items(&d->sys[base]) * sd_sys_per(&d->sys[base]);
	return i + (item == UINT32_MAX ? 0 : item * sd_sys_per(&d->sys[s]));
}

/* The items of system s drawn: every one, or PLOT_ITEMS_MAX evenly spaced. */
static uint32_t drawn(const struct sd_system *s, uint32_t k)
{
	uint32_t n = sd_sys_items(s);

	return n <= PLOT_ITEMS_MAX ? k : (uint32_t)((uint64_t)k * n / PLOT_ITEMS_MAX);
}

static uint32_t ndrawn(const struct sd_system *s)
{
	uint32_t n = sd_sys_items(s);

	return n < PLOT_ITEMS_MAX ? n : PLOT_ITEMS_MAX;
}

/* Top (x, z) or side (x, y) view of every node's path, keys marked, and
 * the paths of the systems' items (surface samples, particles, members). */
static int view(struct page *p, double x, double y, uint32_t vaxis, const char *title)
{
	const struct scene_desc *d = &p->sf->desc;
	struct chart c = { x, y, VIEW_W, VIEW_H, 0, 0, 0, 0, true, p->next_id++ };
	double xlo = INFINITY, xhi = -INFINITY, ylo = INFINITY, yhi = -INFINITY;
	uint32_t i, k, s, n = p->ps->n;

	for (i = 0; i < d->nnodes; i++) {
		range_of(plot_series(p->ps, 3 * i), n, &xlo, &xhi);
		range_of(plot_series(p->ps, 3 * i + vaxis), n, &ylo, &yhi);
	}
	for (s = 0; s < d->nsys; s++)
		for (k = 0; k < ndrawn(&d->sys[s]); k++) {
			uint32_t c0 = sys_chan(p->ch, d, s, drawn(&d->sys[s], k));

			range_of(plot_series(p->ps, c0), n, &xlo, &xhi);
			range_of(plot_series(p->ps, c0 + vaxis), n, &ylo, &yhi);
		}
	if (!d->nnodes && !d->nsys)
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
	for (s = 0; s < d->nsys; s++)
		for (k = 0; k < ndrawn(&d->sys[s]); k++) {
			uint32_t c0 = sys_chan(p->ch, d, s, drawn(&d->sys[s], k));

			chart_line(p->f, &c, plot_series(p->ps, c0), plot_series(p->ps, c0 + vaxis),
				   n, svg_color(d->nnodes + s), 0.8, NULL);
		}
	return 0;
}

/* One chart of channel k of every (drawn) item of system s against
 * frames. */
static void sys_chart(struct page *p, double x, double y, uint32_t s, uint32_t k)
{
	const struct scene_desc *d = &p->sf->desc;
	const struct sd_system *sys = &d->sys[s];
	const struct plot_samples *ps = p->ps;
	struct chart c = { x, y, CHART_W, CHART_H, 0, 0, 0, 0, false, p->next_id++ };
	double lo = INFINITY, hi = -INFINITY;
	uint32_t i, nd = ndrawn(sys), c0 = sys_chan(p->ch, d, s, UINT32_MAX);
	char title[160];

	for (i = 0; i < nd; i++)
		range_of(plot_series(ps, c0 + drawn(sys, i) * sd_sys_per(sys) + k), ps->n, &lo, &hi);
	chart_fit(&c, ps->frame[0], ps->frame[ps->n - 1], lo, hi);
	snprintf(title, sizeof(title), "%s.*.%s%s (%u of %u %s)", sd_sys_name(sys),
		 sd_sys_suffix(sys, k), sd_sys_angle(sys, k) ? ", degrees" : "", nd,
		 sd_sys_items(sys), sys->kind == SD_SURFACE ? "samples" :
		 sys->kind == SD_FLOCK ? "members" : "slots");
	chart_axes(p->f, &c, title, "frame", sd_sys_angle(sys, k) ? "deg" : "");
	for (i = 0; i < nd; i++)
		chart_line(p->f, &c, ps->frame,
			   plot_series(ps, c0 + drawn(sys, i) * sd_sys_per(sys) + k), ps->n,
			   svg_color(i), 0.8, NULL);
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
 * its angles together, an aim's pan and tilt together, a system's items
 * all on one chart per channel (sys_chart), every other channel alone. */
static uint32_t chart_group(const struct chan_list *ch, uint32_t i, char *title, size_t size)
{
	const struct chan *c = &ch->c[i];

	if (c->kind == CHAN_AIM) {
		snprintf(title, size, "%.*s (.pan .tilt, degrees)",
			 (int)(strrchr(c->name, '.') - c->name), c->name);
		return 2;
	}
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

	for (i = 0; i < ch->n && ch->c[i].kind != CHAN_SYS; i += n, groups++)
		n = chart_group(ch, i, title, sizeof(title));
	for (n = 0; n < sf->desc.nsys; n++)
		groups += sd_sys_per(&sf->desc.sys[n]);
	for (; i < ch->n; i++)
		groups += ch->c[i].kind == CHAN_AIM && ch->c[i].comp == 0;
	height = 90 + VIEW_H + 90 + ((groups + 1) / 2) * (CHART_H + GAP_Y) + 20;
	p.at_key = calloc(ch->n ? ch->n : 1, sizeof(*p.at_key));
	if (!p.at_key)
		return -ENOMEM;
	svg_begin(f, PAGE_W, height);
	snprintf(title, sizeof(title), "%s - %s", sf->desc.name[0] ? sf->desc.name : "scene",
		 sf->path);
	svg_text(f, LEFT, 30, 18, "start", "#000", title);
	err = view(&p, LEFT, 80, 2, sf->desc.nsys ? "top view (x, z): node and item paths, keys ringed" :
						     "top view (x, z): node paths, keys ringed");
	if (!err)
		err = view(&p, LEFT + VIEW_W + GAP_X, 80, 1,
			   sf->desc.nsys ? "side view (x, y): node and item paths, keys ringed" :
					   "side view (x, y): node paths, keys ringed");
	y = 80 + VIEW_H + 40;
	for (i = 0; i < sf->desc.nnodes + sf->desc.nsys; i++)
		svg_legend(f, LEFT + (i % 8) * 140, y + (i / 8) * 16, svg_color(i),
			   i < sf->desc.nnodes ? sf->desc.nodes[i].name :
						 sd_sys_name(&sf->desc.sys[i - sf->desc.nnodes]),
			   NULL);
	y += ((sf->desc.nnodes + sf->desc.nsys + 7) / 8) * 16 + 40;
	for (i = 0; !err && i < ch->n; i += n) {
		if (ch->c[i].kind == CHAN_SYS) {
			/* a system: one chart per channel of an item */
			uint32_t s = ch->c[i].owner, k, per = sd_sys_per(&sf->desc.sys[s]);

			for (k = 0; k < per; k++) {
				sys_chart(&p, LEFT + col * (CHART_W + GAP_X), y, s, k);
				if (++col == 2) {
					col = 0;
					y += CHART_H + GAP_Y;
				}
			}
			n = sd_sys_items(&sf->desc.sys[s]) * per;
			continue;
		}
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
