/* SPDX-License-Identifier: MIT */
/*
 * imp_yaml.c - a model as a scene file (see imp.h). Numbers are written
 * with 17 significant digits, so that the loader reads back the very doubles
 * the importer computed: a key frame float32 has moved off a whole frame
 * stays where the file put it.
 */
#include "imp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void num(FILE *o, double v)
{
	if (v == 0)
		v = 0; /* no -0 */
	fprintf(o, "%.17g", v);
}

static void vec(FILE *o, const double *v, uint32_t n)
{
	uint32_t i;

	fputc('[', o);
	for (i = 0; i < n; i++) {
		if (i)
			fputs(", ", o);
		num(o, v[i]);
	}
	fputc(']', o);
}

static bool is_default(const struct imp_node *n, int path)
{
	if (path == IMP_T)
		return !n->t[0] && !n->t[1] && !n->t[2];
	if (path == IMP_S)
		return n->s[0] == 1 && n->s[1] == 1 && n->s[2] == 1;
	return n->q[0] == 1 && !n->q[1] && !n->q[2] && !n->q[3];
}

static const char *group_interp(enum imp_interp i)
{
	return i == IMP_STEP ? "step" : i == IMP_LINEAR ? "linear" : "hermite";
}

static int cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

/* Index of the key of c at exactly frame f, or -1 (c's frames increase). */
static long key_at(const struct imp_chan *c, double f)
{
	uint32_t lo = 0, hi = c->n;

	while (lo < hi) {
		uint32_t mid = lo + (hi - lo) / 2;

		if (c->frame[mid] < f)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo < c->n && c->frame[lo] == f ? (long)lo : -1;
}

/* A free node has a strand when something moves or sets it. */
static bool free_keyed(const struct imp_node *n)
{
	int p;

	if (n->has_matrix)
		return true;
	for (p = 0; p < IMP_NPATHS; p++)
		if (n->ch[p].n || !is_default(n, p))
			return true;
	return false;
}

static void free_strand(FILE *o, const struct imp_node *n)
{
	static const char *const field[IMP_NPATHS] = { "translate", "quat", "scale" };
	const struct imp_chan *ch = n->ch;
	double *frames, rest[IMP_NPATHS][4], f0;
	uint32_t total = 0, nf = 0, i, p;

	for (p = 0; p < IMP_NPATHS; p++)
		total += ch[p].n;
	if (n->has_matrix) {
		fprintf(o, "  - node: %s\n    keys:\n      - {frame: 0, matrix: [", n->name);
		for (i = 0; i < 4; i++) {
			if (i)
				fputs(", ", o);
			vec(o, n->matrix[i], 4);
		}
		fputs("]}\n", o);
		return;
	}
	frames = malloc((total ? total : 1) * sizeof(*frames));
	if (!frames)
		return;
	for (p = 0; p < IMP_NPATHS; p++)
		for (i = 0; i < ch[p].n; i++)
			frames[nf++] = ch[p].frame[i];
	qsort(frames, nf, sizeof(*frames), cmp_double);
	for (i = total = 0; i < nf; i++)
		if (!total || frames[total - 1] != frames[i])
			frames[total++] = frames[i];
	nf = total;
	f0 = nf ? frames[0] : 0;
	memcpy(rest[IMP_T], n->t, sizeof(n->t));
	memcpy(rest[IMP_R], n->q, sizeof(n->q));
	memcpy(rest[IMP_S], n->s, sizeof(n->s));
	fprintf(o, "  - node: %s\n", n->name);
	fprintf(o, "    interpolation: {translate: %s, scale: %s}\n", group_interp(ch[IMP_T].interp),
		group_interp(ch[IMP_S].interp));
	fprintf(o, "    rotation: %s\n", !ch[IMP_R].n || ch[IMP_R].interp == IMP_LINEAR ? "slerp" :
		ch[IMP_R].interp == IMP_STEP ? "step" : "cubic");
	fputs("    compact: true\n    keys:\n", o);
	for (i = 0; i < (nf ? nf : 1); i++) {
		double f = nf ? frames[i] : 0;

		fputs("      - {frame: ", o);
		num(o, f);
		for (p = 0; p < IMP_NPATHS; p++) {
			const struct imp_chan *c = &ch[p];
			long k = c->n ? key_at(c, f) : -1;
			uint32_t dim = p == IMP_R ? 4 : 3;

			if (!c->n && f == f0 && !is_default(n, (int)p)) {
				fprintf(o, ", %s: ", field[p]);
				vec(o, rest[p], dim);
			}
			if (k < 0)
				continue;
			fprintf(o, ", %s: ", field[p]);
			vec(o, c->v + (size_t)k * dim, dim);
			if (c->interp == IMP_CUBIC) {
				fprintf(o, ", %s_in: ", field[p]);
				vec(o, c->in + (size_t)k * dim, dim);
				fprintf(o, ", %s_out: ", field[p]);
				vec(o, c->out + (size_t)k * dim, dim);
			}
		}
		fputs("}\n", o);
	}
	free(frames);
}

static void joint_keys(FILE *o, const struct imp_chan *c, const char *field)
{
	uint32_t i;

	fprintf(o, "    interpolation: %s\n", group_interp(c->interp));
	fputs("    compact: true\n    keys:\n", o);
	for (i = 0; i < c->n; i++) {
		fputs("      - {frame: ", o);
		num(o, c->frame[i]);
		fprintf(o, ", %s: ", field);
		num(o, c->v[i]);
		if (c->interp == IMP_CUBIC) {
			fputs(", in: ", o);
			num(o, c->in[i]);
			fputs(", out: ", o);
			num(o, c->out[i]);
		}
		fputs("}\n", o);
	}
}

static void node_entry(FILE *o, const struct imp_model *m, const struct imp_node *n)
{
	fprintf(o, "  - name: %s\n", n->name);
	if (n->parent >= 0)
		fprintf(o, "    parent: %s\n", m->nodes[n->parent].name);
	if (n->pivot[0] || n->pivot[1] || n->pivot[2]) {
		fputs("    pivot: ", o);
		vec(o, n->pivot, 3);
		fputc('\n', o);
	}
	if (n->kind == IMP_FREE)
		return;
	fprintf(o, "    joint: {type: %s, axis: ", n->kind == IMP_REVOLUTE ? "revolute" : "prismatic");
	vec(o, n->axis, 3);
	fputs("}\n", o);
	if (n->mimic >= 0) {
		fprintf(o, "    mimic: {joint: %s, multiplier: ", m->nodes[n->mimic].name);
		num(o, n->mult);
		fputs(", offset: ", o);
		num(o, n->offset);
		fputs("}\n", o);
	} else if (n->rest) {
		fputs("    rest: ", o);
		num(o, n->rest);
		fputc('\n', o);
	}
	if (n->has_min || n->has_max || n->has_vel) {
		const char *sep = "";

		fputs("    limits: {", o);
		if (n->has_min) {
			fputs("min: ", o);
			num(o, n->min);
			sep = ", ";
		}
		if (n->has_max) {
			fprintf(o, "%smax: ", sep);
			num(o, n->max);
			sep = ", ";
		}
		if (n->has_vel) {
			fprintf(o, "%svelocity: ", sep);
			num(o, n->vel);
		}
		fputs("}\n", o);
	}
}

bool imp_has_strands(const struct imp_model *m)
{
	uint32_t i;

	for (i = 0; i < m->nnodes; i++) {
		const struct imp_node *n = &m->nodes[i];

		if (n->kind == IMP_FREE ? free_keyed(n) : n->ch[0].n > 0 && n->mimic < 0)
			return true;
	}
	return false;
}

int imp_yaml_write(FILE *o, const struct imp_model *m, unsigned sections)
{
	double first, last;
	const char *line;
	uint32_t i;
	bool strands = false;

	for (line = m->comment; line && *line;) {
		const char *end = strchr(line, '\n');
		size_t len = end ? (size_t)(end - line) : strlen(line);

		fprintf(o, "# %.*s\n", (int)len, line);
		line += len + (end != NULL);
	}
	imp_span(m, &first, &last);
	if (sections & IMP_YAML_TIMING) {
		fputs("timing:\n", o);
		fprintf(o, "  tick_hz: %u\n", m->tick_hz);
		if (m->rate_den == 1)
			fprintf(o, "  frame_rate: %u\n", m->rate_num);
		else
			fprintf(o, "  frame_rate: \"%u/%u\"\n", m->rate_num, m->rate_den);
		fprintf(o, "  frames: [%.0f, %.0f]\n", floor(first),
			ceil(last) > floor(first) ? ceil(last) : floor(first) + 1);
	}
	if (m->nnodes && (sections & IMP_YAML_NODES))
		fputs("nodes:\n", o);
	for (i = 0; i < m->nnodes && (sections & IMP_YAML_NODES); i++)
		node_entry(o, m, &m->nodes[i]);
	for (i = 0; i < m->nnodes && (sections & IMP_YAML_STRANDS); i++) {
		const struct imp_node *n = &m->nodes[i];
		const struct imp_chan *c = &n->ch[0];
		/* a mimic's keys are its master's, mapped by the loader */
		bool keyed = n->kind == IMP_FREE ? free_keyed(n) : c->n > 0 && n->mimic < 0;

		if (!keyed)
			continue;
		if (n->kind == IMP_FREE) {
			if (!strands)
				fputs("strands:\n", o);
			strands = true;
			free_strand(o, n);
			continue;
		}
		if (!strands)
			fputs("strands:\n", o);
		strands = true;
		fprintf(o, "  - node: %s\n", n->name);
		joint_keys(o, c, n->kind == IMP_REVOLUTE ? "angle" : "position");
	}
	if (m->nattrs && (sections & IMP_YAML_STRANDS))
		fputs("attributes:\n", o);
	for (i = 0; i < m->nattrs && (sections & IMP_YAML_STRANDS); i++) {
		const struct imp_attr *a = &m->attrs[i];
		uint32_t k;

		fprintf(o, "  - name: %s\n    interpolation: %s\n    keys:\n", a->name,
			group_interp(a->ch.interp));
		for (k = 0; k < a->ch.n; k++) {
			fputs("      - {frame: ", o);
			num(o, a->ch.frame[k]);
			fputs(", value: ", o);
			num(o, a->ch.v[k]);
			fputs("}\n", o);
		}
	}
	return ferror(o) ? -1 : 0;
}
