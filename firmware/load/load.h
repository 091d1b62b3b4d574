/* SPDX-License-Identifier: MIT */
/*
 * load.h - scene files: YAML in, a struct scene_desc out (README "Scene
 * files" is the schema).
 *
 * The loader checks everything it can say something useful about, so that a
 * mistake is reported once, as one line `file:line:column: message`, at the
 * place in the file where it was made: unknown keys (with the closest valid
 * one), wrong types, missing fields, key order, the hierarchy, node kinds,
 * singular matrices, the frame rate, and every number against the core's
 * range. What only the core can judge (a curve whose prepared coefficients
 * overflow, a camera that pans too fast for its grid) is found by
 * scene_file_build() and mapped back to the key or strand it came from.
 *
 * Not real-time: loading allocates (a pool owned by the scene_file).
 */
#ifndef STRAND_LOAD_H
#define STRAND_LOAD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rig/rig_desc.h"
#include "scene/scene_desc.h"
#include "yaml/pool.h"

/* Largest scene file the loader reads. */
#define LOAD_MAX_BYTES (16u << 20)

/* Where a scene file went wrong. code is a negative errno:
 *   -EINVAL   the file breaks the schema (wrong key, type, order, ...)
 *   -ERANGE   a number outside the core's range
 *   -EBADMSG  not YAML, or truncated
 *   -EIO, -ENOENT, -EFBIG, ...   the file could not be read (line = 0)
 *   -ENOMEM   out of memory */
struct load_err {
	int code;
	uint32_t line, col; /* 1-based; 0 when there is no position */
	char msg[256];      /* without the file:line:col prefix */
};

/* A position in the scene file (1-based; 0 = unknown). */
struct ld_mark {
	uint32_t line, col;
};

/* What the file said about one node's strand, for `info` and `plot`. */
struct sf_strand {
	bool present;
	enum mot_interp interp;
	bool squad;          /* free nodes: rotation by squad */
	const char *rotation; /* free nodes: slerp, squad, cubic or step */
	bool rpm;            /* revolute joints keyed by speed */
	uint32_t nkeys;      /* keys in the file */
	const double *key_frames; /* nkeys frames, as written */
	struct ld_mark at;   /* the strand's mapping */
};

struct sf_marks;

struct scene_file {
	struct scene_desc desc;
	struct rig_desc rig;       /* devices:, outputs:, triggers:, inputs: (all 0 if none) */
	const char *path;          /* as given to the loader */
	uint8_t digest[32];        /* SHA-256 of the file's bytes (scene/sha256.h) */
	const struct sf_strand *strand; /* desc.nnodes entries */
	struct sf_marks *marks;    /* positions for the build's errors */
	struct pool pool;          /* owns everything above */
};

/* Read and parse a scene file. 0, or a negative errno with *err filled. On
 * error sf holds nothing to free (scene_file_free is still safe). */
int scene_file_load(struct scene_file *sf, const char *path, struct load_err *err);

/* Parse a scene from memory; `path` names it in messages. */
int scene_file_parse(struct scene_file *sf, const char *path, const char *buf, size_t len,
		     struct load_err *err);

void scene_file_free(struct scene_file *sf);

/*
 * Build the core's scene from a loaded file (scene_build), mapping a failure
 * back to the place in the file it came from: 0 or a negative errno
 * (-EINVAL, -ERANGE, -ENOMEM) with *err filled.
 */
int scene_file_build(const struct scene_file *sf, struct scene_built *out, struct load_err *err);

/* Index of the node called `name`, or -1. */
int scene_file_node(const struct scene_file *sf, const char *name);

#endif /* STRAND_LOAD_H */
