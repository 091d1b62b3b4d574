/* SPDX-License-Identifier: MIT */
/* limit.c - the one limit predicate (see limit.h). */
#include "limit.h"

#include <math.h>

#include "move.h"

/* One Q32.32 step, and a double's relative step. */
#define STEP (1.0 / 4294967296.0)
#define DBL_REL (1.0 / 4503599627370496.0) /* 2^-52 */

struct lim_bounds lim_bounds_of(const struct sd_limits *l, enum src_unit unit)
{
	double k = unit == SRC_UNIT_TURNS ? 1.0 / 360.0 : 1.0;

	return (struct lim_bounds){
		.min = l->has_min ? l->min * k : -INFINITY,
		.max = l->has_max ? l->max * k : INFINITY,
		.vel = l->has_vel ? l->vel * k : INFINITY,
		.acc = l->has_acc ? l->acc * k : INFINITY,
		.vel_ch = unit == SRC_UNIT_RPM,
	};
}

void lim_stencil_init(struct lim_stencil *s, uint32_t tick_hz)
{
	s->h = (tick_hz + 999) / 1000;
	if (s->h < 1)
		s->h = 1;
	s->tick_hz = tick_hz;
	s->rate = (double)tick_hz / s->h;
}

void STRAND_RT lim_meter_reset(struct lim_meter *m, const struct lim_stencil *s, mot_q32 *ring,
			       mot_q32 x, bool history)
{
	uint32_t i;

	m->ring = ring;
	m->len = (uint32_t)LIM_METER_LEN(s->h);
	m->head = 0;
	for (i = 0; i < m->len; i++)
		ring[i] = x;
	m->seen = history ? m->len : 0;
}

void STRAND_RT lim_meter_push(struct lim_meter *m, mot_q32 x)
{
	m->ring[m->head] = x;
	m->head = m->head + 1 == m->len ? 0 : m->head + 1;
	m->seen++;
}

/* The sample j pushes back (1: the newest, up to len). */
static mot_q32 STRAND_RT back(const struct lim_meter *m, uint32_t j)
{
	uint32_t at = m->head + m->len - j;

	return m->ring[at >= m->len ? at - m->len : at];
}

/* a - b as a double, exact to the double's precision however far apart. */
static double STRAND_RT diff(mot_q32 a, mot_q32 b)
{
	int64_t d;

	if (__builtin_sub_overflow(a, b, &d))
		return ((double)a - (double)b) * STEP;
	return (double)d * STEP;
}

void STRAND_RT lim_measure(const struct lim_meter *m, const struct lim_stencil *s, mot_q32 x,
			   struct lim_measure *me)
{
	mot_q32 x0 = x, x1 = back(m, s->h), x2 = back(m, 2 * s->h);
	double big = fmax(fabs((double)x0), fmax(fabs((double)x1), fabs((double)x2))) * STEP;

	me->x = (double)x0 * STEP;
	me->noise = STEP + big * DBL_REL;
	me->has_v = m->seen >= (int64_t)s->h;
	me->has_a = m->seen >= 2 * (int64_t)s->h;
	me->v = me->has_v ? diff(x0, x1) * s->rate : 0;
	me->v1 = m->seen >= 1 ? diff(x0, back(m, 1)) * s->tick_hz : 0;
	/* (x0 - x1) - (x1 - x2): each difference exact, their difference
	 * to the double's precision */
	me->a = me->has_a ? (diff(x0, x1) - diff(x1, x2)) * s->rate * s->rate : 0;
}

uint32_t STRAND_RT lim_test(const struct lim_stencil *s, const struct lim_bounds *b,
			    const struct lim_measure *me, struct lim_hit *hit)
{
	double nv = 4 * me->noise * s->rate, na = 4 * me->noise * s->rate * s->rate;
	uint32_t n = 0;

	if (me->x < b->min - me->noise)
		hit[n++] = (struct lim_hit){ LIM_MIN, me->x, b->min };
	if (me->x > b->max + me->noise)
		hit[n++] = (struct lim_hit){ LIM_MAX, me->x, b->max };
	if (me->has_v && fabs(me->v) > b->vel + nv)
		hit[n++] = (struct lim_hit){ LIM_VEL, me->v, copysign(b->vel, me->v) };
	if (me->has_a && fabs(me->a) > b->acc + na)
		hit[n++] = (struct lim_hit){ LIM_ACC, me->a, copysign(b->acc, me->a) };
	if (me->has_v && !b->vel_ch && isfinite(b->acc) && (isfinite(b->min) || isfinite(b->max))) {
		double at = me->x + copysign(move_stop_distance(me->v1, b->acc, s->tick_hz), me->v1);

		if (at < b->min - me->noise)
			hit[n++] = (struct lim_hit){ LIM_STOP, at, b->min };
		else if (at > b->max + me->noise)
			hit[n++] = (struct lim_hit){ LIM_STOP, at, b->max };
	}
	return n;
}
