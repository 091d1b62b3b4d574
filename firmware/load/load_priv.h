/* SPDX-License-Identifier: MIT */
/*
 * load_priv.h - what the parts of the scene file loader share: the walk
 * state, the positions kept for the build's errors, and the typed readers of
 * YAML nodes (yaml/yml.h, under the loader's names) that report a wrong
 * type, a missing field or an unknown key with its position. Not a public
 * interface (see load.h).
 */
#ifndef STRAND_LOAD_PRIV_H
#define STRAND_LOAD_PRIV_H

#include <yaml.h>

#include "load.h"
#include "yaml/yml.h"

/* Positions of one curve: its strand's mapping and each key (parallel to
 * the sd_curve's keys). */
struct sf_curve_marks {
	struct ld_mark at;
	struct ld_mark ease;
	const struct ld_mark *key;
};

struct sf_node_marks {
	struct ld_mark at, pivot, axis, rest;
	struct ld_mark ease; /* the strand's ease (free strands) */
	struct sf_curve_marks value, spin, ch[MOT_FREE_NCHANNELS], rot;
};

struct sf_marks {
	struct ld_mark root, timing, nodes;
	struct sf_node_marks *node;           /* nnodes */
	struct ld_mark camera;
	struct sf_curve_marks cam[MOT_CAM_NCHANNELS];
	struct ld_mark *cycle;                /* ncycles */
	struct sf_curve_marks *attr;          /* nattrs */
	struct ld_mark *sys;                  /* nsys: each system's mapping */
	struct ld_mark *aim;                  /* naims: each aim's mapping */
};

/* A joint that mimics another (`mimic:` on a node): its value is
 * multiplier x the master's + offset, the master's curve mapped at load
 * time (ld_mimics). */
struct ld_mimic {
	int32_t master;       /* -1: not a mimic */
	double mult, offset;  /* offset in the mimic's degrees or units */
	const yaml_node_t *at;
};

/* The walk: one per parse. */
struct ld {
	struct yml y;              /* first: the readers' walk (document, pool, errors) */
	struct scene_file *sf;
	struct scene_desc *d;
	struct sf_marks *mk;
	struct load_err *err;
	struct pool *pool;
	struct sd_node *nodes;     /* d->nodes, writable */
	struct sf_strand *strand;  /* sf->strand, writable */
	const char **node_names;   /* nnodes + 1, NULL-terminated, for suggestions */
	struct ld_mimic *mimic;    /* nnodes */
	uint32_t *by_name;         /* node indices sorted by name */
};

/* Index of the node called name (len bytes), or -1 (load_node.c). */
int ld_find_node(const struct ld *l, const char *name, size_t len);

/* ---- errors (load_yaml.c) ---------------------------------------------- */

/* The readers' errors go where ld_fail's do; pool is the scene file's. */
void ld_init(struct ld *l, struct pool *pool);

struct ld_mark ld_mark_of(const yaml_node_t *n);

/* Record the error (the first one only: later ones are consequences) and
 * return code. The message is formatted here, once. */
int ld_fail_at(struct ld *l, struct ld_mark m, int code, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));
int ld_fail(struct ld *l, const yaml_node_t *at, int code, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));
int ld_nomem(struct ld *l);

/*
 * A number that must fit the core once multiplied by `scale` (1/360 for
 * degrees): |v * scale| < 2^30, as sd_to_q32() will check. `unit` names it
 * in the message ("scene units", "degrees", "frames", ...).
 */
int ld_q32(struct ld *l, const yaml_node_t *n, double scale, const char *unit, double *out);

/* A sequence of exactly `count` numbers, each checked like ld_q32. */
int ld_vec(struct ld *l, yaml_node_t *n, size_t count, double scale, const char *unit,
	   double *out);

/* ---- the readers of yml.h, on the loader's walk ------------------------------ */

static inline const char *ld_describe(const yaml_node_t *n, char *buf, size_t size)
{
	return yml_describe(n, buf, size);
}

static inline const char *ld_suggest(const char *word, const char *const *names)
{
	return yml_suggest(word, names);
}

static inline yaml_node_t *ld_node(struct ld *l, int index)
{
	return yml_node(&l->y, index);
}

static inline int ld_map(struct ld *l, yaml_node_t *n, const char *what,
			 const char *const *names, yaml_node_t **vals)
{
	return yml_map(&l->y, n, what, names, vals);
}

static inline int ld_map_req(struct ld *l, yaml_node_t *n, const char *what,
			     const char *const *names, yaml_node_t **vals, uint32_t required)
{
	return yml_map_req(&l->y, n, what, names, vals, required);
}

static inline int ld_require(struct ld *l, const yaml_node_t *map, const char *what,
			     const yaml_node_t *v, const char *name)
{
	return yml_require(&l->y, map, what, v, name);
}

static inline int ld_seq(struct ld *l, yaml_node_t *n, const char *what,
			 yaml_node_item_t **items, size_t *count)
{
	return yml_seq(&l->y, n, what, items, count);
}

static inline int ld_num(struct ld *l, const yaml_node_t *n, double *out)
{
	return yml_num(&l->y, n, out);
}

static inline int ld_positive(struct ld *l, const yaml_node_t *n, double *out)
{
	return yml_positive(&l->y, n, out);
}

static inline int ld_int(struct ld *l, const yaml_node_t *n, long long min, long long max,
			 long long *out)
{
	return yml_int(&l->y, n, min, max, out);
}

static inline int ld_str(struct ld *l, const yaml_node_t *n, const char **out)
{
	return yml_str(&l->y, n, out);
}

static inline int ld_enum(struct ld *l, const yaml_node_t *n, const char *what,
			  const char *const *names, int *out)
{
	return yml_enum(&l->y, n, what, names, out);
}

static inline int ld_bool(struct ld *l, const yaml_node_t *n, bool *out)
{
	return yml_bool(&l->y, n, out);
}

static inline int ld_name(struct ld *l, const yaml_node_t *n, const char **out)
{
	return yml_name(&l->y, n, out);
}

/* A `limits:` mapping (min, max, velocity, acceleration) in degrees or in
 * scene units (load_node.c). */
int ld_limits(struct ld *l, yaml_node_t *n, bool degrees, struct sd_limits *lim);

/* ---- the parts of a scene file ---------------------------------------------- */

/* Options shared by every curve: interpolation, ease, beta (load_curve.c). */
struct ld_curve_opts {
	yaml_node_t *interp, *ease, *beta;
};
int ld_curve_opts(struct ld *l, const struct ld_curve_opts *o, struct sd_curve *c,
		  struct ld_mark *ease_mark);

/* The frame, ease_in and ease_out of key i, checked against key i-1 (load_curve.c). */
struct ld_key_common {
	yaml_node_t *frame, *ease_in, *ease_out;
};
int ld_key_common(struct ld *l, yaml_node_t *map, const struct ld_key_common *k,
		  const struct sd_key *prev, struct sd_key *out);

/* The checks of a whole curve the core would refuse: ease fractions summing
 * above 1, strand ease longer than the span, Bezier key count (load_curve.c). */
int ld_curve_check(struct ld *l, const struct sd_curve *c, const struct sf_curve_marks *m);

int ld_timing(struct ld *l, yaml_node_t *n);     /* load_timing.c */
int ld_nodes(struct ld *l, yaml_node_t *n);      /* load_node.c */
int ld_strands(struct ld *l, yaml_node_t *n);    /* load_strand.c */
/* Every mimic joint's curve from its master's, after the strands are read
 * (load_node.c). */
int ld_mimics(struct ld *l);

/* Fields of a strand key of any kind; which ones a node accepts depends on
 * its kind (load_strand.c). */
enum {
	K_FRAME, K_EASE_IN, K_EASE_OUT, K_ANGLE, K_RPM, K_POSITION, K_IN, K_OUT,
	K_TRANSLATE, K_ROTATE, K_QUAT, K_SCALE, K_SHEAR, K_MATRIX,
	K_TRANSLATE_IN, K_TRANSLATE_OUT, K_SCALE_IN, K_SCALE_OUT, K_QUAT_IN, K_QUAT_OUT, K_COUNT
};
extern const char *const ld_key_fields[];

/* A strand key's fields (v[K_COUNT]), checked against the node's kind (no
 * joint field on a free node and the other way round), with its frame and
 * ease fractions read after key prev. */
int ld_strand_key(struct ld *l, uint32_t node, yaml_node_t *map, yaml_node_t **v,
		  const struct sd_key *prev, struct sd_key *out);

/* The keys of a free node's strand (load_free.c). */
struct ld_free_opts {
	yaml_node_t *interp, *ease, *beta, *rotation, *compact, *keys;
};
int ld_free_strand(struct ld *l, uint32_t node, const struct ld_free_opts *o);

/* A key's explicit tangent (tan_set) on a curve that is not hermite, or one
 * whose handle over its interval, h x tangent x scale (1/360 for degrees),
 * reaches 2^31 units or turns, beyond the core's range (curve.h): the error
 * at the key (load_curve.c). */
int ld_tangent_check(struct ld *l, const struct sd_curve *c, const struct ld_mark *marks,
		     const char *field, double scale);
int ld_camera(struct ld *l, yaml_node_t *n);     /* load_camera.c */
int ld_cycles(struct ld *l, yaml_node_t *n);     /* load_cycle.c */
int ld_attributes(struct ld *l, yaml_node_t *n); /* load_attr.c */
/* surfaces:, particles:, flocks: (appended to the scene's systems, in
 * that order) and aims: (load_system.c). */
int ld_systems(struct ld *l, yaml_node_t *n, enum sd_sys_kind kind);
int ld_aims(struct ld *l, yaml_node_t *n);

/* The rig: devices:, outputs:, triggers:, inputs: (load_rig.c). */
struct ld_rig_sections {
	yaml_node_t *devices, *outputs, *triggers, *inputs;
};
int ld_rig(struct ld *l, const struct ld_rig_sections *s);
/* boards: and lockstep: (load_boards.c), after the rig's devices:. */
int ld_boards(struct ld *l, yaml_node_t *boards, yaml_node_t *lockstep, yaml_node_t *devices);

#endif /* STRAND_LOAD_PRIV_H */
