/* SPDX-License-Identifier: MIT */
/*
 * imp_csv.c - a table of positions per frame as a model (imp.h): a 'frame'
 * column and one column per channel, the shape of Dragonframe's raw move
 * export and of `strand export`. NODE.angle, NODE.position and NODE.rpm
 * columns each become a joint (revolute about y, prismatic along x, a
 * spin), any other name an attribute; `tick` and a node's .x/.y/.z (what
 * `strand export` derives) are skipped, so that an export imports again.
 * One key per row, frames strictly increasing.
 */
#include "imp.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_COLS 4096

struct col {
	int kind;     /* 0 skip, 1 frame, 2 joint (angle, position, rpm), 3 attribute */
	int32_t idx;  /* node or attribute */
};

/* The fields of one line, split at commas in place; *n fields. */
static int split(char *line, char **f, int max, int *n)
{
	int k = 0;

	for (;;) {
		char *c = strchr(line, ',');

		if (k == max)
			return -E2BIG;
		f[k++] = line;
		if (!c)
			break;
		*c = 0;
		line = c + 1;
	}
	*n = k;
	return 0;
}

static char *trim(char *s)
{
	char *e;

	while (*s == ' ' || *s == '\t')
		s++;
	e = s + strlen(s);
	while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r'))
		*--e = 0;
	return s;
}

static int header(struct imp_model *m, char **f, int n, struct col *cols, char *err,
		  size_t errsize)
{
	int k, frame = -1;

	for (k = 0; k < n; k++) {
		char *name = trim(f[k]), *dot = strrchr(name, '.');

		cols[k].kind = 0;
		if (!strcmp(name, "frame")) {
			if (frame >= 0) {
				snprintf(err, errsize, "line 1: two 'frame' columns");
				return -EINVAL;
			}
			frame = k;
			cols[k].kind = 1;
		} else if (!strcmp(name, "tick") || (dot && (!strcmp(dot, ".x") || !strcmp(dot, ".y") ||
							     !strcmp(dot, ".z")))) {
			continue;
		} else if (dot && (!strcmp(dot, ".angle") || !strcmp(dot, ".position") ||
				   !strcmp(dot, ".rpm"))) {
			int i;

			*dot = 0;
			i = imp_node_add(m, name);
			if (i < 0)
				return -ENOMEM;
			m->nodes[i].kind = !strcmp(dot + 1, "position") ? IMP_PRISMATIC : IMP_REVOLUTE;
			if (m->nodes[i].kind == IMP_REVOLUTE) {
				m->nodes[i].axis[0] = 0;
				m->nodes[i].axis[1] = 1;
			}
			/* an rpm column is a spin: not written by this reader */
			if (!strcmp(dot + 1, "rpm")) {
				snprintf(err, errsize, "line 1, column %d: '%s.rpm': import a spin's speed as an attribute or key its angle",
					 k + 1, name);
				return -EINVAL;
			}
			cols[k].kind = 2;
			cols[k].idx = i;
		} else {
			struct imp_attr *a = realloc(m->attrs, (m->nattrs + 1) * sizeof(*a));

			if (!a)
				return -ENOMEM;
			m->attrs = a;
			memset(&a[m->nattrs], 0, sizeof(*a));
			if (!(a[m->nattrs].name = strdup(name)))
				return -ENOMEM;
			cols[k].kind = 3;
			cols[k].idx = (int32_t)m->nattrs++;
		}
	}
	if (frame < 0) {
		snprintf(err, errsize, "line 1: no 'frame' column");
		return -EINVAL;
	}
	return 0;
}

int imp_csv(struct imp_model *m, const char *path, const uint8_t *buf, size_t len,
	    const struct imp_opts *o, FILE *warn, char *err, size_t errsize)
{
	char *text = malloc(len + 1), *line, *next, **f = NULL;
	struct col *cols = NULL;
	size_t rows = 0, lineno = 0, row = 0;
	int ncols = 0, n, k, rc = 0;
	uint32_t i;

	f = malloc(MAX_COLS * sizeof(*f));
	cols = calloc(MAX_COLS, sizeof(*cols));
	if (!text || !f || !cols) {
		rc = -ENOMEM;
		goto out;
	}
	memcpy(text, buf, len);
	text[len] = 0;
	if (memchr(buf, 0, len)) {
		snprintf(err, errsize, "not a text file (a NUL byte)");
		rc = -EINVAL;
		goto out;
	}
	for (line = text; *line; line++)
		rows += *line == '\n';
	rows += 1;
	m->rate_num = o->rate_num;
	m->rate_den = o->rate_den;
	m->tick_hz = o->tick_hz;
	for (line = text; line && !rc; line = next) {
		double frame = 0;

		next = strchr(line, '\n');
		if (next)
			*next++ = 0;
		lineno++;
		if (!*trim(line) || line[0] == '#')
			continue;
		rc = split(line, f, MAX_COLS, &n);
		if (rc) {
			snprintf(err, errsize, "line %zu: more than %d columns", lineno, MAX_COLS);
			break;
		}
		if (!ncols) {
			ncols = n;
			rc = header(m, f, n, cols, err, errsize);
			for (i = 0; !rc && i < m->nnodes; i++)
				rc = imp_chan_alloc(&m->nodes[i].ch[0], (uint32_t)rows, 1,
						    o->interp);
			for (i = 0; !rc && i < m->nattrs; i++)
				rc = imp_chan_alloc(&m->attrs[i].ch, (uint32_t)rows, 1, o->interp);
			continue;
		}
		if (n != ncols) {
			snprintf(err, errsize, "line %zu: %d fields, the header has %d", lineno, n, ncols);
			rc = -EINVAL;
			break;
		}
		for (k = 0; k < n && !rc; k++) {
			char *s = trim(f[k]), *end;
			double v;

			if (!cols[k].kind)
				continue;
			v = strtod(s, &end);
			if (!*s || *end || !isfinite(v)) {
				snprintf(err, errsize, "line %zu, column %d: '%s' is not a finite number",
					 lineno, k + 1, s);
				rc = -EINVAL;
			} else if (cols[k].kind == 1) {
				frame = v;
			}
		}
		if (rc)
			break;
		if (row && !(frame > (m->nnodes ? m->nodes[0].ch[0].frame[row - 1] :
				       m->nattrs ? m->attrs[0].ch.frame[row - 1] : -INFINITY))) {
			snprintf(err, errsize, "line %zu: frame %.10g is not after the previous row's",
				 lineno, frame);
			rc = -EINVAL;
			break;
		}
		for (k = 0; k < n; k++) {
			struct imp_chan *c = cols[k].kind == 2 ? &m->nodes[cols[k].idx].ch[0] :
					     cols[k].kind == 3 ? &m->attrs[cols[k].idx].ch : NULL;

			if (!c)
				continue;
			c->frame[row] = frame;
			c->v[row] = strtod(trim(f[k]), NULL);
		}
		row++;
	}
	if (!rc && !ncols) {
		snprintf(err, errsize, "line 1: an empty table (no header)");
		rc = -EINVAL;
	}
	if (!rc && !row) {
		snprintf(err, errsize, "line %zu: no rows under the header", lineno);
		rc = -EINVAL;
	}
	for (i = 0; !rc && i < m->nnodes; i++)
		m->nodes[i].ch[0].n = (uint32_t)row;
	for (i = 0; !rc && i < m->nattrs; i++)
		m->attrs[i].ch.n = (uint32_t)row;
	if (!rc) {
		imp_note(m, "imported by strand import from %s (a table): %zu rows, %u joints, %u attributes, %s",
			 path, row, m->nnodes, m->nattrs, o->interp == IMP_STEP ? "step" :
			 o->interp == IMP_LINEAR ? "linear" : "hermite");
		rc = imp_names(m, path, warn);
	}
out:
	free(text);
	free(f);
	free(cols);
	return rc;
}
