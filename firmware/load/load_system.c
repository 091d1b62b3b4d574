/* SPDX-License-Identifier: MIT */
/*
 * load_system.c - the `surfaces:`, `particles:`, `flocks:` and `aims:`
 * sections (README "Systems" has the schema; motion/system.h the
 * mathematics). Every number is held to its range here, at its place in
 * the file; what only the core can judge (a step too long for a lattice's
 * springs, a target too fast for an aim's grid) comes back from the build
 * at the system's mapping (load_build.c).
 */
#include "load_priv.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Most items a system has, and lattice points: far above any rig, and
 * what the channel list (a name each) can hold comfortably. */
#define SYS_ITEMS_MAX 65536u
#define STEP_HZ_DEFAULT 100

/* ---- shared pieces ---------------------------------------------------------------- */

/* step_hz: a whole number of steps a second, or `frame` (one a frame). */
static int step_rate(struct ld *l, yaml_node_t *n, uint32_t *num, uint32_t *den)
{
	long long v;

	*num = STEP_HZ_DEFAULT;
	*den = 1;
	if (!n)
		return 0;
	if (n->type == YAML_SCALAR_NODE && !strcmp((const char *)n->data.scalar.value, "frame")) {
		*num = l->d->rate_num;
		*den = l->d->rate_den;
		if ((uint64_t)*num > (uint64_t)MOT_STEP_HZ_MAX * *den)
			return ld_fail(l, n, -ERANGE, "one step a frame is above %u steps a second",
				       MOT_STEP_HZ_MAX);
		return 0;
	}
	if (ld_int(l, n, 1, MOT_STEP_HZ_MAX, &v))
		return -EINVAL;
	*num = (uint32_t)v;
	return 0;
}

/* limits: {x: {min, max, velocity, acceleration}, ...} by channel suffix */
static int sys_limits(struct ld *l, yaml_node_t *n, const struct sd_system *s,
		      struct sd_limits *lim)
{
	const char *names[SD_SYS_CHANNELS + 1];
	yaml_node_t *v[SD_SYS_CHANNELS];
	uint32_t k, per = sd_sys_per(s);
	int err;

	for (k = 0; k < per; k++)
		names[k] = sd_sys_suffix(s, k);
	names[per] = NULL;
	err = ld_map(l, n, "limits (by channel: x, y, ...)", names, v);
	for (k = 0; !err && k < per; k++)
		if (v[k])
			err = ld_limits(l, v[k], sd_sys_angle(s, k), &lim[k]);
	return err;
}

static int count(struct ld *l, yaml_node_t *n, long long min, long long max, uint32_t *out)
{
	long long v;
	int err = ld_int(l, n, min, max, &v);

	*out = (uint32_t)v;
	return err;
}

/* A pair of whole numbers [a, b], each 1 to max. */
static int pair(struct ld *l, yaml_node_t *n, long long max, uint32_t out[2])
{
	yaml_node_item_t *it;
	size_t c;
	int err = ld_seq(l, n, "a pair of counts", &it, &c);

	if (!err && c != 2)
		err = ld_fail(l, n, -EINVAL, "expected two whole numbers [rows, columns], found %zu",
			      c);
	if (!err)
		err = count(l, ld_node(l, it[0]), 1, max, &out[0]);
	if (!err)
		err = count(l, ld_node(l, it[1]), 1, max, &out[1]);
	return err;
}

static int nonneg(struct ld *l, yaml_node_t *n, const char *what, double *out)
{
	int err = ld_q32(l, n, 1.0, "", out);

	if (!err && *out < 0)
		err = ld_fail(l, n, -EINVAL, "%s must not be below 0", what);
	return err;
}

static int above0(struct ld *l, yaml_node_t *n, const char *what, double *out)
{
	int err = ld_q32(l, n, 1.0, "", out);

	if (!err && !(*out > 0))
		err = ld_fail(l, n, -EINVAL, "%s must be above 0", what);
	return err;
}

/*
 * Keyed fields: a mapping {interpolation, ease, beta, keys: [...]} whose
 * keys each give a frame (or `age`, a fraction of a life) and any of the
 * fields; each number of a field becomes a curve over the keys that set
 * it (as a free node's channels, load_free.c). A field has `width` numbers:
 * 1 (a number), 2 ([low, high]), 3 ([x, y, z]) or 6 ([[x, y, z], [x, y, z]]:
 * a low and a high vector).
 */
struct kfield {
	const char *name;
	uint32_t width;
	struct sd_curve *out[6]; /* the curve of each number */
};

static int field_numbers(struct ld *l, yaml_node_t *n, uint32_t width, double *v)
{
	yaml_node_item_t *it;
	size_t c;
	int err;

	if (width == 1)
		return ld_q32(l, n, 1.0, "", v);
	if (width == 2 || width == 3)
		return ld_vec(l, n, width, 1.0, "scene units", v);
	err = ld_seq(l, n, "a range", &it, &c);
	if (!err && c != 2)
		err = ld_fail(l, n, -EINVAL, "expected a range [[low x, y, z], [high x, y, z]]");
	if (!err)
		err = ld_vec(l, ld_node(l, it[0]), 3, 1.0, "scene units", v);
	if (!err)
		err = ld_vec(l, ld_node(l, it[1]), 3, 1.0, "scene units", v + 3);
	return err;
}

/* The keys of map (its interpolation, ease and beta in o, its keys:). */
static int keyed_nodes(struct ld *l, yaml_node_t *map, const struct ld_curve_opts *o,
		       yaml_node_t *keys_node, const char *what, const char *frame_key,
		       struct kfield *f, uint32_t nf)
{
	const char *names[16];
	yaml_node_t *kv[16];
	yaml_node_item_t *it;
	struct sd_curve tmpl = { 0 };
	struct ld_mark ease = { 0, 0 };
	struct sd_key *prev = NULL, cur, prevk;
	struct sd_key **keys;
	struct ld_mark **marks;
	size_t n, i;
	uint32_t j, c, total = 0;
	int err;

	err = ld_require(l, map, what, keys_node, "keys");
	if (!err)
		err = ld_curve_opts(l, o, &tmpl, &ease);
	if (!err)
		err = ld_seq(l, keys_node, "keys", &it, &n);
	if (err)
		return err;
	if (!n)
		return ld_fail(l, keys_node, -EINVAL, "%s needs at least one key", what);
	names[0] = frame_key;
	names[1] = "ease_in";
	names[2] = "ease_out";
	for (j = 0; j < nf; j++) {
		names[3 + j] = f[j].name;
		total += f[j].width;
	}
	names[3 + nf] = NULL;
	keys = pool_array(l->pool, total, sizeof(*keys));
	marks = pool_array(l->pool, total, sizeof(*marks));
	if (!keys || !marks)
		return ld_nomem(l);
	for (c = 0; c < total; c++) {
		keys[c] = pool_array(l->pool, n, sizeof(**keys));
		marks[c] = pool_array(l->pool, n, sizeof(**marks));
		if (!keys[c] || !marks[c])
			return ld_nomem(l);
	}
	for (j = 0, c = 0; j < nf; c += f[j].width, j++)
		for (i = 0; i < f[j].width; i++) {
			*f[j].out[i] = tmpl;
			f[j].out[i]->keys = keys[c + i];
			f[j].out[i]->nkeys = 0;
		}
	for (i = 0; i < n; i++) {
		yaml_node_t *km = ld_node(l, it[i]);
		struct ld_key_common kc;
		bool any = false;

		memset(&cur, 0, sizeof(cur));
		err = ld_map(l, km, "key", names, kv);
		if (err)
			return err;
		kc.frame = kv[0];
		kc.ease_in = kv[1];
		kc.ease_out = kv[2];
		err = ld_key_common(l, km, &kc, prev, &cur);
		if (!err && !strcmp(frame_key, "age") && (cur.frame < 0 || cur.frame > 1))
			err = ld_fail(l, kv[0], -EINVAL, "age is a fraction of a life: 0 to 1");
		if (err)
			return err;
		for (j = 0, c = 0; j < nf; c += f[j].width, j++) {
			double val[6];
			uint32_t w;

			if (!kv[3 + j])
				continue;
			any = true;
			err = field_numbers(l, kv[3 + j], f[j].width, val);
			if (err)
				return err;
			for (w = 0; w < f[j].width; w++) {
				struct sd_curve *sc = f[j].out[w];
				struct sd_key *k = &keys[c + w][sc->nkeys];


				*k = cur;
				k->value = val[w];
				marks[c + w][sc->nkeys] = ld_mark_of(km);
				sc->nkeys++;
			}
		}
		if (!any)
			return ld_fail(l, km, -EINVAL, "key sets nothing");
		prevk = cur;
		prev = &prevk;
	}
	for (c = 0; c < total; c++) {
		struct sf_curve_marks cm = { ld_mark_of(map), ease, marks[c] };
		struct sd_curve *sc = NULL;

		for (j = 0, i = 0; j < nf && !sc; i += f[j].width, j++)
			if (c < i + f[j].width)
				sc = f[j].out[c - i];
		err = ld_curve_check(l, sc, &cm);
		if (err)
			return err;
	}
	return 0;
}

/* A mapping of its own: {interpolation, ease, beta, keys}. */
static int keyed(struct ld *l, yaml_node_t *map, const char *what, const char *frame_key,
		 struct kfield *f, uint32_t nf)
{
	static const char *const top[] = { "interpolation", "ease", "beta", "keys", NULL };
	yaml_node_t *v[4];
	struct ld_curve_opts o;
	int err = ld_map(l, map, what, top, v);

	if (err)
		return err;
	o.interp = v[0];
	o.ease = v[1];
	o.beta = v[2];
	return keyed_nodes(l, map, &o, v[3], what, frame_key, f, nf);
}

/* ---- surfaces ----------------------------------------------------------------------- */

/* heights: rows x columns numbers, or points: rows x columns [x, y, z] */
static int grid(struct ld *l, yaml_node_t *n, uint32_t rows, uint32_t cols, bool points,
		double *out)
{
	yaml_node_item_t *r, *c;
	size_t nr, nc, i, j;
	int err = ld_seq(l, n, points ? "points" : "heights", &r, &nr);

	if (!err && nr != rows)
		err = ld_fail(l, n, -EINVAL, "expected %u rows (control: [%u, %u]), found %zu", rows,
			      rows, cols, nr);
	for (i = 0; !err && i < rows; i++) {
		yaml_node_t *row = ld_node(l, r[i]);

		err = ld_seq(l, row, "a row", &c, &nc);
		if (!err && nc != cols)
			err = ld_fail(l, row, -EINVAL, "expected %u %s in the row, found %zu", cols,
				      points ? "points" : "heights", nc);
		for (j = 0; !err && j < cols; j++) {
			yaml_node_t *e = ld_node(l, c[j]);

			if (points)
				err = ld_vec(l, e, 3, 1.0, "scene units", out + (i * cols + j) * 3);
			else
				err = ld_q32(l, e, 1.0, "scene units", out + (i * cols + j));
		}
	}
	return err;
}

static int surface_keys(struct ld *l, yaml_node_t *map, const struct ld_curve_opts *o,
			yaml_node_t *keys_node, struct sd_surface *s, struct sd_curve *curve,
			bool *moved)
{
	static const char *const fields[] = { "frame", "ease_in", "ease_out", "heights",
					      "points", NULL };
	uint32_t n3 = s->ncu * s->ncv * 3, c;
	yaml_node_t *kv[5];
	yaml_node_item_t *it;
	struct sd_curve tmpl = { 0 };
	struct ld_mark ease = { 0, 0 }, *marks;
	struct sd_key *keys, prev;
	double *val;
	size_t n, i;
	int err;

	err = ld_curve_opts(l, o, &tmpl, &ease);
	if (!err)
		err = ld_seq(l, keys_node, "keys", &it, &n);
	if (err)
		return err;
	if (!n)
		return ld_fail(l, keys_node, -EINVAL, "a surface needs at least one key");
	keys = pool_array(l->pool, (size_t)n3 * n, sizeof(*keys));
	marks = pool_array(l->pool, n, sizeof(*marks));
	val = pool_array(l->pool, n3, sizeof(*val));
	if (!keys || !marks || !val)
		return ld_nomem(l);
	for (c = 0; c < n3; c++) {
		curve[c] = tmpl;
		curve[c].keys = keys + (size_t)c * n;
		moved[c] = false;
	}
	for (i = 0; i < n; i++) {
		yaml_node_t *km = ld_node(l, it[i]);
		struct ld_key_common kc;
		struct sd_key cur;

		memset(&cur, 0, sizeof(cur));
		marks[i] = ld_mark_of(km);
		err = ld_map(l, km, "surface key", fields, kv);
		if (err)
			return err;
		kc.frame = kv[0];
		kc.ease_in = kv[1];
		kc.ease_out = kv[2];
		err = ld_key_common(l, km, &kc, i ? &prev : NULL, &cur);
		if (err)
			return err;
		if (!kv[3] == !kv[4])
			return ld_fail(l, km, -EINVAL,
				       "a surface key gives heights (y above the rest net) or points "
				       "(every control point), one of them");
		if (kv[3]) {
			err = grid(l, kv[3], s->ncu, s->ncv, false, val);
			for (c = 0; !err && c < s->ncu * s->ncv; c++) {
				double y = s->rest[c * 3 + 1] + val[c];
				mot_q32 q;

				if (!sd_to_q32(y, &q))
					err = ld_fail(l, kv[3], -ERANGE, "height %.10g puts a control "
						      "point outside the core's range", val[c]);
				val[c] = y;
			}
			/* heights move y only: x and z stay on the rest net */
			for (c = s->ncu * s->ncv; !err && c-- > 0;) {
				val[c * 3 + 1] = val[c];
				val[c * 3] = s->rest[c * 3];
				val[c * 3 + 2] = s->rest[c * 3 + 2];
			}
		} else {
			err = grid(l, kv[4], s->ncu, s->ncv, true, val);
		}
		if (err)
			return err;
		for (c = 0; c < n3; c++) {
			if (kv[4] || c % 3 == 1)
				moved[c] = true;
			keys[(size_t)c * n + i] = cur;
			keys[(size_t)c * n + i].value = val[c];
		}
		prev = cur;
	}
	for (c = 0; c < n3; c++) {
		struct sf_curve_marks cm = { ld_mark_of(map), ease, marks };

		curve[c].nkeys = moved[c] ? (uint32_t)n : 0;
		err = ld_curve_check(l, &curve[c], &cm);
		if (err)
			return err;
	}
	return 0;
}

static int surface(struct ld *l, yaml_node_t *map, struct sd_surface *s, struct sd_system *sys)
{
	static const char *const keys[] = { "name", "basis", "control", "origin", "size",
					    "samples", "interpolation", "ease", "beta", "keys",
					    "limits", NULL };
	static const char *const bases[] = { "bezier", "bspline", NULL };
	enum { S_NAME, S_BASIS, S_CTL, S_ORIGIN, S_SIZE, S_SAMPLES, S_INTERP, S_EASE, S_BETA,
	       S_KEYS, S_LIMITS, S_N };
	yaml_node_t *v[S_N];
	uint32_t ctl[2], smp[2], a, b;
	double origin[3] = { 0, 0, 0 }, size[2] = { 1, 1 };
	double *rest;
	struct sd_curve *curve;
	bool *moved;
	int basis = MOT_SURFACE_BSPLINE, err;

	err = ld_map_req(l, map, "surface", keys, v,
			 YML_REQ(S_NAME) | YML_REQ(S_CTL) | YML_REQ(S_SAMPLES) | YML_REQ(S_KEYS));
	if (!err)
		err = ld_name(l, v[S_NAME], &s->name);
	if (!err && v[S_BASIS])
		err = ld_enum(l, v[S_BASIS], "basis", bases, &basis);
	if (!err)
		err = pair(l, v[S_CTL], MOT_SURFACE_MAX_CTL, ctl);
	if (!err)
		err = pair(l, v[S_SAMPLES], MOT_SURFACE_MAX_SAMPLES, smp);
	if (!err && v[S_ORIGIN])
		err = ld_vec(l, v[S_ORIGIN], 3, 1.0, "scene units", origin);
	if (!err && v[S_SIZE])
		err = ld_vec(l, v[S_SIZE], 2, 1.0, "scene units", size);
	if (err)
		return err;
	if (basis == MOT_SURFACE_BEZIER &&
	    (ctl[0] < 4 || (ctl[0] - 1) % 3 || ctl[1] < 4 || (ctl[1] - 1) % 3))
		return ld_fail(l, v[S_CTL], -EINVAL,
			       "a net of Bezier patches has 3p + 1 points a side (4, 7, 10, ...), "
			       "found [%u, %u]", ctl[0], ctl[1]);
	if ((uint64_t)smp[0] * smp[1] > SYS_ITEMS_MAX)
		return ld_fail(l, v[S_SAMPLES], -EINVAL, "%u x %u samples: at most %u", smp[0],
			       smp[1], SYS_ITEMS_MAX);
	s->basis = (enum mot_surface_basis)basis;
	s->ncu = ctl[0];
	s->ncv = ctl[1];
	s->nsu = smp[0];
	s->nsv = smp[1];
	rest = pool_array(l->pool, (size_t)ctl[0] * ctl[1] * 3, sizeof(*rest));
	curve = pool_array(l->pool, (size_t)ctl[0] * ctl[1] * 3, sizeof(*curve));
	moved = pool_array(l->pool, (size_t)ctl[0] * ctl[1] * 3, sizeof(*moved));
	if (!rest || !curve || !moved)
		return ld_nomem(l);
	/* the rest net: rows along z, columns along x, in the y = origin plane */
	for (a = 0; a < ctl[0]; a++)
		for (b = 0; b < ctl[1]; b++) {
			double *r = rest + ((size_t)a * ctl[1] + b) * 3;

			r[0] = origin[0] + (ctl[1] > 1 ? size[0] * b / (ctl[1] - 1) : 0);
			r[1] = origin[1];
			r[2] = origin[2] + (ctl[0] > 1 ? size[1] * a / (ctl[0] - 1) : 0);
		}
	s->rest = rest;
	s->curve = curve;
	{
		struct ld_curve_opts o = { v[S_INTERP], v[S_EASE], v[S_BETA] };

		err = surface_keys(l, map, &o, v[S_KEYS], s, curve, moved);
	}
	sys->kind = SD_SURFACE;
	sys->surface = s;
	if (!err && v[S_LIMITS])
		err = sys_limits(l, v[S_LIMITS], sys, s->lim);
	return err;
}

/* ---- particles -------------------------------------------------------------------------- */

static int emission(struct ld *l, yaml_node_t *n, struct sd_particles *p)
{
	struct kfield f[] = {
		{ "rate", 1, { &p->c[MOT_PC_RATE] } },
		{ "spread", 1, { &p->c[MOT_PC_SPREAD] } },
		{ "position", 6, { &p->c[MOT_PC_POS_LO], &p->c[MOT_PC_POS_LO_Y],
				   &p->c[MOT_PC_POS_LO_Z], &p->c[MOT_PC_POS_HI],
				   &p->c[MOT_PC_POS_HI_Y], &p->c[MOT_PC_POS_HI_Z] } },
		{ "velocity", 6, { &p->c[MOT_PC_VEL_LO], &p->c[MOT_PC_VEL_LO_Y],
				   &p->c[MOT_PC_VEL_LO_Z], &p->c[MOT_PC_VEL_HI],
				   &p->c[MOT_PC_VEL_HI_Y], &p->c[MOT_PC_VEL_HI_Z] } },
		{ "lifetime", 2, { &p->c[MOT_PC_LIFE_LO], &p->c[MOT_PC_LIFE_HI] } },
		{ "size", 2, { &p->c[MOT_PC_SIZE_LO], &p->c[MOT_PC_SIZE_HI] } },
		{ "colour", 6, { &p->c[MOT_PC_COL_LO], &p->c[MOT_PC_COL_LO_G], &p->c[MOT_PC_COL_LO_B],
				 &p->c[MOT_PC_COL_HI], &p->c[MOT_PC_COL_HI_G],
				 &p->c[MOT_PC_COL_HI_B] } },
		{ "alpha", 2, { &p->c[MOT_PC_ALPHA_LO], &p->c[MOT_PC_ALPHA_HI] } },
	};
	uint32_t k;
	int err = keyed(l, n, "emit", "frame", f, sizeof(f) / sizeof(f[0]));

	/* a lifetime is drawn between its bounds: neither may fall to zero */
	for (k = MOT_PC_LIFE_LO; !err && k <= MOT_PC_LIFE_HI; k++) {
		uint32_t i;

		for (i = 0; i < p->c[k].nkeys; i++)
			if (!(p->c[k].keys[i].value > 0))
				return ld_fail(l, n, -EINVAL,
					       "lifetime %.10g at frame %.10g: a lifetime is above "
					       "0 seconds", p->c[k].keys[i].value,
					       p->c[k].keys[i].frame);
	}
	return err;
}

static int over_life(struct ld *l, yaml_node_t *n, struct sd_particles *p)
{
	struct kfield f[] = {
		{ "colour", 3, { &p->c[MOT_PC_AGE_R], &p->c[MOT_PC_AGE_G], &p->c[MOT_PC_AGE_B] } },
		{ "alpha", 1, { &p->c[MOT_PC_AGE_ALPHA] } },
		{ "size", 1, { &p->c[MOT_PC_AGE_SIZE] } },
	};

	return keyed(l, n, "over_life", "age", f, sizeof(f) / sizeof(f[0]));
}

static int lattice(struct ld *l, yaml_node_t *n, struct sd_particles *p)
{
	static const char *const keys[] = { "size", "spacing", "origin", "shear", NULL };
	yaml_node_t *v[4];
	uint32_t sz[2];
	int err = ld_map_req(l, n, "lattice", keys, v, YML_REQ(0));

	if (!err)
		err = pair(l, v[0], SYS_ITEMS_MAX, sz);
	if (!err && (uint64_t)sz[0] * sz[1] > SYS_ITEMS_MAX)
		err = ld_fail(l, v[0], -EINVAL, "%u x %u points: at most %u", sz[0], sz[1],
			      SYS_ITEMS_MAX);
	p->spacing[0] = p->spacing[1] = 0.1;
	if (!err && v[1])
		err = ld_vec(l, v[1], 2, 1.0, "scene units", p->spacing);
	if (!err && v[1] && !(p->spacing[0] > 0 && p->spacing[1] > 0))
		err = ld_fail(l, v[1], -EINVAL, "spacing is above 0 both ways");
	if (!err && v[2])
		err = ld_vec(l, v[2], 3, 1.0, "scene units", p->origin);
	if (!err && v[3])
		err = ld_bool(l, v[3], &p->shear);
	p->lu = sz[0];
	p->lv = sz[1];
	return err;
}

static int pins(struct ld *l, yaml_node_t *seq, struct sd_particles *p)
{
	static const char *const keys[] = { "at", "interpolation", "ease", "beta", "keys", NULL };
	struct sd_pin *pin;
	yaml_node_item_t *it;
	size_t n, i, j;
	int err = ld_seq(l, seq, "pins", &it, &n);

	if (err)
		return err;
	pin = pool_array(l->pool, n ? n : 1, sizeof(*pin));
	if (!pin)
		return ld_nomem(l);
	for (i = 0; i < n; i++) {
		yaml_node_t *map = ld_node(l, it[i]), *v[5];
		uint32_t at[2];

		err = ld_map_req(l, map, "pin", keys, v, YML_REQ(0));
		if (!err)
			err = pair(l, v[0], SYS_ITEMS_MAX, at);
		if (!err && (at[0] > p->lu || at[1] > p->lv || !at[0] || !at[1]))
			err = ld_fail(l, v[0], -EINVAL,
				      "pin at [%u, %u] is off the %u x %u lattice (rows and columns "
				      "count from 1)", at[0], at[1], p->lu, p->lv);
		for (j = 0; !err && j < i; j++)
			if (pin[j].row == at[0] - 1 && pin[j].col == at[1] - 1)
				err = ld_fail(l, v[0], -EINVAL, "lattice point [%u, %u] is pinned "
					      "twice", at[0], at[1]);
		if (err)
			return err;
		memset(&pin[i], 0, sizeof(pin[i]));
		pin[i].row = at[0] - 1;
		pin[i].col = at[1] - 1;
		if (v[4] || v[1] || v[2] || v[3]) {
			struct kfield f = { "offset", 3, { &pin[i].off[0], &pin[i].off[1],
							   &pin[i].off[2] } };
			struct ld_curve_opts o = { v[1], v[2], v[3] };

			err = keyed_nodes(l, map, &o, v[4], "pin", "frame", &f, 1);
			if (err)
				return err;
		}
	}
	p->pins = pin;
	p->npins = (uint32_t)n;
	return 0;
}

static int particles(struct ld *l, yaml_node_t *map, struct sd_particles *p,
		     struct sd_system *sys)
{
	static const char *const keys[] = { "name", "motion", "pool", "step_hz", "seed", "emit",
					    "over_life", "gravity", "drag", "ground", "pairs",
					    "lattice", "mass", "springs", "pins", "limits", NULL };
	static const char *const motions[] = { "scripted", "newtonian", NULL };
	enum { P_NAME, P_MOTION, P_POOL, P_HZ, P_SEED, P_EMIT, P_LIFE, P_GRAV, P_DRAG, P_GROUND,
	       P_PAIRS, P_LATTICE, P_MASS, P_SPRINGS, P_PINS, P_LIMITS, P_N };
	yaml_node_t *v[P_N], *w[2];
	long long seed = 1;
	double mass = 1;
	int motion = MOT_PARTICLES_SCRIPTED, err, k;

	err = ld_map_req(l, map, "particles", keys, v, YML_REQ(P_NAME));
	if (!err)
		err = ld_name(l, v[P_NAME], &p->name);
	if (!err && v[P_MOTION])
		err = ld_enum(l, v[P_MOTION], "motion", motions, &motion);
	if (err)
		return err;
	p->motion = (enum mot_particles_motion)motion;
	p->emit = v[P_EMIT] != NULL;
	if (!v[P_EMIT] == !v[P_LATTICE])
		return ld_fail(l, map, -EINVAL,
			       "particles are emitted (emit: and pool:) or a lattice (lattice:), "
			       "one of them");
	if (p->emit && !v[P_POOL])
		return ld_fail(l, map, -EINVAL, "emitted particles need a pool: of slots");
	if (!p->emit && v[P_POOL])
		return ld_fail(l, v[P_POOL], -EINVAL, "a lattice's slots are its points: no pool");
	if (p->motion == MOT_PARTICLES_SCRIPTED)
		for (k = P_DRAG; k <= P_PINS; k++)
			if (v[k] && k != P_LATTICE)
				return ld_fail(l, v[k], -EINVAL,
					       "'%s' is a force: it moves newtonian particles "
					       "(motion: newtonian), not scripted ones", keys[k]);
	if (p->motion == MOT_PARTICLES_SCRIPTED && !p->emit)
		return ld_fail(l, v[P_LATTICE], -EINVAL,
			       "a lattice is moved by its springs: motion: newtonian");
	if (p->emit && (v[P_SPRINGS] || v[P_PINS] || v[P_MASS]))
		return ld_fail(l, v[P_SPRINGS] ? v[P_SPRINGS] : v[P_PINS] ? v[P_PINS] : v[P_MASS],
			       -EINVAL, "springs, pins and mass belong to a lattice");
	/* the constants where nothing is keyed: appearance 1 over the life,
	 * a second's life, nothing else */
	for (k = MOT_PC_AGE_R; k <= MOT_PC_AGE_SIZE; k++)
		p->v[k] = 1;
	p->v[MOT_PC_LIFE_LO] = p->v[MOT_PC_LIFE_HI] = 1;
	p->v[MOT_PC_ALPHA_LO] = p->v[MOT_PC_ALPHA_HI] = 1;
	for (k = MOT_PC_COL_LO; k <= MOT_PC_COL_HI_B; k++)
		p->v[k] = 1;
	if (v[P_POOL])
		err = count(l, v[P_POOL], 1, SYS_ITEMS_MAX, &p->npool);
	if (!err)
		err = step_rate(l, v[P_HZ], &p->rate_num, &p->rate_den);
	if (!err && v[P_SEED])
		err = ld_int(l, v[P_SEED], 0, INT64_MAX, &seed);
	p->seed = (uint64_t)seed;
	if (!err && v[P_EMIT])
		err = emission(l, v[P_EMIT], p);
	if (!err && v[P_LIFE])
		err = over_life(l, v[P_LIFE], p);
	if (!err && v[P_GRAV])
		err = ld_vec(l, v[P_GRAV], 3, 1.0, "scene units/s^2", p->gravity);
	if (!err && v[P_DRAG])
		err = nonneg(l, v[P_DRAG], "drag", &p->drag);
	if (!err && v[P_GROUND]) {
		static const char *const gk[] = { "height", "restitution", NULL };

		p->ground = true;
		p->restitution = 0.5;
		err = ld_map(l, v[P_GROUND], "ground", gk, w);
		if (!err && w[0])
			err = ld_q32(l, w[0], 1.0, "scene units", &p->ground_y);
		if (!err && w[1])
			err = nonneg(l, w[1], "restitution", &p->restitution);
		if (!err && w[1] && p->restitution > 1)
			err = ld_fail(l, w[1], -EINVAL, "restitution is 0 (dead) to 1 (elastic)");
	}
	if (!err && v[P_PAIRS]) {
		static const char *const pk[] = { "radius", "strength", NULL };

		err = ld_map_req(l, v[P_PAIRS], "pairs", pk, w, YML_REQ(0) | YML_REQ(1));
		if (!err)
			err = above0(l, w[0], "radius", &p->pair_radius);
		if (!err)
			err = ld_q32(l, w[1], 1.0, "scene units/s^2", &p->pair_strength);
	}
	if (!err && v[P_LATTICE])
		err = lattice(l, v[P_LATTICE], p);
	if (!err && v[P_MASS])
		err = above0(l, v[P_MASS], "mass", &mass);
	if (!err && v[P_SPRINGS]) {
		static const char *const sk[] = { "stiffness", "damping", NULL };

		err = ld_map_req(l, v[P_SPRINGS], "springs", sk, w, YML_REQ(0));
		if (!err)
			err = above0(l, w[0], "stiffness", &p->spring_k);
		if (!err && w[1])
			err = nonneg(l, w[1], "damping", &p->spring_c);
		/* the core takes them per unit mass */
		p->spring_k /= mass;
		p->spring_c /= mass;
		if (!err && !sd_to_q32(p->spring_k, &(mot_q32){ 0 }))
			err = ld_fail(l, w[0], -ERANGE, "stiffness / mass %.10g is outside the core's "
				      "range", p->spring_k);
	}
	if (!err && v[P_PINS])
		err = pins(l, v[P_PINS], p);
	sys->kind = SD_PARTICLES;
	sys->particles = p;
	if (!err && v[P_LIMITS])
		err = sys_limits(l, v[P_LIMITS], sys, p->lim);
	return err;
}

/* ---- flocks ------------------------------------------------------------------------------ */

static int weight(struct ld *l, yaml_node_t *n, double *out)
{
	return nonneg(l, n, "a weight", out);
}

static int flock(struct ld *l, yaml_node_t *map, struct sd_flock *f, struct sd_system *sys)
{
	static const char *const keys[] = { "name", "members", "step_hz", "seed", "start",
					    "neighbours", "separation", "cohesion", "alignment",
					    "goal", "obstacles", "avoid", "speed", "acceleration",
					    "limits", NULL };
	enum { F_NAME, F_N, F_HZ, F_SEED, F_START, F_NB, F_SEP, F_COH, F_ALI, F_GOAL, F_OBST,
	       F_AVOID, F_SPEED, F_ACC, F_LIMITS, F_COUNT };
	yaml_node_t *v[F_COUNT], *w[8];
	long long seed = 1;
	int err;

	err = ld_map_req(l, map, "flock", keys, v,
			 YML_REQ(F_NAME) | YML_REQ(F_N) | YML_REQ(F_SPEED) | YML_REQ(F_ACC));
	if (!err)
		err = ld_name(l, v[F_NAME], &f->name);
	if (!err)
		err = count(l, v[F_N], 1, SYS_ITEMS_MAX, &f->n);
	if (!err)
		err = step_rate(l, v[F_HZ], &f->rate_num, &f->rate_den);
	if (!err && v[F_SEED])
		err = ld_int(l, v[F_SEED], 0, INT64_MAX, &seed);
	f->seed = (uint64_t)seed;
	if (!err)
		err = above0(l, v[F_SPEED], "speed", &f->vmax);
	if (!err)
		err = above0(l, v[F_ACC], "acceleration", &f->amax);
	f->radius = 1;
	f->max_neighbours = 8;
	f->margin = 1;
	if (!err && v[F_START]) {
		static const char *const sk[] = { "centre", "spread", "velocity", "velocity_spread",
						   NULL };

		err = ld_map(l, v[F_START], "start", sk, w);
		if (!err && w[0])
			err = ld_vec(l, w[0], 3, 1.0, "scene units", f->start_c);
		if (!err && w[1])
			err = nonneg(l, w[1], "spread", &f->start_r);
		if (!err && w[2])
			err = ld_vec(l, w[2], 3, 1.0, "scene units/s", f->start_v);
		if (!err && w[3])
			err = nonneg(l, w[3], "velocity_spread", &f->start_dv);
	}
	if (!err && v[F_NB]) {
		static const char *const nk[] = { "radius", "max", NULL };
		long long mx = 8;

		err = ld_map(l, v[F_NB], "neighbours", nk, w);
		if (!err && w[0])
			err = above0(l, w[0], "radius", &f->radius);
		if (!err && w[1])
			err = ld_int(l, w[1], 0, 1024, &mx);
		f->max_neighbours = (uint32_t)mx;
	}
	if (!err && v[F_SEP]) {
		static const char *const sk[] = { "distance", "weight", NULL };

		err = ld_map(l, v[F_SEP], "separation", sk, w);
		if (!err && w[0])
			err = nonneg(l, w[0], "distance", &f->sep);
		if (!err && w[1])
			err = weight(l, w[1], &f->w_sep);
	}
	if (!err && v[F_COH])
		err = weight(l, v[F_COH], &f->w_coh);
	if (!err && v[F_ALI])
		err = weight(l, v[F_ALI], &f->w_ali);
	if (!err && v[F_GOAL]) {
		yaml_node_t *wt = NULL, *rest = v[F_GOAL];
		static const char *const gk[] = { "weight", "interpolation", "ease", "beta", "keys",
						   NULL };

		err = ld_map(l, rest, "goal", gk, w);
		wt = w[0];
		if (!err && wt)
			err = weight(l, wt, &f->w_goal);
		if (!err) {
			struct ld_curve_opts o = { w[1], w[2], w[3] };
			struct kfield kf[2] = {
				{ "position", 3, { &f->goal_c[0], &f->goal_c[1], &f->goal_c[2] } },
				{ "direction", 3, { &f->goal_c[0], &f->goal_c[1], &f->goal_c[2] } },
			};
			struct sd_curve dir[3];
			struct kfield kd = { "direction", 3, { &dir[0], &dir[1], &dir[2] } };
			yaml_node_item_t *it;
			size_t nk;

			/* a goal point or a direction: whichever the first key gives */
			err = ld_require(l, rest, "goal", w[4], "keys");
			if (!err)
				err = ld_seq(l, w[4], "keys", &it, &nk);
			if (!err && nk && yml_value(&l->y, ld_node(l, it[0]), "direction")) {
				err = keyed_nodes(l, rest, &o, w[4], "goal", "frame", &kd, 1);
				memcpy(f->goal_c, dir, sizeof(dir));
				f->goal = MOT_FLOCK_GOAL_DIRECTION;
			} else if (!err) {
				err = keyed_nodes(l, rest, &o, w[4], "goal", "frame", kf, 1);
				f->goal = MOT_FLOCK_GOAL_POINT;
			}
		}
	}
	if (!err && v[F_OBST]) {
		struct sd_obstacle *ob;
		yaml_node_item_t *it;
		size_t n, i;

		err = ld_seq(l, v[F_OBST], "obstacles", &it, &n);
		ob = err ? NULL : pool_array(l->pool, n ? n : 1, sizeof(*ob));
		if (!err && !ob)
			return ld_nomem(l);
		for (i = 0; !err && i < n; i++) {
			static const char *const ok[] = { "centre", "radius", NULL };
			yaml_node_t *m = ld_node(l, it[i]);

			err = ld_map_req(l, m, "obstacle", ok, w, YML_REQ(0) | YML_REQ(1));
			if (!err)
				err = ld_vec(l, w[0], 3, 1.0, "scene units", ob[i].c);
			if (!err)
				err = above0(l, w[1], "radius", &ob[i].r);
		}
		f->obst = ob;
		f->nobst = (uint32_t)n;
	}
	if (!err && v[F_AVOID]) {
		static const char *const ak[] = { "margin", "weight", NULL };

		err = ld_map(l, v[F_AVOID], "avoid", ak, w);
		if (!err && w[0])
			err = above0(l, w[0], "margin", &f->margin);
		if (!err && w[1])
			err = weight(l, w[1], &f->w_obst);
	}
	sys->kind = SD_FLOCK;
	sys->flock = f;
	if (!err && v[F_LIMITS])
		err = sys_limits(l, v[F_LIMITS], sys, f->lim);
	return err;
}

/* ---- the sections ------------------------------------------------------------------------ */

static int grow(struct ld *l, size_t add)
{
	struct sd_system *s = pool_array(l->pool, l->d->nsys + add, sizeof(*s));
	struct ld_mark *m = pool_array(l->pool, l->d->nsys + add, sizeof(*m));

	if (!s || !m)
		return ld_nomem(l);
	if (l->d->nsys) {
		memcpy(s, l->d->sys, l->d->nsys * sizeof(*s));
		memcpy(m, l->mk->sys, l->d->nsys * sizeof(*m));
	}
	l->d->sys = s;
	l->mk->sys = m;
	return 0;
}

int ld_systems(struct ld *l, yaml_node_t *seq, enum sd_sys_kind kind)
{
	static const char *const what[] = { "surfaces", "particles", "flocks" };
	yaml_node_item_t *it;
	struct sd_system *sys;
	size_t n, i;
	int err = ld_seq(l, seq, what[kind], &it, &n);

	if (!err)
		err = grow(l, n);
	if (err)
		return err;
	sys = (struct sd_system *)l->d->sys;
	for (i = 0; i < n; i++) {
		yaml_node_t *map = ld_node(l, it[i]);
		struct sd_system *s = &sys[l->d->nsys];

		memset(s, 0, sizeof(*s));
		l->mk->sys[l->d->nsys] = ld_mark_of(map);
		if (kind == SD_SURFACE) {
			struct sd_surface *x = pool_array(l->pool, 1, sizeof(*x));

			err = x ? surface(l, map, x, s) : ld_nomem(l);
		} else if (kind == SD_PARTICLES) {
			struct sd_particles *x = pool_array(l->pool, 1, sizeof(*x));

			err = x ? particles(l, map, x, s) : ld_nomem(l);
		} else {
			struct sd_flock *x = pool_array(l->pool, 1, sizeof(*x));

			err = x ? flock(l, map, x, s) : ld_nomem(l);
		}
		if (err)
			return err;
		l->d->nsys++;
	}
	return 0;
}

/* The system called name, or -1. */
static int find_sys(const struct scene_desc *d, const char *name, size_t len)
{
	uint32_t i;

	for (i = 0; i < d->nsys; i++) {
		const char *s = sd_sys_name(&d->sys[i]);

		if (strlen(s) == len && !strncmp(s, name, len))
			return (int)i;
	}
	return -1;
}

/*
 * A target: a node's name, or an item of a system: `birds.3`, `skin.2.5`
 * (row, column), `fountain.0`. With count, a system's name alone: its
 * items 0 .. count - 1, one for each head.
 */
static int target(struct ld *l, yaml_node_t *n, struct sd_aim *a, uint32_t k, bool group)
{
	const char *t, *dot;
	int sys, node;
	unsigned long i1 = 0, i2 = 0;
	char tail[2];
	int got;
	int err = ld_str(l, n, &t);

	if (err)
		return err;
	a->node = a->sys = -1;
	dot = strchr(t, '.');
	if (group) {
		sys = find_sys(l->d, t, strlen(t));
		if (sys < 0)
			return ld_fail(l, n, -EINVAL, "aims with count follow a system's items: "
				       "'%s' is not a system", t);
		if (k >= sd_sys_items(&l->d->sys[sys]))
			return ld_fail(l, n, -EINVAL, "'%s' has %u items, fewer than the aims",
				       t, sd_sys_items(&l->d->sys[sys]));
		a->sys = sys;
		a->item = k;
		return 0;
	}
	node = ld_find_node(l, t, strlen(t));
	if (node >= 0) {
		a->node = node;
		return 0;
	}
	sys = dot ? find_sys(l->d, t, (size_t)(dot - t)) : -1;
	if (sys < 0)
		return ld_fail(l, n, -EINVAL, "unknown target '%s': a node, or an item of a system "
			       "(birds.3, skin.2.5)", t);
	if (l->d->sys[sys].kind == SD_SURFACE) {
		const struct sd_surface *s = l->d->sys[sys].surface;

		got = sscanf(dot + 1, "%lu.%lu%1s", &i1, &i2, tail);
		if (got != 2 || i1 >= s->nsu || i2 >= s->nsv)
			return ld_fail(l, n, -EINVAL, "'%s': a sample of surface '%s' is ROW.COLUMN, "
				       "within %u x %u", t, s->name, s->nsu, s->nsv);
		a->item = (uint32_t)(i1 * s->nsv + i2);
	} else {
		got = sscanf(dot + 1, "%lu%1s", &i1, tail);
		if (got != 1 || i1 >= sd_sys_items(&l->d->sys[sys]))
			return ld_fail(l, n, -EINVAL, "'%s': '%s' has items 0 to %u", t,
				       sd_sys_name(&l->d->sys[sys]),
				       sd_sys_items(&l->d->sys[sys]) - 1);
		a->item = (uint32_t)i1;
	}
	a->sys = sys;
	return 0;
}

int ld_aims(struct ld *l, yaml_node_t *seq)
{
	static const char *const keys[] = { "name", "at", "step", "count", "target", "grid",
					    "limits", NULL };
	enum { A_NAME, A_AT, A_STEP, A_COUNT, A_TARGET, A_GRID, A_LIMITS, A_N };
	yaml_node_item_t *it;
	struct sd_aim *aims = NULL;
	size_t n, i, total = 0;
	int err = ld_seq(l, seq, "aims", &it, &n);

	if (err)
		return err;
	l->mk->aim = pool_array(l->pool, n ? n : 1, sizeof(*l->mk->aim));
	if (!l->mk->aim)
		return ld_nomem(l);
	for (i = 0; i < n; i++) {
		yaml_node_t *map = ld_node(l, it[i]), *v[A_N];
		const char *name;
		double at[3], step[3] = { 0, 0, 0 };
		long long cnt = 1, sub = 4;
		struct sd_aim *grown;
		struct sd_limits lim[2];
		uint32_t k;

		memset(lim, 0, sizeof(lim));
		l->mk->aim[i] = ld_mark_of(map);
		err = ld_map_req(l, map, "aim", keys, v,
				 YML_REQ(A_NAME) | YML_REQ(A_AT) | YML_REQ(A_TARGET));
		if (!err)
			err = ld_name(l, v[A_NAME], &name);
		if (!err)
			err = ld_vec(l, v[A_AT], 3, 1.0, "scene units", at);
		if (!err && v[A_COUNT])
			err = ld_int(l, v[A_COUNT], 1, SYS_ITEMS_MAX, &cnt);
		if (!err && v[A_STEP] && !v[A_COUNT])
			err = ld_fail(l, v[A_STEP], -EINVAL, "step spaces a row of heads: give count");
		if (!err && v[A_STEP])
			err = ld_vec(l, v[A_STEP], 3, 1.0, "scene units", step);
		if (!err && v[A_GRID])
			err = ld_int(l, v[A_GRID], 1, MOT_AIM_SUB_MAX, &sub);
		if (!err && v[A_LIMITS]) {
			static const char *const lk[] = { "pan", "tilt", NULL };
			yaml_node_t *w[2];

			err = ld_map(l, v[A_LIMITS], "limits", lk, w);
			for (k = 0; !err && k < 2; k++)
				if (w[k])
					err = ld_limits(l, w[k], true, &lim[k]);
		}
		if (err)
			return err;
		grown = pool_array(l->pool, total + (size_t)cnt, sizeof(*grown));
		if (!grown)
			return ld_nomem(l);
		if (total)
			memcpy(grown, aims, total * sizeof(*aims));
		aims = grown;
		for (k = 0; k < cnt; k++) {
			struct sd_aim *a = &aims[total + k];
			char buf[96];
			int c;

			memset(a, 0, sizeof(*a));
			if (v[A_COUNT]) {
				snprintf(buf, sizeof(buf), "%s.%u", name, k);
				a->name = pool_strndup(l->pool, buf, strlen(buf));
				if (!a->name)
					return ld_nomem(l);
			} else {
				a->name = name;
			}
			for (c = 0; c < 3; c++)
				a->at[c] = at[c] + step[c] * k;
			a->sub = (uint32_t)sub;
			a->lim[0] = lim[0];
			a->lim[1] = lim[1];
			err = target(l, v[A_TARGET], a, k, v[A_COUNT] != NULL);
			if (err)
				return err;
			/* each head's position in range too */
			for (c = 0; c < 3; c++)
				if (!sd_to_q32(a->at[c], &(mot_q32){ 0 }))
					return ld_fail(l, v[A_STEP], -ERANGE, "head %u of '%s' is "
						       "outside the core's range", k, name);
		}
		total += (size_t)cnt;
	}
	/* the marks follow the aims one for one (a group's heads share one) */
	{
		struct ld_mark *m = pool_array(l->pool, total ? total : 1, sizeof(*m));
		size_t j = 0;

		if (!m)
			return ld_nomem(l);
		for (i = 0; i < n; i++) {
			yaml_node_t *cn = yml_value(&l->y, ld_node(l, it[i]), "count");
			long long c = 1;

			if (cn)
				ld_int(l, cn, 1, SYS_ITEMS_MAX, &c);
			while (c-- > 0)
				m[j++] = l->mk->aim[i];
		}
		l->mk->aim = m;
	}
	l->d->aims = aims;
	l->d->naims = (uint32_t)total;
	return 0;
}
