/* SPDX-License-Identifier: MIT */
/*
 * load_camera.c - the `camera:` section: keys of eye, look_at and twist,
 * seven scalar curves over the same frames (FORMULAS section 10).
 */
#include "load_priv.h"

#include <errno.h>

int ld_camera(struct ld *l, yaml_node_t *n)
{
	static const char *const keys[] = { "interpolation", "ease", "beta", "keys", NULL };
	static const char *const key_fields[] = { "frame", "ease_in", "ease_out", "eye",
						  "look_at", "twist", NULL };
	enum { C_INTERP, C_EASE, C_BETA, C_KEYS };
	enum { F_FRAME, F_EASE_IN, F_EASE_OUT, F_EYE, F_LOOK, F_TWIST, F_COUNT };
	struct sd_camera *cam = &l->d->camera;
	struct sf_curve_marks *cm = l->mk->cam;
	struct sd_curve tmpl = { 0 };
	struct sd_key *k[MOT_CAM_NCHANNELS];
	yaml_node_t *v[4], *f[F_COUNT];
	yaml_node_item_t *it;
	struct ld_mark *marks;
	struct ld_curve_opts o;
	size_t count, i, ch;
	int err;

	l->mk->camera = ld_mark_of(n);
	err = ld_map_req(l, n, "camera", keys, v, YML_REQ(C_KEYS));
	if (err)
		return err;
	o.interp = v[C_INTERP];
	o.ease = v[C_EASE];
	o.beta = v[C_BETA];
	err = ld_curve_opts(l, &o, &tmpl, &cm[0].ease);
	if (!err)
		err = ld_seq(l, v[C_KEYS], "keys", &it, &count);
	if (err)
		return err;
	if (count == 0)
		return ld_fail(l, v[C_KEYS], -EINVAL, "a camera move needs at least one key");
	marks = pool_array(l->pool, count, sizeof(*marks));
	if (!marks)
		return ld_nomem(l);
	for (ch = 0; ch < MOT_CAM_NCHANNELS; ch++) {
		k[ch] = pool_array(l->pool, count, sizeof(*k[ch]));
		if (!k[ch])
			return ld_nomem(l);
	}
	for (i = 0; i < count; i++) {
		yaml_node_t *map = ld_node(l, it[i]);
		struct ld_key_common c;
		double eye[3], look[3], twist = 0;

		marks[i] = ld_mark_of(map);
		err = ld_map_req(l, map, "camera key", key_fields, f,
				 YML_REQ(F_EYE) | YML_REQ(F_LOOK));
		if (err)
			return err;
		c.frame = f[F_FRAME];
		c.ease_in = f[F_EASE_IN];
		c.ease_out = f[F_EASE_OUT];
		err = ld_key_common(l, map, &c, i ? &k[0][i - 1] : NULL, &k[0][i]);
		if (!err)
			err = ld_vec(l, f[F_EYE], 3, 1.0, "scene units", eye);
		if (!err)
			err = ld_vec(l, f[F_LOOK], 3, 1.0, "scene units", look);
		if (!err && f[F_TWIST])
			err = ld_q32(l, f[F_TWIST], 1.0 / 360, "degrees", &twist);
		if (err)
			return err;
		if (eye[0] == look[0] && eye[1] == look[1] && eye[2] == look[2])
			return ld_fail(l, f[F_LOOK], -EINVAL,
				       "look_at is the eye itself: the camera has no direction");
		for (ch = 0; ch < MOT_CAM_NCHANNELS; ch++) {
			k[ch][i] = k[0][i];
			k[ch][i].value = ch < 3 ? eye[ch] : ch < 6 ? look[ch - 3] : twist;
		}
	}
	for (ch = 0; ch < MOT_CAM_NCHANNELS; ch++) {
		cam->ch[ch] = tmpl;
		cam->ch[ch].ease_in = cam->ch[ch].ease_out = 0; /* the camera's warp eases */
		cam->ch[ch].keys = k[ch];
		cam->ch[ch].nkeys = (uint32_t)count;
		cm[ch].at = l->mk->camera;
		cm[ch].ease = cm[0].ease;
		cm[ch].key = marks;
	}
	cam->ease_in = tmpl.ease_in;
	cam->ease_out = tmpl.ease_out;
	l->d->has_camera = true;
	/* the span check wants the strand-wide ease on the curve it checks */
	tmpl.keys = k[0];
	tmpl.nkeys = (uint32_t)count;
	return ld_curve_check(l, &tmpl, &cm[0]);
}
