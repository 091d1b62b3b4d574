/* SPDX-License-Identifier: MIT */
/*
 * load_yaml.c - typed readers of YAML document nodes for the scene loader,
 * and its error messages (see load_priv.h).
 */
#include "load_priv.h"

#include <ctype.h>
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

yaml_node_t *ld_node(struct ld *l, int index)
{
	return yaml_document_get_node(l->doc, index);
}

static const char *scalar(const yaml_node_t *n)
{
	return (const char *)n->data.scalar.value;
}

static bool is_scalar(const yaml_node_t *n)
{
	return n && n->type == YAML_SCALAR_NODE;
}

const char *ld_describe(const yaml_node_t *n, char *buf, size_t size)
{
	size_t i, o = 0, len;

	if (!n)
		return "nothing";
	if (n->type == YAML_MAPPING_NODE)
		return "a mapping";
	if (n->type == YAML_SEQUENCE_NODE)
		return "a sequence";
	len = n->data.scalar.length;
	if (len == 0)
		return "nothing";
	/* quoted, shortened, and with anything unprintable shown as '?' */
	buf[o++] = '\'';
	for (i = 0; i < len && o + 5 < size; i++) {
		unsigned char c = (unsigned char)scalar(n)[i];

		buf[o++] = (c >= 0x20 && c < 0x7f) ? (char)c : '?';
	}
	if (i < len && o + 4 < size) {
		memcpy(buf + o, "...", 3);
		o += 3;
	}
	buf[o++] = '\'';
	buf[o] = '\0';
	return buf;
}

/* ---- closest name ------------------------------------------------------------- */

/* Levenshtein distance with a two-row table; names here are short, longer
 * words are cut (they are not typos of a schema name anyway). */
static unsigned edit_distance(const char *a, const char *b)
{
	enum { MAXLEN = 32 };
	unsigned row[2][MAXLEN + 1];
	size_t la = strnlen(a, MAXLEN), lb = strnlen(b, MAXLEN), i, j;

	for (j = 0; j <= lb; j++)
		row[0][j] = (unsigned)j;
	for (i = 1; i <= la; i++) {
		unsigned *cur = row[i & 1], *prev = row[(i - 1) & 1];

		cur[0] = (unsigned)i;
		for (j = 1; j <= lb; j++) {
			unsigned sub = prev[j - 1] + (a[i - 1] != b[j - 1]);
			unsigned del = prev[j] + 1, ins = cur[j - 1] + 1;

			cur[j] = sub < del ? (sub < ins ? sub : ins) : (del < ins ? del : ins);
		}
	}
	return row[la & 1][lb];
}

const char *ld_suggest(const char *word, const char *const *names)
{
	const char *best = NULL;
	unsigned best_d = ~0u, limit;
	size_t len = strlen(word);

	/* a typo changes at most about a third of a word, and never all of it */
	limit = len < 3 ? 1 : (unsigned)(len / 3 + 1);
	for (; *names; names++) {
		unsigned d = edit_distance(word, *names);

		if (d < best_d) {
			best_d = d;
			best = *names;
		}
	}
	return best_d <= limit && best_d < strlen(best) ? best : NULL;
}

/* ---- readers ------------------------------------------------------------------ */

static size_t name_count(const char *const *names)
{
	size_t n = 0;

	while (names[n])
		n++;
	return n;
}

static int unknown_key(struct ld *l, const yaml_node_t *key, const char *what,
		       const char *const *names)
{
	char buf[64], list[160];
	const char *word = scalar(key), *best = ld_suggest(word, names);
	size_t o = 0, i;

	if (best)
		return ld_fail(l, key, -EINVAL, "unknown key %s in %s (did you mean '%s'?)",
			       ld_describe(key, buf, sizeof(buf)), what, best);
	list[0] = '\0';
	for (i = 0; names[i] && o < sizeof(list); i++)
		o += (size_t)snprintf(list + o, sizeof(list) - o, "%s%s", i ? ", " : "", names[i]);
	return ld_fail(l, key, -EINVAL, "unknown key %s in %s (valid keys: %s)",
		       ld_describe(key, buf, sizeof(buf)), what, list);
}

int ld_map(struct ld *l, yaml_node_t *n, const char *what, const char *const *names,
	   yaml_node_t **vals)
{
	size_t count = name_count(names), i;
	yaml_node_pair_t *p;
	char buf[64];

	for (i = 0; i < count; i++)
		vals[i] = NULL;
	if (!n || n->type != YAML_MAPPING_NODE)
		return ld_fail(l, n, -EINVAL, "expected a mapping for %s, found %s", what,
			       ld_describe(n, buf, sizeof(buf)));
	for (p = n->data.mapping.pairs.start; p < n->data.mapping.pairs.top; p++) {
		yaml_node_t *k = ld_node(l, p->key), *v = ld_node(l, p->value);

		if (!is_scalar(k))
			return ld_fail(l, k, -EINVAL, "expected a key name in %s, found %s", what,
				       ld_describe(k, buf, sizeof(buf)));
		for (i = 0; i < count; i++)
			if (strlen(names[i]) == k->data.scalar.length &&
			    !memcmp(names[i], scalar(k), k->data.scalar.length))
				break;
		if (i == count)
			return unknown_key(l, k, what, names);
		if (vals[i])
			return ld_fail(l, k, -EINVAL, "duplicate key '%s' in %s (first at line %u)",
				       names[i], what, ld_mark_of(vals[i]).line);
		vals[i] = v;
	}
	return 0;
}

int ld_require(struct ld *l, const yaml_node_t *map, const char *what, const yaml_node_t *v,
	       const char *name)
{
	if (v)
		return 0;
	return ld_fail(l, map, -EINVAL, "missing field '%s' in %s", name, what);
}

int ld_seq(struct ld *l, yaml_node_t *n, const char *what, yaml_node_item_t **items,
	   size_t *count)
{
	char buf[64];

	if (!n || n->type != YAML_SEQUENCE_NODE)
		return ld_fail(l, n, -EINVAL, "expected a sequence for %s, found %s", what,
			       ld_describe(n, buf, sizeof(buf)));
	*items = n->data.sequence.items.start;
	*count = (size_t)(n->data.sequence.items.top - n->data.sequence.items.start);
	return 0;
}

/* Plain decimal notation: [+-] digits [. digits] [e [+-] digits], or with
 * the digits after the point only. Hex, octal, '_', .inf and .nan are not
 * numbers of a scene. */
static bool is_decimal(const char *s, size_t len, bool integer)
{
	size_t i = 0, digits = 0;

	if (i < len && (s[i] == '+' || s[i] == '-'))
		i++;
	while (i < len && isdigit((unsigned char)s[i]))
		i++, digits++;
	if (!integer && i < len && s[i] == '.') {
		i++;
		while (i < len && isdigit((unsigned char)s[i]))
			i++, digits++;
	}
	if (!digits)
		return false;
	if (!integer && i < len && (s[i] == 'e' || s[i] == 'E')) {
		size_t e = 0;

		i++;
		if (i < len && (s[i] == '+' || s[i] == '-'))
			i++;
		while (i < len && isdigit((unsigned char)s[i]))
			i++, e++;
		if (!e)
			return false;
	}
	return i == len;
}

static bool plain_scalar(const yaml_node_t *n)
{
	return is_scalar(n) && n->data.scalar.style == YAML_PLAIN_SCALAR_STYLE;
}

int ld_num(struct ld *l, const yaml_node_t *n, double *out)
{
	char buf[64];

	if (!plain_scalar(n) || !is_decimal(scalar(n), n->data.scalar.length, false))
		return ld_fail(l, n, -EINVAL, "expected a number, found %s",
			       ld_describe(n, buf, sizeof(buf)));
	/* the scalar is NUL-terminated by libyaml and all decimal here */
	*out = strtod(scalar(n), NULL);
	if (!isfinite(*out))
		return ld_fail(l, n, -ERANGE, "%s is outside the core's range",
			       ld_describe(n, buf, sizeof(buf)));
	return 0;
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

int ld_int(struct ld *l, const yaml_node_t *n, long long min, long long max, long long *out)
{
	char buf[64];

	if (!plain_scalar(n) || !is_decimal(scalar(n), n->data.scalar.length, true))
		return ld_fail(l, n, -EINVAL, "expected a whole number, found %s",
			       ld_describe(n, buf, sizeof(buf)));
	errno = 0;
	*out = strtoll(scalar(n), NULL, 10);
	if (errno || *out < min || *out > max)
		return ld_fail(l, n, -ERANGE, "%s is out of range (%lld to %lld)",
			       ld_describe(n, buf, sizeof(buf)), min, max);
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

int ld_str(struct ld *l, const yaml_node_t *n, const char **out)
{
	char buf[64];

	if (!is_scalar(n))
		return ld_fail(l, n, -EINVAL, "expected a name, found %s",
			       ld_describe(n, buf, sizeof(buf)));
	*out = pool_strndup(l->pool, scalar(n), n->data.scalar.length);
	return *out ? 0 : ld_nomem(l);
}

int ld_enum(struct ld *l, const yaml_node_t *n, const char *what, const char *const *names,
	    int *out)
{
	char buf[64], list[160];
	const char *best;
	size_t i, o = 0;

	if (!is_scalar(n))
		return ld_fail(l, n, -EINVAL, "expected %s, found %s", what,
			       ld_describe(n, buf, sizeof(buf)));
	for (i = 0; names[i]; i++) {
		if (strlen(names[i]) == n->data.scalar.length &&
		    !memcmp(names[i], scalar(n), n->data.scalar.length)) {
			*out = (int)i;
			return 0;
		}
	}
	best = ld_suggest(scalar(n), names);
	if (best)
		return ld_fail(l, n, -EINVAL, "unknown %s %s (did you mean '%s'?)", what,
			       ld_describe(n, buf, sizeof(buf)), best);
	list[0] = '\0';
	for (i = 0; names[i] && o < sizeof(list); i++)
		o += (size_t)snprintf(list + o, sizeof(list) - o, "%s%s", i ? ", " : "", names[i]);
	return ld_fail(l, n, -EINVAL, "unknown %s %s (one of: %s)", what,
		       ld_describe(n, buf, sizeof(buf)), list);
}

int ld_name(struct ld *l, const yaml_node_t *n, const char **out)
{
	char buf[64];
	size_t i, len;
	const char *s;

	if (!is_scalar(n) || n->data.scalar.length == 0)
		return ld_fail(l, n, -EINVAL, "expected a name, found %s",
			       ld_describe(n, buf, sizeof(buf)));
	s = scalar(n);
	len = n->data.scalar.length;
	for (i = 0; i < len; i++) {
		unsigned char c = (unsigned char)s[i];

		if (!(isalpha(c) || c == '_' || (i > 0 && (isdigit(c) || c == '-'))))
			return ld_fail(l, n, -EINVAL,
				       "name %s: use letters, digits, '_' and '-', starting with a letter or '_'",
				       ld_describe(n, buf, sizeof(buf)));
	}
	if (len > 64)
		return ld_fail(l, n, -EINVAL, "name %s is longer than 64 characters",
			       ld_describe(n, buf, sizeof(buf)));
	return ld_str(l, n, out);
}

int ld_bool(struct ld *l, const yaml_node_t *n, bool *out)
{
	const char *v = (const char *)n->data.scalar.value;
	char what[48];

	if (n->type == YAML_SCALAR_NODE && n->data.scalar.style == YAML_PLAIN_SCALAR_STYLE) {
		if (!strcmp(v, "true")) {
			*out = true;
			return 0;
		}
		if (!strcmp(v, "false")) {
			*out = false;
			return 0;
		}
	}
	return ld_fail(l, n, -EINVAL, "expected true or false, found %s",
		       ld_describe(n, what, sizeof(what)));
}
