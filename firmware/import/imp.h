/* SPDX-License-Identifier: MIT */
/*
 * imp.h - what `strand import` reads a glTF 2.0 file, a URDF or a table
 * into, and the scene file it writes from it (imp_yaml.c).
 *
 * A model is a list of nodes, parents before children, each a free node
 * (a rest transform and up to three channels: translate, rotation, scale)
 * or a joint (revolute or prismatic, its pivot and axis in the model's rest
 * coordinates, one value channel, limits, or a mimic of another joint), and
 * attributes (a table's plain columns). Channels keep what the source says:
 * key frames (seconds times the frame rate, not rounded), values, and for
 * cubic channels the tangents per frame. Everything is malloc'd and owned
 * by the model (imp_model_free). Not real-time.
 */
#ifndef STRAND_IMP_H
#define STRAND_IMP_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

enum imp_interp { IMP_STEP, IMP_LINEAR, IMP_CUBIC, IMP_HERMITE };
enum imp_path { IMP_T, IMP_R, IMP_S, IMP_NPATHS };
enum imp_kind { IMP_FREE, IMP_REVOLUTE, IMP_PRISMATIC };

struct imp_chan {
	enum imp_interp interp; /* cubic: explicit tangents; hermite: Catmull-Rom */
	uint32_t n, dim;        /* keys; components (1, 3 or 4: w, x, y, z) */
	double *frame;          /* n */
	double *v;              /* n * dim */
	double *in, *out;       /* n * dim, per frame (cubic only) */
};

struct imp_node {
	char *name;
	int32_t parent;     /* earlier node, or -1 */
	enum imp_kind kind;
	double pivot[3];
	double axis[3];     /* joints: unit */
	/* free nodes: a static matrix (rows, row vectors), or the rest
	 * translate, rotation (w, x, y, z) and scale that channels override */
	bool has_matrix;
	double matrix[4][4];
	double t[3], q[4], s[3];
	struct imp_chan ch[IMP_NPATHS]; /* joints: ch[0], degrees or units */
	double rest;                    /* joints */
	bool has_min, has_max, has_vel;
	double min, max, vel;           /* degrees or units, per second */
	int32_t mimic;                  /* joints: the master, or -1 */
	double mult, offset;
};

struct imp_attr {
	char *name;
	struct imp_chan ch;
};

struct imp_model {
	char *comment;                /* lines for the file's top, without '#' */
	uint32_t rate_num, rate_den;  /* frames per second */
	uint32_t tick_hz;
	uint32_t nnodes, nattrs;
	struct imp_node *nodes;
	struct imp_attr *attrs;
};

/* An empty node at the end of m (grown with realloc); its index, or -1. */
int imp_node_add(struct imp_model *m, const char *name);
/* Keys of a channel: arrays for n keys of dim components (cubic: tangents
 * too). 0 or -ENOMEM. */
int imp_chan_alloc(struct imp_chan *c, uint32_t n, uint32_t dim, enum imp_interp interp);
void imp_model_free(struct imp_model *m);

/* Append a line to the comment (printf-style). */
void imp_note(struct imp_model *m, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/*
 * Names as a scene file takes them: every character other than a letter,
 * digit, '_' or '-' becomes '_', an empty name becomes "node<i>", and a name
 * taken by an earlier node or attribute (or "camera") gets "_2", "_3", ...
 * Each change of the last kind is said on warn (one line, "FILE: ...").
 * 0 or -ENOMEM.
 */
int imp_names(struct imp_model *m, const char *file, FILE *warn);

/* Every character other than a letter, digit, '_' or '-' turned into '_'. */
void imp_name_clean(char *s);

/* The scene file: a comment saying where it came from, then the sections
 * asked for: timing over the keys' whole frames, nodes, strands (compact
 * where the keys allow) and attributes. */
enum {
	IMP_YAML_TIMING = 1,
	IMP_YAML_NODES = 2,   /* the nodes: section */
	IMP_YAML_STRANDS = 4, /* strands: and attributes: */
	IMP_YAML_ALL = 7,
};
int imp_yaml_write(FILE *out, const struct imp_model *m, unsigned sections);

/* Whether the model writes a strands: section. */
bool imp_has_strands(const struct imp_model *m);

/* The frame span of every key (0, 0 when there is none). */
void imp_span(const struct imp_model *m, double *first, double *last);

/* ---- the readers -------------------------------------------------------------- */

struct imp_opts {
	uint32_t rate_num, rate_den; /* frames per second (--fps) */
	uint32_t tick_hz;
	const char *anim;            /* glTF: animation name or index, NULL: the first */
	enum imp_interp interp;      /* tables: step, linear or hermite */
};

/*
 * Each reads a whole file from buf (len bytes; `path` names it and locates
 * files beside it) into an empty model. 0, or a negative errno with the
 * first fault in err as "<where>: what is wrong" (a JSON path, an XML line,
 * a table's line); warn (may be NULL) gets one line per thing left out.
 */
int imp_gltf(struct imp_model *m, const char *path, const uint8_t *buf, size_t len,
	     const struct imp_opts *o, FILE *warn, char *err, size_t errsize);
int imp_urdf(struct imp_model *m, const char *path, const uint8_t *buf, size_t len,
	     const struct imp_opts *o, FILE *warn, char *err, size_t errsize);
int imp_csv(struct imp_model *m, const char *path, const uint8_t *buf, size_t len,
	    const struct imp_opts *o, FILE *warn, char *err, size_t errsize);

/* A glTF key time's frame: t x num / den, or the whole frame n whose time
 * float32 holds as t (imp_gltf.c). */
double imp_gltf_frame(double t, double num, double den);

/* A joint of an existing scene, for a glTF animation to drive by name. */
struct imp_joint {
	const char *name;
	enum imp_kind kind;  /* revolute or prismatic */
	double axis[3];      /* unit, in the scene's rest coordinates */
};

/*
 * A glTF animation onto joints (imp_gltf_joint.c): the model gets one node
 * per joint that an animated node of the same name drives, with its keys
 * (the nodes themselves are the scene's). *matched counts them; 0 when no
 * animated node has a joint's name.
 */
int imp_gltf_joints(struct imp_model *m, const char *path, const uint8_t *buf, size_t len,
		    const struct imp_opts *o, const struct imp_joint *joints, uint32_t njoints,
		    uint32_t *matched, FILE *warn, char *err, size_t errsize);

#endif /* STRAND_IMP_H */
