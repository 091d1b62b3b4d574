/* SPDX-License-Identifier: MIT */
/*
 * xmltree.h - an XML document's elements as a tree, read with Debian's
 * expat (xmltree.c): names, attributes and the line each starts on; text
 * and comments are dropped (URDF keeps everything in attributes). expat
 * rather than libxml2: libxml2 links ICU (33 MB of shared libraries), which
 * every strand process would map and `strand play`'s mlockall would lock.
 * Not real-time.
 */
#ifndef STRAND_XMLTREE_H
#define STRAND_XMLTREE_H

#include <stddef.h>

struct xel {
	char *name;
	char **attr;        /* name, value, name, value, ..., NULL */
	long line;          /* 1-based */
	struct xel *first;  /* first child element */
	struct xel *next;   /* next sibling */
	struct xel *all;    /* every element, for freeing */
};

struct xml_doc {
	struct xel *root;
	struct xel *all; /* every element, linked by their `all` */
};

/* Parse len bytes: 0 and d->root, or -EINVAL with "line N: not well-formed
 * XML: why" in err, or -ENOMEM (d holds nothing then). Free with xml_free. */
int xml_parse(struct xml_doc *d, const char *buf, size_t len, char *err, size_t errsize);
void xml_free(struct xml_doc *d);

/* An attribute's value, or NULL. */
const char *xml_attr(const struct xel *e, const char *name);
/* The first child element of that name, or NULL. */
struct xel *xml_child(const struct xel *e, const char *name);

#endif /* STRAND_XMLTREE_H */
