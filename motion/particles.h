/* SPDX-License-Identifier: MIT */
/*
 * particles.h - particle systems (the seed paper section 10): a fixed pool
 * of slots, each an actuator's channels (a light's position, colour and
 * transparency, a valve), filled by emission or by a lattice.
 *
 * Emission (10.1). At each step n -> n + 1 the system releases
 *     N(t) = M(t) + r V(t)        particles a second, r uniform in [-1, 1)
 * (M and V keyed, r from the system's seeded generator, rng.h), N h of them
 * a step with the fraction carried to the next; their births are spread
 * evenly over the step, the last at n + 1. Each takes the lowest free slot
 * (one whose particle has died by then) and draws its initial position,
 * velocity, lifetime, size, colour and alpha, each uniformly between two
 * keyed bounds at the step's frame. A particle finding no free slot is
 * dropped and counted: the build records the first step that drops one, so
 * that `strand check` proves the pool large enough or names the first frame
 * it is not. Over its life a particle's colour, alpha and size are its
 * drawn ones times curves keyed over the fraction of its life (0 to 1, in
 * the curves' frame field). A dead slot holds its position, alpha 0.
 *
 * Motion. Scripted particles follow their script in closed form: p(t) =
 * p0 + v0 a + g a^2 / 2 at age a. Newtonian ones (10.2) are integrated by
 * velocity Verlet (FSAL: one force evaluation a step),
 *     v' = v + a h/2,  p(n+1) = p + v' h,  a(n+1) = F(p(n+1), v + a h),
 *     v(n+1) = v' + a(n+1) h/2
 * under gravity, linear drag (-drag v), springs between fixed pairs with
 * damping along the spring (a mass-spring lattice: a table cloth of
 * winches), pairwise attraction or repulsion within a radius (found on a
 * neighbour grid, grid.h), and a ground plane with restitution. Velocity
 * Verlet is second order and symplectic: an undamped spring's energy
 * oscillates within O((w h)^2) of its true value without drifting, and a
 * projectile follows its parabola exactly but for rounding
 * (tests/motion/test_particles.c measures both). It is stable for w h < 2
 * with w the highest frequency of the springs: the build refuses a system
 * whose Gershgorin bound max_i sqrt(2 sum_j k_ij) h reaches 1.8, or whose
 * drag and damping h (drag + 2 sum_j c_ij) reach 1.
 *
 * Between steps a tick sees every particle on the cubic Hermite curve
 * through its positions and velocities at both ends (its birth or death if
 * they fall between): continuous in position and velocity, no staircase.
 *
 * Units: lengths in scene units, time in seconds, colours and alpha plain
 * numbers (0 to 1 by convention), springs and forces per unit mass.
 */
#ifndef MOT_PARTICLES_H
#define MOT_PARTICLES_H

#include "curve.h"
#include "fix.h"
#include "grid.h"
#include "steps.h"

enum mot_particles_motion {
	MOT_PARTICLES_SCRIPTED,
	MOT_PARTICLES_NEWTON,
};

/* The system's keyed values: each a curve index or -1 for a constant. */
enum mot_pc {
	MOT_PC_RATE, MOT_PC_SPREAD,                    /* M(t), V(t): particles a second */
	MOT_PC_POS_LO, MOT_PC_POS_LO_Y, MOT_PC_POS_LO_Z, /* initial position bounds */
	MOT_PC_POS_HI, MOT_PC_POS_HI_Y, MOT_PC_POS_HI_Z,
	MOT_PC_VEL_LO, MOT_PC_VEL_LO_Y, MOT_PC_VEL_LO_Z, /* initial velocity bounds */
	MOT_PC_VEL_HI, MOT_PC_VEL_HI_Y, MOT_PC_VEL_HI_Z,
	MOT_PC_LIFE_LO, MOT_PC_LIFE_HI,                /* seconds */
	MOT_PC_SIZE_LO, MOT_PC_SIZE_HI,
	MOT_PC_COL_LO, MOT_PC_COL_LO_G, MOT_PC_COL_LO_B,
	MOT_PC_COL_HI, MOT_PC_COL_HI_G, MOT_PC_COL_HI_B,
	MOT_PC_ALPHA_LO, MOT_PC_ALPHA_HI,
	/* over the life, keyed by its fraction: multipliers */
	MOT_PC_AGE_R, MOT_PC_AGE_G, MOT_PC_AGE_B, MOT_PC_AGE_ALPHA, MOT_PC_AGE_SIZE,
	MOT_PC_COUNT
};

/* Channels of a slot: x y z, then with emission r g b alpha size. */
enum { MOT_PART_X, MOT_PART_Y, MOT_PART_Z, MOT_PART_R, MOT_PART_G, MOT_PART_B,
       MOT_PART_ALPHA, MOT_PART_SIZE, MOT_PART_NOUT };

struct mot_spring {
	uint32_t i, j;   /* particles */
	mot_q32 rest;    /* rest length, scene units */
};

struct mot_pin {
	uint32_t i;      /* particle held */
	int32_t ch[3];   /* curves of its offset from its rest position, or -1 (0) */
};

/* One slot of the pool, as a state holds it. */
struct mot_particle {
	mot_q32 p[3], v[3], a[3]; /* at the state's step, or at death */
	mot_q32 p0[3], v0[3];     /* at birth */
	mot_q32 birth, death;     /* step positions (Q32.32 steps) */
	mot_q32 inv_life;         /* 1 / lifetime, per second */
	mot_q32 size, col[3], alpha;
	int64_t used;             /* a particle has been here */
};

/* The whole state: this head, then the pool. */
struct mot_particles_head {
	uint64_t rng;
	mot_q32 carry;       /* fraction of a particle owed to the next step */
	int64_t dropped;     /* particles that found no free slot, so far */
	int64_t first_drop;  /* the step that dropped the first, or -1 */
	int64_t live;        /* particles alive at this step */
};

struct mot_particles {
	uint32_t motion;          /* enum mot_particles_motion */
	uint32_t npool;           /* slots */
	bool emit;                /* emission (and appearance channels) */
	uint32_t nout;            /* channels a slot: 3, or MOT_PART_NOUT with emission */
	int32_t curve[MOT_PC_COUNT];
	mot_q32 value[MOT_PC_COUNT]; /* where curve is -1 */
	uint64_t seed;
	mot_q32 gravity[3];       /* units/s^2 */
	mot_q32 drag;             /* 1/s */
	bool ground;
	mot_q32 ground_y, restitution;
	mot_q32 pair_radius;      /* 0: no pairwise force */
	mot_q32 pair_strength;    /* units/s^2 at contact: > 0 repels, < 0 attracts */
	mot_q32 spring_k;         /* 1/s^2 (stiffness per mass) */
	mot_q32 spring_c;         /* 1/s (damping per mass) */
	uint32_t nsprings;
	const struct mot_spring *springs;
	uint32_t npins;
	const struct mot_pin *pins;
	const mot_q32 (*rest)[3]; /* lattice: npool rest positions; NULL with emission */
	struct mot_steps steps;
	/* results of the build's run over the span */
	int64_t dropped;          /* particles dropped over the span */
	int64_t first_drop;       /* the first step that dropped one, or -1 */
	int64_t peak;             /* most particles alive at once */
};

/* Bytes of one state (a multiple of 8). */
static inline uint32_t mot_particles_state_bytes(uint32_t npool)
{
	return (uint32_t)(sizeof(struct mot_particles_head) +
			  (size_t)npool * sizeof(struct mot_particle));
}

/* Scratch an evaluation and the build need: the neighbour grid. */
struct mot_particles_scratch {
	struct mot_grid grid;
	bool has_grid;      /* the grid is set up (needed with pair_radius > 0) */
	mot_q32 (*vp)[3];   /* npool: velocity predictors */
	uint32_t *deg;      /* npool: springs a particle (the build's only) */
};

/*
 * Prepare and run the whole span: steps must be set (mot_steps_init with
 * mot_particles_state_bytes) with its ckpt array; a and b are two states of
 * scratch; sc the grid scratch (its grid set up when pair_radius > 0).
 * Checks the fields, the springs and pins (MOT_E_INVAL), stability
 * (MOT_E_RANGE), fills every checkpoint and the results. Init only.
 */
int mot_particles_init(struct mot_particles *ps, const struct mot_curve *curves,
		       uint32_t ncurves, void *a, void *b, struct mot_particles_scratch *sc,
		       uint32_t *sat);

/* Every slot's channels at a frame, into out[slot * nout + channel]; the
 * cache's states belong to the evaluation. Real-time safe (one step, or up
 * to steps.every after a jump: steps.h). */
void mot_particles_eval(const struct mot_particles *ps, const struct mot_curve *curves,
			struct mot_steps_cache *c, struct mot_particles_scratch *sc,
			mot_q32 frame, mot_q32 *out, uint32_t *sat);

/* One step, exposed for the tests: the state of step n + 1 from step n. */
void mot_particles_step(const void *sys, const struct mot_curve *curves, const void *in,
			void *out, int64_t n, void *scratch, uint32_t *sat);

#endif /* MOT_PARTICLES_H */
