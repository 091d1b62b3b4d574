/* SPDX-License-Identifier: MIT */
/* yedit.c - keys of a scene file edited in place (yedit.h). */
#include "yedit.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

struct ydoc {
	yaml_parser_t p;
	yaml_document_t d;
	const char *text;
	size_t len;
	yaml_node_t *strands;  /* the strands: sequence, or NULL */
	yaml_node_t *strand;   /* the node's strand mapping, or NULL */
	yaml_node_t *keys;     /* its keys: sequence, or NULL */
};

static yaml_node_t *node_at(struct ydoc *y, int i)
{
	return yaml_document_get_node(&y->d, i);
}

static yaml_node_t *map_get(struct ydoc *y, yaml_node_t *m, const char *name)
{
	yaml_node_pair_t *p;

	if (!m || m->type != YAML_MAPPING_NODE)
		return NULL;
	for (p = m->data.mapping.pairs.start; p < m->data.mapping.pairs.top; p++) {
		yaml_node_t *k = node_at(y, p->key);

		if (k && k->type == YAML_SCALAR_NODE && !strcmp((char *)k->data.scalar.value, name))
			return node_at(y, p->value);
	}
	return NULL;
}

static bool scalar_num(yaml_node_t *n, double *v)
{
	char *end;

	if (!n || n->type != YAML_SCALAR_NODE)
		return false;
	*v = strtod((char *)n->data.scalar.value, &end);
	return end != (char *)n->data.scalar.value && !*end;
}

static int ydoc_open(struct ydoc *y, const char *text, size_t len, const char *node, char *err,
		     size_t errsize)
{
	yaml_node_t *root, *item;
	yaml_node_item_t *it;

	memset(y, 0, sizeof(*y));
	y->text = text;
	y->len = len;
	if (!yaml_parser_initialize(&y->p)) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	yaml_parser_set_input_string(&y->p, (const unsigned char *)text, len);
	if (!yaml_parser_load(&y->p, &y->d)) {
		snprintf(err, errsize, "the scene is not valid YAML");
		yaml_parser_delete(&y->p);
		return -EBADMSG;
	}
	root = yaml_document_get_root_node(&y->d);
	if (!strcmp(node, "camera")) {
		/* the camera's keys: camera: {keys: [...]}, a strand of its own */
		y->strand = map_get(y, root, "camera");
		y->keys = map_get(y, y->strand, "keys");
		if (y->keys && y->keys->type != YAML_SEQUENCE_NODE)
			y->keys = NULL;
		return 0;
	}
	y->strands = map_get(y, root, "strands");
	if (y->strands && y->strands->type != YAML_SEQUENCE_NODE)
		y->strands = NULL;
	for (it = y->strands ? y->strands->data.sequence.items.start : NULL;
	     it && it < y->strands->data.sequence.items.top; it++) {
		yaml_node_t *name;

		item = node_at(y, *it);
		name = map_get(y, item, "node");
		if (name && name->type == YAML_SCALAR_NODE &&
		    !strcmp((char *)name->data.scalar.value, node)) {
			y->strand = item;
			y->keys = map_get(y, item, "keys");
			if (y->keys && y->keys->type != YAML_SEQUENCE_NODE)
				y->keys = NULL;
			break;
		}
	}
	return 0;
}

static void ydoc_close(struct ydoc *y)
{
	yaml_document_delete(&y->d);
	yaml_parser_delete(&y->p);
}

/* text with [a, b) replaced by rep */
static int splice(const char *text, size_t len, size_t a, size_t b, const char *rep, char **out,
		  size_t *outlen, char *err, size_t errsize)
{
	size_t r = strlen(rep), n = len - (b - a) + r;
	char *s = malloc(n + 1);

	if (!s) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	memcpy(s, text, a);
	memcpy(s + a, rep, r);
	memcpy(s + a + r, text + b, len - b);
	s[n] = 0;
	*out = s;
	*outlen = n;
	return 0;
}

static size_t line_start(const char *t, size_t i)
{
	while (i > 0 && t[i - 1] != '\n')
		i--;
	return i;
}

static size_t line_end(const char *t, size_t len, size_t i)
{
	while (i < len && t[i] != '\n')
		i++;
	return i;
}

/* Where an item's text really ends: a block collection's end mark may lie
 * at the next token, past blank lines and comments. */
static size_t item_end(const char *t, yaml_node_t *n)
{
	size_t e = n->end_mark.index, s = n->start_mark.index;

	if (n->type == YAML_SCALAR_NODE || (n->type == YAML_MAPPING_NODE &&
					    n->data.mapping.style == YAML_FLOW_MAPPING_STYLE))
		return e;
	while (e > s && (t[e - 1] == ' ' || t[e - 1] == '\n' || t[e - 1] == '\t'))
		e--;
	return e;
}

static void fmt_num(char *buf, size_t size, double v)
{
	snprintf(buf, size, "%.10g", v == 0 ? 0 : v);
}

/* The index of the key at frame f in y->keys (or -1), and of the first
 * key after it (*after: nkeys when none). */
static int find_key(struct ydoc *y, double f, int *after)
{
	yaml_node_item_t *it;
	int i = 0;

	*after = 0;
	if (!y->keys)
		return -1;
	for (it = y->keys->data.sequence.items.start; it < y->keys->data.sequence.items.top;
	     it++, i++) {
		double kf;

		if (!scalar_num(map_get(y, node_at(y, *it), "frame"), &kf))
			continue;
		if (kf == f)
			return i;
		if (kf < f)
			*after = i + 1;
	}
	return -1;
}

static yaml_node_t *key_item(struct ydoc *y, int i)
{
	return node_at(y, y->keys->data.sequence.items.start[i]);
}

static int nkeys(struct ydoc *y)
{
	const yaml_node_t *k = y->keys;

	return k ? (int)(k->data.sequence.items.top - k->data.sequence.items.start) : 0;
}

/* A new strand at the end of strands: (block style). */
static int add_strand(struct ydoc *y, const char *node, const char *key, char **out,
		      size_t *outlen, char *err, size_t errsize)
{
	char rep[720], ind[64];
	yaml_node_t *last;
	size_t at, ls, k;
	int n;

	if (!y->strands) {
		/* no strands: yet: a block of its own at the end */
		at = y->len;
		snprintf(rep, sizeof(rep), "%sstrands:\n  - node: %s\n    keys:\n      - %s\n",
			 at && y->text[at - 1] != '\n' ? "\n" : "", node, key);
		return splice(y->text, y->len, at, at, rep, out, outlen, err, errsize);
	}
	if (y->strands->data.sequence.style == YAML_FLOW_SEQUENCE_STYLE) {
		snprintf(err, errsize, "strands: is a flow sequence; teach adds strands to a block "
			 "sequence only");
		return -ENOTSUP;
	}
	n = (int)(y->strands->data.sequence.items.top - y->strands->data.sequence.items.start);
	last = node_at(y, y->strands->data.sequence.items.start[n - 1]);
	ls = line_start(y->text, last->start_mark.index);
	for (k = 0; ls + k < last->start_mark.index && y->text[ls + k] != '-' && k < 60; k++)
		ind[k] = y->text[ls + k];
	ind[k] = 0;
	at = line_end(y->text, y->len, item_end(y->text, last));
	snprintf(rep, sizeof(rep), "\n%s- node: %s\n%s  keys:\n%s    - %s", ind, node, ind, ind,
		 key);
	return splice(y->text, y->len, at, at, rep, out, outlen, err, errsize);
}

int yedit_key_set(const char *text, size_t len, const char *node, const char *field,
		  double frame, double value, char **out, size_t *outlen, char *err,
		  size_t errsize)
{
	char num[40];

	fmt_num(num, sizeof(num), value);
	return yedit_key_set_text(text, len, node, field, frame, num, out, outlen, err, errsize);
}

int yedit_key_set_text(const char *text, size_t len, const char *node, const char *field,
		       double frame, const char *num, char **out, size_t *outlen, char *err,
		       size_t errsize)
{
	char key[320], fr[40], rep[720];
	struct ydoc y;
	yaml_node_t *item, *v;
	int i, after, rc;

	fmt_num(fr, sizeof(fr), frame);
	snprintf(key, sizeof(key), "{frame: %s, %s: %s}", fr, field, num);
	rc = ydoc_open(&y, text, len, node, err, errsize);
	if (rc)
		return rc;
	if (!y.strand && !strcmp(node, "camera")) {
		snprintf(err, errsize, "the scene has no camera: keys");
		rc = -ENOENT;
		goto out;
	}
	if (!y.strand) {
		rc = add_strand(&y, node, key, out, outlen, err, errsize);
		goto out;
	}
	if (!y.keys || nkeys(&y) == 0) {
		snprintf(err, errsize, "strand of '%s': keys: is not a sequence of keys", node);
		rc = -EINVAL;
		goto out;
	}
	i = find_key(&y, frame, &after);
	if (i >= 0) {
		item = key_item(&y, i);
		v = map_get(&y, item, field);
		if (v && (v->type == YAML_SCALAR_NODE ||
			  (v->type == YAML_SEQUENCE_NODE &&
			   v->data.sequence.style == YAML_FLOW_SEQUENCE_STYLE))) {
			rc = splice(text, len, v->start_mark.index, v->end_mark.index, num, out,
				    outlen, err, errsize);
		} else if (item->type == YAML_MAPPING_NODE &&
			   item->data.mapping.style == YAML_FLOW_MAPPING_STYLE) {
			/* before the closing brace */
			snprintf(rep, sizeof(rep), ", %s: %s", field, num);
			rc = splice(text, len, item->end_mark.index - 1, item->end_mark.index - 1,
				    rep, out, outlen, err, errsize);
		} else {
			yaml_node_t *f = map_get(&y, item, "frame");
			size_t at = line_end(text, len, f->end_mark.index);
			size_t ls = line_start(text, f->start_mark.index);
			int ind = (int)(f->start_mark.index - ls) - 7; /* "frame: " */

			snprintf(rep, sizeof(rep), "\n%*s%s: %s", ind > 0 ? ind : 0, "", field,
				 num);
			rc = splice(text, len, at, at, rep, out, outlen, err, errsize);
		}
		goto out;
	}
	if (y.keys->data.sequence.style == YAML_FLOW_SEQUENCE_STYLE) {
		if (after < nkeys(&y)) {
			snprintf(rep, sizeof(rep), "%s, ", key);
			item = key_item(&y, after);
			rc = splice(text, len, item->start_mark.index, item->start_mark.index, rep,
				    out, outlen, err, errsize);
		} else {
			snprintf(rep, sizeof(rep), ", %s", key);
			item = key_item(&y, after - 1);
			rc = splice(text, len, item_end(text, item), item_end(text, item), rep, out,
				    outlen, err, errsize);
		}
	} else {
		/* a line of its own, with the prefix of its neighbour's ("    - ") */
		size_t ls, at;

		item = key_item(&y, after < nkeys(&y) ? after : after - 1);
		ls = line_start(text, item->start_mark.index);
		if (after < nkeys(&y)) {
			snprintf(rep, sizeof(rep), "%.*s%s\n",
				 (int)(item->start_mark.index - ls), text + ls, key);
			at = ls;
		} else {
			snprintf(rep, sizeof(rep), "\n%.*s%s", (int)(item->start_mark.index - ls),
				 text + ls, key);
			at = line_end(text, len, item_end(text, item));
		}
		/* the prefix must be indentation and a dash only */
		if (strspn(rep + (rep[0] == '\n'), " -") != (size_t)(item->start_mark.index - ls)) {
			snprintf(err, errsize, "strand of '%s': its keys share lines with other "
				 "text; teach edits keys written one a line", node);
			rc = -ENOTSUP;
			goto out;
		}
		rc = splice(text, len, at, at, rep, out, outlen, err, errsize);
	}
out:
	ydoc_close(&y);
	return rc;
}

int yedit_key_delete(const char *text, size_t len, const char *node, double frame, char **out,
		     size_t *outlen, char *err, size_t errsize)
{
	struct ydoc y;
	yaml_node_t *item;
	size_t a, b;
	int i, after, rc;

	rc = ydoc_open(&y, text, len, node, err, errsize);
	if (rc)
		return rc;
	i = find_key(&y, frame, &after);
	if (!y.strand || i < 0) {
		snprintf(err, errsize, "'%s' has no key at frame %.10g", node, frame);
		rc = -ENOENT;
		goto out;
	}
	if (nkeys(&y) == 1) {
		snprintf(err, errsize, "frame %.10g is the only key of '%s': a strand keeps one",
			 frame, node);
		rc = -EINVAL;
		goto out;
	}
	item = key_item(&y, i);
	if (y.keys->data.sequence.style == YAML_FLOW_SEQUENCE_STYLE) {
		a = item->start_mark.index;
		b = item_end(text, item);
		if (i + 1 < nkeys(&y)) {
			b = key_item(&y, i + 1)->start_mark.index;
		} else {
			yaml_node_t *prev = key_item(&y, i - 1);

			a = item_end(text, prev);
		}
	} else {
		a = line_start(text, item->start_mark.index);
		b = line_end(text, len, item_end(text, item));
		if (b < len)
			b++;
	}
	rc = splice(text, len, a, b, "", out, outlen, err, errsize);
out:
	ydoc_close(&y);
	return rc;
}

int yedit_key_move(const char *text, size_t len, const char *node, double from, double to,
		   char **out, size_t *outlen, char *err, size_t errsize)
{
	struct ydoc y;
	yaml_node_t *f;
	char num[40];
	double lo = -INFINITY, hi = INFINITY;
	int i, after, rc;

	rc = ydoc_open(&y, text, len, node, err, errsize);
	if (rc)
		return rc;
	i = find_key(&y, from, &after);
	if (!y.strand || i < 0) {
		snprintf(err, errsize, "'%s' has no key at frame %.10g", node, from);
		rc = -ENOENT;
		goto out;
	}
	if (i > 0)
		scalar_num(map_get(&y, key_item(&y, i - 1), "frame"), &lo);
	if (i + 1 < nkeys(&y))
		scalar_num(map_get(&y, key_item(&y, i + 1), "frame"), &hi);
	if (!(to > lo && to < hi)) {
		snprintf(err, errsize, "frame %.10g is not between the neighbouring keys' (%.10g "
			 "and %.10g): keys stay in order; delete it and teach anew", to, lo, hi);
		rc = -ERANGE;
		goto out;
	}
	f = map_get(&y, key_item(&y, i), "frame");
	fmt_num(num, sizeof(num), to);
	rc = splice(text, len, f->start_mark.index, f->end_mark.index, num, out, outlen, err,
		    errsize);
out:
	ydoc_close(&y);
	return rc;
}
