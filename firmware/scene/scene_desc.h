/* SPDX-License-Identifier: MIT */
/*
 * scene_desc.h - a scene as the user wrote it: plain numbers in the scene
 * file's units (scene units, degrees, frames, rpm), before conversion to the
 * core's Q32.32. The YAML loader fills one; so do the tests and benchmarks,
 * which also evaluate it directly in double precision as their reference.
 * scene_build() turns it into the core's struct mot_scene in one block.
 *
 * Ownership: a description owns nothing; whoever fills it keeps the arrays
 * alive until scene_build() returns (the built scene copies what it needs).
 */
#ifndef STRAND_SCENE_DESC_H
#define STRAND_SCENE_DESC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "motion/curve.h"
#include "motion/cycle.h"
#include "motion/scene.h"
#include "motion/system.h"

struct sd_key {
	double frame;
	double value; /* scene units, degrees or rpm by the curve's role */
	double ease_in, ease_out;
	/* hermite: explicit tangents, value per frame (units or degrees), on
	 * the sides tan_set says (MOT_TANGENT_IN | MOT_TANGENT_OUT) */
	double tan_in, tan_out;
	uint32_t tan_set;
};

struct sd_curve {
	enum mot_interp interp;
	uint32_t nkeys; /* 0: no curve */
	const struct sd_key *keys;
	double beta1, beta2;             /* beta: bias and tension */
	double ease_in, ease_out;        /* strand-wide, frames */
	bool compact;                    /* step, linear: keys only (curve.h) */
};

struct sd_rot_key {
	double frame;
	double q[4]; /* w, x, y, z; normalised by the builder */
	double ease_in, ease_out;
};

struct sd_free {
	struct sd_curve ch[MOT_FREE_NCHANNELS]; /* translate, scale, shear; nkeys 0 = rest */
	uint32_t nrot;
	const struct sd_rot_key *rot;
	bool squad;
	bool rot_compact; /* the slerp track kept as its keys (strand.h) */
	double ease_in, ease_out; /* strand-wide, frames, over the strand's whole span */
	/* or the rotation as four curves of w, x, y, z, normalised when
	 * evaluated (cubic, step); nkeys 0 = none. Not with nrot. */
	struct sd_curve quat[4];
};

struct sd_limits {
	bool has_min, has_max, has_vel, has_acc;
	double min, max;  /* degrees or units */
	double vel, acc;  /* per second, per second squared */
};

struct sd_node {
	const char *name;
	int32_t parent; /* -1 for a root */
	enum mot_node_kind kind;
	enum mot_axis axis_id;
	double axis[3]; /* normalised by the builder */
	double pivot[3];
	double rest;          /* degrees or units */
	struct sd_curve value; /* joints: angle (deg) or position (units) keys */
	struct sd_curve spin;  /* revolute: rpm keys */
	struct sd_free free;   /* free nodes */
	bool has_free;
	struct sd_limits limits;
};

struct sd_camera {
	struct sd_curve ch[MOT_CAM_NCHANNELS]; /* eye xyz, look_at xyz, twist (deg) */
	double ease_in, ease_out;
};

struct sd_cycle {
	const char *name;
	int32_t first, last, skip;
	enum mot_cycle_mode mode;
	int64_t frames_per_step;
	int64_t start_frame;
};

struct sd_attr {
	const char *name;
	struct sd_curve curve;
};

/*
 * The seed's advanced systems (motion/system.h). Each has a name, the prefix
 * of its channels, and limits per channel of an item (`y` of every sample,
 * `alpha` of every slot), in the file's units; their channels are ordinary
 * channels of the scene (channel.h).
 */
#define SD_SYS_CHANNELS 8 /* most channels an item has */

/* Soft surface: a control net of ncu x ncv points, each coordinate a curve
 * or its rest value, sampled at nsu x nsv points. */
struct sd_surface {
	const char *name;
	enum mot_surface_basis basis;
	uint32_t ncu, ncv, nsu, nsv;
	const double *rest;           /* ncu * ncv * 3: (row a, column b, coordinate k) */
	const struct sd_curve *curve; /* ncu * ncv * 3: nkeys 0 = the rest value */
	struct sd_limits lim[3];      /* x, y, z of every sample */
};

struct sd_pin {
	uint32_t row, col;            /* the lattice point held */
	struct sd_curve off[3];       /* its offset from rest (nkeys 0: none) */
};

/* A particle system: emitted (emit) or a lattice (lu x lv particles). */
struct sd_particles {
	const char *name;
	enum mot_particles_motion motion;
	uint32_t npool;               /* with emission */
	bool emit;
	struct sd_curve c[MOT_PC_COUNT]; /* keyed values; nkeys 0: v[k] */
	double v[MOT_PC_COUNT];       /* seconds, scene units, plain numbers */
	uint64_t seed;
	double gravity[3], drag;
	bool ground;
	double ground_y, restitution;
	double pair_radius, pair_strength;
	double spring_k, spring_c;    /* per unit mass: stiffness / mass, damping / mass */
	uint32_t lu, lv;              /* lattice rows (along z) and columns (along x) */
	double origin[3], spacing[2]; /* lattice point (i, j) rests at origin + (j sx, 0, i sz) */
	bool shear;                   /* diagonal springs too */
	uint32_t npins;
	const struct sd_pin *pins;
	uint32_t rate_num, rate_den;  /* steps a second */
	struct sd_limits lim[MOT_PART_NOUT];
};

struct sd_obstacle {
	double c[3], r;
};

struct sd_flock {
	const char *name;
	uint32_t n;
	uint64_t seed;
	double start_c[3], start_r, start_v[3], start_dv;
	double radius, sep;
	uint32_t max_neighbours;
	double w_sep, w_coh, w_ali, w_goal, w_obst;
	enum mot_flock_goal goal;
	struct sd_curve goal_c[3];    /* nkeys 0: goal_v[k] */
	double goal_v[3];
	uint32_t nobst;
	const struct sd_obstacle *obst;
	double margin;
	double vmax, amax;
	uint32_t rate_num, rate_den;
	struct sd_limits lim[MOT_FLOCK_NOUT]; /* x y z heading (degrees) */
};

enum sd_sys_kind { SD_SURFACE, SD_PARTICLES, SD_FLOCK };

/* A system in the order of the scene's systems: the surfaces, then the
 * particle systems, then the flocks. */
struct sd_system {
	enum sd_sys_kind kind;
	const struct sd_surface *surface;
	const struct sd_particles *particles;
	const struct sd_flock *flock;
};

/* A pan/tilt head following a target: a node's pivot, or item `item` of
 * system `sys` (its x, y, z). */
struct sd_aim {
	const char *name;             /* its channels: <name>.pan, <name>.tilt */
	double at[3];
	int32_t node;                 /* or -1 */
	int32_t sys;                  /* or -1 */
	uint32_t item;
	uint32_t sub;                 /* pan grid points a frame */
	struct sd_limits lim[2];      /* pan, tilt (degrees) */
};

struct scene_desc {
	const char *name;
	uint32_t rate_num, rate_den; /* frames per second */
	uint32_t tick_hz;
	double frame_first, frame_last; /* the span play and export cover */
	uint32_t nnodes;
	const struct sd_node *nodes;
	bool has_camera;
	struct sd_camera camera;
	uint32_t ncycles;
	const struct sd_cycle *cycles;
	uint32_t nattrs;
	const struct sd_attr *attrs;
	uint32_t nsys;
	const struct sd_system *sys;
	uint32_t naims;
	const struct sd_aim *aims;
	uint32_t ckpt_every;          /* steps between checkpoints (0: the default) */
};

/* The channels an item of system s has (3 a sample, 3 or 8 a slot, 4 a
 * member), and their suffixes. */
uint32_t sd_sys_per(const struct sd_system *s);
uint32_t sd_sys_items(const struct sd_system *s);
const char *sd_sys_name(const struct sd_system *s);
const char *sd_sys_suffix(const struct sd_system *s, uint32_t k);
/* The limits of channel k of an item of system s. */
const struct sd_limits *sd_sys_limits(const struct sd_system *s, uint32_t k);
/* Is channel k of an item an angle (degrees in files, turns in the core)? */
bool sd_sys_angle(const struct sd_system *s, uint32_t k);

/* A built scene: the core's view plus the one block that holds it. */
struct scene_built {
	struct mot_scene sc;
	void *block;       /* everything sc points to; free() it with scene_built_free */
	size_t block_size; /* bytes the scene needs in the core */
};

/* The names scene_build_err.what gives the channels of a free strand and of
 * the camera. */
extern const char *const sd_free_names[MOT_FREE_NCHANNELS];
extern const char *const sd_quat_names[4];
extern const char *const sd_cam_names[MOT_CAM_NCHANNELS];

/* Where a build failed, for the message at the edge. */
struct scene_build_err {
	int code;         /* MOT_E_* */
	int node;         /* node index or -1 */
	const char *what; /* "value", "spin", "translate.x", "rotation", "camera", ... */
	uint32_t key;     /* key index within it, when known, else UINT32_MAX */
};

/*
 * Convert and validate: 0, or a negative MOT_E_* code with *err saying where.
 * Allocates exactly one block (measured first), and for a curve with explicit
 * tangents a scratch array freed before it returns. Not real-time.
 */
int scene_build(struct scene_built *out, const struct scene_desc *d, struct scene_build_err *err);
void scene_built_free(struct scene_built *b);

/* Q32.32 from a double in the scene's units, and degrees to turns, with the
 * range check the loader reports (false: does not fit the core's format). */
bool sd_to_q32(double v, mot_q32 *out);
bool sd_deg_to_turns(double deg, mot_q32 *out);

/* Fresh evaluation state for a built scene (one malloc'd cursor array). */
int scene_eval_new(struct mot_eval *ev, const struct mot_scene *sc);
void scene_eval_free(struct mot_eval *ev);

/* Pose arrays sized for the scene (malloc'd; free with scene_pose_free). */
int scene_pose_new(struct mot_pose *p, const struct mot_scene *sc);
void scene_pose_free(struct mot_pose *p);

#endif /* STRAND_SCENE_DESC_H */
