/* SPDX-License-Identifier: MIT */
/*
 * load.c - a scene file from bytes to a struct scene_desc: the YAML document,
 * its top-level sections, and the names they share (see load.h).
 */
#include "load_priv.h"
#include "scene/sha256.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const top_keys[] = { "scene",      "timing",  "nodes",   "strands",
					"camera",     "cycles",  "attributes", "surfaces",
					"particles",  "flocks",  "aims",    "devices",
					"outputs",    "triggers", "inputs",  "boards",
					"lockstep",   NULL };
enum { T_SCENE, T_TIMING, T_NODES, T_STRANDS, T_CAMERA, T_CYCLES, T_ATTRS, T_SURFACES,
       T_PARTICLES, T_FLOCKS, T_AIMS, T_DEVICES, T_OUTPUTS, T_TRIGGERS, T_INPUTS, T_BOARDS,
       T_LOCKSTEP, T_COUNT };

static int yaml_error(struct ld *l, const yaml_parser_t *p)
{
	struct ld_mark m = { (uint32_t)p->problem_mark.line + 1,
			     (uint32_t)p->problem_mark.column + 1 };

	if (p->error == YAML_MEMORY_ERROR)
		return ld_nomem(l);
	if (p->context)
		return ld_fail_at(l, m, -EBADMSG, "not valid YAML: %s %s",
				  p->problem ? p->problem : "error", p->context);
	return ld_fail_at(l, m, -EBADMSG, "not valid YAML: %s", p->problem ? p->problem : "error");
}

/* The name of anything before system or aim i that a channel name begins
 * with, or NULL. */
static const char *taken(struct ld *l, const char *name, uint32_t sys, uint32_t aim)
{
	const struct scene_desc *d = l->d;
	uint32_t j;

	if (ld_find_node(l, name, strlen(name)) >= 0)
		return "a node";
	if (!strcmp(name, "camera"))
		return "the camera";
	for (j = 0; j < d->ncycles; j++)
		if (!strcmp(name, d->cycles[j].name))
			return "a cycle";
	for (j = 0; j < d->nattrs; j++)
		if (!strcmp(name, d->attrs[j].name))
			return "an attribute";
	for (j = 0; j < sys && j < d->nsys; j++)
		if (!strcmp(name, sd_sys_name(&d->sys[j])))
			return "a system";
	for (j = 0; j < aim; j++)
		if (!strcmp(name, d->aims[j].name))
			return "an aim";
	return NULL;
}

/* Systems and aims share the channels' namespace too. */
static int unique_sys_names(struct ld *l)
{
	const struct scene_desc *d = l->d;
	const char *what;
	uint32_t i;

	for (i = 0; i < d->nsys; i++)
		if ((what = taken(l, sd_sys_name(&d->sys[i]), i, 0)))
			return ld_fail_at(l, l->mk->sys[i], -EINVAL,
					  "system name '%s' is already the name of %s",
					  sd_sys_name(&d->sys[i]), what);
	for (i = 0; i < d->naims; i++)
		if ((what = taken(l, d->aims[i].name, d->nsys, i)))
			return ld_fail_at(l, l->mk->aim[i], -EINVAL,
					  "aim name '%s' is already the name of %s", d->aims[i].name,
					  what);
	return 0;
}

/* Node, cycle and attribute names are channel prefixes: one namespace. */
static int unique_names(struct ld *l)
{
	const struct scene_desc *d = l->d;
	uint32_t i, j;

	for (i = 0; i < d->ncycles; i++) {
		const char *name = d->cycles[i].name;
		int node = ld_find_node(l, name, strlen(name));

		if (node >= 0 || !strcmp(name, "camera"))
			return ld_fail_at(l, l->mk->cycle[i], -EINVAL,
					  "cycle name '%s' is already the name of %s", name,
					  node >= 0 ? "a node" : "the camera");
		for (j = 0; j < i; j++)
			if (!strcmp(name, d->cycles[j].name))
				return ld_fail_at(l, l->mk->cycle[i], -EINVAL,
						  "duplicate cycle name '%s' (first at line %u)",
						  name, l->mk->cycle[j].line);
	}
	for (i = 0; i < d->nattrs; i++) {
		const char *name = d->attrs[i].name;
		int node = ld_find_node(l, name, strlen(name));

		if (node >= 0 || !strcmp(name, "camera"))
			return ld_fail_at(l, l->mk->attr[i].at, -EINVAL,
					  "attribute name '%s' is already the name of %s", name,
					  node >= 0 ? "a node" : "the camera");
		for (j = 0; j < d->ncycles; j++)
			if (!strcmp(name, d->cycles[j].name))
				return ld_fail_at(l, l->mk->attr[i].at, -EINVAL,
						  "attribute name '%s' is already the name of a cycle (line %u)",
						  name, l->mk->cycle[j].line);
		for (j = 0; j < i; j++)
			if (!strcmp(name, d->attrs[j].name))
				return ld_fail_at(l, l->mk->attr[i].at, -EINVAL,
						  "duplicate attribute name '%s' (first at line %u)",
						  name, l->mk->attr[j].at.line);
	}
	if (ld_find_node(l, "camera", 6) >= 0)
		return ld_fail_at(l, l->mk->node[ld_find_node(l, "camera", 6)].at, -EINVAL,
				  "'camera' names the camera's channels; call the node something else");
	return unique_sys_names(l);
}

static int sections(struct ld *l, yaml_node_t *root)
{
	yaml_node_t *v[T_COUNT];
	int err;

	l->mk->root = ld_mark_of(root);
	err = ld_map_req(l, root, "the scene", top_keys, v, YML_REQ(T_TIMING));
	if (err)
		return err;
	l->d->name = "";
	if (v[T_SCENE]) {
		err = ld_str(l, v[T_SCENE], &l->d->name);
		if (err)
			return err;
	}
	err = ld_timing(l, v[T_TIMING]);
	if (!err && v[T_NODES])
		err = ld_nodes(l, v[T_NODES]);
	if (err)
		return err;
	l->strand = pool_array(l->pool, l->d->nnodes ? l->d->nnodes : 1, sizeof(*l->strand));
	if (!l->strand)
		return ld_nomem(l);
	if (v[T_STRANDS])
		err = ld_strands(l, v[T_STRANDS]);
	if (!err)
		err = ld_mimics(l);
	if (!err && v[T_CAMERA])
		err = ld_camera(l, v[T_CAMERA]);
	if (!err && v[T_CYCLES])
		err = ld_cycles(l, v[T_CYCLES]);
	if (!err && v[T_ATTRS])
		err = ld_attributes(l, v[T_ATTRS]);
	if (!err && v[T_SURFACES])
		err = ld_systems(l, v[T_SURFACES], SD_SURFACE);
	if (!err && v[T_PARTICLES])
		err = ld_systems(l, v[T_PARTICLES], SD_PARTICLES);
	if (!err && v[T_FLOCKS])
		err = ld_systems(l, v[T_FLOCKS], SD_FLOCK);
	if (!err && v[T_AIMS])
		err = ld_aims(l, v[T_AIMS]);
	if (!err)
		err = unique_names(l);
	if (!err) {
		/* the rig refers to the scene's channels: read it last */
		struct ld_rig_sections rs = { v[T_DEVICES], v[T_OUTPUTS], v[T_TRIGGERS],
					      v[T_INPUTS] };

		err = ld_rig(l, &rs);
	}
	if (!err)
		err = ld_boards(l, v[T_BOARDS], v[T_LOCKSTEP], v[T_DEVICES]);
	return err;
}

/* The document, then a check that nothing follows it: a second document,
 * or the broken rest of a truncated one, is an error too. */
static int parse_doc(struct ld *l, yaml_parser_t *p, yaml_document_t *doc)
{
	yaml_document_t extra;
	yaml_node_t *root;
	int err;

	if (!yaml_parser_load(p, doc))
		return yaml_error(l, p);
	root = yaml_document_get_root_node(doc);
	if (!root) {
		yaml_document_delete(doc);
		return ld_fail_at(l, (struct ld_mark){ 1, 1 }, -EINVAL,
				  "empty scene file (expected a mapping with timing, nodes, strands)");
	}
	if (!yaml_parser_load(p, &extra)) {
		yaml_document_delete(doc);
		return yaml_error(l, p);
	}
	if (yaml_document_get_root_node(&extra)) {
		struct ld_mark m = ld_mark_of(yaml_document_get_root_node(&extra));

		yaml_document_delete(&extra);
		yaml_document_delete(doc);
		return ld_fail_at(l, m, -EINVAL, "a scene file holds one YAML document");
	}
	yaml_document_delete(&extra);
	l->y.doc = doc;
	err = sections(l, root);
	yaml_document_delete(doc);
	l->y.doc = NULL;
	return err;
}

int scene_file_parse(struct scene_file *sf, const char *path, const char *buf, size_t len,
		     struct load_err *err)
{
	struct scene_desc d;
	struct sf_marks *mk;
	yaml_parser_t p;
	yaml_document_t doc;
	struct ld l;
	int rc;

	memset(sf, 0, sizeof(*sf));
	memset(err, 0, sizeof(*err));
	memset(&d, 0, sizeof(d));
	pool_init(&sf->pool);
	if (len > LOAD_MAX_BYTES) {
		err->code = -EFBIG;
		snprintf(err->msg, sizeof(err->msg), "larger than %u MiB: not a scene file",
			 LOAD_MAX_BYTES >> 20);
		return err->code;
	}
	mk = pool_alloc(&sf->pool, sizeof(*mk));
	memset(&l, 0, sizeof(l));
	ld_init(&l, &sf->pool);
	l.sf = sf;
	l.d = &d;
	l.mk = mk;
	l.err = err;
	if (!mk) {
		err->code = -ENOMEM;
		snprintf(err->msg, sizeof(err->msg), "out of memory");
		return err->code;
	}
	if (!yaml_parser_initialize(&p)) {
		pool_free(&sf->pool);
		err->code = -ENOMEM;
		snprintf(err->msg, sizeof(err->msg), "out of memory");
		return err->code;
	}
	yaml_parser_set_input_string(&p, (const unsigned char *)buf, len);
	rc = parse_doc(&l, &p, &doc);
	yaml_parser_delete(&p);
	if (rc) {
		pool_free(&sf->pool);
		memset(sf, 0, sizeof(*sf));
		return rc;
	}
	sf->desc = d;
	sha256(sf->digest, buf, len);
	sf->path = pool_strndup(&sf->pool, path, strlen(path));
	sf->strand = l.strand;
	sf->marks = mk;
	if (!sf->path) {
		pool_free(&sf->pool);
		memset(sf, 0, sizeof(*sf));
		err->code = -ENOMEM;
		snprintf(err->msg, sizeof(err->msg), "out of memory");
		return err->code;
	}
	return 0;
}

int scene_file_load(struct scene_file *sf, const char *path, struct load_err *err)
{
	FILE *f = fopen(path, "rb");
	size_t cap = 65536, len = 0, got;
	char *buf = NULL;
	int rc;

	memset(sf, 0, sizeof(*sf));
	memset(err, 0, sizeof(*err));
	if (!f) {
		err->code = -errno;
		snprintf(err->msg, sizeof(err->msg), "cannot open: %s", strerror(errno));
		return err->code;
	}
	for (;;) {
		char *nb;

		if (len == cap || !buf) {
			if (buf)
				cap *= 2;
			nb = realloc(buf, cap);
			if (!nb) {
				rc = -ENOMEM;
				snprintf(err->msg, sizeof(err->msg), "out of memory");
				goto out;
			}
			buf = nb;
		}
		got = fread(buf + len, 1, cap - len, f);
		len += got;
		if (got == 0)
			break;
		if (len > LOAD_MAX_BYTES) {
			rc = -EFBIG;
			snprintf(err->msg, sizeof(err->msg), "larger than %u MiB: not a scene file",
				 LOAD_MAX_BYTES >> 20);
			goto out;
		}
	}
	if (ferror(f)) {
		rc = -EIO;
		snprintf(err->msg, sizeof(err->msg), "cannot read: %s", strerror(EIO));
		goto out;
	}
	rc = scene_file_parse(sf, path, buf, len, err);
	free(buf);
	fclose(f);
	return rc;
out:
	err->code = rc;
	free(buf);
	fclose(f);
	return rc;
}

void scene_file_free(struct scene_file *sf)
{
	pool_free(&sf->pool);
	memset(sf, 0, sizeof(*sf));
}

int scene_file_node(const struct scene_file *sf, const char *name)
{
	uint32_t i;

	for (i = 0; i < sf->desc.nnodes; i++)
		if (!strcmp(sf->desc.nodes[i].name, name))
			return (int)i;
	return -1;
}
