/* SPDX-License-Identifier: MIT */
/* dll.c - the delay-locked loop (see dll.h). */
#include "dll.h"

#include <math.h>

void STRAND_RT hal_dll_init(struct hal_dll *d, double per_nom, double dx_nom, double bw_hz)
{
	double w = 2 * M_PI * bw_hz * dx_nom * per_nom * 1e-9;

	d->per_nom = per_nom;
	d->dx_nom = dx_nom;
	d->b = sqrt(2) * w;
	d->c = w * w;
	d->x_ref = 0;
	d->t_ref = 0;
	d->per = per_nom;
	d->n = 0;
}

void STRAND_RT hal_dll_restart(struct hal_dll *d, double x, double t)
{
	d->x_ref = x;
	d->t_ref = t;
	d->n = 1;
}

void STRAND_RT hal_dll_update(struct hal_dll *d, double x, double t)
{
	double b, c, e, dx, n;

	if (d->n == 0) {
		hal_dll_restart(d, x, t);
		return;
	}
	dx = x - d->x_ref;
	if (!(dx > 0)) /* a reading that does not move x on says nothing of the rate */
		return;
	d->n++;
	n = (double)d->n;
	/* the growing fit's gains for this reading (n >= 2), until they are
	 * below the fixed loop's */
	b = 2 * (2 * n - 1) / (n * (n + 1));
	c = 6 / (n * (n + 1));
	if (b < d->b) {
		b = d->b;
		c = d->c;
	}
	e = t - (d->t_ref + dx * d->per);
	d->t_ref += dx * d->per + b * e;
	d->x_ref = x;
	d->per += c * e / dx;
}
