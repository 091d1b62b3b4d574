/* SPDX-License-Identifier: MIT */
/*
 * load_free.c - the keys of a free node's strand (FORMULAS sections 2-4).
 *
 * A key may set any of translate, rotation (Euler `rotate` or `quat`),
 * scale and shear, or a whole `matrix`, which is decomposed here into all
 * four. Each of the nine scalar channels becomes a curve over the keys that
 * set it, and the rotations a track of quaternions, so a key that sets only
 * a translation leaves the rotation's interpolation alone.
 */
#include "load_priv.h"

#include <errno.h>
#include <math.h>
#include <string.h>

#include "affine.h"

enum { G_T, G_S, G_H, G_R, G_COUNT }; /* translate, scale, shear, rotation */

struct fkey {
	struct sd_key k;        /* frame and ease fractions */
	bool has[G_COUNT];
	double v[3][3];         /* translate, scale, shear */
	double q[4];
	/* explicit tangents per frame: translate, scale (tset[g]) and quat */
	double tin[2][3], tout[2][3], qin[4], qout[4];
	uint32_t tset[2], qset;
	struct ld_mark mark;
};

/* The tangent fields of a key: translate_in/out, scale_in/out, quat_in/out. */
static int tangent_fields(struct ld *l, yaml_node_t **v, struct fkey *fk)
{
	static const int field[3][2] = { { K_TRANSLATE_IN, K_TRANSLATE_OUT },
					 { K_SCALE_IN, K_SCALE_OUT },
					 { K_QUAT_IN, K_QUAT_OUT } };
	static const int value[3] = { K_TRANSLATE, K_SCALE, K_QUAT };
	int g, side, err;

	for (g = 0; g < 3; g++)
		for (side = 0; side < 2; side++) {
			yaml_node_t *n = v[field[g][side]];
			size_t dim = g == 2 ? 4 : 3;
			double *out = g == 2 ? (side ? fk->qout : fk->qin) :
				      (side ? fk->tout[g] : fk->tin[g]);
			uint32_t *set = g == 2 ? &fk->qset : &fk->tset[g];

			if (!n)
				continue;
			if (!v[value[g]])
				return ld_fail(l, n, -EINVAL,
					       "'%s' is the tangent of '%s', which this key does not set",
					       ld_key_fields[field[g][side]], ld_key_fields[value[g]]);
			err = ld_vec(l, n, dim, 1.0, "per frame", out);
			if (err)
				return err;
			*set |= side ? MOT_TANGENT_OUT : MOT_TANGENT_IN;
		}
	return 0;
}

static const char *const group_field[3] = { "translate", "scale", "shear" };

static int quat_field(struct ld *l, yaml_node_t *n, double q[4])
{
	int err = ld_vec(l, n, 4, 1.0, "", q);

	if (err)
		return err;
	if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 1e-18))
		return ld_fail(l, n, -EINVAL, "a rotation quaternion must not be zero");
	return 0;
}

/* A whole 4x4 matrix, decomposed into the key's four groups. */
static int matrix_field(struct ld *l, yaml_node_t *n, struct fkey *fk)
{
	static const char axis_name[] = "xyz";
	yaml_node_item_t *rows;
	struct affine_decomp dc;
	double m[4][4], check[9];
	size_t count, i;
	mot_q32 q;
	int err, axis = 0;

	err = ld_seq(l, n, "matrix", &rows, &count);
	if (err)
		return err;
	if (count != 4)
		return ld_fail(l, n, -EINVAL, "a matrix key has 4 rows of 4 numbers, found %zu rows",
			       count);
	for (i = 0; i < 4; i++) {
		err = ld_vec(l, ld_node(l, rows[i]), 4, 1.0, "scene units", m[i]);
		if (err)
			return err;
	}
	switch (affine_decompose(&dc, (const double(*)[4])m, &axis)) {
	case AFFINE_E_NOT_AFFINE:
		return ld_fail(l, n, -EINVAL,
			       "a matrix key must be affine: its last column must be (0, 0, 0, 1)");
	case AFFINE_E_SINGULAR:
		return ld_fail(l, n, -EINVAL,
			       "singular matrix key: its %c scale is below 1e-9 of its largest row",
			       axis_name[axis]);
	default:
		break;
	}
	memcpy(check, dc.scale, sizeof(dc.scale));
	memcpy(check + 3, dc.shear, sizeof(dc.shear));
	memcpy(check + 6, dc.translate, sizeof(dc.translate));
	for (i = 0; i < 9; i++)
		if (!sd_to_q32(check[i], &q))
			return ld_fail(l, n, -ERANGE,
				       "matrix key decomposes to a %s of %.10g, outside the core's range",
				       group_field[i < 3 ? 1 : i < 6 ? 2 : 0], check[i]);
	for (i = 0; i < 3; i++) {
		fk->v[G_T][i] = dc.translate[i];
		fk->v[G_S][i] = dc.scale[i];
		fk->v[G_H][i] = dc.shear[i];
	}
	memcpy(fk->q, dc.q, sizeof(fk->q));
	fk->has[G_T] = fk->has[G_S] = fk->has[G_H] = fk->has[G_R] = true;
	return 0;
}

static int free_key(struct ld *l, uint32_t node, yaml_node_t *map, struct fkey *fk,
		    const struct fkey *prev)
{
	yaml_node_t *v[K_COUNT];
	int err, f;

	fk->mark = ld_mark_of(map);
	err = ld_strand_key(l, node, map, v, prev ? &prev->k : NULL, &fk->k);
	if (err)
		return err;
	if (v[K_MATRIX]) {
		for (f = K_TRANSLATE; f < K_COUNT; f++)
			if (v[f] && f != K_MATRIX)
				return ld_fail(l, v[f], -EINVAL,
					       "'matrix' sets the whole transform; a key with it cannot also set '%s'",
					       ld_key_fields[f]);
		return matrix_field(l, v[K_MATRIX], fk);
	}
	if (v[K_ROTATE] && v[K_QUAT])
		return ld_fail(l, v[K_QUAT], -EINVAL,
			       "'rotate' and 'quat' both set the rotation; keep one");
	if (!v[K_TRANSLATE] && !v[K_ROTATE] && !v[K_QUAT] && !v[K_SCALE] && !v[K_SHEAR])
		return ld_fail(l, map, -EINVAL,
			       "key sets nothing: give translate, rotate, quat, scale, shear or matrix");
	if (v[K_TRANSLATE]) {
		err = ld_vec(l, v[K_TRANSLATE], 3, 1.0, "scene units", fk->v[G_T]);
		fk->has[G_T] = true;
	}
	if (!err && v[K_SCALE]) {
		err = ld_vec(l, v[K_SCALE], 3, 1.0, "", fk->v[G_S]);
		fk->has[G_S] = true;
	}
	if (!err && v[K_SHEAR]) {
		err = ld_vec(l, v[K_SHEAR], 3, 1.0, "", fk->v[G_H]);
		fk->has[G_H] = true;
	}
	if (!err && v[K_ROTATE]) {
		double deg[3];

		err = ld_vec(l, v[K_ROTATE], 3, 1.0 / 360, "degrees", deg);
		if (!err)
			affine_euler_quat(fk->q, deg);
		fk->has[G_R] = true;
	}
	if (!err && v[K_QUAT]) {
		err = quat_field(l, v[K_QUAT], fk->q);
		fk->has[G_R] = true;
	}
	return err ? err : tangent_fields(l, v, fk);
}

/* The three channel curves of one group over the keys that set it. */
static int group_curves(struct ld *l, uint32_t node, const struct fkey *fk, size_t n, int g,
			const struct sd_curve *tmpl)
{
	struct sd_free *sf = &l->nodes[node].free;
	struct sf_node_marks *nm = &l->mk->node[node];
	struct ld_mark *marks;
	size_t count = 0, i, j;
	int ch, err;

	for (i = 0; i < n; i++)
		count += fk[i].has[g];
	if (!count)
		return 0;
	marks = pool_array(l->pool, count, sizeof(*marks));
	if (!marks)
		return ld_nomem(l);
	for (ch = 0; ch < 3; ch++) {
		struct sd_curve *c = &sf->ch[g * 3 + ch];
		struct sf_curve_marks *cm = &nm->ch[g * 3 + ch];
		struct sd_key *keys = pool_array(l->pool, count, sizeof(*keys));

		if (!keys)
			return ld_nomem(l);
		*c = *tmpl;
		c->ease_in = c->ease_out = 0; /* the strand's ease is the free strand's warp */
		for (i = j = 0; i < n; i++) {
			if (!fk[i].has[g])
				continue;
			keys[j] = fk[i].k;
			keys[j].value = fk[i].v[g][ch];
			if (g < G_H) {
				keys[j].tan_in = fk[i].tin[g][ch];
				keys[j].tan_out = fk[i].tout[g][ch];
				keys[j].tan_set = fk[i].tset[g];
			}
			marks[j++] = fk[i].mark;
		}
		c->keys = keys;
		c->nkeys = (uint32_t)count;
		cm->at = nm->value.at;
		cm->key = marks;
		err = ld_tangent_check(l, c, marks, g == G_T ? "translate_in' or 'translate_out" :
					       "scale_in' or 'scale_out", 1.0);
		if (!err)
			err = ld_curve_check(l, c, cm);
		if (err)
			return err;
	}
	return 0;
}

/* A rotation as four curves of its components, normalised when evaluated:
 * cubic (hermite, with quat_in / quat_out tangents) or step. */
static int rotation_curves(struct ld *l, uint32_t node, const struct fkey *fk, size_t n,
			   enum mot_interp interp)
{
	struct sd_free *sf = &l->nodes[node].free;
	struct sf_curve_marks *cm = &l->mk->node[node].rot;
	struct ld_mark *marks;
	size_t count = 0, i, j;
	int c, err;

	for (i = 0; i < n; i++)
		count += fk[i].has[G_R];
	if (!count)
		return 0;
	marks = pool_array(l->pool, count, sizeof(*marks));
	if (!marks)
		return ld_nomem(l);
	for (c = 0; c < 4; c++) {
		struct sd_key *keys = pool_array(l->pool, count, sizeof(*keys));

		if (!keys)
			return ld_nomem(l);
		for (i = j = 0; i < n; i++) {
			if (!fk[i].has[G_R])
				continue;
			if (fk[i].k.ease_in || fk[i].k.ease_out)
				return ld_fail_at(l, fk[i].mark, -EINVAL,
						  "a cubic or step rotation takes no ease_in or ease_out (shape it with quat_in and quat_out)");
			memset(&keys[j], 0, sizeof(keys[j]));
			keys[j].frame = fk[i].k.frame;
			keys[j].value = fk[i].q[c];
			keys[j].tan_in = fk[i].qin[c];
			keys[j].tan_out = fk[i].qout[c];
			keys[j].tan_set = fk[i].qset;
			marks[j++] = fk[i].mark;
		}
		sf->quat[c] = (struct sd_curve){ .interp = interp, .nkeys = (uint32_t)count,
						 .keys = keys, .beta1 = 1 };
		err = ld_tangent_check(l, &sf->quat[c], marks, "quat_in' or 'quat_out", 1.0);
		if (err)
			return err;
	}
	cm->at = l->mk->node[node].value.at;
	cm->key = marks;
	return 0;
}

static int rotation_track(struct ld *l, uint32_t node, const struct fkey *fk, size_t n)
{
	struct sd_free *sf = &l->nodes[node].free;
	struct sf_curve_marks *cm = &l->mk->node[node].rot;
	struct sd_rot_key *keys;
	struct ld_mark *marks;
	size_t count = 0, i, j;

	for (i = 0; i < n; i++)
		count += fk[i].has[G_R];
	if (!count)
		return 0;
	keys = pool_array(l->pool, count, sizeof(*keys));
	marks = pool_array(l->pool, count, sizeof(*marks));
	if (!keys || !marks)
		return ld_nomem(l);
	for (i = j = 0; i < n; i++) {
		if (!fk[i].has[G_R])
			continue;
		if (fk[i].qset)
			return ld_fail_at(l, fk[i].mark, -EINVAL,
					  "'quat_in' and 'quat_out' are tangents of a cubic rotation; this strand's rotation is slerp or squad");
		keys[j].frame = fk[i].k.frame;
		keys[j].ease_in = fk[i].k.ease_in;
		keys[j].ease_out = fk[i].k.ease_out;
		memcpy(keys[j].q, fk[i].q, sizeof(keys[j].q));
		marks[j] = fk[i].mark;
		if (j && keys[j - 1].ease_out + keys[j].ease_in > 1)
			return ld_fail_at(l, marks[j], -EINVAL,
					  "ease_out %.10g leaving frame %.10g and ease_in %.10g arriving at frame %.10g add up to more than the interval",
					  keys[j - 1].ease_out, keys[j - 1].frame, keys[j].ease_in,
					  keys[j].frame);
		j++;
	}
	sf->rot = keys;
	sf->nrot = (uint32_t)count;
	cm->at = l->mk->node[node].value.at;
	cm->key = marks;
	return 0;
}

/* The interpolation of each group (translate, scale, shear): one name for
 * all, or a mapping {translate: linear, scale: step, shear: hermite} with
 * hermite for a group it leaves out. */
static int group_opts(struct ld *l, const struct ld_free_opts *o, struct sd_curve tmpl[3],
		      struct ld_mark *ease_mark)
{
	static const char *const groups[] = { "translate", "scale", "shear", NULL };
	yaml_node_t *v[3] = { NULL, NULL, NULL };
	bool per_group = o->interp && o->interp->type == YAML_MAPPING_NODE;
	int g, err = 0;

	if (per_group)
		err = ld_map(l, o->interp, "interpolation", groups, v);
	for (g = 0; !err && g < 3; g++) {
		struct ld_curve_opts co = { per_group ? v[g] : o->interp, o->ease, o->beta };

		memset(&tmpl[g], 0, sizeof(tmpl[g]));
		err = ld_curve_opts(l, &co, &tmpl[g], ease_mark);
	}
	return err;
}

int ld_free_strand(struct ld *l, uint32_t node, const struct ld_free_opts *o)
{
	static const char *const rot_names[] = { "slerp", "squad", "cubic", "step", NULL };
	struct sd_node *sn = &l->nodes[node];
	struct sf_strand *st = &l->strand[node];
	struct sf_node_marks *nm = &l->mk->node[node];
	struct sd_curve tmpl[3];
	yaml_node_item_t *it;
	struct fkey *fk;
	double *frames, span;
	size_t count, i;
	int err, rot = 0, g;
	bool compact = false;

	err = group_opts(l, o, tmpl, &nm->ease);
	if (!err && o->rotation)
		err = ld_enum(l, o->rotation, "rotation interpolation", rot_names, &rot);
	if (!err && o->compact)
		err = ld_bool(l, o->compact, &compact);
	if (!err)
		err = ld_seq(l, o->keys, "keys", &it, &count);
	if (err)
		return err;
	if (count == 0)
		return ld_fail(l, o->keys, -EINVAL, "a strand needs at least one key");
	fk = pool_array(l->pool, count, sizeof(*fk));
	frames = pool_array(l->pool, count, sizeof(*frames));
	if (!fk || !frames)
		return ld_nomem(l);
	for (i = 0; i < count; i++) {
		err = free_key(l, node, ld_node(l, it[i]), &fk[i], i ? &fk[i - 1] : NULL);
		if (err)
			return err;
		frames[i] = fk[i].k.frame;
	}
	span = frames[count - 1] - frames[0];
	if (tmpl[0].ease_in + tmpl[0].ease_out > span)
		return ld_fail(l, o->ease, -EINVAL,
			       "ease in %.10g + out %.10g frames is longer than the keys' span of %.10g frames",
			       tmpl[0].ease_in, tmpl[0].ease_out, span);
	/* compact is a storage choice: step and linear channels and slerp
	 * rotations without ease keep their keys alone (curve.h, strand.h) */
	compact = compact && !tmpl[0].ease_in && !tmpl[0].ease_out;
	for (i = 0; compact && i < count; i++)
		compact = !fk[i].k.ease_in && !fk[i].k.ease_out;
	for (g = G_T; g <= G_H; g++) {
		tmpl[g].compact = compact && tmpl[g].interp <= MOT_INTERP_LINEAR;
		err = group_curves(l, node, fk, count, g, &tmpl[g]);
		if (err)
			return err;
	}
	if (rot >= 2)
		err = rotation_curves(l, node, fk, count,
				      rot == 2 ? MOT_INTERP_HERMITE : MOT_INTERP_STEP);
	else
		err = rotation_track(l, node, fk, count);
	if (err)
		return err;
	sn->has_free = true;
	sn->free.squad = rot == 1;
	sn->free.rot_compact = compact && rot == 0;
	sn->free.ease_in = tmpl[0].ease_in;
	sn->free.ease_out = tmpl[0].ease_out;
	st->interp = tmpl[0].interp;
	st->squad = rot == 1;
	st->rotation = rot_names[rot];
	st->nkeys = (uint32_t)count;
	st->key_frames = frames;
	return 0;
}
