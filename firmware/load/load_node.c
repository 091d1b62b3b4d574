/* SPDX-License-Identifier: MIT */
/*
 * load_node.c - the `nodes:` section: names, the hierarchy, pivots, joints
 * and their limits (FORMULAS section 3).
 */
#define _GNU_SOURCE /* qsort_r */
#include "load_priv.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { N_NAME, N_PARENT, N_PIVOT, N_JOINT, N_REST, N_LIMITS, N_MIMIC, N_COUNT };
static const char *const node_keys[] = { "name", "parent", "pivot", "joint", "rest", "limits",
					 "mimic", NULL };

static int by_name_cmp(const void *a, const void *b, void *names)
{
	const char *const *nm = names;

	return strcmp(nm[*(const uint32_t *)a], nm[*(const uint32_t *)b]);
}

int ld_find_node(const struct ld *l, const char *name, size_t len)
{
	size_t lo = 0, hi = l->d->nnodes;

	if (!l->by_name || memchr(name, '\0', len))
		return -1;
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		const char *s = l->node_names[l->by_name[mid]];
		int c = strncmp(s, name, len);

		if (c == 0 && s[len] != '\0')
			c = 1;
		if (c == 0)
			return (int)l->by_name[mid];
		if (c < 0)
			lo = mid + 1;
		else
			hi = mid;
	}
	return -1;
}

static int joint(struct ld *l, uint32_t i, yaml_node_t *n)
{
	static const char *const keys[] = { "type", "axis", NULL };
	static const char *const types[] = { "revolute", "prismatic", NULL };
	static const char *const axes[] = { "x", "y", "z", NULL };
	struct sd_node *sn = &l->nodes[i];
	yaml_node_t *v[2];
	int type, axis, err;

	err = ld_map_req(l, n, "joint", keys, v, YML_REQ(0) | YML_REQ(1));
	if (!err)
		err = ld_enum(l, v[0], "joint type", types, &type);
	if (err)
		return err;
	sn->kind = type == 0 ? MOT_NODE_REVOLUTE : MOT_NODE_PRISMATIC;
	l->mk->node[i].axis = ld_mark_of(v[1]);
	if (v[1]->type == YAML_SEQUENCE_NODE) {
		err = ld_vec(l, v[1], 3, 1.0, "", sn->axis);
		if (err)
			return err;
		if (!(sqrt(sn->axis[0] * sn->axis[0] + sn->axis[1] * sn->axis[1] +
			   sn->axis[2] * sn->axis[2]) > 1e-9))
			return ld_fail(l, v[1], -EINVAL, "the joint axis must not be zero");
		sn->axis_id = MOT_AXIS_VEC;
		return 0;
	}
	err = ld_enum(l, v[1], "axis (x, y, z or [ax, ay, az])", axes, &axis);
	if (err)
		return err;
	sn->axis_id = (enum mot_axis)axis;
	sn->axis[axis] = 1.0;
	return 0;
}

int ld_limits(struct ld *l, yaml_node_t *n, bool degrees, struct sd_limits *lim)
{
	static const char *const keys[] = { "min", "max", "velocity", "acceleration", NULL };
	double scale = degrees ? 1.0 / 360 : 1.0;
	const char *unit = degrees ? "degrees" : "scene units";
	yaml_node_t *v[4];
	int err;

	err = ld_map(l, n, "limits", keys, v);
	if (!err && v[0]) {
		err = ld_q32(l, v[0], scale, unit, &lim->min);
		lim->has_min = true;
	}
	if (!err && v[1]) {
		err = ld_q32(l, v[1], scale, unit, &lim->max);
		lim->has_max = true;
	}
	if (!err && v[2]) {
		err = ld_q32(l, v[2], scale, unit, &lim->vel);
		lim->has_vel = true;
		if (!err && !(lim->vel > 0))
			err = ld_fail(l, v[2], -EINVAL, "velocity limit must be above zero");
		else if (!err && lim->vel < RIG_LIMIT_RATE_MIN)
			err = ld_fail(l, v[2], -ERANGE,
				      "velocity limit %.6g is below %g %s a second (too slow to "
				      "plan a move with)", lim->vel, RIG_LIMIT_RATE_MIN, unit);
	}
	if (!err && v[3]) {
		err = ld_q32(l, v[3], scale, unit, &lim->acc);
		lim->has_acc = true;
		if (!err && !(lim->acc > 0))
			err = ld_fail(l, v[3], -EINVAL, "acceleration limit must be above zero");
		else if (!err && lim->acc < RIG_LIMIT_RATE_MIN)
			err = ld_fail(l, v[3], -ERANGE,
				      "acceleration limit %.6g is below %g %s a second squared "
				      "(too slow to plan a move with)", lim->acc,
				      RIG_LIMIT_RATE_MIN, unit);
	}
	if (!err && lim->has_min && lim->has_max && lim->min > lim->max)
		err = ld_fail(l, v[1], -EINVAL, "limit max %.10g is below min %.10g", lim->max,
			      lim->min);
	return err;
}

/* Why parent p (at or after node i) is wrong: a cycle back to i, or simply
 * listed too late. */
static int bad_parent(struct ld *l, uint32_t i, uint32_t p, const yaml_node_t *at,
		      const int32_t *parent_of)
{
	char path[200];
	size_t o;
	uint32_t step, j = p;

	if (p == i)
		return ld_fail(l, at, -EINVAL, "node '%s' is its own parent", l->nodes[i].name);
	for (step = 0; step < l->d->nnodes && parent_of[j] >= 0; step++) {
		j = (uint32_t)parent_of[j];
		if (j == i)
			break;
	}
	if (j != i)
		return ld_fail(l, at, -EINVAL,
			       "parent '%s' is defined after '%s' (list parents before their children)",
			       l->nodes[p].name, l->nodes[i].name);
	/* spell the cycle out: i -> p -> ... -> i */
	o = (size_t)snprintf(path, sizeof(path), "%s -> %s", l->nodes[i].name, l->nodes[p].name);
	for (j = p; parent_of[j] >= 0 && (uint32_t)parent_of[j] != i && o < sizeof(path);)
		j = (uint32_t)parent_of[j],
		o += (size_t)snprintf(path + o, sizeof(path) - o, " -> %s", l->nodes[j].name);
	if (o < sizeof(path))
		snprintf(path + o, sizeof(path) - o, " -> %s", l->nodes[i].name);
	return ld_fail(l, at, -EINVAL, "cycle in the hierarchy: %s", path);
}

/* Resolve every parent name (they may name any node, so the cycle message
 * can be exact), then demand parents before children. */
static int parents(struct ld *l, yaml_node_t **parent_node)
{
	uint32_t n = l->d->nnodes, i;
	int32_t *parent_of = pool_array(l->pool, n ? n : 1, sizeof(*parent_of));
	char buf[64];

	if (!parent_of)
		return ld_nomem(l);
	for (i = 0; i < n; i++) {
		const yaml_node_t *pn = parent_node[i];
		const char *best;
		int p;

		parent_of[i] = -1;
		if (!pn)
			continue;
		if (pn->type != YAML_SCALAR_NODE)
			return ld_fail(l, pn, -EINVAL, "expected a parent node's name, found %s",
				       ld_describe(pn, buf, sizeof(buf)));
		p = ld_find_node(l, (const char *)pn->data.scalar.value, pn->data.scalar.length);
		if (p >= 0) {
			parent_of[i] = p;
			continue;
		}
		best = ld_suggest((const char *)pn->data.scalar.value, l->node_names);
		if (best)
			return ld_fail(l, pn, -EINVAL, "unknown parent %s (did you mean '%s'?)",
				       ld_describe(pn, buf, sizeof(buf)), best);
		return ld_fail(l, pn, -EINVAL, "unknown parent %s (no node has that name)",
			       ld_describe(pn, buf, sizeof(buf)));
	}
	for (i = 0; i < n; i++) {
		if (parent_of[i] >= (int32_t)i)
			return bad_parent(l, i, (uint32_t)parent_of[i], parent_node[i], parent_of);
		l->nodes[i].parent = parent_of[i];
	}
	return 0;
}

/* `mimic: {joint: NAME, multiplier: M, offset: O}` on joint i. */
static int mimic(struct ld *l, uint32_t i, yaml_node_t *n, const yaml_node_t *rest)
{
	static const char *const keys[] = { "joint", "multiplier", "offset", NULL };
	struct ld_mimic *mm = &l->mimic[i];
	const struct sd_node *sn = &l->nodes[i];
	yaml_node_t *v[3];
	char buf[64];
	int err, m;

	err = ld_map_req(l, n, "mimic", keys, v, YML_REQ(0));
	if (err)
		return err;
	if (sn->kind == MOT_NODE_FREE)
		return ld_fail(l, n, -EINVAL, "'mimic' makes a joint follow another, but '%s' is a free node",
			       sn->name);
	if (rest)
		return ld_fail(l, rest, -EINVAL,
			       "'%s' mimics a joint: its rest is the master's, mapped (give 'offset' instead)",
			       sn->name);
	m = -1;
	if (v[0]->type == YAML_SCALAR_NODE)
		m = ld_find_node(l, (const char *)v[0]->data.scalar.value,
				 v[0]->data.scalar.length);
	if (m < 0)
		return ld_fail(l, v[0], -EINVAL, "mimic of unknown joint %s",
			       ld_describe(v[0], buf, sizeof(buf)));
	if ((uint32_t)m == i)
		return ld_fail(l, v[0], -EINVAL, "'%s' cannot mimic itself", sn->name);
	mm->master = m;
	mm->at = n;
	mm->mult = 1;
	mm->offset = 0;
	if (v[1])
		err = ld_num(l, v[1], &mm->mult);
	if (!err && v[2])
		err = ld_q32(l, v[2], sn->kind == MOT_NODE_REVOLUTE ? 1.0 / 360 : 1.0,
			     sn->kind == MOT_NODE_REVOLUTE ? "degrees" : "scene units", &mm->offset);
	return err;
}

static int node_body(struct ld *l, uint32_t i, yaml_node_t **v)
{
	struct sd_node *sn = &l->nodes[i];
	int err = 0;

	if (v[N_PIVOT]) {
		l->mk->node[i].pivot = ld_mark_of(v[N_PIVOT]);
		err = ld_vec(l, v[N_PIVOT], 3, 1.0, "scene units", sn->pivot);
	}
	if (!err && v[N_JOINT])
		err = joint(l, i, v[N_JOINT]);
	if (err)
		return err;
	if (v[N_REST]) {
		l->mk->node[i].rest = ld_mark_of(v[N_REST]);
		if (sn->kind == MOT_NODE_FREE)
			return ld_fail(l, v[N_REST], -EINVAL,
				       "'rest' is a joint's value, but '%s' is a free node (it has no joint)",
				       sn->name);
		err = ld_q32(l, v[N_REST], sn->kind == MOT_NODE_REVOLUTE ? 1.0 / 360 : 1.0,
			     sn->kind == MOT_NODE_REVOLUTE ? "degrees" : "scene units", &sn->rest);
	}
	if (!err && v[N_MIMIC])
		err = mimic(l, i, v[N_MIMIC], v[N_REST]);
	if (!err && v[N_LIMITS]) {
		if (sn->kind == MOT_NODE_FREE)
			return ld_fail(l, v[N_LIMITS], -EINVAL,
				       "limits apply to joints, but '%s' is a free node (it has no joint)",
				       sn->name);
		err = ld_limits(l, v[N_LIMITS], l->nodes[i].kind == MOT_NODE_REVOLUTE,
				&l->nodes[i].limits);
	}
	return err;
}

int ld_nodes(struct ld *l, yaml_node_t *seq)
{
	yaml_node_item_t *it;
	yaml_node_t **parent_node, *(*v)[N_COUNT];
	size_t count, i;
	int err;

	l->mk->nodes = ld_mark_of(seq);
	err = ld_seq(l, seq, "nodes", &it, &count);
	if (err)
		return err;
	if (count > INT32_MAX / 2)
		return ld_fail(l, seq, -ERANGE, "too many nodes");
	l->nodes = pool_array(l->pool, count, sizeof(*l->nodes));
	l->mk->node = pool_array(l->pool, count, sizeof(*l->mk->node));
	l->node_names = pool_array(l->pool, count + 1, sizeof(*l->node_names));
	l->by_name = pool_array(l->pool, count, sizeof(*l->by_name));
	l->mimic = pool_array(l->pool, count ? count : 1, sizeof(*l->mimic));
	parent_node = pool_array(l->pool, count, sizeof(*parent_node));
	v = pool_array(l->pool, count, sizeof(*v));
	if (!l->nodes || !l->mk->node || !l->node_names || !l->by_name || !parent_node || !v ||
	    !l->mimic)
		return ld_nomem(l);
	for (i = 0; i < count; i++)
		l->mimic[i].master = -1;
	l->d->nodes = l->nodes;
	/* first every name, so that parents and strands can refer to any node */
	for (i = 0; i < count; i++) {
		yaml_node_t *n = ld_node(l, it[i]);

		err = ld_map(l, n, "node", node_keys, v[i]);
		if (!err)
			err = ld_require(l, n, "node", v[i][N_NAME], "name");
		if (!err)
			err = ld_name(l, v[i][N_NAME], &l->nodes[i].name);
		if (err)
			return err;
		l->mk->node[i].at = ld_mark_of(n);
		l->node_names[i] = l->nodes[i].name;
		l->nodes[i].kind = MOT_NODE_FREE;
		l->nodes[i].parent = -1;
		parent_node[i] = v[i][N_PARENT];
		l->by_name[i] = (uint32_t)i;
	}
	l->d->nnodes = (uint32_t)count;
	qsort_r(l->by_name, count, sizeof(*l->by_name), by_name_cmp, l->node_names);
	for (i = 1; i < count; i++) {
		uint32_t a = l->by_name[i - 1], b = l->by_name[i];

		if (!strcmp(l->node_names[a], l->node_names[b])) {
			uint32_t first = a < b ? a : b, second = a < b ? b : a;

			return ld_fail(l, v[second][N_NAME], -EINVAL,
				       "duplicate node name '%s' (first at line %u)",
				       l->node_names[second], l->mk->node[first].at.line);
		}
	}
	err = parents(l, parent_node);
	for (i = 0; !err && i < count; i++)
		err = node_body(l, (uint32_t)i, v[i]);
	return err;
}

/*
 * A mimic's curve is its master's with every value mapped, v' = m v + o, and
 * every tangent, m t: each interpolation is linear in the values and the
 * ease only warps time, so the mapped curve is exactly m x the master's
 * curve + o at every frame. Without a master strand the mimic holds m x the
 * master's rest + o.
 */
int ld_mimics(struct ld *l)
{
	uint32_t i, k;

	for (i = 0; l->mimic && i < l->d->nnodes; i++) {
		const struct ld_mimic *mm = &l->mimic[i];
		struct sd_node *sn = &l->nodes[i];
		const struct sd_node *ms;
		struct sd_key *keys;

		if (mm->master < 0)
			continue;
		ms = &l->nodes[mm->master];
		if (ms->kind == MOT_NODE_FREE || l->mimic[mm->master].master >= 0)
			return ld_fail(l, mm->at, -EINVAL,
				       "'%s' mimics '%s', which is not a joint of its own (a free node or a mimic)",
				       sn->name, ms->name);
		if (l->strand[i].present)
			return ld_fail_at(l, l->strand[i].at, -EINVAL,
					  "'%s' mimics '%s': its motion is the master's, it takes no strand",
					  sn->name, ms->name);
		if (ms->spin.nkeys)
			return ld_fail(l, mm->at, -EINVAL,
				       "'%s' mimics '%s', whose strand keys rpm: a mimic follows an angle or a position",
				       sn->name, ms->name);
		sn->rest = mm->mult * ms->rest + mm->offset;
		if (!ms->value.nkeys)
			continue;
		keys = pool_array(l->pool, ms->value.nkeys, sizeof(*keys));
		if (!keys)
			return ld_nomem(l);
		for (k = 0; k < ms->value.nkeys; k++) {
			keys[k] = ms->value.keys[k];
			keys[k].value = mm->mult * keys[k].value + mm->offset;
			keys[k].tan_in *= mm->mult;
			keys[k].tan_out *= mm->mult;
		}
		sn->value = ms->value;
		sn->value.keys = keys;
		l->mk->node[i].value = l->mk->node[mm->master].value;
		l->strand[i] = l->strand[mm->master];
	}
	return 0;
}
