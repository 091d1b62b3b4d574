/* SPDX-License-Identifier: MIT */
/*
 * yml.h - typed readers of a YAML document's nodes, shared by the scene
 * loader (load/) and the rig's drivers (rig/drv_*.c), which read their own
 * settings in a scene file the way a kernel driver reads its own
 * device-tree properties: through this generic API, with the file's
 * positions and the loader's kind of message.
 *
 * A wrong type, a missing field or an unknown key (with the closest valid
 * one) is reported once, through the walk's fail callback, at the node it
 * concerns; the owner of the walk (the loader) decides which error stands
 * (the first: later ones are consequences) and where an error that has no
 * node goes. Strings are copied into the walk's pool, so that what a
 * reader returns outlives the document.
 *
 * Not real-time: reading allocates from the pool.
 */
#ifndef STRAND_YML_H
#define STRAND_YML_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <yaml.h>

#include "pool.h"

struct yml {
	yaml_document_t *doc;
	struct pool *pool; /* what strings are copied into */
	/* Record an error at node at (NULL: no node, the document as a
	 * whole) and return code. */
	int (*fail)(struct yml *y, const yaml_node_t *at, int code, const char *fmt, va_list ap);
};

/* The walk's error at node at, formatted once; returns code. */
int yml_fail(struct yml *y, const yaml_node_t *at, int code, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));
/* -ENOMEM, "out of memory", at no node. */
int yml_nomem(struct yml *y);

/* "a mapping", "a sequence", "'text'", "nothing": what a node is, for a
 * wrong-type message. */
const char *yml_describe(const yaml_node_t *n, char *buf, size_t size);

/* The valid name closest to `word` by edit distance, or NULL when none is
 * close enough to be a likely typo. */
const char *yml_suggest(const char *word, const char *const *names);

/* The node of a document index (a mapping's key or value, an item). */
yaml_node_t *yml_node(struct yml *y, int index);

/*
 * Check that n is a mapping whose keys are all in `names` (NULL-terminated),
 * each at most once, and store each key's value node in vals[] at the
 * name's index (NULL when absent). `what` names the mapping in messages
 * ("node", "key", ...).
 */
int yml_map(struct yml *y, yaml_node_t *n, const char *what, const char *const *names,
	    yaml_node_t **vals);

/* The keys of `names` a mapping must have, for yml_map_req: a bit per index. */
#define YML_REQ(i) (UINT32_C(1) << (i))

/*
 * yml_map(), then yml_require() of each name whose index is set in
 * `required` (among the first 32), the lowest index first: the first one
 * missing is the error.
 */
int yml_map_req(struct yml *y, yaml_node_t *n, const char *what, const char *const *names,
		yaml_node_t **vals, uint32_t required);

/* The value of key `name` in mapping map, or NULL (no check of the rest:
 * for a position, once yml_map has read the mapping). */
yaml_node_t *yml_value(struct yml *y, const yaml_node_t *map, const char *name);

/* "missing field 'name' in <what>" at the mapping unless v is set. */
int yml_require(struct yml *y, const yaml_node_t *map, const char *what, const yaml_node_t *v,
		const char *name);

/* A sequence: its item count and items (document indices). */
int yml_seq(struct yml *y, yaml_node_t *n, const char *what, yaml_node_item_t **items,
	    size_t *count);

/* A finite number in plain YAML notation (no quotes, no .inf/.nan). */
int yml_num(struct yml *y, const yaml_node_t *n, double *out);

/* A number above zero. */
int yml_positive(struct yml *y, const yaml_node_t *n, double *out);

/* A number in [min, max]; out of it, "<key> V is outside MIN to MAX<unit>"
 * (unit: "" or with its space, " ms"). -ERANGE */
int yml_range(struct yml *y, const yaml_node_t *n, const char *key, double min, double max,
	      const char *unit, double *out);

/* A whole number in [min, max]. */
int yml_int(struct yml *y, const yaml_node_t *n, long long min, long long max, long long *out);

/* A scalar's text, copied into the pool. */
int yml_str(struct yml *y, const yaml_node_t *n, const char **out);

/* A scalar that must be one of `names` (NULL-terminated): its index. */
int yml_enum(struct yml *y, const yaml_node_t *n, const char *what, const char *const *names,
	     int *out);

/* true or false. */
int yml_bool(struct yml *y, const yaml_node_t *n, bool *out);

/* A name: letters, digits, '_' and '-', starting with a letter or '_' (no
 * '.': channels are `<name>.x`), at most 64 characters. */
int yml_name(struct yml *y, const yaml_node_t *n, const char **out);

#endif /* STRAND_YML_H */
