/* SPDX-License-Identifier: MIT */
/*
 * load_yaml.c - the scene loader's side of the YAML readers (yaml/yml.h):
 * where its errors go (the first one stands, with its position), and the
 * readers of numbers the core must hold.
 */
#include "load_priv.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct ld_mark ld_mark_of(const yaml_node_t *n)
{
	struct ld_mark m = { 0, 0 };

	if (n) {
		m.line = (uint32_t)n->start_mark.line + 1;
		m.col = (uint32_t)n->start_mark.column + 1;
	}
	return m;
}

static int fail_v(struct ld *l, struct ld_mark m, int code, const char *fmt, va_list ap)
{
	if (l->err->code)
		return code;
	l->err->code = code;
	l->err->line = m.line;
	l->err->col = m.col;
	vsnprintf(l->err->msg, sizeof(l->err->msg), fmt, ap);
	return code;
}

int ld_fail_at(struct ld *l, struct ld_mark m, int code, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	fail_v(l, m, code, fmt, ap);
	va_end(ap);
	return code;
}

int ld_fail(struct ld *l, const yaml_node_t *at, int code, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	fail_v(l, at ? ld_mark_of(at) : l->mk->root, code, fmt, ap);
	va_end(ap);
	return code;
}

int ld_nomem(struct ld *l)
{
	return ld_fail_at(l, l->mk->root, -ENOMEM, "out of memory");
}

/* The readers' errors (yml.h), the drivers' among them: at their node, or
 * at the document's root. */
static int yml_fail_cb(struct yml *y, const yaml_node_t *at, int code, const char *fmt,
		       va_list ap)
{
	struct ld *l = (struct ld *)y; /* y is the first member */

	return fail_v(l, at ? ld_mark_of(at) : l->mk->root, code, fmt, ap);
}

void ld_init(struct ld *l, struct pool *pool)
{
	l->y.pool = pool;
	l->y.fail = yml_fail_cb;
	l->pool = pool;
}

int ld_q32(struct ld *l, const yaml_node_t *n, double scale, const char *unit, double *out)
{
	mot_q32 q;
	int err = ld_num(l, n, out);

	if (err)
		return err;
	if (!sd_to_q32(*out * scale, &q))
		return ld_fail(l, n, -ERANGE,
			       "%.10g is outside the core's range (|value| < %.10g %s)", *out,
			       1073741824.0 / scale, unit);
	return 0;
}

int ld_vec(struct ld *l, yaml_node_t *n, size_t count, double scale, const char *unit,
	   double *out)
{
	yaml_node_item_t *it;
	size_t got, i;
	char buf[64];
	int err;

	if (!n || n->type != YAML_SEQUENCE_NODE)
		return ld_fail(l, n, -EINVAL, "expected a sequence of %zu numbers, found %s",
			       count, ld_describe(n, buf, sizeof(buf)));
	err = ld_seq(l, n, "a vector", &it, &got);
	if (err)
		return err;
	if (got != count)
		return ld_fail(l, n, -EINVAL, "expected %zu numbers, found %zu", count, got);
	for (i = 0; i < count; i++) {
		err = ld_q32(l, ld_node(l, it[i]), scale, unit, &out[i]);
		if (err)
			return err;
	}
	return 0;
}
