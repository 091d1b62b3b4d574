/* SPDX-License-Identifier: MIT */
/*
 * cmd_info.c - `strand info SCENE`: the hierarchy as a tree (the seed
 * paper's Figure 2, the scene as its picture node), each strand's keys and
 * method, the timing, and the bytes the scene takes in the core.
 */
#include <getopt.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "exitcode.h"

#define TREE_MAX_DEPTH 24 /* deeper levels are drawn at this indentation */

static const char *const interp_name[] = { "step", "linear", "hermite", "bspline", "beta",
					   "bezier" };

static void node_line(FILE *out, const struct scene_desc *d, uint32_t i)
{
	const struct sd_node *n = &d->nodes[i];
	static const char *const axis[] = { "x", "y", "z" };

	fprintf(out, "%s", n->name);
	if (n->kind == MOT_NODE_FREE) {
		fprintf(out, "  (free)\n");
		return;
	}
	fprintf(out, "  (%s ", n->kind == MOT_NODE_REVOLUTE ? "revolute" : "prismatic");
	if (n->axis_id == MOT_AXIS_VEC)
		fprintf(out, "[%g, %g, %g])\n", n->axis[0], n->axis[1], n->axis[2]);
	else
		fprintf(out, "%s)\n", axis[n->axis_id]);
}

/* Push node's children (the list head[]/next[]) so that they pop in file
 * order: push them, then reverse the pushed run. */
static uint32_t push_children(uint32_t *stack, uint32_t *depth, uint32_t top, int32_t child,
			      const int32_t *next, uint32_t dep)
{
	uint32_t from = top, a, b;

	for (; child >= 0; child = next[child])
		stack[top] = (uint32_t)child, depth[top++] = dep;
	for (a = from, b = top; a + 1 < b; a++, b--) {
		uint32_t t = stack[a];

		stack[a] = stack[b - 1];
		stack[b - 1] = t;
	}
	return top;
}

/*
 * Depth first without recursion (a scene may be a chain thousands deep).
 * head[p] and next[] list each node's children in file order (head[n]: the
 * roots). more[k] says whether the ancestor at depth k still has siblings
 * to come, which decides between a bar and a blank in the prefix.
 */
static int tree(FILE *out, const struct scene_desc *d)
{
	uint32_t n = d->nnodes, top, i;
	uint32_t *stack = malloc((n ? n : 1) * sizeof(*stack));
	uint32_t *depth = malloc((n ? n : 1) * sizeof(*depth));
	int32_t *head = malloc((n + 1) * sizeof(*head));
	int32_t *next = malloc((n ? n : 1) * sizeof(*next));
	bool more[TREE_MAX_DEPTH + 1];

	if (!stack || !depth || !head || !next) {
		free(stack);
		free(depth);
		free(head);
		free(next);
		return -1;
	}
	for (i = 0; i <= n; i++)
		head[i] = -1;
	for (i = n; i-- > 0;) {
		uint32_t p = d->nodes[i].parent < 0 ? n : (uint32_t)d->nodes[i].parent;

		next[i] = head[p];
		head[p] = (int32_t)i;
	}
	fprintf(out, "%s\n", d->name[0] ? d->name : "(scene)");
	top = push_children(stack, depth, 0, head[n], next, 0);
	while (top) {
		uint32_t node = stack[--top], dep = depth[top], k;
		bool last = next[node] < 0;

		for (k = 0; k < dep && k < TREE_MAX_DEPTH; k++)
			fputs(more[k] ? "│   " : "    ", out);
		fputs(last ? "└── " : "├── ", out);
		more[dep < TREE_MAX_DEPTH ? dep : TREE_MAX_DEPTH] = !last;
		node_line(out, d, node);
		top = push_children(stack, depth, top, head[node], next, dep + 1);
	}
	free(stack);
	free(depth);
	free(head);
	free(next);
	return 0;
}

static void strands(FILE *out, const struct scene_file *sf)
{
	const struct scene_desc *d = &sf->desc;
	uint32_t i, count = 0;

	for (i = 0; i < d->nnodes; i++)
		count += sf->strand[i].present;
	fprintf(out, "\nstrands: %u\n", count);
	for (i = 0; i < d->nnodes; i++) {
		const struct sf_strand *s = &sf->strand[i];
		const struct sd_node *n = &d->nodes[i];
		const char *what;
		char rot[48];

		if (!s->present)
			continue;
		snprintf(rot, sizeof(rot), "transform, rotation %s", s->rotation ? s->rotation : "slerp");
		what = n->kind == MOT_NODE_FREE ? rot :
		       s->rpm ? "rpm" : n->kind == MOT_NODE_REVOLUTE ? "angle" : "position";
		fprintf(out, "  %-16s %-8s %4u key%s  frames %g to %g  (%s)\n", n->name,
			interp_name[s->interp], s->nkeys, s->nkeys == 1 ? " " : "s",
			s->key_frames[0], s->key_frames[s->nkeys - 1], what);
	}
}

static void others(FILE *out, const struct scene_desc *d)
{
	static const char *const mode[] = { "loop", "bounce", "growth" };
	uint32_t i;

	if (d->has_camera) {
		const struct sd_curve *c = &d->camera.ch[0];

		fprintf(out, "\ncamera: %-8s %4u key%s  frames %g to %g  ease in %g out %g\n",
			interp_name[c->interp], c->nkeys, c->nkeys == 1 ? " " : "s",
			c->keys[0].frame, c->keys[c->nkeys - 1].frame, d->camera.ease_in,
			d->camera.ease_out);
	}
	if (d->ncycles)
		fprintf(out, "\ncycles: %u\n", d->ncycles);
	for (i = 0; i < d->ncycles; i++) {
		const struct sd_cycle *c = &d->cycles[i];

		fprintf(out, "  %-16s %-6s %d to %d step %d, %lld frame%s per step from frame %lld\n",
			c->name, mode[c->mode], c->first, c->last, c->skip,
			(long long)c->frames_per_step, c->frames_per_step == 1 ? "" : "s",
			(long long)c->start_frame);
	}
	if (d->nattrs)
		fprintf(out, "\nattributes: %u\n", d->nattrs);
	for (i = 0; i < d->nattrs; i++) {
		const struct sd_curve *c = &d->attrs[i].curve;

		fprintf(out, "  %-16s %-8s %4u key%s  frames %g to %g\n", d->attrs[i].name,
			interp_name[c->interp], c->nkeys, c->nkeys == 1 ? " " : "s",
			c->keys[0].frame, c->keys[c->nkeys - 1].frame);
	}
}

/* The systems and aims: what each is, its items and channels, its steps
 * and checkpoints (what seeking costs). */
static void systems(FILE *out, const struct scene_desc *d, const struct mot_scene *sc)
{
	uint32_t i;

	if (d->nsys)
		fprintf(out, "\nsystems: %u\n", d->nsys);
	for (i = 0; i < d->nsys; i++) {
		const struct sd_system *s = &d->sys[i];
		const struct mot_system *m = &sc->sys[i];
		const struct mot_steps *st = m->kind == MOT_SYS_PARTICLES ? &m->particles->steps :
					     m->kind == MOT_SYS_FLOCK ? &m->flock->steps : NULL;

		fprintf(out, "  %-16s ", sd_sys_name(s));
		if (s->kind == SD_SURFACE)
			fprintf(out, "surface, %s net %u x %u, %u x %u samples", s->surface->basis ==
				MOT_SURFACE_BEZIER ? "Bezier" : "B-spline", s->surface->ncu,
				s->surface->ncv, s->surface->nsu, s->surface->nsv);
		else if (s->kind == SD_PARTICLES)
			fprintf(out, "particles, %s, %s of %u", s->particles->motion ==
				MOT_PARTICLES_NEWTON ? "newtonian" : "scripted",
				s->particles->emit ? "a pool" : "a lattice", m->nitems);
		else
			fprintf(out, "flock of %u", m->nitems);
		fprintf(out, ": %u channels", m->nout);
		if (st)
			fprintf(out, ", %lld steps at %g a second, a checkpoint every %u",
				(long long)st->nsteps, (double)st->rate_num / st->rate_den, st->every);
		fprintf(out, "\n");
	}
	if (d->naims)
		fprintf(out, "\naims: %u (pan and tilt, %u grid points a frame)\n", d->naims,
			sc->aims[0].sub);
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	static const struct option opts[] = { { "help", no_argument, NULL, 'h' }, { 0 } };
	const struct scene_desc *d;
	struct scene_file sf;
	struct scene_built b;
	const char *path;
	int rc;

	rc = cli_scene_args(cmd, argc, argv, out, err, opts, NULL, NULL, &path, &sf, &b);
	if (rc >= 0)
		return rc;
	rc = STRAND_EXIT_OK;
	d = &sf.desc;
	fprintf(out, "scene %s (%s)\n", d->name[0] ? d->name : "(unnamed)", path);
	fprintf(out, "timing: %u", d->rate_num);
	if (d->rate_den != 1)
		fprintf(out, "/%u", d->rate_den);
	fprintf(out, " frames/s, %u ticks/s, frames %g to %g (%.3f s)\n", d->tick_hz,
		d->frame_first, d->frame_last,
		(d->frame_last - d->frame_first) * d->rate_den / d->rate_num);
	fprintf(out, "\nhierarchy: %u node%s\n", d->nnodes, d->nnodes == 1 ? "" : "s");
	if (tree(out, d)) {
		rc = STRAND_EXIT_INTERNAL;
		fprintf(err, "strand info: out of memory\n");
	}
	strands(out, &sf);
	others(out, d);
	systems(out, d, &b.sc);
	fprintf(out, "\ncore: %zu bytes in one block (%u curves, %u rotation tracks, %u free strands)\n",
		b.block_size, b.sc.ncurves, b.sc.nrot, b.sc.nfree);
	scene_built_free(&b);
	scene_file_free(&sf);
	return rc;
}

const struct cli_cmd cmd_info = {
	.name = "info",
	.summary = "describe a scene: hierarchy, strands, timing, core memory",
	.help = "usage: strand info SCENE.yaml\n\n"
		"Print the node hierarchy as a tree, each strand's key count and\n"
		"interpolation, the camera, cycles and attributes, the timing, and the\n"
		"bytes the scene takes in the motion core (one block, sized at load).\n\n"
		"exit codes: 0 ok, 2 invalid scene, 3 usage, 4 I/O\n",
	.run = run,
};
