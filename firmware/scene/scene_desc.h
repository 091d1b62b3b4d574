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
};

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
