/* SPDX-License-Identifier: MIT */
/*
 * gltf.h - a glTF 2.0 file as strand reads it (gltf.c): its nodes with
 * their rest transforms and parents, and one animation's channels with
 * their samplers decoded from the buffers into doubles (the file's float32
 * values exactly, normalised integers as the specification scales them).
 * Meshes, materials, skins' matrices and cameras are counted, not read.
 *
 * Everything is checked where it is read, and the first fault is one line,
 * "<JSON path>: what is wrong" ("/accessors/3: 40 elements of 12 bytes
 * from byte 0 pass the end of bufferView 1 (400 bytes)"). Not real-time.
 */
#ifndef STRAND_GLTF_H
#define STRAND_GLTF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

enum gltf_path { GLTF_T, GLTF_R, GLTF_S };
enum gltf_interp { GLTF_STEP, GLTF_LINEAR, GLTF_CUBIC };

struct gltf_node {
	char *name;        /* NULL when the file gives none */
	int32_t parent;    /* -1 for a root */
	bool has_matrix;
	double matrix[16]; /* column-major, as the file */
	double t[3], r[4], s[3]; /* r: x, y, z, w as the file */
};

struct gltf_channel {
	int32_t node;
	enum gltf_path path;
	enum gltf_interp interp;
	uint32_t n, dim;   /* keys; 3 (translation, scale) or 4 (rotation) */
	double *time;      /* n seconds, strictly increasing, >= 0 */
	double *v;         /* n * dim; cubic: n * 3 * dim (in-tangent, value, out-tangent) */
};

struct gltf {
	uint32_t nnodes;
	struct gltf_node *nodes;
	uint32_t nanims;            /* animations in the file */
	char *anim_name;            /* the one read (NULL: unnamed or none) */
	uint32_t anim_index;
	uint32_t nchannels;
	struct gltf_channel *channels;
	uint32_t nmeshes, ncameras, nskins, nmaterials, nweights; /* ignored */
};

/*
 * Read a .gltf (JSON, buffers in data URIs or in files beside it) or a .glb
 * (binary, detected by its magic) from buf. `path` locates relative buffer
 * files; `anim` chooses the animation by name or index (NULL: the first).
 * 0, or -EINVAL with the message in err (errsize bytes), -ENOMEM, or -EIO
 * for a buffer file that cannot be read. g holds nothing to free on error.
 */
int gltf_read(struct gltf *g, const char *path, const uint8_t *buf, size_t len,
	      const char *anim, char *err, size_t errsize);
void gltf_free(struct gltf *g);

#endif /* STRAND_GLTF_H */
