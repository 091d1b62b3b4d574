/* SPDX-License-Identifier: MIT */
/*
 * camera.h - camera choreography (FORMULAS.md section 10; the seed paper
 * section 7).
 *
 * A camera strand keys the eye, the point looked at and a twist; each of the
 * seven components is a scalar curve over the same key frames, with one
 * interpolation kind and a strand-wide slow-in/slow-out. From d = look - eye:
 *     pan  = atan2(-dx, -dz)
 *     tilt = atan2(dy, sqrt(dx^2 + dz^2))
 *     roll = twist
 * and the camera's matrix is Rz(roll) . Rx(tilt) . Ry(pan) . T(eye): at rest
 * it looks down -z with y up.
 *
 * Pan is continuous. A pan/tilt head must never swing back through a full
 * turn because atan2 wrapped at +-180 degrees, so pan starts at its principal
 * value at the first key and is unwrapped from there. To keep evaluation a
 * pure function of the frame (random access equals playback, bit for bit),
 * the unwrapped pan is sampled once at init on a grid of MOT_CAMERA_SUB
 * points per key interval; at run time the principal pan is unwrapped to the
 * turn nearest the grid sample at or before the frame. Init marches on a grid
 * four times finer and rejects a move whose pan turns by a quarter turn in
 * one fine step or strays 3/8 turn from its grid sample: add keys.
 */
#ifndef MOT_CAMERA_H
#define MOT_CAMERA_H

#include "curve.h"
#include "fix.h"
#include "mat.h"
#include "strand.h"

#define MOT_CAMERA_SUB 16 /* pan samples per key interval */

enum mot_camera_channel {
	MOT_CAM_EYE_X, MOT_CAM_EYE_Y, MOT_CAM_EYE_Z,
	MOT_CAM_LOOK_X, MOT_CAM_LOOK_Y, MOT_CAM_LOOK_Z,
	MOT_CAM_TWIST, /* turns */
	MOT_CAM_NCHANNELS,
};

struct mot_camera {
	int32_t ch[MOT_CAM_NCHANNELS]; /* curve indices in the scene, all with the same key frames */
	struct mot_warp warp;
	uint32_t nref;  /* (nkeys - 1) * MOT_CAMERA_SUB + 1 */
	mot_q32 *pan_ref; /* unwrapped pan on the grid, turns */
};

struct mot_cam_pose {
	mot_q32 eye[3], look[3];
	mot_q32 pan, tilt, roll; /* turns; pan continuous */
	struct mot_mat m;
};

/*
 * The pan and tilt (turns) that look along d from a point (section 10):
 * pan = atan2(-dx, -dz), tilt = atan2(dy, sqrt(dx^2 + dz^2)). Returns
 * false when d is vertical (or zero): pan is then undefined (set to 0).
 * Real-time safe. The camera and the aims (aim.h) share it.
 */
bool mot_look(const mot_q32 d[3], mot_q32 *pan, mot_q32 *tilt, uint32_t *sat);

/* The representative of `principal` (mod 1 turn) nearest to ref. */
static inline mot_q32 mot_pan_unwrap(mot_q32 principal, mot_q32 ref)
{
	/* k = round(ref - principal) in whole turns */
	mot_q32 k = (ref - principal + MOT_Q32_HALF) >> 32;

	return principal + k * MOT_Q32_ONE;
}

/* Number of pan samples init needs for a camera with nkeys keys. */
uint32_t mot_camera_ref_count(uint32_t nkeys);

/*
 * Prepare the pan grid into pan_ref (caller-owned, nref entries). The seven
 * curves must be initialised and share key frames (MOT_E_INVAL otherwise);
 * MOT_E_RANGE when the pan turns too fast for the grid; MOT_E_CAPACITY when
 * nref is too small. cam->ch and cam->warp must be set before. Init only.
 */
int mot_camera_init(struct mot_camera *cam, const struct mot_curve *curves, mot_q32 *pan_ref,
		    uint32_t nref, uint32_t *sat);

/* The camera at a frame. cursors is the scene's cursor array (indexed like
 * curves) or NULL. Real-time safe. */
void mot_camera_eval(struct mot_cam_pose *out, const struct mot_camera *cam,
		     const struct mot_curve *curves, struct mot_cursor *cursors, mot_q32 frame,
		     uint32_t *sat);

#endif /* MOT_CAMERA_H */
