/* SPDX-License-Identifier: MIT */
/*
 * flock.h - behavioural animation (the seed paper section 10.3, after
 * Reynolds 1987): members that avoid their nearest mates, keep close to the
 * others, match their velocity and follow a global position or direction,
 * around spherical obstacles, within their own speed and acceleration limits
 * (a robot or a moving-head light must be able to follow them).
 *
 * Each step, for member i with mates j within `radius` (at most
 * max_neighbours of them, found on a neighbour grid: grid.h), the steering
 * accelerations, each a dimensionless urge times its weight (units/s^2):
 *     separation  sum over mates closer than sep:  (p_i - p_j) (sep - d) / (sep d)
 *     cohesion    (mean p_j - p_i) / radius
 *     alignment   (mean v_j - v_i) / vmax
 *     goal        (vmax u - v_i) / vmax, u the unit vector toward the goal
 *                 point (scaled down within `radius` of it: arriving, not
 *                 circling), or the goal direction itself
 *     obstacles   (p_i - c) / |p_i - c| (m - e) / m for each sphere (c, r)
 *                 whose surface is e < m = margin away
 * summed, cut to amax in magnitude; then
 *     v(n+1) = v + a h, cut to vmax;   p(n+1) = p + h (v + (v(n+1) - v) / 2)
 * so that within a step a member moves at the constant acceleration
 * (v(n+1) - v) / h, which a tick reads exactly: position and velocity are
 * continuous and |v| <= vmax, |a| <= amax at every tick, not only at the
 * steps (cutting v onto the ball moves it by no more than a h).
 *
 * A member's heading is the pan of its velocity, atan2(-vx, -vz) as the
 * camera's (FORMULAS section 10), continuous: unwrapped from step to step,
 * held while it stands still.
 */
#ifndef MOT_FLOCK_H
#define MOT_FLOCK_H

#include "curve.h"
#include "fix.h"
#include "grid.h"
#include "steps.h"

enum { MOT_FLOCK_X, MOT_FLOCK_Y, MOT_FLOCK_Z, MOT_FLOCK_HEADING, MOT_FLOCK_NOUT };

enum mot_flock_goal {
	MOT_FLOCK_GOAL_NONE,
	MOT_FLOCK_GOAL_POINT,     /* steer toward a keyed point */
	MOT_FLOCK_GOAL_DIRECTION, /* fly along a keyed direction */
};

struct mot_obstacle {
	mot_q32 c[3];
	mot_q32 r;
};

struct mot_member {
	mot_q32 p[3], v[3];
	mot_q32 heading; /* turns, continuous */
};

struct mot_flock {
	uint32_t n;               /* members */
	uint64_t seed;
	mot_q32 start_c[3];       /* members start in the cube start_c +- start_r ... */
	mot_q32 start_r;
	mot_q32 start_v[3];       /* ... all with this velocity, plus +- start_dv a component */
	mot_q32 start_dv;
	mot_q32 radius, sep;      /* neighbourhood, separation distance */
	uint32_t max_neighbours;
	mot_q32 w_sep, w_coh, w_ali, w_goal, w_obst; /* units/s^2 */
	uint32_t goal;            /* enum mot_flock_goal */
	int32_t goal_ch[3];       /* curves of the goal point or direction, or -1 */
	mot_q32 goal_value[3];    /* where goal_ch is -1 */
	uint32_t nobst;
	const struct mot_obstacle *obst;
	mot_q32 margin;
	mot_q32 vmax, amax;       /* units/s, units/s^2 */
	struct mot_steps steps;
	/* prepared by init: divisions by the radius and the speed limit as
	 * products (within 1 LSB) */
	struct mot_recip inv_radius, inv_vmax;
};

static inline uint32_t mot_flock_state_bytes(uint32_t n)
{
	return (uint32_t)((size_t)n * sizeof(struct mot_member));
}

/* An evaluation's and the build's scratch: the grid over the members. */
struct mot_flock_scratch {
	struct mot_grid grid;
};

/* The steering acceleration of member i in state m (exposed for the
 * tests), before the cut to amax. */
void mot_flock_steer(const struct mot_flock *f, const struct mot_curve *curves,
		     const struct mot_member *m, uint32_t i, mot_q32 frame,
		     struct mot_flock_scratch *sc, mot_q32 a[3], uint32_t *sat);

/* Check (MOT_E_INVAL), place the members (the seeded start) and run the
 * whole span into the checkpoints (steps set with mot_flock_state_bytes).
 * Init only. */
int mot_flock_init(struct mot_flock *f, const struct mot_curve *curves, uint32_t ncurves,
		   void *a, void *b, struct mot_flock_scratch *sc, uint32_t *sat);

/* One step (the tests'). */
void mot_flock_step(const void *sys, const struct mot_curve *curves, const void *in, void *out,
		    int64_t n, void *scratch, uint32_t *sat);

/* Every member's x, y, z, heading at a frame into out[i * MOT_FLOCK_NOUT
 * + k]. Real-time safe (as particles). */
void mot_flock_eval(const struct mot_flock *f, const struct mot_curve *curves,
		    struct mot_steps_cache *c, struct mot_flock_scratch *sc, mot_q32 frame,
		    mot_q32 *out, uint32_t *sat);

#endif /* MOT_FLOCK_H */
