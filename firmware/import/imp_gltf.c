/* SPDX-License-Identifier: MIT */
/*
 * imp_gltf.c - a glTF 2.0 file's nodes and one animation as a model
 * (imp.h): every node a free node, parents before children, with its rest
 * transform; each channel's keys at time x fps frames, unrounded.
 *
 * glTF's local transform is T . R . S on column vectors; on strand's row
 * vectors (FORMULAS section 1) that is S . R . T, a free node with pivot 0,
 * and its rotation quaternion is strand's, (w, x, y, z) from the file's
 * (x, y, z, w): the row-vector matrix of FORMULAS section 4 is the
 * transpose of glTF's column-vector one. A matrix node's column-major array
 * is, four numbers at a time, the rows of strand's matrix key. The
 * interpolations map one to one (specification, appendix C): STEP, LINEAR
 * (slerp the short way for rotations) and CUBICSPLINE (a hermite curve
 * with explicit tangents, per second there, per frame here; for rotations
 * four such curves normalised).
 */
#include "imp.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gltf.h"

/* Node order: each after its parent, otherwise as the file lists them. */
static int order(const struct gltf *g, uint32_t i, int32_t *newidx, uint32_t *next,
		 uint32_t *seq)
{
	if (newidx[i] >= 0)
		return 0;
	if (g->nodes[i].parent >= 0)
		order(g, (uint32_t)g->nodes[i].parent, newidx, next, seq);
	newidx[i] = (int32_t)*next;
	seq[(*next)++] = i;
	return 0;
}

/*
 * A key's frame: time x fps, except that a time the exporter wrote for a
 * whole frame n, which float32 could only hold as the float nearest to
 * n / fps seconds, is frame n exactly. Otherwise a STEP key written for
 * frame 70 would take effect 2e-6 frames after frame 70's sample, not at
 * it, and every key would sit off its frame by float32's rounding of its
 * time (2.4e-7 s at 4 s). Other times stay as the file has them.
 */
double imp_gltf_frame(double t, double num, double den)
{
	double f = t * num / den, n = nearbyint(f);

	return (float)(n * den / num) == (float)t ? n : f;
}

static int channel(struct imp_node *n, const struct gltf_channel *c, double num, double den)
{
	static const int perm[4] = { 3, 0, 1, 2 }; /* w, x, y, z from x, y, z, w */
	enum imp_interp in = c->interp == GLTF_STEP ? IMP_STEP :
			     c->interp == GLTF_LINEAR ? IMP_LINEAR : IMP_CUBIC;
	struct imp_chan *ch = &n->ch[c->path == GLTF_T ? IMP_T : c->path == GLTF_R ? IMP_R : IMP_S];
	uint32_t dim = c->dim, per = in == IMP_CUBIC ? 3 : 1, i, k;
	int err = imp_chan_alloc(ch, c->n, dim, in);

	if (err)
		return err;
	for (i = 0; i < c->n; i++) {
		ch->frame[i] = imp_gltf_frame(c->time[i], num, den);
		for (k = 0; k < dim; k++) {
			uint32_t src = dim == 4 ? (uint32_t)perm[k] : k;
			const double *e = c->v + (size_t)i * per * dim;

			if (in == IMP_CUBIC) {
				/* tangents per second to per frame */
				ch->in[i * dim + k] = e[src] * den / num;
				ch->v[i * dim + k] = e[dim + src];
				ch->out[i * dim + k] = e[2 * dim + src] * den / num;
			} else {
				ch->v[i * dim + k] = e[src];
			}
		}
	}
	return 0;
}

int imp_gltf(struct imp_model *m, const char *path, const uint8_t *buf, size_t len,
	     const struct imp_opts *o, FILE *warn, char *err, size_t errsize)
{
	struct gltf g;
	int32_t *newidx = NULL;
	uint32_t *seq = NULL, next = 0, i, r, c;
	int rc = gltf_read(&g, path, buf, len, o->anim, err, errsize);

	if (rc)
		return rc;
	newidx = malloc((g.nnodes ? g.nnodes : 1) * sizeof(*newidx));
	seq = malloc((g.nnodes ? g.nnodes : 1) * sizeof(*seq));
	if (!newidx || !seq) {
		rc = -ENOMEM;
		goto out;
	}
	for (i = 0; i < g.nnodes; i++)
		newidx[i] = -1;
	for (i = 0; i < g.nnodes; i++)
		order(&g, i, newidx, &next, seq);
	m->rate_num = o->rate_num;
	m->rate_den = o->rate_den;
	m->tick_hz = o->tick_hz;
	for (i = 0; i < g.nnodes; i++) {
		const struct gltf_node *gn = &g.nodes[seq[i]];
		struct imp_node *n;

		if (imp_node_add(m, gn->name) < 0) {
			rc = -ENOMEM;
			goto out;
		}
		n = &m->nodes[i];
		n->parent = gn->parent >= 0 ? newidx[gn->parent] : -1;
		n->has_matrix = gn->has_matrix;
		for (r = 0; r < 4; r++)
			for (c = 0; c < 4; c++)
				n->matrix[r][c] = gn->matrix[r * 4 + c];
		if (gn->has_matrix && (n->matrix[0][3] || n->matrix[1][3] || n->matrix[2][3] ||
				       n->matrix[3][3] != 1)) {
			snprintf(err, errsize, "/nodes/%u/matrix: not an affine transform", seq[i]);
			rc = -EINVAL;
			goto out;
		}
		memcpy(n->t, gn->t, sizeof(n->t));
		memcpy(n->s, gn->s, sizeof(n->s));
		n->q[0] = gn->r[3];
		n->q[1] = gn->r[0];
		n->q[2] = gn->r[1];
		n->q[3] = gn->r[2];
		if (!n->q[0] && !n->q[1] && !n->q[2] && !n->q[3]) {
			snprintf(err, errsize, "/nodes/%u/rotation: a zero quaternion", seq[i]);
			rc = -EINVAL;
			goto out;
		}
	}
	for (i = 0; i < g.nchannels; i++) {
		rc = channel(&m->nodes[newidx[g.channels[i].node]], &g.channels[i], o->rate_num,
			     o->rate_den);
		if (rc)
			goto out;
	}
	imp_note(m, "imported by strand import from %s (glTF 2.0): %u nodes, animation %u%s%s%s of %u",
		 path, g.nnodes, g.anim_index, g.anim_name ? " '" : "",
		 g.anim_name ? g.anim_name : "", g.anim_name ? "'" : "", g.nanims);
	imp_note(m, "key frames: seconds x %u/%u fps; a time float32 holds for a whole frame is that frame",
		 o->rate_num, o->rate_den);
	if (warn && (g.nmeshes || g.ncameras || g.nskins || g.nmaterials || g.nweights))
		fprintf(warn,
			"%s: left out: %u meshes, %u materials, %u skins' bind matrices, %u cameras, %u morph weight channels (their nodes are kept)\n",
			path, g.nmeshes, g.nmaterials, g.nskins, g.ncameras, g.nweights);
	rc = imp_names(m, path, warn);
out:
	free(newidx);
	free(seq);
	gltf_free(&g);
	return rc;
}
