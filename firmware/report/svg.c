/* SPDX-License-Identifier: MIT */
/* svg.c - SVG documents and charts for `strand plot` (see svg.h). */
#include "svg.h"

#include <math.h>

#include "numfmt.h"

static const char *const palette[] = {
	"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
	"#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22",
};

const char *svg_color(uint32_t i)
{
	return palette[i % (sizeof(palette) / sizeof(palette[0]))];
}

void svg_begin(FILE *f, double w, double h)
{
	fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
		   "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
		   "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\">\n"
		   "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
		w, h, w, h);
}

void svg_end(FILE *f)
{
	fprintf(f, "</svg>\n");
}

static void escape(FILE *f, const char *s)
{
	for (; *s; s++) {
		switch (*s) {
		case '&': fputs("&amp;", f); break;
		case '<': fputs("&lt;", f); break;
		case '>': fputs("&gt;", f); break;
		case '"': fputs("&quot;", f); break;
		default:
			/* XML 1.0 allows no control characters but tab and newlines */
			fputc((unsigned char)*s < 0x20 ? '?' : *s, f);
		}
	}
}

void svg_text(FILE *f, double x, double y, double size, const char *anchor, const char *color,
	      const char *text)
{
	fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%.0f\" text-anchor=\"%s\" fill=\"%s\">",
		x, y, size, anchor, color);
	escape(f, text);
	fputs("</text>\n", f);
}

static double map_x(const struct chart *c, double x)
{
	return c->px + (x - c->x0) / (c->x1 - c->x0) * c->pw;
}

static double map_y(const struct chart *c, double y)
{
	return c->py + c->ph - (y - c->y0) / (c->y1 - c->y0) * c->ph;
}

static void widen(double *lo, double *hi)
{
	double span = *hi - *lo, mid = (*hi + *lo) / 2;

	if (!(span > 1e-9 * fmax(1.0, fabs(mid)))) {
		*lo = mid - 0.5;
		*hi = mid + 0.5;
		return;
	}
	*lo -= span * 0.05;
	*hi += span * 0.05;
}

void chart_fit(struct chart *c, double xlo, double xhi, double ylo, double yhi)
{
	widen(&xlo, &xhi);
	widen(&ylo, &yhi);
	if (c->equal) {
		double sx = (xhi - xlo) / c->pw, sy = (yhi - ylo) / c->ph, s = fmax(sx, sy);
		double mx = (xhi + xlo) / 2, my = (yhi + ylo) / 2;

		xlo = mx - s * c->pw / 2;
		xhi = mx + s * c->pw / 2;
		ylo = my - s * c->ph / 2;
		yhi = my + s * c->ph / 2;
	}
	c->x0 = xlo;
	c->x1 = xhi;
	c->y0 = ylo;
	c->y1 = yhi;
}

/* A round step (1, 2 or 5 times a power of ten) giving about n ticks. */
static double nice_step(double span, int n)
{
	double raw = span / n, p = pow(10, floor(log10(raw))), m = raw / p;

	return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

void chart_axes(FILE *f, const struct chart *c, const char *title, const char *xlabel,
		const char *ylabel)
{
	double step, v;
	char num[NUMFMT_MAX];

	fprintf(f, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#fafafa\" "
		   "stroke=\"#444\" stroke-width=\"1\"/>\n",
		c->px, c->py, c->pw, c->ph);
	step = nice_step(c->x1 - c->x0, 6);
	for (v = ceil(c->x0 / step) * step; v <= c->x1; v += step) {
		double x = map_x(c, v);

		fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n",
			x, c->py, x, c->py + c->ph);
		numfmt_double(num, fabs(v) < step * 1e-6 ? 0 : v);
		svg_text(f, x, c->py + c->ph + 14, 11, "middle", "#333", num);
	}
	step = nice_step(c->y1 - c->y0, 4);
	for (v = ceil(c->y0 / step) * step; v <= c->y1; v += step) {
		double y = map_y(c, v);

		fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n",
			c->px, y, c->px + c->pw, y);
		numfmt_double(num, fabs(v) < step * 1e-6 ? 0 : v);
		svg_text(f, c->px - 4, y + 4, 11, "end", "#333", num);
	}
	svg_text(f, c->px, c->py - 6, 13, "start", "#000", title);
	if (xlabel)
		svg_text(f, c->px + c->pw, c->py + c->ph + 28, 11, "end", "#555", xlabel);
	if (ylabel)
		svg_text(f, c->px + c->pw, c->py - 6, 11, "end", "#555", ylabel);
	/* each chart clips its own lines */
	fprintf(f, "<clipPath id=\"c%u\"><rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"/></clipPath>\n",
		c->id, c->px, c->py, c->pw, c->ph);
}

void chart_line(FILE *f, const struct chart *c, const double *x, const double *y, uint32_t n,
		const char *color, double width, const char *dash)
{
	uint32_t i;

	fprintf(f, "<polyline clip-path=\"url(#c%u)\" fill=\"none\" stroke=\"%s\" stroke-width=\"%.1f\"%s%s%s points=\"",
		c->id, color, width, dash ? " stroke-dasharray=\"" : "", dash ? dash : "",
		dash ? "\"" : "");
	for (i = 0; i < n; i++)
		fprintf(f, "%s%.2f,%.2f", i ? " " : "", map_x(c, x[i]), map_y(c, y[i]));
	fputs("\"/>\n", f);
}

void chart_mark(FILE *f, const struct chart *c, double x, double y, const char *color)
{
	fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"4\" fill=\"white\" stroke=\"%s\" stroke-width=\"2\"/>\n",
		map_x(c, x), map_y(c, y), color);
}

void svg_legend(FILE *f, double x, double y, const char *color, const char *label,
		const char *dash)
{
	fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"2.5\"%s%s%s/>\n",
		x, y - 4, x + 18, y - 4, color, dash ? " stroke-dasharray=\"" : "", dash ? dash : "",
		dash ? "\"" : "");
	svg_text(f, x + 22, y, 11, "start", "#000", label);
}
