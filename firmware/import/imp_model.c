/* SPDX-License-Identifier: MIT */
/* imp_model.c - the importers' model: nodes, channels, names (see imp.h). */
#include "imp.h"

#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

int imp_node_add(struct imp_model *m, const char *name)
{
	struct imp_node *nodes = realloc(m->nodes, (m->nnodes + 1) * sizeof(*nodes));
	struct imp_node *n;

	if (!nodes)
		return -1;
	m->nodes = nodes;
	n = &nodes[m->nnodes];
	memset(n, 0, sizeof(*n));
	n->name = strdup(name ? name : "");
	if (!n->name)
		return -1;
	n->parent = -1;
	n->mimic = -1;
	n->q[0] = 1;
	n->s[0] = n->s[1] = n->s[2] = 1;
	n->axis[0] = 1;
	n->mult = 1;
	return (int)m->nnodes++;
}

int imp_chan_alloc(struct imp_chan *c, uint32_t n, uint32_t dim, enum imp_interp interp)
{
	c->interp = interp;
	c->n = n;
	c->dim = dim;
	c->frame = calloc(n ? n : 1, sizeof(double));
	c->v = calloc((size_t)(n ? n : 1) * dim, sizeof(double));
	c->in = interp == IMP_CUBIC ? calloc((size_t)(n ? n : 1) * dim, sizeof(double)) : NULL;
	c->out = interp == IMP_CUBIC ? calloc((size_t)(n ? n : 1) * dim, sizeof(double)) : NULL;
	if (!c->frame || !c->v || (interp == IMP_CUBIC && (!c->in || !c->out)))
		return -ENOMEM;
	return 0;
}

static void chan_free(struct imp_chan *c)
{
	free(c->frame);
	free(c->v);
	free(c->in);
	free(c->out);
	memset(c, 0, sizeof(*c));
}

void imp_model_free(struct imp_model *m)
{
	uint32_t i, k;

	for (i = 0; i < m->nnodes; i++) {
		free(m->nodes[i].name);
		for (k = 0; k < IMP_NPATHS; k++)
			chan_free(&m->nodes[i].ch[k]);
	}
	for (i = 0; i < m->nattrs; i++) {
		free(m->attrs[i].name);
		chan_free(&m->attrs[i].ch);
	}
	free(m->nodes);
	free(m->attrs);
	free(m->comment);
	memset(m, 0, sizeof(*m));
}

void imp_note(struct imp_model *m, const char *fmt, ...)
{
	size_t old = m->comment ? strlen(m->comment) : 0;
	va_list ap;
	char *c;
	int len;

	va_start(ap, fmt);
	len = vsnprintf(NULL, 0, fmt, ap);
	va_end(ap);
	if (len < 0 || !(c = realloc(m->comment, old + (size_t)len + 2)))
		return;
	m->comment = c;
	va_start(ap, fmt);
	vsnprintf(c + old, (size_t)len + 1, fmt, ap);
	va_end(ap);
	c[old + (size_t)len] = '\n';
	c[old + (size_t)len + 1] = '\0';
}

static bool taken(char *const *names, uint32_t n, const char *name)
{
	uint32_t i;

	if (!strcmp(name, "camera"))
		return true;
	for (i = 0; i < n; i++)
		if (!strcmp(names[i], name))
			return true;
	return false;
}

void imp_name_clean(char *s)
{
	for (; *s; s++)
		if (!isalnum((unsigned char)*s) && *s != '_' && *s != '-')
			*s = '_';
}

/* One name made valid and unique among the first n of names. */
static int fix_name(char **name, char *const *names, uint32_t n, uint32_t index,
		    const char *file, FILE *warn)
{
	char *s = *name, *u;
	size_t len = strlen(s);
	unsigned suffix;

	imp_name_clean(s);
	if (len == 0) {
		free(s);
		if (!(s = malloc(24)))
			return -ENOMEM;
		snprintf(s, 24, "node%u", index);
		*name = s;
		len = strlen(s);
	}
	if (!taken(names, n, s))
		return 0;
	if (!(u = malloc(len + 16)))
		return -ENOMEM;
	for (suffix = 2;; suffix++) {
		snprintf(u, len + 16, "%s_%u", s, suffix);
		if (!taken(names, n, u))
			break;
	}
	if (warn)
		fprintf(warn, "%s: the name '%s' is taken: it is '%s' in the scene\n", file, s, u);
	free(s);
	*name = u;
	return 0;
}

int imp_names(struct imp_model *m, const char *file, FILE *warn)
{
	uint32_t total = m->nnodes + m->nattrs, i;
	char **names = calloc(total ? total : 1, sizeof(*names));
	int err = 0;

	if (!names)
		return -ENOMEM;
	for (i = 0; i < total && !err; i++) {
		char **nm = i < m->nnodes ? &m->nodes[i].name : &m->attrs[i - m->nnodes].name;

		err = fix_name(nm, names, i, i, file, warn);
		names[i] = *nm;
	}
	free(names);
	return err;
}

void imp_span(const struct imp_model *m, double *first, double *last)
{
	bool any = false;
	uint32_t i, k;

	*first = *last = 0;
	for (i = 0; i < m->nnodes + m->nattrs; i++)
		for (k = 0; k < IMP_NPATHS; k++) {
			const struct imp_chan *c = i < m->nnodes ? &m->nodes[i].ch[k] :
					   k ? NULL : &m->attrs[i - m->nnodes].ch;

			if (!c || !c->n)
				continue;
			if (!any || c->frame[0] < *first)
				*first = c->frame[0];
			if (!any || c->frame[c->n - 1] > *last)
				*last = c->frame[c->n - 1];
			any = true;
		}
}
