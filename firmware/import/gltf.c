/* SPDX-License-Identifier: MIT */
/*
 * gltf.c - reading glTF 2.0 (see gltf.h) with Debian's jansson: the JSON,
 * the binary container (.glb: a 12-byte header, a JSON chunk and a BIN
 * chunk), buffers (data URIs in base64, files beside the .gltf, the BIN
 * chunk), bufferViews and accessors, as the specification's sections 3.6
 * and 5 define them. Every index, offset and count is checked before a
 * byte is read, so a hostile file gives an error, never a read outside
 * what was loaded.
 */
#include "gltf.h"

#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct buf {
	uint8_t *data;
	size_t len;
	bool owned;
};

struct rd {
	json_t *root;
	struct buf *bufs;
	size_t nbufs;
	const uint8_t *bin;  /* the GLB's BIN chunk, or NULL */
	size_t binlen;
	const char *path;
	char *err;
	size_t errsize;
};

static int fail(struct rd *r, int code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail(struct rd *r, int code, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(r->err, r->errsize, fmt, ap);
	va_end(ap);
	return code;
}

/* ---- JSON helpers ----------------------------------------------------------------- */

static json_t *array_of(struct rd *r, const char *name, size_t *n)
{
	json_t *a = json_object_get(r->root, name);

	*n = json_is_array(a) ? json_array_size(a) : 0;
	return json_is_array(a) ? a : NULL;
}

/* An index property: absent (*out = -1, when optional), or an integer in
 * [0, limit). */
static int get_index(struct rd *r, json_t *obj, const char *key, size_t limit, bool required,
		     const char *where, long long *out)
{
	json_t *v = json_object_get(obj, key);

	*out = -1;
	if (!v) {
		if (required)
			return fail(r, -EINVAL, "%s: missing '%s'", where, key);
		return 0;
	}
	if (!json_is_integer(v) || json_integer_value(v) < 0 ||
	    (unsigned long long)json_integer_value(v) >= limit)
		return fail(r, -EINVAL, "%s/%s: not an index below %zu", where, key, limit);
	*out = json_integer_value(v);
	return 0;
}

/* A non-negative integer property, default def when absent. */
static int get_size(struct rd *r, json_t *obj, const char *key, long long def, const char *where,
		    long long *out)
{
	json_t *v = json_object_get(obj, key);

	*out = def;
	if (!v)
		return def < 0 ? fail(r, -EINVAL, "%s: missing '%s'", where, key) : 0;
	if (!json_is_integer(v) || json_integer_value(v) < 0 ||
	    json_integer_value(v) > ((long long)1 << 40))
		return fail(r, -EINVAL, "%s/%s: not a size (a whole number from 0 to 2^40)", where,
			    key);
	*out = json_integer_value(v);
	return 0;
}

/* An array of n finite numbers, if present. */
static int get_numbers(struct rd *r, json_t *obj, const char *key, size_t n, const char *where,
		       double *out, bool *present)
{
	json_t *a = json_object_get(obj, key);
	size_t i;

	*present = a != NULL;
	if (!a)
		return 0;
	if (!json_is_array(a) || json_array_size(a) != n)
		return fail(r, -EINVAL, "%s/%s: not an array of %zu numbers", where, key, n);
	for (i = 0; i < n; i++) {
		json_t *v = json_array_get(a, i);

		if (!json_is_number(v) || !isfinite(json_number_value(v)))
			return fail(r, -EINVAL, "%s/%s/%zu: not a finite number", where, key, i);
		out[i] = json_number_value(v);
	}
	return 0;
}

/* ---- buffers -------------------------------------------------------------------------- */

static int b64(int c)
{
	if (c >= 'A' && c <= 'Z')
		return c - 'A';
	if (c >= 'a' && c <= 'z')
		return c - 'a' + 26;
	if (c >= '0' && c <= '9')
		return c - '0' + 52;
	return c == '+' ? 62 : c == '/' ? 63 : -1;
}

static int decode_b64(struct rd *r, const char *s, struct buf *b, const char *where)
{
	size_t len = strlen(s), i, o = 0;
	uint32_t acc = 0;
	int bits = 0;

	b->data = malloc(len / 4 * 3 + 3);
	if (!b->data)
		return -ENOMEM;
	b->owned = true;
	for (i = 0; i < len && s[i] != '='; i++) {
		int v = b64((unsigned char)s[i]);

		if (v < 0)
			return fail(r, -EINVAL, "%s/uri: not base64 at character %zu", where, i);
		acc = acc << 6 | (uint32_t)v;
		bits += 6;
		if (bits >= 8) {
			bits -= 8;
			b->data[o++] = (uint8_t)(acc >> bits);
		}
	}
	b->len = o;
	return 0;
}

static int read_file(struct rd *r, const char *uri, struct buf *b, const char *where)
{
	const char *slash = strrchr(r->path, '/');
	size_t dir = slash ? (size_t)(slash - r->path) + 1 : 0;
	char *full;
	FILE *f;
	long size;

	if (strstr(uri, "://") || uri[0] == '/')
		return fail(r, -EINVAL, "%s/uri: '%s' is not a relative file name", where, uri);
	full = malloc(dir + strlen(uri) + 1);
	if (!full)
		return -ENOMEM;
	memcpy(full, r->path, dir);
	strcpy(full + dir, uri);
	f = fopen(full, "rb");
	if (!f || fseek(f, 0, SEEK_END) || (size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET)) {
		int e = errno;

		if (f)
			fclose(f);
		fail(r, -EIO, "%s/uri: cannot read '%s' (%s)", where, full, strerror(e ? e : EIO));
		free(full);
		return -EIO;
	}
	free(full);
	b->data = malloc((size_t)size + 1);
	b->owned = true;
	if (!b->data) {
		fclose(f);
		return -ENOMEM;
	}
	b->len = fread(b->data, 1, (size_t)size, f);
	fclose(f);
	return 0;
}

static int load_buffers(struct rd *r)
{
	size_t n, i;
	json_t *a = array_of(r, "buffers", &n);
	char where[48];
	int err;

	r->bufs = calloc(n ? n : 1, sizeof(*r->bufs));
	if (!r->bufs)
		return -ENOMEM;
	r->nbufs = n;
	for (i = 0; i < n; i++) {
		json_t *o = json_array_get(a, i), *u = json_object_get(o, "uri");
		struct buf *b = &r->bufs[i];
		long long len;

		snprintf(where, sizeof(where), "/buffers/%zu", i);
		if (!json_is_object(o))
			return fail(r, -EINVAL, "%s: not an object", where);
		err = get_size(r, o, "byteLength", -1, where, &len);
		if (err)
			return err;
		if (!u) {
			if (i != 0 || !r->bin)
				return fail(r, -EINVAL, "%s: no 'uri', and it is not a .glb's BIN chunk",
					    where);
			b->data = (uint8_t *)r->bin;
			b->len = r->binlen;
		} else if (!json_is_string(u)) {
			return fail(r, -EINVAL, "%s/uri: not a string", where);
		} else if (!strncmp(json_string_value(u), "data:", 5)) {
			const char *s = strstr(json_string_value(u), ";base64,");

			if (!s)
				return fail(r, -EINVAL, "%s/uri: a data URI that is not base64", where);
			err = decode_b64(r, s + 8, b, where);
		} else {
			err = read_file(r, json_string_value(u), b, where);
		}
		if (err)
			return err;
		if (b->len < (size_t)len)
			return fail(r, -EINVAL, "%s: byteLength %lld, but it holds %zu bytes", where,
				    len, b->len);
		b->len = (size_t)len;
	}
	return 0;
}

/* ---- accessors ------------------------------------------------------------------------ */

static double component(const uint8_t *p, int type, bool normalized)
{
	float f;
	int16_t s;
	uint16_t us;

	switch (type) {
	case 5126:
		memcpy(&f, p, 4);
		return f;
	case 5120:
		return normalized ? fmax((int8_t)p[0] / 127.0, -1.0) : (int8_t)p[0];
	case 5121:
		return normalized ? p[0] / 255.0 : p[0];
	case 5122:
		memcpy(&s, p, 2);
		return normalized ? fmax(s / 32767.0, -1.0) : s;
	default: /* 5123 */
		memcpy(&us, p, 2);
		return normalized ? us / 65535.0 : us;
	}
}

/* Accessor idx as doubles: count elements of dim components, which the
 * caller requires. */
static int accessor(struct rd *r, long long idx, uint32_t dim, bool float_only, double **out,
		    uint32_t *count)
{
	static const char *const types[] = { NULL, "SCALAR", NULL, "VEC3", "VEC4" };
	size_t nacc, nviews;
	json_t *acc = array_of(r, "accessors", &nacc), *views = array_of(r, "bufferViews", &nviews);
	json_t *a, *view, *t;
	char where[48];
	long long bv, boff, cnt, voff, vlen, stride, vbuf;
	int ctype, csize, err;
	bool norm;
	size_t esize, i, k;
	const uint8_t *base;

	snprintf(where, sizeof(where), "/accessors/%lld", idx);
	if (idx < 0 || (size_t)idx >= nacc || !json_is_object(a = json_array_get(acc, (size_t)idx)))
		return fail(r, -EINVAL, "%s: no such accessor", where);
	if (json_object_get(a, "sparse"))
		return fail(r, -EINVAL, "%s: sparse accessors are not supported", where);
	t = json_object_get(a, "type");
	if (!json_is_string(t) || !types[dim] || strcmp(json_string_value(t), types[dim]))
		return fail(r, -EINVAL, "%s/type: expected %s", where, types[dim] ? types[dim] : "?");
	t = json_object_get(a, "componentType");
	ctype = json_is_integer(t) ? (int)json_integer_value(t) : 0;
	norm = json_is_true(json_object_get(a, "normalized"));
	if (ctype != 5126 && (float_only || !norm || ctype < 5120 || ctype > 5123))
		return fail(r, -EINVAL, "%s/componentType: expected float (5126)%s", where,
			    float_only ? "" : " or a normalized integer type");
	csize = ctype == 5126 ? 4 : ctype >= 5122 ? 2 : 1;
	err = get_size(r, a, "count", -1, where, &cnt);
	if (!err)
		err = get_size(r, a, "byteOffset", 0, where, &boff);
	if (!err)
		err = get_index(r, a, "bufferView", nviews, true, where, &bv);
	if (err)
		return err;
	if (cnt < 1 || cnt > (1 << 26))
		return fail(r, -EINVAL, "%s/count: %lld elements (1 to 2^26)", where, cnt);
	view = json_array_get(views, (size_t)bv);
	snprintf(where, sizeof(where), "/bufferViews/%lld", bv);
	if (!json_is_object(view))
		return fail(r, -EINVAL, "%s: not an object", where);
	err = get_index(r, view, "buffer", r->nbufs, true, where, &vbuf);
	if (!err)
		err = get_size(r, view, "byteOffset", 0, where, &voff);
	if (!err)
		err = get_size(r, view, "byteLength", -1, where, &vlen);
	if (!err)
		err = get_size(r, view, "byteStride", 0, where, &stride);
	if (err)
		return err;
	if ((size_t)(voff + vlen) > r->bufs[vbuf].len)
		return fail(r, -EINVAL, "%s: bytes %lld to %lld pass the end of buffer %lld (%zu bytes)",
			    where, voff, voff + vlen, vbuf, r->bufs[vbuf].len);
	esize = (size_t)csize * dim;
	if (!stride)
		stride = (long long)esize;
	if ((size_t)stride < esize)
		return fail(r, -EINVAL, "%s/byteStride: %lld, below the element's %zu bytes", where,
			    stride, esize);
	if (boff + stride * (cnt - 1) + (long long)esize > vlen)
		return fail(r, -EINVAL,
			    "/accessors/%lld: %lld elements of %zu bytes from byte %lld pass the end of bufferView %lld (%lld bytes)",
			    idx, cnt, esize, boff, bv, vlen);
	if (boff % csize || voff % csize)
		return fail(r, -EINVAL, "/accessors/%lld: its data is not aligned to %d bytes", idx,
			    csize);
	base = r->bufs[vbuf].data + voff + boff;
	*out = malloc((size_t)cnt * dim * sizeof(double));
	if (!*out)
		return -ENOMEM;
	for (i = 0; i < (size_t)cnt; i++)
		for (k = 0; k < dim; k++) {
			const uint8_t *p = base + i * (size_t)stride + k * (size_t)csize;
			double v = component(p, ctype, norm);

			if (!isfinite(v)) {
				free(*out);
				*out = NULL;
				return fail(r, -EINVAL, "/accessors/%lld: element %zu is %s", idx, i,
					    isnan(v) ? "NaN" : "infinite");
			}
			(*out)[i * dim + k] = v;
		}
	*count = (uint32_t)cnt;
	return 0;
}

/* ---- nodes ----------------------------------------------------------------------------- */

static int read_nodes(struct rd *r, struct gltf *g)
{
	size_t n, i, k;
	json_t *a = array_of(r, "nodes", &n);
	char where[48];
	bool present;
	int err;

	g->nodes = calloc(n ? n : 1, sizeof(*g->nodes));
	if (!g->nodes)
		return -ENOMEM;
	g->nnodes = (uint32_t)n;
	for (i = 0; i < n; i++) {
		g->nodes[i].parent = -1;
		g->nodes[i].r[3] = 1;
		g->nodes[i].s[0] = g->nodes[i].s[1] = g->nodes[i].s[2] = 1;
	}
	for (i = 0; i < n; i++) {
		json_t *o = json_array_get(a, i), *name, *ch;
		struct gltf_node *nd = &g->nodes[i];

		snprintf(where, sizeof(where), "/nodes/%zu", i);
		if (!json_is_object(o))
			return fail(r, -EINVAL, "%s: not an object", where);
		name = json_object_get(o, "name");
		if (name && json_is_string(name) && !(nd->name = strdup(json_string_value(name))))
			return -ENOMEM;
		err = get_numbers(r, o, "matrix", 16, where, nd->matrix, &nd->has_matrix);
		if (!err)
			err = get_numbers(r, o, "translation", 3, where, nd->t, &present);
		if (!err)
			err = get_numbers(r, o, "rotation", 4, where, nd->r, &present);
		if (!err)
			err = get_numbers(r, o, "scale", 3, where, nd->s, &present);
		if (err)
			return err;
		ch = json_object_get(o, "children");
		if (ch && !json_is_array(ch))
			return fail(r, -EINVAL, "%s/children: not an array", where);
		for (k = 0; ch && k < json_array_size(ch); k++) {
			json_t *c = json_array_get(ch, k);
			long long ci = json_is_integer(c) ? json_integer_value(c) : -1;

			if (ci < 0 || (size_t)ci >= n)
				return fail(r, -EINVAL, "%s/children/%zu: not a node's index", where, k);
			if (g->nodes[ci].parent >= 0)
				return fail(r, -EINVAL,
					    "%s/children/%zu: node %lld is already a child of node %d",
					    where, k, ci, g->nodes[ci].parent);
			g->nodes[ci].parent = (int32_t)i;
		}
	}
	/* a node that is its own ancestor: a walk up longer than the nodes */
	for (i = 0; i < n; i++) {
		int32_t p = g->nodes[i].parent;

		for (k = 0; p >= 0 && k <= n; k++)
			p = g->nodes[p].parent;
		if (p >= 0)
			return fail(r, -EINVAL, "/nodes/%zu: the node is its own ancestor (its children make a cycle)",
				    i);
	}
	return 0;
}

/* ---- the animation ---------------------------------------------------------------------- */

static int choose_anim(struct rd *r, struct gltf *g, const char *want, json_t **anim)
{
	size_t n, i;
	json_t *a = array_of(r, "animations", &n);
	char *end;
	long idx;

	g->nanims = (uint32_t)n;
	*anim = NULL;
	if (!want) {
		*anim = n ? json_array_get(a, 0) : NULL;
		g->anim_index = 0;
		goto found;
	}
	for (i = 0; i < n; i++) {
		json_t *nm = json_object_get(json_array_get(a, i), "name");

		if (json_is_string(nm) && !strcmp(json_string_value(nm), want)) {
			*anim = json_array_get(a, i);
			g->anim_index = (uint32_t)i;
			goto found;
		}
	}
	idx = strtol(want, &end, 10);
	if (*want && !*end && idx >= 0 && (size_t)idx < n) {
		*anim = json_array_get(a, (size_t)idx);
		g->anim_index = (uint32_t)idx;
		goto found;
	}
	return fail(r, -EINVAL, "/animations: no animation named or numbered '%s' (the file has %zu)",
		    want, n);
found:
	if (*anim) {
		json_t *nm = json_object_get(*anim, "name");

		if (!json_is_object(*anim))
			return fail(r, -EINVAL, "/animations/%u: not an object", g->anim_index);
		if (json_is_string(nm) && !(g->anim_name = strdup(json_string_value(nm))))
			return -ENOMEM;
	}
	return 0;
}

static int read_channel(struct rd *r, struct gltf *g, json_t *anim, size_t ci, json_t *samplers,
			size_t nsamp, struct gltf_channel *c, bool *skip)
{
	static const char *const interps[] = { "STEP", "LINEAR", "CUBICSPLINE" };
	json_t *ch = json_array_get(json_object_get(anim, "channels"), ci), *target, *path, *s, *in;
	char where[64];
	long long si, node, ii, oi;
	uint32_t nin, nout, per;
	int err, k;

	*skip = false;
	snprintf(where, sizeof(where), "/animations/%u/channels/%zu", g->anim_index, ci);
	if (!json_is_object(ch))
		return fail(r, -EINVAL, "%s: not an object", where);
	err = get_index(r, ch, "sampler", nsamp, true, where, &si);
	if (err)
		return err;
	target = json_object_get(ch, "target");
	if (!json_is_object(target))
		return fail(r, -EINVAL, "%s/target: not an object", where);
	strcat(where, "/target");
	err = get_index(r, target, "node", g->nnodes, false, where, &node);
	if (err)
		return err;
	path = json_object_get(target, "path");
	if (!json_is_string(path))
		return fail(r, -EINVAL, "%s/path: not a string", where);
	if (!strcmp(json_string_value(path), "weights") || node < 0) {
		g->nweights++;
		*skip = true;
		return 0;
	}
	if (!strcmp(json_string_value(path), "translation"))
		c->path = GLTF_T;
	else if (!strcmp(json_string_value(path), "rotation"))
		c->path = GLTF_R;
	else if (!strcmp(json_string_value(path), "scale"))
		c->path = GLTF_S;
	else
		return fail(r, -EINVAL, "%s/path: '%s' is not translation, rotation, scale or weights",
			    where, json_string_value(path));
	if (g->nodes[node].has_matrix)
		return fail(r, -EINVAL, "%s/node: node %lld has a matrix, which cannot be animated",
			    where, node);
	c->node = (int32_t)node;
	c->dim = c->path == GLTF_R ? 4 : 3;
	snprintf(where, sizeof(where), "/animations/%u/samplers/%lld", g->anim_index, si);
	s = json_array_get(samplers, (size_t)si);
	if (!json_is_object(s))
		return fail(r, -EINVAL, "%s: not an object", where);
	in = json_object_get(s, "interpolation");
	c->interp = GLTF_LINEAR;
	if (in) {
		for (k = 0; k < 3; k++)
			if (json_is_string(in) && !strcmp(json_string_value(in), interps[k]))
				break;
		if (k == 3)
			return fail(r, -EINVAL, "%s/interpolation: not STEP, LINEAR or CUBICSPLINE",
				    where);
		c->interp = (enum gltf_interp)k;
	}
	err = get_index(r, s, "input", (size_t)1 << 31, true, where, &ii);
	if (!err)
		err = get_index(r, s, "output", (size_t)1 << 31, true, where, &oi);
	if (!err)
		err = accessor(r, ii, 1, true, &c->time, &nin);
	if (!err)
		err = accessor(r, oi, c->dim, false, &c->v, &nout);
	if (err)
		return err;
	per = c->interp == GLTF_CUBIC ? 3 : 1;
	if ((uint64_t)nout != (uint64_t)nin * per)
		return fail(r, -EINVAL, "%s: %u outputs for %u inputs (expected %u)", where, nout, nin,
			    nin * per);
	for (k = 0; (uint32_t)k < nin; k++)
		if (c->time[k] < 0 || (k && !(c->time[k] > c->time[k - 1])))
			return fail(r, -EINVAL,
				    "/accessors/%lld: key time %.9g at %d is %s (times are seconds, from 0, strictly increasing)",
				    ii, c->time[k], k, c->time[k] < 0 ? "negative" : "not after the one before");
	c->n = nin;
	return 0;
}

static int read_anim(struct rd *r, struct gltf *g, const char *want)
{
	json_t *anim, *chs, *samplers;
	size_t n, nsamp, i, j;
	int err = choose_anim(r, g, want, &anim);

	if (err || !anim)
		return err;
	chs = json_object_get(anim, "channels");
	samplers = json_object_get(anim, "samplers");
	if (!json_is_array(chs) || !json_is_array(samplers))
		return fail(r, -EINVAL, "/animations/%u: 'channels' and 'samplers' must be arrays",
			    g->anim_index);
	n = json_array_size(chs);
	nsamp = json_array_size(samplers);
	g->channels = calloc(n ? n : 1, sizeof(*g->channels));
	if (!g->channels)
		return -ENOMEM;
	for (i = 0; i < n; i++) {
		struct gltf_channel *c = &g->channels[g->nchannels];
		bool skip;

		err = read_channel(r, g, anim, i, samplers, nsamp, c, &skip);
		if (err) {
			free(c->time);
			free(c->v);
			memset(c, 0, sizeof(*c));
			return err;
		}
		if (skip)
			continue;
		for (j = 0; j < g->nchannels; j++)
			if (g->channels[j].node == c->node && g->channels[j].path == c->path) {
				free(c->time);
				free(c->v);
				memset(c, 0, sizeof(*c));
				return fail(r, -EINVAL,
					    "/animations/%u/channels/%zu: node %d's %s is animated twice",
					    g->anim_index, i, g->channels[j].node,
					    g->channels[j].path == GLTF_T ? "translation" :
					    g->channels[j].path == GLTF_R ? "rotation" : "scale");
			}
		g->nchannels++;
	}
	return 0;
}

/* ---- the file ------------------------------------------------------------------------------ */

static uint32_t le32(const uint8_t *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The JSON chunk (and BIN) of a .glb. */
static int glb(struct rd *r, const uint8_t *buf, size_t len, const char **json, size_t *jlen)
{
	uint32_t total, clen;

	if (len < 20)
		return fail(r, -EINVAL, "a .glb of %zu bytes is shorter than its header", len);
	total = le32(buf + 8);
	if (le32(buf + 4) != 2)
		return fail(r, -EINVAL, "glb version %u, not 2", le32(buf + 4));
	if (total > len)
		return fail(r, -EINVAL, "the .glb says %u bytes but has %zu (truncated)", total, len);
	clen = le32(buf + 12);
	if (le32(buf + 16) != 0x4E4F534Au || clen > total - 20)
		return fail(r, -EINVAL, "the .glb's first chunk is not JSON within the file");
	*json = (const char *)buf + 20;
	*jlen = clen;
	if ((size_t)20 + clen + 8 <= total) {
		const uint8_t *c = buf + 20 + clen;
		uint32_t blen = le32(c);

		if (le32(c + 4) != 0x004E4942u || blen > total - 28 - clen)
			return fail(r, -EINVAL, "the .glb's second chunk is not BIN within the file");
		r->bin = c + 8;
		r->binlen = blen;
	}
	return 0;
}

static void count_ignored(struct rd *r, struct gltf *g)
{
	size_t n;

	array_of(r, "meshes", &n);
	g->nmeshes = (uint32_t)n;
	array_of(r, "cameras", &n);
	g->ncameras = (uint32_t)n;
	array_of(r, "skins", &n);
	g->nskins = (uint32_t)n;
	array_of(r, "materials", &n);
	g->nmaterials = (uint32_t)n;
}

int gltf_read(struct gltf *g, const char *path, const uint8_t *buf, size_t len,
	      const char *anim, char *err, size_t errsize)
{
	struct rd r = { .path = path, .err = err, .errsize = errsize };
	const char *json = (const char *)buf;
	size_t jlen = len, i;
	json_error_t je;
	json_t *ver;
	int rc = 0;

	memset(g, 0, sizeof(*g));
	if (len >= 4 && !memcmp(buf, "glTF", 4))
		rc = glb(&r, buf, len, &json, &jlen);
	if (rc)
		return rc;
	r.root = json_loadb(json, jlen, JSON_REJECT_DUPLICATES, &je);
	if (!r.root)
		return fail(&r, -EINVAL, "not valid JSON: line %d column %d: %s", je.line,
			    je.column, je.text);
	if (!json_is_object(r.root)) {
		rc = fail(&r, -EINVAL, "/: not a JSON object");
		goto out;
	}
	ver = json_object_get(json_object_get(r.root, "asset"), "version");
	if (!json_is_string(ver) || strncmp(json_string_value(ver), "2.", 2)) {
		rc = fail(&r, -EINVAL, "/asset/version: not a glTF 2.x file");
		goto out;
	}
	rc = load_buffers(&r);
	if (!rc)
		rc = read_nodes(&r, g);
	if (!rc)
		rc = read_anim(&r, g, anim);
	if (!rc)
		count_ignored(&r, g);
out:
	for (i = 0; i < r.nbufs; i++)
		if (r.bufs[i].owned)
			free(r.bufs[i].data);
	free(r.bufs);
	json_decref(r.root);
	if (rc) {
		if (rc == -ENOMEM)
			snprintf(err, errsize, "out of memory");
		gltf_free(g);
	}
	return rc;
}

void gltf_free(struct gltf *g)
{
	uint32_t i;

	for (i = 0; i < g->nnodes; i++)
		free(g->nodes[i].name);
	for (i = 0; i < g->nchannels; i++) {
		free(g->channels[i].time);
		free(g->channels[i].v);
	}
	free(g->nodes);
	free(g->channels);
	free(g->anim_name);
	memset(g, 0, sizeof(*g));
}
