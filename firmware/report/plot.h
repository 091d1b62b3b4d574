/* SPDX-License-Identifier: MIT */
/*
 * plot.h - `strand plot`'s pages: the overview (plot.c) and the method
 * comparison (plot_compare.c), and what they share: sampling a built
 * scene's channels over a span of frames.
 */
#ifndef STRAND_PLOT_H
#define STRAND_PLOT_H

#include <stdio.h>

#include "load/load.h"
#include "scene/channel.h"
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

/* The overview page: node paths from above and from the side, then every
 * channel against frames with its keys ringed. 0 or -ENOMEM. */
int plot_overview(FILE *f, const struct scene_file *sf, const struct mot_scene *sc,
		  const struct chan_list *ch, const struct plot_samples *ps);

/* The --compare page: node's keys through every interpolation method. 0 or
 * -ENOMEM. */
int plot_compare(FILE *f, const struct scene_file *sf, uint32_t node);

#endif /* STRAND_PLOT_H */
