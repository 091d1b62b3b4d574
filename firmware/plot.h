/* SPDX-License-Identifier: MIT */
/*
 * plot.h - what `strand plot`'s overview (cmd_plot.c) and its method
 * comparison (plot_compare.c) share: sampling a built scene's channels over
 * a span of frames.
 */
#ifndef STRAND_PLOT_H
#define STRAND_PLOT_H

#include <stdio.h>

#include "channel.h"
#include "cli.h"
#include "svg.h"

/* Every channel at n evenly spaced frames: val[chan * n + sample]. */
struct plot_samples {
	uint32_t n;
	double *frame;
	double *val;
	uint32_t sat; /* the core's saturation bits over the samples */
};

int plot_samples_make(struct plot_samples *ps, const struct scene_file *sf,
		      const struct mot_scene *sc, const struct chan_list *ch, double first,
		      double last, uint32_t n);
void plot_samples_free(struct plot_samples *ps);

static inline const double *plot_series(const struct plot_samples *ps, uint32_t chan)
{
	return ps->val + (size_t)chan * ps->n;
}

/* Every channel at one frame (a fresh evaluation), into out[ch->n]. */
int plot_eval_at(double *out, const struct mot_scene *sc, const struct chan_list *ch,
		 double frame);

/* How many samples to draw a span with. */
uint32_t plot_sample_count(double first, double last);

/* The --compare page: node's keys through every interpolation method. 0 or
 * -ENOMEM. */
int plot_compare(FILE *f, const struct scene_file *sf, uint32_t node);

#endif /* STRAND_PLOT_H */
