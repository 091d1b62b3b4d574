/* SPDX-License-Identifier: MIT */
/* camera.c - camera strands with a continuous pan (see camera.h). */
#include "camera.h"
#include "trig.h"

struct cam_dir {
	mot_q32 eye[3], look[3], twist;
	mot_q32 pan, tilt; /* principal pan */
	bool vertical;     /* looking straight up or down: pan undefined */
};

static void cam_dir_at(struct cam_dir *d, const struct mot_camera *cam,
		       const struct mot_curve *curves, struct mot_cursor *cursors, mot_q32 g,
		       uint32_t *sat)
{
	mot_q32 v[MOT_CAM_NCHANNELS], dir[3];
	int k;

	for (k = 0; k < MOT_CAM_NCHANNELS; k++)
		v[k] = mot_curve_eval(&curves[cam->ch[k]], cursors ? &cursors[cam->ch[k]] : NULL,
				      g, sat);
	for (k = 0; k < 3; k++) {
		d->eye[k] = v[MOT_CAM_EYE_X + k];
		d->look[k] = v[MOT_CAM_LOOK_X + k];
	}
	d->twist = v[MOT_CAM_TWIST];
	for (k = 0; k < 3; k++)
		dir[k] = mot_sub_sat(d->look[k], d->eye[k], sat);
	d->vertical = !mot_look(dir, &d->pan, &d->tilt, sat);
}

bool mot_look(const mot_q32 d[3], mot_q32 *pan, mot_q32 *tilt, uint32_t *sat)
{
	mot_q32 h = (mot_q32)mot_isqrt_acc(mot_acc_mac(mot_acc_mul(d[0], d[0]), d[2], d[2]), sat);

	*pan = mot_atan2(-d[0], -d[2]);
	*tilt = mot_atan2(d[1], h);
	return d[0] != 0 || d[2] != 0;
}

static mot_q32 unwrap(mot_q32 principal, mot_q32 ref)
{
	return mot_pan_unwrap(principal, ref);
}

/* Shortest signed difference a - b on the circle, in (-1/2, 1/2] turn. */
static mot_q32 wrap_diff(mot_q32 a, mot_q32 b)
{
	return unwrap(a, b) - b;
}

uint32_t mot_camera_ref_count(uint32_t nkeys)
{
	return nkeys < 2 ? 1 : (nkeys - 1) * MOT_CAMERA_SUB + 1;
}

static const struct mot_key *cam_keys(const struct mot_camera *cam, const struct mot_curve *c)
{
	return c[cam->ch[0]].keys;
}

int mot_camera_init(struct mot_camera *cam, const struct mot_curve *curves, mot_q32 *pan_ref,
		    uint32_t nref, uint32_t *sat)
{
	const struct mot_curve *c0 = &curves[cam->ch[0]];
	const struct mot_key *keys = c0->keys;
	uint32_t n = c0->nkeys, need = mot_camera_ref_count(n), i, j, k;
	struct cam_dir d;
	mot_q32 prev = 0, ref = 0;
	bool have_prev = false;

	for (k = 1; k < MOT_CAM_NCHANNELS; k++) {
		const struct mot_curve *ck = &curves[cam->ch[k]];

		if (ck->nkeys != n)
			return MOT_E_INVAL;
		for (i = 0; i < n; i++)
			if (ck->keys[i].frame != keys[i].frame)
				return MOT_E_INVAL;
	}
	if (nref < need)
		return MOT_E_CAPACITY;
	cam->nref = need;
	cam->pan_ref = pan_ref;
	if (n < 2) {
		cam_dir_at(&d, cam, curves, NULL, keys[0].frame, sat);
		pan_ref[0] = d.pan;
		return MOT_OK;
	}
	/*
	 * March through every key interval on a grid four times finer than
	 * the stored one, unwrapping as we go. A step of a quarter turn or more
	 * is too fast to unwrap reliably from the stored grid.
	 */
	for (i = 0; i + 1 < n; i++) {
		mot_q32 f0 = keys[i].frame, h = keys[i + 1].frame - f0;
		uint32_t fine = MOT_CAMERA_SUB * 4, last = (i + 2 == n) ? fine : fine - 1;

		for (j = 0; j <= last; j++) {
			mot_q32 g = f0 + mot_muldiv(h, j, fine, sat);
			mot_q32 p;

			cam_dir_at(&d, cam, curves, NULL, g, sat);
			if (d.vertical && have_prev) {
				p = prev;
			} else if (!have_prev) {
				p = d.pan;
			} else {
				mot_q32 step = wrap_diff(d.pan, prev);

				if (step >= MOT_Q32_ONE / 4 || step <= -MOT_Q32_ONE / 4)
					return MOT_E_RANGE;
				p = prev + step;
			}
			prev = p;
			have_prev = true;
			if (j % 4 == 0) {
				ref = p;
				pan_ref[i * MOT_CAMERA_SUB + j / 4] = p;
			}
			/* run time unwraps from the grid point at or before the
			 * frame: keep every frame well within half a turn of it */
			if (p - ref >= MOT_Q32_ONE * 3 / 8 || ref - p >= MOT_Q32_ONE * 3 / 8)
				return MOT_E_RANGE;
		}
	}
	return MOT_OK;
}

void mot_camera_eval(struct mot_cam_pose *out, const struct mot_camera *cam,
		     const struct mot_curve *curves, struct mot_cursor *cursors, mot_q32 frame,
		     uint32_t *sat)
{
	const struct mot_key *keys = cam_keys(cam, curves);
	uint32_t n = curves[cam->ch[0]].nkeys, idx;
	mot_q32 g = mot_warp_apply(&cam->warp, frame, sat), ref;
	struct mot_mat r;
	struct cam_dir d;
	int k;

	cam_dir_at(&d, cam, curves, cursors, g, sat);
	if (n < 2 || g <= keys[0].frame) {
		idx = 0;
	} else if (g >= keys[n - 1].frame) {
		idx = cam->nref - 1;
	} else {
		uint32_t lo = 0, hi = n - 1;
		mot_q32 h;

		while (hi - lo > 1) {
			uint32_t mid = lo + (hi - lo) / 2;

			if (keys[mid].frame <= g)
				lo = mid;
			else
				hi = mid;
		}
		/* the grid point at or before g */
		h = keys[lo + 1].frame - keys[lo].frame;
		idx = lo * MOT_CAMERA_SUB +
		      (uint32_t)((g - keys[lo].frame) * MOT_CAMERA_SUB / h);
		if (idx >= cam->nref)
			idx = cam->nref - 1;
	}
	ref = cam->pan_ref[idx];
	for (k = 0; k < 3; k++) {
		out->eye[k] = d.eye[k];
		out->look[k] = d.look[k];
	}
	out->pan = d.vertical ? ref : unwrap(d.pan, ref);
	out->tilt = d.tilt;
	out->roll = d.twist;
	/* Rz(roll) . Rx(tilt) . Ry(pan) . T(eye) */
	mot_mat_rot_z(&out->m, out->roll);
	mot_mat_rot_x(&r, out->tilt);
	mot_mat_mul(&out->m, &out->m, &r, sat);
	mot_mat_rot_y(&r, out->pan);
	mot_mat_mul(&out->m, &out->m, &r, sat);
	for (k = 0; k < 3; k++)
		out->m.m[3][k] = out->eye[k];
}
