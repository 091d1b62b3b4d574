/* SPDX-License-Identifier: MIT */
/*
 * load_curve.c - what every keyed curve of a scene file shares: the
 * interpolation, slow-in/slow-out and Beta-spline options, each key's frame
 * and ease fractions, and the checks the core would otherwise refuse
 * without saying where (FORMULAS sections 6 and 7).
 */
#include "load_priv.h"

#include <errno.h>
#include <math.h>

#define INTERP_DEFAULT MOT_INTERP_HERMITE

static const char *const interp_names[] = { "step", "linear", "hermite", "bspline",
					    "beta", "bezier", NULL };

int ld_curve_opts(struct ld *l, const struct ld_curve_opts *o, struct sd_curve *c,
		  struct ld_mark *ease_mark)
{
	static const char *const ease_keys[] = { "in", "out", NULL };
	static const char *const beta_keys[] = { "bias", "tension", NULL };
	yaml_node_t *v[2];
	int kind = INTERP_DEFAULT, err;

	c->beta1 = 1.0;
	c->beta2 = 0.0;
	if (o->interp) {
		err = ld_enum(l, o->interp, "interpolation", interp_names, &kind);
		if (err)
			return err;
	}
	c->interp = (enum mot_interp)kind;
	if (o->ease) {
		*ease_mark = ld_mark_of(o->ease);
		err = ld_map(l, o->ease, "ease", ease_keys, v);
		if (!err && v[0])
			err = ld_q32(l, v[0], 1.0, "frames", &c->ease_in);
		if (!err && v[1])
			err = ld_q32(l, v[1], 1.0, "frames", &c->ease_out);
		if (err)
			return err;
		if (c->ease_in < 0 || c->ease_out < 0)
			return ld_fail(l, o->ease, -EINVAL, "ease in and out are frames, not below 0");
	}
	if (o->beta) {
		if (c->interp != MOT_INTERP_BETA)
			return ld_fail(l, o->beta, -EINVAL,
				       "'beta' shapes a Beta-spline, but the interpolation is '%s'",
				       interp_names[c->interp]);
		err = ld_map(l, o->beta, "beta", beta_keys, v);
		if (!err && v[0])
			err = ld_q32(l, v[0], 1.0, "", &c->beta1);
		if (!err && v[1])
			err = ld_q32(l, v[1], 1.0, "", &c->beta2);
		if (err)
			return err;
		if (!(c->beta1 > 0))
			return ld_fail(l, v[0], -EINVAL, "beta bias must be above 0");
		if (c->beta2 < 0)
			return ld_fail(l, v[1], -EINVAL, "beta tension must not be below 0");
	}
	return 0;
}

static int fraction(struct ld *l, const yaml_node_t *n, const char *name, double *out)
{
	int err = ld_q32(l, n, 1.0, "", out);

	if (err)
		return err;
	if (!(*out >= 0 && *out <= 1))
		return ld_fail(l, n, -EINVAL, "%s is a fraction of the interval: 0 to 1, found %.10g",
			       name, *out);
	return 0;
}

int ld_key_common(struct ld *l, yaml_node_t *map, const struct ld_key_common *k,
		  const struct sd_key *prev, struct sd_key *out)
{
	int err = ld_require(l, map, "key", k->frame, "frame");

	if (!err)
		err = ld_q32(l, k->frame, 1.0, "frames", &out->frame);
	if (err)
		return err;
	if (prev && !(out->frame > prev->frame))
		return ld_fail(l, k->frame, -EINVAL,
			       "key frame %.10g is not after the previous key's frame %.10g (keys must be strictly increasing)",
			       out->frame, prev->frame);
	if (k->ease_in) {
		err = fraction(l, k->ease_in, "ease_in", &out->ease_in);
		if (err)
			return err;
	}
	if (k->ease_out)
		return fraction(l, k->ease_out, "ease_out", &out->ease_out);
	return 0;
}

int ld_curve_check(struct ld *l, const struct sd_curve *c, const struct sf_curve_marks *m)
{
	uint32_t i;
	double span;

	if (c->nkeys == 0)
		return 0;
	if (c->interp == MOT_INTERP_BEZIER && c->nkeys > MOT_BEZIER_MAX_KEYS)
		return ld_fail_at(l, m->key[MOT_BEZIER_MAX_KEYS], -EINVAL,
				  "a bezier strand takes at most %d keys (it is one curve through all of them)",
				  MOT_BEZIER_MAX_KEYS);
	for (i = 1; i < c->nkeys; i++)
		if (c->keys[i - 1].ease_out + c->keys[i].ease_in > 1)
			return ld_fail_at(l, m->key[i], -EINVAL,
					  "ease_out %.10g leaving frame %.10g and ease_in %.10g arriving at frame %.10g add up to more than the interval",
					  c->keys[i - 1].ease_out, c->keys[i - 1].frame,
					  c->keys[i].ease_in, c->keys[i].frame);
	span = c->keys[c->nkeys - 1].frame - c->keys[0].frame;
	if (c->ease_in + c->ease_out > span)
		return ld_fail_at(l, m->ease.line ? m->ease : m->at, -EINVAL,
				  "ease in %.10g + out %.10g frames is longer than the keys' span of %.10g frames",
				  c->ease_in, c->ease_out, span);
	return 0;
}

int ld_tangent_check(struct ld *l, const struct sd_curve *c, const struct ld_mark *marks,
		     const char *field, double scale)
{
	const struct sd_key *k = c->keys;
	uint32_t i;

	for (i = 0; i < c->nkeys; i++) {
		double hin = i ? k[i].frame - k[i - 1].frame : 0;
		double hout = i + 1 < c->nkeys ? k[i + 1].frame - k[i].frame : 0;

		if (!k[i].tan_set)
			continue;
		if (c->interp != MOT_INTERP_HERMITE)
			return ld_fail_at(l, marks[i], -EINVAL,
					  "'%s' is a tangent, which only a hermite curve takes (this one is '%s')",
					  field, interp_names[c->interp]);
		if (((k[i].tan_set & MOT_TANGENT_IN) && fabs(hin * k[i].tan_in * scale) >= 0x1p31) ||
		    ((k[i].tan_set & MOT_TANGENT_OUT) && fabs(hout * k[i].tan_out * scale) >= 0x1p31))
			return ld_fail_at(l, marks[i], -ERANGE,
					  "a tangent of this key times its interval reaches beyond the core's range (below 2^31 %s)",
					  scale == 1 ? "units" : "turns");
	}
	return 0;
}
