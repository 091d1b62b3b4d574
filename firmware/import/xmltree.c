/* SPDX-License-Identifier: MIT */
/* xmltree.c - XML elements as a tree with expat (see xmltree.h). */
#include "xmltree.h"

#include <errno.h>
#include <expat.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Deeper nesting than any URDF has is refused, so that nothing recurses or
 * allocates without bound on a hostile file. */
#define MAX_DEPTH 64

struct build {
	XML_Parser p;
	struct xel *root, *all;
	struct xel *stack[MAX_DEPTH];
	struct xel *last[MAX_DEPTH]; /* the last child of each open element */
	int depth;
	int fault;                   /* -ENOMEM, -EINVAL (too deep) */
};

static void on_start(void *ud, const XML_Char *name, const XML_Char **atts)
{
	struct build *b = ud;
	struct xel *e;
	size_t n = 0, k;

	if (b->fault)
		return;
	if (b->depth == MAX_DEPTH) {
		b->fault = -E2BIG;
		XML_StopParser(b->p, XML_FALSE);
		return;
	}
	while (atts[n])
		n++;
	e = calloc(1, sizeof(*e));
	if (!e || !(e->attr = calloc(n + 1, sizeof(char *))) || !(e->name = strdup(name))) {
		if (e) {
			free(e->attr);
			free(e);
		}
		b->fault = -ENOMEM;
		XML_StopParser(b->p, XML_FALSE);
		return;
	}
	e->all = b->all;
	b->all = e;
	for (k = 0; k < n; k++)
		if (!(e->attr[k] = strdup(atts[k]))) {
			b->fault = -ENOMEM;
			XML_StopParser(b->p, XML_FALSE);
			return;
		}
	e->line = (long)XML_GetCurrentLineNumber(b->p);
	if (b->depth == 0)
		b->root = e;
	else if (b->last[b->depth - 1])
		b->last[b->depth - 1]->next = e;
	else
		b->stack[b->depth - 1]->first = e;
	if (b->depth > 0)
		b->last[b->depth - 1] = e;
	b->stack[b->depth] = e;
	b->last[b->depth] = NULL;
	b->depth++;
}

static void on_end(void *ud, const XML_Char *name)
{
	struct build *b = ud;

	(void)name;
	if (!b->fault && b->depth > 0)
		b->depth--;
}

static void free_all(struct xel *e)
{
	while (e) {
		struct xel *n = e->all;
		size_t k;

		for (k = 0; e->attr && e->attr[k]; k++)
			free(e->attr[k]);
		free(e->attr);
		free(e->name);
		free(e);
		e = n;
	}
}

int xml_parse(struct xml_doc *d, const char *buf, size_t len, char *err, size_t errsize)
{
	struct build b;
	enum XML_Status st;

	memset(&b, 0, sizeof(b));
	d->root = d->all = NULL;
	if (len > INT_MAX) {
		snprintf(err, errsize, "too large for an XML file (%zu bytes)", len);
		return -EINVAL;
	}
	b.p = XML_ParserCreate(NULL);
	if (!b.p)
		return -ENOMEM;
	XML_SetUserData(b.p, &b);
	XML_SetElementHandler(b.p, on_start, on_end);
	st = XML_Parse(b.p, buf, (int)len, XML_TRUE);
	if (b.fault == -E2BIG)
		snprintf(err, errsize, "line %lu: elements nested more than %d deep",
			 (unsigned long)XML_GetCurrentLineNumber(b.p), MAX_DEPTH);
	else if (!b.fault && st != XML_STATUS_OK)
		snprintf(err, errsize, "line %lu: not well-formed XML: %s",
			 (unsigned long)XML_GetCurrentLineNumber(b.p),
			 XML_ErrorString(XML_GetErrorCode(b.p)));
	XML_ParserFree(b.p);
	if (st != XML_STATUS_OK || b.fault || !b.root) {
		free_all(b.all);
		if (b.fault == -ENOMEM)
			return -ENOMEM;
		if (!b.fault && st == XML_STATUS_OK)
			snprintf(err, errsize, "line 1: no element");
		return -EINVAL;
	}
	d->root = b.root;
	d->all = b.all;
	return 0;
}

void xml_free(struct xml_doc *d)
{
	free_all(d->all);
	d->root = d->all = NULL;
}

const char *xml_attr(const struct xel *e, const char *name)
{
	size_t k;

	for (k = 0; e->attr[k] && e->attr[k + 1]; k += 2)
		if (!strcmp(e->attr[k], name))
			return e->attr[k + 1];
	return NULL;
}

struct xel *xml_child(const struct xel *e, const char *name)
{
	struct xel *c;

	for (c = e->first; c; c = c->next)
		if (!strcmp(c->name, name))
			return c;
	return NULL;
}
