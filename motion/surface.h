/* SPDX-License-Identifier: MIT */
/*
 * surface.h - soft surfaces (the seed paper section 9): a parametric
 * surface deformed by moving the control points of its patches, sampled at
 * a grid of points, one actuator each (a winch's ball, a pin of an array).
 *
 * The control net has ncu x ncv points (rows along u, columns along v);
 * each coordinate of each point is a keyed curve (curve.h, any
 * interpolation kind) or a constant. The surface is the tensor product of
 * the seed's curves of sections 5.3.3 and 5.3.4 in two parameters:
 *
 *   bezier   bicubic Bezier patches sharing their edges: ncu = 3 pu + 1
 *            points make pu patches along u (the same along v); the
 *            surface passes through the corner points of every patch and
 *            is continuous (C0) across patch edges, smooth (C1) where the
 *            points either side of an edge are collinear with it.
 *   bspline  a uniform bicubic B-spline with the first and last row and
 *            column repeated three times (FORMULAS section 6's curve in
 *            each parameter): C2 everywhere, through the four corner
 *            points, inside the convex hull of the net.
 *
 * Samples sit on the parameter grid u_i = i / (nsu - 1), v_j = j / (nsv -
 * 1) (0.5 for a single one). Their basis weights do not change, so they
 * are prepared once, in Q2.62. A tick evaluates the keyed control
 * coordinates, then the surface separably: along u for each sample row and
 * control column, then along v for each sample, 4 (nsu ncv + nsu nsv)
 * products per moving coordinate. Coordinates no curve moves are sampled
 * once at init.
 *
 * Accuracy (tests/motion/test_surface.c, against a double evaluation of the
 * same control values): each sample within 1 LSB of the exact surface of
 * the Q32.32 control values (the row values are rounded once, then the
 * sample), plus the curves' own error.
 */
#ifndef MOT_SURFACE_H
#define MOT_SURFACE_H

#include "curve.h"
#include "fix.h"

enum mot_surface_basis {
	MOT_SURFACE_BEZIER,
	MOT_SURFACE_BSPLINE,
};

/* Largest control net and sample grid along one parameter. */
#define MOT_SURFACE_MAX_CTL 1024u
#define MOT_SURFACE_MAX_SAMPLES 4096u

/* The basis weights of one sample parameter: the 4 control indices and
 * their weights (Q2.62, summing to 1). */
struct mot_surface_w {
	uint32_t idx[4];
	int64_t w[4];
};

struct mot_surface {
	uint32_t basis;          /* enum mot_surface_basis */
	uint32_t ncu, ncv;       /* control points along u and v */
	uint32_t nsu, nsv;       /* samples along u and v */
	const int32_t *curve;    /* ncu * ncv * 3: curve of coordinate k of point (a, b)
				  * at [(a ncv + b) 3 + k], or -1 */
	const mot_q32 *rest;     /* ncu * ncv * 3: the constant where curve is -1 */
	bool moving[3];          /* coordinate k has a curve somewhere */
	struct mot_surface_w *wu; /* nsu */
	struct mot_surface_w *wv; /* nsv */
	mot_q32 *fixed;          /* nsu * nsv * 3: samples of the coordinates that do not move */
};

/* The evaluation's scratch: control values and one row. */
static inline uint32_t mot_surface_scratch_count(const struct mot_surface *s)
{
	return s->ncu * s->ncv * 3 + s->ncv;
}

/*
 * Validate the net for the basis (MOT_E_INVAL: ncu or ncv not 3p + 1 for
 * bezier, zero, or above MOT_SURFACE_MAX_CTL; samples 0 or above
 * MOT_SURFACE_MAX_SAMPLES; a curve index out of range) and prepare the
 * weights and the fixed samples. basis, the counts, curve, rest, wu, wv and
 * fixed must be set (the arrays sized as above). Init only.
 */
int mot_surface_init(struct mot_surface *s, uint32_t ncurves, uint32_t *sat);

/*
 * The samples at a frame into out[(i nsv + j) 3 + k]; scratch has
 * mot_surface_scratch_count() values, cursors are the scene's (indexed like
 * curves) or NULL. Real-time safe.
 */
void mot_surface_eval(const struct mot_surface *s, const struct mot_curve *curves,
		      struct mot_cursor *cursors, mot_q32 frame, mot_q32 *scratch, mot_q32 *out,
		      uint32_t *sat);

/* The 4 weights and indices of parameter i of n samples over m control
 * points (exposed for the tests). */
void mot_surface_weights(struct mot_surface_w *w, uint32_t basis, uint32_t m, uint32_t i,
			 uint32_t n);

#endif /* MOT_SURFACE_H */
