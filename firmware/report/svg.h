/* SPDX-License-Identifier: MIT */
/*
 * svg.h - just enough SVG for `strand plot`: a document, text, and charts
 * (a framed box with a data range, axes with round-numbered ticks, lines
 * and key marks). Coordinates are pixels; a chart maps data into its box.
 */
#ifndef STRAND_SVG_H
#define STRAND_SVG_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

struct chart {
	double px, py, pw, ph; /* the plotting box, pixels (y down) */
	double x0, x1, y0, y1; /* the data range shown */
	bool equal;            /* same scale on both axes (views) */
	uint32_t id;           /* unique in the document: names its clip path */
};

void svg_begin(FILE *f, double w, double h);
void svg_end(FILE *f);

/* Text, XML-escaped. anchor: "start", "middle" or "end". */
void svg_text(FILE *f, double x, double y, double size, const char *anchor, const char *color,
	      const char *text);

/* The palette's i-th colour (cycles). */
const char *svg_color(uint32_t i);

/* Fit a chart's data range to [lo, hi] on each axis with a margin (a flat
 * range gets a unit-wide band); for an equal chart, grow the narrower axis
 * so that one unit is as long on both. */
void chart_fit(struct chart *c, double xlo, double xhi, double ylo, double yhi);

/* The box, grid, tick labels, title and axis labels. */
void chart_axes(FILE *f, const struct chart *c, const char *title, const char *xlabel,
		const char *ylabel);

/* A polyline through (x[i], y[i]), clipped to the box by the chart's
 * clip path. dash may be NULL. */
void chart_line(FILE *f, const struct chart *c, const double *x, const double *y, uint32_t n,
		const char *color, double width, const char *dash);

/* A key mark (a ringed dot) at a data point. */
void chart_mark(FILE *f, const struct chart *c, double x, double y, const char *color);

/* A legend entry: a short line and a label, at a pixel position. */
void svg_legend(FILE *f, double x, double y, const char *color, const char *label,
		const char *dash);

#endif /* STRAND_SVG_H */
