/* SPDX-License-Identifier: MIT */
/*
 * load_strand.c - the `strands:` section: which node each strand moves, its
 * options, and the keys of joint strands (angle, position or rpm). Free
 * nodes' keys are in load_free.c.
 */
#include "load_priv.h"

#include <errno.h>
#include <string.h>

enum { S_NODE, S_INTERP, S_EASE, S_BETA, S_ROTATION, S_COMPACT, S_KEYS, S_COUNT };
static const char *const strand_keys[] = { "node", "interpolation", "ease", "beta",
					   "rotation", "compact", "keys", NULL };

static const char *kind_name(enum mot_node_kind k)
{
	return k == MOT_NODE_REVOLUTE ? "a revolute joint" :
	       k == MOT_NODE_PRISMATIC ? "a prismatic joint" : "a free node";
}

const char *const ld_key_fields[] = { "frame", "ease_in", "ease_out", "angle", "rpm",
				      "position", "in", "out", "translate", "rotate", "quat",
				      "scale", "shear", "matrix", "translate_in", "translate_out",
				      "scale_in", "scale_out", "quat_in", "quat_out", NULL };

static int key_kind(struct ld *l, uint32_t node, yaml_node_t **v)
{
	const struct sd_node *sn = &l->nodes[node];
	int i;

	if (sn->kind == MOT_NODE_FREE) {
		for (i = K_ANGLE; i <= K_OUT; i++)
			if (v[i])
				return ld_fail(l, v[i], -EINVAL,
					       "'%s' keys a joint, but '%s' is a free node (key translate, rotate, quat, scale, shear or matrix)",
					       ld_key_fields[i], sn->name);
		return 0;
	}
	for (i = K_TRANSLATE; i < K_COUNT; i++)
		if (v[i])
			return ld_fail(l, v[i], -EINVAL,
				       "'%s' keys a free node, but '%s' is %s (key '%s')",
				       ld_key_fields[i], sn->name, kind_name(sn->kind),
				       sn->kind == MOT_NODE_REVOLUTE ? "angle' or 'rpm" : "position");
	if (sn->kind == MOT_NODE_PRISMATIC && (v[K_ANGLE] || v[K_RPM]))
		return ld_fail(l, v[K_ANGLE] ? v[K_ANGLE] : v[K_RPM], -EINVAL,
			       "'%s' keys a revolute joint, but '%s' is a prismatic joint (key 'position')",
			       v[K_ANGLE] ? "angle" : "rpm", sn->name);
	if (sn->kind == MOT_NODE_REVOLUTE && v[K_POSITION])
		return ld_fail(l, v[K_POSITION], -EINVAL,
			       "'position' keys a prismatic joint, but '%s' is a revolute joint (key 'angle' or 'rpm')",
			       sn->name);
	return 0;
}

int ld_strand_key(struct ld *l, uint32_t node, yaml_node_t *map, yaml_node_t **v,
		  const struct sd_key *prev, struct sd_key *out)
{
	struct ld_key_common c;
	int err = ld_map(l, map, "key", ld_key_fields, v);

	if (!err)
		err = key_kind(l, node, v);
	if (err)
		return err;
	c.frame = v[K_FRAME];
	c.ease_in = v[K_EASE_IN];
	c.ease_out = v[K_EASE_OUT];
	return ld_key_common(l, map, &c, prev, out);
}

/* One key of a joint strand. *rpm is decided by the first key. */
static int joint_key(struct ld *l, uint32_t node, yaml_node_t *map, uint32_t i,
		     struct sd_key *keys, bool *rpm)
{
	const struct sd_node *sn = &l->nodes[node];
	yaml_node_t *v[K_COUNT], *val;
	int err;

	err = ld_strand_key(l, node, map, v, i ? &keys[i - 1] : NULL, &keys[i]);
	if (err)
		return err;
	/* tangents: value per frame, degrees or units like the value */
	keys[i].tan_set = (v[K_IN] ? MOT_TANGENT_IN : 0) | (v[K_OUT] ? MOT_TANGENT_OUT : 0);
	if (v[K_IN])
		err = ld_q32(l, v[K_IN], sn->kind == MOT_NODE_REVOLUTE ? 1.0 / 360 : 1.0,
			     "per frame", &keys[i].tan_in);
	if (!err && v[K_OUT])
		err = ld_q32(l, v[K_OUT], sn->kind == MOT_NODE_REVOLUTE ? 1.0 / 360 : 1.0,
			     "per frame", &keys[i].tan_out);
	if (err)
		return err;
	if (sn->kind == MOT_NODE_PRISMATIC) {
		err = ld_require(l, map, "key", v[K_POSITION], "position");
		return err ? err : ld_q32(l, v[K_POSITION], 1.0, "scene units", &keys[i].value);
	}
	if (v[K_ANGLE] && v[K_RPM])
		return ld_fail(l, v[K_RPM], -EINVAL,
			       "a key sets 'angle' or 'rpm', not both (a strand keys one of them)");
	if (!v[K_ANGLE] && !v[K_RPM])
		return ld_fail(l, map, -EINVAL, "missing field 'angle' (or 'rpm') in key");
	if (i == 0)
		*rpm = v[K_RPM] != NULL;
	val = *rpm ? v[K_RPM] : v[K_ANGLE];
	if (!val)
		return ld_fail(l, v[K_RPM] ? v[K_RPM] : v[K_ANGLE], -EINVAL,
			       "this strand keys '%s' from its first key; a key cannot switch to '%s'",
			       *rpm ? "rpm" : "angle", *rpm ? "angle" : "rpm");
	if (*rpm)
		return ld_q32(l, val, 1.0, "rpm", &keys[i].value);
	return ld_q32(l, val, 1.0 / 360, "degrees", &keys[i].value);
}

/* Speed strands are integrated in closed form: only the interpolating kinds
 * have one, and a time warp would change the integral (strand.h). */
static int rpm_rules(struct ld *l, const struct sd_curve *c, yaml_node_t **v,
		     const struct ld_mark *key_marks)
{
	uint32_t i;

	if (c->interp > MOT_INTERP_HERMITE)
		return ld_fail(l, v[S_INTERP], -EINVAL,
			       "an rpm strand is integrated in closed form: use step, linear or hermite");
	if (v[S_EASE])
		return ld_fail(l, v[S_EASE], -EINVAL,
			       "an rpm strand takes no ease (slow-in/slow-out is in its rpm keys)");
	for (i = 0; i < c->nkeys; i++)
		if (c->keys[i].ease_in || c->keys[i].ease_out)
			return ld_fail_at(l, key_marks[i], -EINVAL,
					  "an rpm strand takes no ease_in or ease_out (shape the speed with keys)");
	return 0;
}

static int joint_strand(struct ld *l, uint32_t node, yaml_node_t **v)
{
	struct sd_node *sn = &l->nodes[node];
	struct sf_node_marks *nm = &l->mk->node[node];
	struct sf_strand *st = &l->strand[node];
	struct sd_curve c = { 0 };
	struct sf_curve_marks cm = { 0 };
	struct ld_curve_opts o = { v[S_INTERP], v[S_EASE], v[S_BETA] };
	yaml_node_item_t *it;
	struct ld_mark *marks;
	struct sd_key *keys;
	double *frames;
	size_t count, i;
	bool rpm = false;
	int err;

	if (v[S_ROTATION])
		return ld_fail(l, v[S_ROTATION], -EINVAL,
			       "'rotation' interpolates a free node's rotation keys, but '%s' is %s",
			       sn->name, kind_name(sn->kind));
	err = ld_curve_opts(l, &o, &c, &cm.ease);
	if (!err && v[S_COMPACT])
		err = ld_bool(l, v[S_COMPACT], &c.compact);
	if (!err)
		err = ld_seq(l, v[S_KEYS], "keys", &it, &count);
	if (err)
		return err;
	if (count == 0)
		return ld_fail(l, v[S_KEYS], -EINVAL, "a strand needs at least one key");
	keys = pool_array(l->pool, count, sizeof(*keys));
	marks = pool_array(l->pool, count, sizeof(*marks));
	frames = pool_array(l->pool, count, sizeof(*frames));
	if (!keys || !marks || !frames)
		return ld_nomem(l);
	for (i = 0; i < count; i++) {
		yaml_node_t *map = ld_node(l, it[i]);

		marks[i] = ld_mark_of(map);
		err = joint_key(l, node, map, (uint32_t)i, keys, &rpm);
		if (err)
			return err;
		frames[i] = keys[i].frame;
	}
	c.nkeys = (uint32_t)count;
	c.keys = keys;
	cm.key = marks;
	/* a storage choice: only step and linear curves keep their keys alone */
	c.compact = c.compact && c.interp <= MOT_INTERP_LINEAR && !c.ease_in && !c.ease_out && !rpm;
	for (i = 0; c.compact && i < count; i++)
		c.compact = !keys[i].ease_in && !keys[i].ease_out;
	if (rpm)
		err = rpm_rules(l, &c, v, marks);
	if (!err)
		err = ld_tangent_check(l, &c, marks, "in' or 'out",
				       sn->kind == MOT_NODE_REVOLUTE && !rpm ? 1.0 / 360 : 1.0);
	if (!err)
		err = ld_curve_check(l, &c, &cm);
	if (err)
		return err;
	if (rpm) {
		sn->spin = c;
		nm->spin = cm;
	} else {
		sn->value = c;
		nm->value = cm;
	}
	st->interp = c.interp;
	st->rpm = rpm;
	st->nkeys = c.nkeys;
	st->key_frames = frames;
	return 0;
}

static int strand(struct ld *l, yaml_node_t *map)
{
	yaml_node_t *v[S_COUNT];
	const yaml_node_t *nn;
	const char *best;
	char buf[64];
	int node, err;

	err = ld_map_req(l, map, "strand", strand_keys, v, YML_REQ(S_NODE) | YML_REQ(S_KEYS));
	if (err)
		return err;
	nn = v[S_NODE];
	if (nn->type != YAML_SCALAR_NODE)
		return ld_fail(l, nn, -EINVAL, "expected a node's name, found %s",
			       ld_describe(nn, buf, sizeof(buf)));
	node = ld_find_node(l, (const char *)nn->data.scalar.value, nn->data.scalar.length);
	if (node < 0) {
		best = l->node_names ? ld_suggest((const char *)nn->data.scalar.value,
						  l->node_names) : NULL;
		if (best)
			return ld_fail(l, nn, -EINVAL, "strand for unknown node %s (did you mean '%s'?)",
				       ld_describe(nn, buf, sizeof(buf)), best);
		return ld_fail(l, nn, -EINVAL, "strand for unknown node %s (no node has that name)",
			       ld_describe(nn, buf, sizeof(buf)));
	}
	if (l->strand[node].present)
		return ld_fail(l, nn, -EINVAL, "node '%s' already has a strand (at line %u)",
			       l->nodes[node].name, l->strand[node].at.line);
	l->strand[node].present = true;
	l->strand[node].at = ld_mark_of(map);
	l->mk->node[node].value.at = l->mk->node[node].spin.at = ld_mark_of(map);
	if (l->nodes[node].kind != MOT_NODE_FREE)
		return joint_strand(l, (uint32_t)node, v);
	{
		struct ld_free_opts fo = { v[S_INTERP], v[S_EASE], v[S_BETA], v[S_ROTATION],
					   v[S_COMPACT], v[S_KEYS] };

		return ld_free_strand(l, (uint32_t)node, &fo);
	}
}

int ld_strands(struct ld *l, yaml_node_t *seq)
{
	yaml_node_item_t *it;
	size_t count, i;
	int err = ld_seq(l, seq, "strands", &it, &count);

	for (i = 0; !err && i < count; i++)
		err = strand(l, ld_node(l, it[i]));
	return err;
}
