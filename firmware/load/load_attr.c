/* SPDX-License-Identifier: MIT */
/* load_attr.c - the `attributes:` section: named scalar channels (dye, opacity, ...). */
#include "load_priv.h"

#include <errno.h>

static int attribute(struct ld *l, yaml_node_t *map, struct sd_attr *a,
		     struct sf_curve_marks *cm)
{
	static const char *const keys[] = { "name", "interpolation", "ease", "beta", "keys",
					    NULL };
	static const char *const key_fields[] = { "frame", "ease_in", "ease_out", "value",
						  NULL };
	enum { A_NAME, A_INTERP, A_EASE, A_BETA, A_KEYS, A_COUNT };
	yaml_node_t *v[A_COUNT], *f[4];
	struct ld_curve_opts o;
	yaml_node_item_t *it;
	struct ld_mark *marks;
	struct sd_key *k;
	size_t count, i;
	int err;

	cm->at = ld_mark_of(map);
	err = ld_map_req(l, map, "attribute", keys, v, YML_REQ(A_NAME) | YML_REQ(A_KEYS));
	if (!err)
		err = ld_name(l, v[A_NAME], &a->name);
	if (err)
		return err;
	o.interp = v[A_INTERP];
	o.ease = v[A_EASE];
	o.beta = v[A_BETA];
	err = ld_curve_opts(l, &o, &a->curve, &cm->ease);
	if (!err)
		err = ld_seq(l, v[A_KEYS], "keys", &it, &count);
	if (err)
		return err;
	if (count == 0)
		return ld_fail(l, v[A_KEYS], -EINVAL, "an attribute needs at least one key");
	k = pool_array(l->pool, count, sizeof(*k));
	marks = pool_array(l->pool, count, sizeof(*marks));
	if (!k || !marks)
		return ld_nomem(l);
	for (i = 0; i < count; i++) {
		yaml_node_t *km = ld_node(l, it[i]);
		struct ld_key_common c;

		marks[i] = ld_mark_of(km);
		err = ld_map_req(l, km, "key", key_fields, f, YML_REQ(3));
		if (err)
			return err;
		c.frame = f[0];
		c.ease_in = f[1];
		c.ease_out = f[2];
		err = ld_key_common(l, km, &c, i ? &k[i - 1] : NULL, &k[i]);
		if (!err)
			err = ld_q32(l, f[3], 1.0, "", &k[i].value);
		if (err)
			return err;
	}
	a->curve.keys = k;
	a->curve.nkeys = (uint32_t)count;
	cm->key = marks;
	return ld_curve_check(l, &a->curve, cm);
}

int ld_attributes(struct ld *l, yaml_node_t *seq)
{
	struct sd_attr *attrs;
	yaml_node_item_t *it;
	size_t count, i;
	int err = ld_seq(l, seq, "attributes", &it, &count);

	if (err)
		return err;
	attrs = pool_array(l->pool, count, sizeof(*attrs));
	l->mk->attr = pool_array(l->pool, count, sizeof(*l->mk->attr));
	if (!attrs || !l->mk->attr)
		return ld_nomem(l);
	for (i = 0; i < count; i++) {
		err = attribute(l, ld_node(l, it[i]), &attrs[i], &l->mk->attr[i]);
		if (err)
			return err;
	}
	l->d->attrs = attrs;
	l->d->nattrs = (uint32_t)count;
	return 0;
}
