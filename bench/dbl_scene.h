/* SPDX-License-Identifier: MIT */
/*
 * dbl_scene.h - the "double reference doing the same work" of issue 2's
 * benchmark: a double-precision twin of mot_scene_eval() for timing the
 * fixed-point core against.
 *
 * Same work means the core's algorithms and preparation, not the tests'
 * reference formulas (tests/ref_scene.c bisects to the last bit and
 * recomputes tangents per call: right for accuracy, useless for timing):
 *   - curves: dbl_curve.h (prepared cubics, cursors, the same Newton solve,
 *     de Casteljau for Bezier, ease, closed-form spin integrals);
 *   - rotation tracks: slerp prepared per key interval (and squad's inner
 *     slerp), one sincos per in-between, squad's outer slerp per tick as in
 *     strand.c; the matrices of the held end keys made at init;
 *   - scene.c's memo: a joint whose value did not change keeps its sine and
 *     cosine, and with its parent unmoved its matrix and position;
 *   - the hierarchy in one pass in index order, as scene.c: the pivot's
 *     world position (p + t) . P_lin + P_t and the world translation
 *     pos - p . W_lin from it; revolute joints about x, y or z mixing two
 *     rows of the parent, prismatic joints and free nodes without rotation,
 *     scale or shear as a translated parent, free nodes and tilted axes as
 *     their linear part times the parent's; tilted axes by Rodrigues'
 *     formula on the axis' squares and products prepared per node.
 * Built from the same scene description, quantised as scene_build() does, in
 * one block. Compiled -O2 like the core, without -ffast-math.
 *
 * Scenes with a camera, cycles or attributes are refused: the benchmark's
 * scenes have none, and the twin stays small.
 */
#ifndef DBL_SCENE_H
#define DBL_SCENE_H

#include "dbl_curve.h"
#include "dbl_mat.h"
#include "scene/scene_desc.h"

struct dbl_rot_seg {
	struct dbl_slerp arc, inner; /* inner: squad's s(i) -> s(i+1), else arc */
	struct dbl_ease ease;
	double inv_h;
};

struct dbl_rot {
	uint32_t n;
	bool squad;
	double *frame;
	struct dbl_quat q0; /* the key of a one-key track */
	struct dbl_rot_seg *seg;
	struct dbl_mat end[2]; /* R of the held first and last key (strand.h's end) */
};

struct dbl_warp {
	bool on;
	double f0, f1;
	struct dbl_ease ease;
};

struct dbl_free {
	int32_t ch[MOT_FREE_NCHANNELS]; /* curve index or -1 */
	int32_t rot;                    /* rotation track or -1 */
	struct dbl_warp warp;
};

struct dbl_node {
	int32_t parent;
	enum mot_node_kind kind;
	enum mot_axis axis_id;
	double pivot[3], axis[3], rest;
	int32_t curve, spin, strand;
	double rot_sq[3], rot_pr[3]; /* tilted axis: struct mot_node's */
	uint32_t prow; /* struct mot_node_memo's: the pivot's one nonzero component, 3: more */
};

struct dbl_scene {
	uint32_t rate_num, rate_den;
	uint32_t nnodes, ncurves, nrot, nfree;
	struct dbl_node *nodes;
	struct dbl_curve *curves;
	struct dbl_rot *rot;
	struct dbl_free *free;
	void *block; /* everything above points into it */
};

struct dbl_memo {
	double value, s, c;
	bool moved, fresh;
	struct dbl_piece piece; /* the joint's curve (scene.c's piece memo) */
};

struct dbl_eval {
	struct dbl_cursor *cursors; /* curves, then rotation tracks */
	struct dbl_memo *memo;      /* one per node */
	const struct dbl_mat *memo_world; /* the pose it describes, or NULL */
};

struct dbl_pose {
	struct dbl_mat *world;
	double (*pos)[3];
	double *value, *rpm;
};

/* 0, or -1 when the description has what the twin does not do or does not
 * fit Q32.32. Allocates one block. */
int dbl_scene_new(struct dbl_scene *sc, const struct scene_desc *d);
void dbl_scene_free(struct dbl_scene *sc);

int dbl_eval_new(struct dbl_eval *ev, const struct dbl_scene *sc);
void dbl_eval_free(struct dbl_eval *ev);
int dbl_pose_new(struct dbl_pose *p, const struct dbl_scene *sc);
void dbl_pose_free(struct dbl_pose *p);

/* Every node at a frame (the Q32.32 frame of the core's tick, converted
 * exactly). */
void dbl_scene_eval(const struct dbl_scene *sc, struct dbl_eval *ev, double frame,
		    struct dbl_pose *out);

#endif /* DBL_SCENE_H */
