/* SPDX-License-Identifier: MIT */
/*
 * scene.h - a scene: a flattened forest of nodes, their strands, the camera,
 * cycled objects and attribute channels, and their evaluation at a frame
 * (FORMULAS.md section 3; the seed paper sections 3 and 5).
 *
 * Nodes sit in an array with every parent before its children, so one pass
 * in index order computes every world matrix without recursion:
 *     L = T(-p) . S . H . R . T(p) . T(t)       free node (strand channels)
 *     L = T(-p) . R(axis, angle) . T(p)         revolute joint
 *     L = T(position . axis)                    prismatic joint
 *     W(root) = L, W(child) = L . W(parent)
 * and a node's reported position is its pivot in world space, (p, 1) . W.
 * Both are computed for every node on every evaluation, each entry rounded
 * once from the parent's world matrix: the position as (p + t) . W(parent)
 * (t: the node's translation), which the rounded W maps the pivot onto
 * within half an LSB (scene.c's node_world explains why and how W's
 * translation shares its products).
 *
 * All arrays are owned by the caller (the scene loader packs them into one
 * block, see arena.h); the scene itself is read-only while it plays. The
 * mutable part of an evaluation — one cursor per curve and rotation track,
 * and a sticky status word — lives in struct mot_eval, one per evaluating
 * thread.
 */
#ifndef MOT_SCENE_H
#define MOT_SCENE_H

#include "aim.h"
#include "camera.h"
#include "curve.h"
#include "cycle.h"
#include "fix.h"
#include "mat.h"
#include "strand.h"
#include "system.h"
#include "timing.h"

enum mot_node_kind {
	MOT_NODE_FREE,
	MOT_NODE_REVOLUTE,  /* value: angle in turns */
	MOT_NODE_PRISMATIC, /* value: position along the axis, scene units */
};

enum mot_axis {
	MOT_AXIS_X,
	MOT_AXIS_Y,
	MOT_AXIS_Z,
	MOT_AXIS_VEC, /* any unit vector */
};

struct mot_node {
	/* What every node reads on every evaluation comes first: a joint about
	 * a coordinate axis reads the first 56 bytes (128 in all). */
	int32_t parent;   /* index of the parent, -1 for a root; < own index */
	uint32_t kind;    /* enum mot_node_kind */
	uint32_t axis_id; /* enum mot_axis (joints) */
	int32_t curve;    /* joints: curve of the value, or -1 */
	int32_t spin;     /* revolute joints: rpm curve (prepared with integral), or -1 */
	int32_t strand;   /* free nodes: index into scene->free, or -1 */
	mot_q32 pivot[3]; /* rest coordinates shared with the parent */
	mot_q32 rest;     /* joints: value when no strand moves it */
	mot_q32 axis[3];  /* joints: unit axis (set for every axis_id) */
	/* Derived from axis by mot_node_prepare(), for revolute joints about a
	 * tilted axis (zero otherwise): the constant parts of the rotation
	 * matrix, in Q2.62, with (k, j, l) = (k, k+1, k+2) mod 3:
	 *     R[j][j] = 1 - (1 - cos) rot_sq[j],  rot_sq[j] = a_k^2 + a_l^2
	 *     R[j][l], R[l][j] = (1 - cos) rot_pr[k] +- sin a_k, rot_pr[k] = a_j a_l */
	int64_t rot_sq[3];
	int64_t rot_pr[3];
};

struct mot_scene {
	struct mot_timing timing;
	uint32_t nnodes;
	const struct mot_node *nodes;
	uint32_t ncurves;
	const struct mot_curve *curves;
	uint32_t nrot;
	const struct mot_rot_track *rot;
	uint32_t nfree;
	const struct mot_free_strand *free;
	const struct mot_camera *camera; /* NULL: no camera */
	uint32_t ncycles;
	const struct mot_cycle *cycles;
	uint32_t nattrs;
	const int32_t *attr_curve; /* curve index of each attribute */
	uint32_t nsys;             /* surfaces, particle systems, flocks (system.h) */
	const struct mot_system *sys;
	uint32_t nsysout;          /* values they write: pose->sysout */
	uint32_t naims;            /* pan/tilt heads following a target (aim.h) */
	const struct mot_aim *aims;
};

/* Where an aim's target is: a node's pivot (index: the node), or three
 * consecutive values x, y, z of pose->sysout (index: the x). */
enum mot_aim_src {
	MOT_AIM_SRC_NODE,
	MOT_AIM_SRC_SYS,
};

/*
 * What one evaluation leaves a node for the next: a joint whose value is
 * the one its matrix was made with keeps its sine and cosine, and a node
 * whose value and parent did not move keeps its matrix and position in the
 * pose (mot_scene_eval). The results are the same bits either way.
 */
struct mot_node_memo {
	/* What both passes read comes first (one cache line where the array
	 * is aligned to it). */
	mot_q32 value;  /* the joint value of the node's matrix */
	mot_q32 s, c;   /* revolute joints: its sine and cosine */
	uint8_t moved;  /* the matrix was made anew in the last evaluation */
	uint8_t fresh;  /* this evaluation's joint value is not `value`'s (scene.c) */
	/* set by mot_eval_reset() from the scene (scene.c, the small case) */
	uint8_t small;  /* every sum of the node's matrix is known to fit */
	uint8_t prow;   /* the pivot's one nonzero component (any if none), 3: more */
	uint8_t pre;    /* small, and the pivot below 2 units: the small kernels
			 * take it pre-scaled (scene.c's PRE_SHIFT, x86-64) */
	uint8_t free;   /* a free node's strand: what its channels are (scene.c);
			 * MOT_MEMO_FREE_OWN below */
	/* A joint's curve between the frames lo (included) and hi (excluded):
	 * the held value `held` (piece NULL) or the piece `piece` of an
	 * interpolating curve, evaluated as `how` says, inline where `op`
	 * says so (scene.c); under a
	 * strand-wide ease (warp: the curve), at the warped frame, and only
	 * where that is between glo and ghi. What the curve is at a frame,
	 * whatever came before: an empty span (lo > hi) until an evaluation
	 * finds it, and always where op says out of line. */
	uint8_t op, how;
	mot_q32 lo, hi;
	mot_q32 held;
	const struct mot_curve_seg *piece;
	const struct mot_curve *warp;
	mot_q32 glo, ghi;
	/* A free node's rotation track (scene.c's rot memo; its joint fields
	 * above unused): between the warped frames lo and hi the key interval
	 * `arc` from its key at f0, or the held end key's matrix `end`, as
	 * `how` says. */
	const struct mot_rot_seg *arc;
	const struct mot_rot_q62 *end;
	mot_q32 f0;
	uint64_t lin;   /* bound on |W_lin|'s 2-norm (raw), UINT64_MAX: none */
	uint64_t bound; /* bound on |W_t| (raw), UINT64_MAX: none */
};

/* A bit of mot_node_memo.free: the node's channel curves take scene.c's own
 * way to mot_curve_eval()'s bits, else the call (the tests clear it to
 * compare the two). */
#define MOT_MEMO_FREE_OWN 16u

/* Mutable evaluation state. cursors has mot_eval_cursor_count() entries,
 * memo mot_eval_memo_count(). */
struct mot_eval {
	struct mot_cursor *cursors; /* curves first, then rotation tracks */
	uint32_t ncursors;
	uint32_t sat;               /* sticky MOT_SAT_* bits of every evaluation */
	struct mot_node_memo *memo; /* one per node */
	uint32_t nmemo;
	const struct mot_mat *memo_world; /* the pose the memo describes, or NULL */
	struct mot_sys_eval *sys;   /* nsys: each laid out by mot_system_eval_init() */
};

/* The result of one evaluation; every array is caller-owned and sized from
 * the scene's counts. */
struct mot_pose {
	struct mot_mat *world; /* nnodes */
	mot_q32 (*pos)[3];     /* nnodes: pivot in world space */
	mot_q32 *value;        /* nnodes: joint value (turns or units), 0 for free nodes */
	mot_q32 *rpm;          /* nnodes: spin speed of spin joints, else 0 */
	struct mot_cam_pose cam;
	int32_t *cycle;        /* ncycles */
	mot_q32 *attr;         /* nattrs */
	const struct mot_eval *by; /* the evaluation that wrote it last (NULL: none) */
	mot_q32 *sysout;       /* nsysout: the systems' values (system.h) */
	mot_q32 (*aim)[2];     /* naims: pan and tilt, turns */
};

/*
 * Fill the derived fields of a node (rot_sq, rot_pr) from its kind, axis_id
 * and axis. Whoever builds the node array calls it for every node once
 * those are set, before mot_scene_validate(). Init only.
 */
void mot_node_prepare(struct mot_node *n);

/*
 * Check the scene's structure: every parent before its child (MOT_E_PARENT),
 * every index in range and of the right kind for its node (MOT_E_KIND,
 * MOT_E_INVAL), every joint axis unit length and every node's derived fields
 * those of mot_node_prepare() (MOT_E_INVAL). Init only.
 */
int mot_scene_validate(const struct mot_scene *sc);

static inline uint32_t mot_eval_cursor_count(const struct mot_scene *sc)
{
	return sc->ncurves + sc->nrot;
}

static inline uint32_t mot_eval_memo_count(const struct mot_scene *sc)
{
	return sc->nnodes;
}

/* Zero the cursors and the status, forget the memo and prepare it (what
 * the scene's structure bounds). MOT_E_CAPACITY when ev->ncursors or
 * ev->nmemo is too small. Init only (O(nodes)). */
int mot_eval_reset(struct mot_eval *ev, const struct mot_scene *sc);

/*
 * Evaluate every node, the camera, cycles and attributes at a frame
 * (Q32.32 frames; the loop passes mot_timing_tick_frame of its tick).
 * Saturations are ORed into ev->sat. Real-time safe: no allocation, bounded
 * time, the scene untouched.
 *
 * The pose is the evaluation's: when out is the pose this ev wrote last
 * (out->by, ev->memo_world) and nothing has saturated, a node whose joint
 * value and parent did not move keeps what out holds, and a joint whose
 * value did not move its sine and cosine (struct mot_node_memo): the same
 * bits as evaluating it again. So write nothing into a pose between two
 * evaluations into it (or mot_eval_reset() the evaluation).
 */
void mot_scene_eval(const struct mot_scene *sc, struct mot_eval *ev, mot_q32 frame,
		    struct mot_pose *out);

/*
 * Prepare every aim's pan grid (aim.h) by marching the scene over the aims'
 * span (they share it, and their grid) with ev and out (sized for sc) and
 * m (naims march states); aims is the scene's array (writable at build).
 * 0, MOT_E_RANGE for a target too fast for an aim's grid (*bad: that aim),
 * MOT_E_INVAL for a target out of range. Init only.
 */
int mot_scene_aims_init(const struct mot_scene *sc, struct mot_aim *aims, struct mot_eval *ev,
			struct mot_pose *out, struct mot_aim_march *m, uint32_t *bad);

/* The local matrix of one node at a frame (for jog/teach and the tests). */
void mot_node_local(struct mot_mat *out, const struct mot_scene *sc, struct mot_eval *ev,
		    uint32_t node, mot_q32 frame, mot_q32 *value, mot_q32 *rpm);

#endif /* MOT_SCENE_H */
