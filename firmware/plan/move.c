/* SPDX-License-Identifier: MIT */
/* move.c - point-to-point moves and stops within limits (see move.h). */
#include "move.h"
#include "hal/rt.h"

#include <errno.h>
#include <math.h>

mot_q32 STRAND_RT move_d2q(double x)
{
	return num_sat_i64(x * 4294967296.0, MOT_Q32_MIN, MOT_Q32_MAX, NULL);
}

/* Shortest time to cover distance d (>= 0) from rest to rest. */
static double STRAND_RT t_min(double d, double v, double a)
{
	if (d <= v * v / a)
		return 2 * sqrt(d / a);
	return d / v + v / a;
}

int STRAND_RT move_plan(struct move *m, struct move_ch *ch, uint32_t n, const mot_q32 *from,
	      const mot_q32 *to, const double *vmax, const double *amax, uint32_t tick_hz)
{
	double t = 0, ticks;
	uint32_t i;
	int rc = 0;

	m->n = n;
	m->ch = ch;
	m->tick_hz = tick_hz;
	for (i = 0; i < n; i++) {
		if (!(vmax[i] > 0) || !(amax[i] > 0) || !isfinite(vmax[i]) || !isfinite(amax[i]))
			return -EINVAL;
		ch[i].from = from[i];
		ch[i].to = to[i];
		ch[i].d = move_q2d(to[i]) - move_q2d(from[i]);
		t = fmax(t, t_min(fabs(ch[i].d), vmax[i], amax[i]));
	}
	ticks = ceil(t * tick_hz - 1e-9);
	if (!(ticks < (double)NUM_TICKS_MAX)) {
		/* the limits allow no shorter move, and no longer one is planned */
		ticks = (double)NUM_TICKS_MAX;
		rc = -ERANGE;
	}
	m->ticks = ticks > 0 ? (int64_t)ticks : 0;
	m->t = (double)m->ticks / tick_hz;
	for (i = 0; i < n; i++) {
		double d = fabs(ch[i].d), a = amax[i], T = m->t, disc;

		ch[i].a = a;
		if (d == 0 || T == 0) {
			ch[i].v = 0;
			ch[i].ta = 0;
			continue;
		}
		/* T >= this channel's shortest time, so the root is real (up to
		 * rounding) and the cruise speed is within vmax. The smaller root
		 * of v^2 - a T v + a d = 0 as 2 d / (T + sqrt(T^2 - 4 d / a)):
		 * (a T - sqrt(a^2 T^2 - 4 a d)) / 2 loses its digits to
		 * cancellation when a T is far above v (a step curve's rig, whose
		 * acceleration limit is huge: 1.4e-4 above vmax, beyond the limit
		 * check's tolerance) */
		disc = T * T - 4 * d / a;
		ch[i].v = 2 * d / (T + sqrt(fmax(disc, 0)));
		ch[i].ta = ch[i].v / a;
	}
	return rc;
}

mot_q32 STRAND_RT move_at(const struct move *m, uint32_t i, int64_t k)
{
	const struct move_ch *c = &m->ch[i];
	double t, s, T = m->t;

	if (k >= m->ticks)
		return c->to;
	if (k <= 0)
		return c->from;
	if (c->v == 0)
		return c->from;
	t = (double)k / m->tick_hz;
	if (t < c->ta)
		s = c->a * t * t / 2;
	else if (t <= T - c->ta)
		s = c->a * c->ta * c->ta / 2 + c->v * (t - c->ta);
	else
		s = fabs(c->d) - c->a * (T - t) * (T - t) / 2;
	return c->from + move_d2q(c->d < 0 ? -s : s);
}

double STRAND_RT move_stop_distance(double v, double amax, uint32_t tick_hz)
{
	double dv = amax / tick_hz, n = floor(fabs(v) / dv);

	if (!(n > 0))
		return 0;
	return (n * fabs(v) - dv * n * (n + 1) / 2) / tick_hz;
}

bool STRAND_RT move_stop_step(mot_q32 *value, double *v, bool vel_ch, double vmax, double amax,
		    uint32_t tick_hz)
{
	double dv = amax / tick_hz, dt = 1.0 / tick_hz, nv;

	if (!vel_ch) {
		nv = *v > 0 ? fmax(*v - dv, 0) : fmin(*v + dv, 0);
		*value = mot_add_sat(*value, move_d2q(nv * dt), NULL);
		*v = nv;
		return nv == 0;
	}
	/* a velocity channel: drive the value itself to 0 along the braking
	 * curve |rate| <= sqrt(2 amax |value|), the rate changing by <= dv */
	{
		double u = move_q2d(*value), want, r;

		if (u == 0 && *v == 0)
			return true;
		want = -copysign(fmin(vmax, sqrt(2 * amax * fabs(u))), u);
		r = fmax(*v - dv, fmin(*v + dv, want));
		/* the last step lands on zero: when it would cross it, and when
		 * what is left is within two Q32.32 steps (a smaller increment
		 * would round to nothing and the value would never arrive) */
		if (fabs(u) <= 2.0 / 4294967296.0 ||
		    (fabs(u) <= fabs(r) * dt && r != 0 && copysign(1, r) != copysign(1, u))) {
			*value = 0;
			*v = 0;
			return true;
		}
		*value = mot_add_sat(*value, move_d2q(r * dt), NULL);
		*v = r;
		return false;
	}
}
