/* SPDX-License-Identifier: MIT */
/* yml.c - typed readers of YAML document nodes (see yml.h). */
#include "yml.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int yml_fail(struct yml *y, const yaml_node_t *at, int code, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	code = y->fail(y, at, code, fmt, ap);
	va_end(ap);
	return code;
}

int yml_nomem(struct yml *y)
{
	return yml_fail(y, NULL, -ENOMEM, "out of memory");
}

yaml_node_t *yml_node(struct yml *y, int index)
{
	return yaml_document_get_node(y->doc, index);
}

/* The 1-based line of a node, for "(first at line N)". */
static unsigned mark_line(const yaml_node_t *n)
{
	return (unsigned)n->start_mark.line + 1;
}

static const char *scalar(const yaml_node_t *n)
{
	return (const char *)n->data.scalar.value;
}

static bool is_scalar(const yaml_node_t *n)
{
	return n && n->type == YAML_SCALAR_NODE;
}

const char *yml_describe(const yaml_node_t *n, char *buf, size_t size)
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

const char *yml_suggest(const char *word, const char *const *names)
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

static int unknown_key(struct yml *y, const yaml_node_t *key, const char *what,
		       const char *const *names)
{
	char buf[64], list[160];
	const char *word = scalar(key), *best = yml_suggest(word, names);
	size_t o = 0, i;

	if (best)
		return yml_fail(y, key, -EINVAL, "unknown key %s in %s (did you mean '%s'?)",
				yml_describe(key, buf, sizeof(buf)), what, best);
	list[0] = '\0';
	for (i = 0; names[i] && o < sizeof(list); i++)
		o += (size_t)snprintf(list + o, sizeof(list) - o, "%s%s", i ? ", " : "", names[i]);
	return yml_fail(y, key, -EINVAL, "unknown key %s in %s (valid keys: %s)",
			yml_describe(key, buf, sizeof(buf)), what, list);
}

int yml_map(struct yml *y, yaml_node_t *n, const char *what, const char *const *names,
	    yaml_node_t **vals)
{
	size_t count = name_count(names), i;
	yaml_node_pair_t *p;
	char buf[64];

	for (i = 0; i < count; i++)
		vals[i] = NULL;
	if (!n || n->type != YAML_MAPPING_NODE)
		return yml_fail(y, n, -EINVAL, "expected a mapping for %s, found %s", what,
				yml_describe(n, buf, sizeof(buf)));
	for (p = n->data.mapping.pairs.start; p < n->data.mapping.pairs.top; p++) {
		yaml_node_t *k = yml_node(y, p->key), *v = yml_node(y, p->value);

		if (!is_scalar(k))
			return yml_fail(y, k, -EINVAL, "expected a key name in %s, found %s", what,
					yml_describe(k, buf, sizeof(buf)));
		for (i = 0; i < count; i++)
			if (strlen(names[i]) == k->data.scalar.length &&
			    !memcmp(names[i], scalar(k), k->data.scalar.length))
				break;
		if (i == count)
			return unknown_key(y, k, what, names);
		if (vals[i])
			return yml_fail(y, k, -EINVAL, "duplicate key '%s' in %s (first at line %u)",
					names[i], what, mark_line(vals[i]));
		vals[i] = v;
	}
	return 0;
}

yaml_node_t *yml_value(struct yml *y, const yaml_node_t *map, const char *name)
{
	yaml_node_pair_t *p;

	if (!map || map->type != YAML_MAPPING_NODE)
		return NULL;
	for (p = map->data.mapping.pairs.start; p < map->data.mapping.pairs.top; p++) {
		yaml_node_t *k = yml_node(y, p->key);

		if (is_scalar(k) && strlen(name) == k->data.scalar.length &&
		    !memcmp(name, scalar(k), k->data.scalar.length))
			return yml_node(y, p->value);
	}
	return NULL;
}

int yml_require(struct yml *y, const yaml_node_t *map, const char *what, const yaml_node_t *v,
		const char *name)
{
	if (v)
		return 0;
	return yml_fail(y, map, -EINVAL, "missing field '%s' in %s", name, what);
}

int yml_map_req(struct yml *y, yaml_node_t *n, const char *what, const char *const *names,
		yaml_node_t **vals, uint32_t required)
{
	int err = yml_map(y, n, what, names, vals);
	size_t i;

	for (i = 0; !err && i < 32 && names[i]; i++)
		if (required & YML_REQ(i))
			err = yml_require(y, n, what, vals[i], names[i]);
	return err;
}

int yml_seq(struct yml *y, yaml_node_t *n, const char *what, yaml_node_item_t **items,
	    size_t *count)
{
	char buf[64];

	if (!n || n->type != YAML_SEQUENCE_NODE)
		return yml_fail(y, n, -EINVAL, "expected a sequence for %s, found %s", what,
				yml_describe(n, buf, sizeof(buf)));
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

int yml_num(struct yml *y, const yaml_node_t *n, double *out)
{
	char buf[64];

	if (!plain_scalar(n) || !is_decimal(scalar(n), n->data.scalar.length, false))
		return yml_fail(y, n, -EINVAL, "expected a number, found %s",
				yml_describe(n, buf, sizeof(buf)));
	/* the scalar is NUL-terminated by libyaml and all decimal here */
	*out = strtod(scalar(n), NULL);
	if (!isfinite(*out))
		return yml_fail(y, n, -ERANGE, "%s is outside the core's range",
				yml_describe(n, buf, sizeof(buf)));
	return 0;
}

int yml_positive(struct yml *y, const yaml_node_t *n, double *out)
{
	int err = yml_num(y, n, out);

	if (!err && !(*out > 0))
		err = yml_fail(y, n, -EINVAL, "must be above zero");
	return err;
}

int yml_range(struct yml *y, const yaml_node_t *n, const char *key, double min, double max,
	      const char *unit, double *out)
{
	int err = yml_num(y, n, out);

	if (!err && !(*out >= min && *out <= max))
		err = yml_fail(y, n, -ERANGE, "%s %.6g is outside %.10g to %.10g%s", key, *out,
			       min, max, unit);
	return err;
}

int yml_int(struct yml *y, const yaml_node_t *n, long long min, long long max, long long *out)
{
	char buf[64];

	if (!plain_scalar(n) || !is_decimal(scalar(n), n->data.scalar.length, true))
		return yml_fail(y, n, -EINVAL, "expected a whole number, found %s",
				yml_describe(n, buf, sizeof(buf)));
	errno = 0;
	*out = strtoll(scalar(n), NULL, 10);
	if (errno || *out < min || *out > max)
		return yml_fail(y, n, -ERANGE, "%s is out of range (%lld to %lld)",
				yml_describe(n, buf, sizeof(buf)), min, max);
	return 0;
}

int yml_str(struct yml *y, const yaml_node_t *n, const char **out)
{
	char buf[64];

	if (!is_scalar(n))
		return yml_fail(y, n, -EINVAL, "expected a name, found %s",
				yml_describe(n, buf, sizeof(buf)));
	*out = pool_strndup(y->pool, scalar(n), n->data.scalar.length);
	return *out ? 0 : yml_nomem(y);
}

int yml_enum(struct yml *y, const yaml_node_t *n, const char *what, const char *const *names,
	     int *out)
{
	char buf[64], list[160];
	const char *best;
	size_t i, o = 0;

	if (!is_scalar(n))
		return yml_fail(y, n, -EINVAL, "expected %s, found %s", what,
				yml_describe(n, buf, sizeof(buf)));
	for (i = 0; names[i]; i++) {
		if (strlen(names[i]) == n->data.scalar.length &&
		    !memcmp(names[i], scalar(n), n->data.scalar.length)) {
			*out = (int)i;
			return 0;
		}
	}
	best = yml_suggest(scalar(n), names);
	if (best)
		return yml_fail(y, n, -EINVAL, "unknown %s %s (did you mean '%s'?)", what,
				yml_describe(n, buf, sizeof(buf)), best);
	list[0] = '\0';
	for (i = 0; names[i] && o < sizeof(list); i++)
		o += (size_t)snprintf(list + o, sizeof(list) - o, "%s%s", i ? ", " : "", names[i]);
	return yml_fail(y, n, -EINVAL, "unknown %s %s (one of: %s)", what,
			yml_describe(n, buf, sizeof(buf)), list);
}

int yml_name(struct yml *y, const yaml_node_t *n, const char **out)
{
	char buf[64];
	size_t i, len;
	const char *s;

	if (!is_scalar(n) || n->data.scalar.length == 0)
		return yml_fail(y, n, -EINVAL, "expected a name, found %s",
				yml_describe(n, buf, sizeof(buf)));
	s = scalar(n);
	len = n->data.scalar.length;
	for (i = 0; i < len; i++) {
		unsigned char c = (unsigned char)s[i];

		if (!(isalpha(c) || c == '_' || (i > 0 && (isdigit(c) || c == '-'))))
			return yml_fail(y, n, -EINVAL,
					"name %s: use letters, digits, '_' and '-', starting with a letter or '_'",
					yml_describe(n, buf, sizeof(buf)));
	}
	if (len > 64)
		return yml_fail(y, n, -EINVAL, "name %s is longer than 64 characters",
				yml_describe(n, buf, sizeof(buf)));
	return yml_str(y, n, out);
}

int yml_bool(struct yml *y, const yaml_node_t *n, bool *out)
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
	return yml_fail(y, n, -EINVAL, "expected true or false, found %s",
			yml_describe(n, what, sizeof(what)));
}
