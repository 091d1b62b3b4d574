/* SPDX-License-Identifier: MIT */
/*
 * imp_urdf.c - a URDF robot as a model (imp.h), read with Debian's expat
 * (xmltree.h).
 *
 * Links and joints become nodes, from the root link down: each joint a node
 * under its parent link's, each child link a node under its joint's. strand
 * keeps pivots and axes in the rest pose's model coordinates (FORMULAS
 * section 3), so every URDF frame is composed down the tree at zero joint
 * values first, F(child) = F(parent) . T(xyz) . R(rpy) with R(rpy) =
 * Rz(yaw) Ry(pitch) Rx(roll) about fixed axes (URDF's convention, column
 * vectors): a joint's pivot is its frame's origin, its axis the frame's
 * rotation of <axis>. revolute and continuous joints are revolute, prismatic
 * prismatic, fixed (and floating, planar: held still) free nodes without a
 * strand. <limit> lower/upper/velocity are the joint's limits in degrees
 * or metres (effort is ignored, said once); <mimic> makes a joint follow
 * its master, value = multiplier x master + offset.
 */
#include "imp.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "xmltree.h"

#define DEG (180.0 / M_PI)

struct ujoint {
	struct xel *x;
	const char *name, *type;
	int parent, child;   /* link indices */
	double xyz[3], rpy[3], axis[3];
	bool has_limit, has_lower, has_upper, has_vel, has_effort;
	double lower, upper, vel;
	const char *mimic;
	double mult, offset;
	int node;            /* its node in the model */
};

struct ulink {
	struct xel *x;
	const char *name;
	int parent_joint;    /* -1 for the root */
	double frame[4][4];  /* rest frame in the model, column vectors */
	bool placed;
};

struct urdf {
	struct ulink *links;
	struct ujoint *joints;
	int nlinks, njoints;
	char *err;
	size_t errsize;
	const char *path;
};

static int fail(struct urdf *u, const struct xel *at, const char *fmt, const char *a, const char *b)
{
	char msg[400];

	snprintf(msg, sizeof(msg), fmt, a, b);
	snprintf(u->err, u->errsize, "line %ld: %s", at ? at->line : 0L, msg);
	return -EINVAL;
}

static const char *attr(struct xel *n, const char *name)
{
	return xml_attr(n, name);
}

static struct xel *child(struct xel *n, const char *name)
{
	return xml_child(n, name);
}

static int numbers(struct urdf *u, struct xel *n, const char *name, double *out, int count)
{
	const char *s = attr(n, name);
	char *end;
	int k;

	if (!s)
		return 0;
	for (k = 0; k < count; k++) {
		out[k] = strtod(s, &end);
		if (end == s || !isfinite(out[k]))
			return fail(u, n, "'%s' takes %s finite numbers", name,
				    count == 1 ? "1" : "3");
		s = end;
	}
	while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
		s++;
	if (*s)
		return fail(u, n, "'%s' takes %s finite numbers", name, count == 1 ? "1" : "3");
	return 0;
}

static int find_link(const struct urdf *u, const char *name)
{
	int i;

	for (i = 0; name && i < u->nlinks; i++)
		if (!strcmp(u->links[i].name, name))
			return i;
	return -1;
}

static int read_joint(struct urdf *u, struct xel *x, struct ujoint *j)
{
	static const char *const types[] = { "revolute", "continuous", "prismatic", "fixed",
					     "floating", "planar", NULL };
	struct xel *c;
	int k, err;

	j->x = x;
	j->name = attr(x, "name");
	j->type = attr(x, "type");
	j->axis[0] = 1;
	j->mult = 1;
	if (!j->name)
		return fail(u, x, "a joint without a name%s%s", "", "");
	for (k = 0; types[k]; k++)
		if (j->type && !strcmp(j->type, types[k]))
			break;
	if (!types[k])
		return fail(u, x, "joint '%s': type '%s' is not revolute, continuous, prismatic, fixed, floating or planar",
			    j->name, j->type ? j->type : "");
	c = child(x, "parent");
	j->parent = find_link(u, c ? attr(c, "link") : NULL);
	if (j->parent < 0)
		return fail(u, c ? c : x, "joint '%s': its parent link '%s' does not exist", j->name,
			    c && attr(c, "link") ? attr(c, "link") : "");
	c = child(x, "child");
	j->child = find_link(u, c ? attr(c, "link") : NULL);
	if (j->child < 0)
		return fail(u, c ? c : x, "joint '%s': its child link '%s' does not exist", j->name,
			    c && attr(c, "link") ? attr(c, "link") : "");
	if ((c = child(x, "origin")) &&
	    ((err = numbers(u, c, "xyz", j->xyz, 3)) || (err = numbers(u, c, "rpy", j->rpy, 3))))
		return err;
	if ((c = child(x, "axis"))) {
		double n;

		if ((err = numbers(u, c, "xyz", j->axis, 3)))
			return err;
		n = sqrt(j->axis[0] * j->axis[0] + j->axis[1] * j->axis[1] +
			 j->axis[2] * j->axis[2]);
		if (!(n > 1e-9))
			return fail(u, c, "joint '%s': a zero axis%s", j->name, "");
		for (k = 0; k < 3; k++)
			j->axis[k] /= n;
	}
	if ((c = child(x, "limit"))) {
		j->has_limit = true;
		j->has_lower = attr(c, "lower") != NULL;
		j->has_upper = attr(c, "upper") != NULL;
		j->has_vel = attr(c, "velocity") != NULL;
		j->has_effort = attr(c, "effort") != NULL;
		if ((err = numbers(u, c, "lower", &j->lower, 1)) ||
		    (err = numbers(u, c, "upper", &j->upper, 1)) ||
		    (err = numbers(u, c, "velocity", &j->vel, 1)))
			return err;
	}
	if ((c = child(x, "mimic"))) {
		j->mimic = attr(c, "joint");
		if (!j->mimic)
			return fail(u, c, "joint '%s': <mimic> without a joint%s", j->name, "");
		if ((err = numbers(u, c, "multiplier", &j->mult, 1)) ||
		    (err = numbers(u, c, "offset", &j->offset, 1)))
			return err;
	}
	return 0;
}

/* a . b for 4x4 matrices (column vectors). */
static void mul(double out[4][4], double a[4][4], double b[4][4])
{
	double r[4][4];
	int i, j, k;

	for (i = 0; i < 4; i++)
		for (j = 0; j < 4; j++)
			for (r[i][j] = 0, k = 0; k < 4; k++)
				r[i][j] += a[i][k] * b[k][j];
	memcpy(out, r, sizeof(r));
}

/* T(xyz) . Rz(y) Ry(p) Rx(r), column vectors. */
static void origin(double m[4][4], const double xyz[3], const double rpy[3])
{
	double cr = cos(rpy[0]), sr = sin(rpy[0]), cp = cos(rpy[1]), sp = sin(rpy[1]);
	double cy = cos(rpy[2]), sy = sin(rpy[2]);
	double r[4][4] = { { cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr, xyz[0] },
			   { sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr, xyz[1] },
			   { -sp, cp * sr, cp * cr, xyz[2] },
			   { 0, 0, 0, 1 } };

	memcpy(m, r, sizeof(r));
}

/* Nodes of link l and everything below it, depth first, joints in file order. */
static int emit(struct urdf *u, struct imp_model *m, int l, int parent_node, int depth)
{
	int node, j, k;

	if (depth > u->nlinks)
		return fail(u, u->links[l].x, "link '%s' is its own ancestor%s", u->links[l].name, "");
	node = imp_node_add(m, u->links[l].name);
	if (node < 0)
		return -ENOMEM;
	m->nodes[node].parent = parent_node;
	for (k = 0; k < 3; k++)
		m->nodes[node].pivot[k] = u->links[l].frame[k][3];
	for (j = 0; j < u->njoints; j++) {
		struct ujoint *jt = &u->joints[j];
		struct imp_node *n;
		double o[4][4];
		int c = jt->child, err;

		if (jt->parent != l)
			continue;
		origin(o, jt->xyz, jt->rpy);
		mul(u->links[c].frame, u->links[l].frame, o);
		jt->node = imp_node_add(m, jt->name);
		if (jt->node < 0)
			return -ENOMEM;
		n = &m->nodes[jt->node];
		n->parent = node;
		for (k = 0; k < 3; k++) {
			double(*f)[4] = u->links[c].frame;

			n->pivot[k] = f[k][3];
			n->axis[k] = f[k][0] * jt->axis[0] + f[k][1] * jt->axis[1] +
				     f[k][2] * jt->axis[2];
		}
		if (!strcmp(jt->type, "revolute") || !strcmp(jt->type, "continuous"))
			n->kind = IMP_REVOLUTE;
		else if (!strcmp(jt->type, "prismatic"))
			n->kind = IMP_PRISMATIC;
		if (n->kind != IMP_FREE && jt->has_limit) {
			double s = n->kind == IMP_REVOLUTE ? DEG : 1;

			n->has_min = jt->has_lower && strcmp(jt->type, "continuous");
			n->has_max = jt->has_upper && strcmp(jt->type, "continuous");
			n->min = jt->lower * s;
			n->max = jt->upper * s;
			n->has_vel = jt->has_vel && jt->vel > 0;
			n->vel = jt->vel * s;
		}
		err = emit(u, m, c, jt->node, depth + 1);
		if (err)
			return err;
	}
	return 0;
}

static int build(struct urdf *u, struct imp_model *m, struct xel *robot, FILE *warn)
{
	int i, j, root = -1, err;
	bool effort = false, odd = false;
	struct xel *c;

	for (c = robot->first; c; c = c->next) {
		if (!strcmp(c->name, "link"))
			u->nlinks++;
		else if (!strcmp(c->name, "joint"))
			u->njoints++;
	}
	u->links = calloc((size_t)u->nlinks + 1, sizeof(*u->links));
	u->joints = calloc((size_t)u->njoints + 1, sizeof(*u->joints));
	if (!u->links || !u->joints)
		return -ENOMEM;
	i = 0;
	for (c = robot->first; c; c = c->next)
		if (!strcmp(c->name, "link")) {
			struct ulink *l = &u->links[i++];

			l->x = c;
			l->name = attr(c, "name");
			l->parent_joint = -1;
			if (!l->name)
				return fail(u, c, "a link without a name%s%s", "", "");
			if (find_link(u, l->name) != i - 1)
				return fail(u, c, "link '%s' is defined twice%s", l->name, "");
		}
	j = 0;
	for (c = robot->first; c; c = c->next)
		if (!strcmp(c->name, "joint")) {
			struct ujoint *jt = &u->joints[j];
			int k;

			err = read_joint(u, c, jt);
			if (err)
				return err;
			for (k = 0; k < j; k++)
				if (!strcmp(u->joints[k].name, jt->name))
					return fail(u, c, "joint '%s' is defined twice%s", jt->name, "");
			if (u->links[jt->child].parent_joint >= 0)
				return fail(u, c, "joint '%s': link '%s' already has a parent joint",
					    jt->name, u->links[jt->child].name);
			u->links[jt->child].parent_joint = j;
			effort = effort || jt->has_effort;
			odd = odd || !strcmp(jt->type, "floating") || !strcmp(jt->type, "planar");
			j++;
		}
	if (!u->nlinks)
		return fail(u, robot, "a robot without links%s%s", "", "");
	for (i = 0; i < u->nlinks; i++)
		if (u->links[i].parent_joint < 0) {
			if (root >= 0)
				return fail(u, u->links[i].x, "two root links, '%s' and '%s' (a URDF is one tree)",
					    u->links[root].name, u->links[i].name);
			root = i;
		}
	if (root < 0)
		return fail(u, robot, "no root link: every link is some joint's child (a cycle)%s",
			    "", "");
	for (i = 0; i < 4; i++)
		u->links[root].frame[i][i] = 1;
	err = emit(u, m, root, -1, 0);
	if (err)
		return err;
	if ((uint32_t)(u->nlinks + u->njoints) != m->nnodes)
		return fail(u, robot, "links not reached from the root '%s' (a cycle)%s",
			    u->links[root].name, "");
	for (j = 0; j < u->njoints; j++) {
		struct ujoint *jt = &u->joints[j];
		struct imp_node *n = &m->nodes[jt->node];
		int k;

		if (!jt->mimic)
			continue;
		for (k = 0; k < u->njoints; k++)
			if (!strcmp(u->joints[k].name, jt->mimic))
				break;
		if (k == u->njoints || m->nodes[u->joints[k].node].kind == IMP_FREE ||
		    n->kind == IMP_FREE || u->joints[k].mimic)
			return fail(u, child(jt->x, "mimic"),
				    "joint '%s' mimics '%s', which is not a moving joint of its own",
				    jt->name, jt->mimic);
		n->mimic = u->joints[k].node;
		n->mult = jt->mult;
		n->offset = jt->offset * (n->kind == IMP_REVOLUTE ? DEG : 1);
	}
	if (warn && effort)
		fprintf(warn, "%s: joint effort limits are ignored (strand limits position and speed)\n",
			u->path);
	if (warn && odd)
		fprintf(warn, "%s: floating and planar joints are held still (fixed)\n", u->path);
	return 0;
}

int imp_urdf(struct imp_model *m, const char *path, const uint8_t *buf, size_t len,
	     const struct imp_opts *o, FILE *warn, char *err, size_t errsize)
{
	struct urdf u = { .err = err, .errsize = errsize, .path = path };
	struct xml_doc doc;
	struct xel *robot;
	int rc = xml_parse(&doc, (const char *)buf, len, err, errsize);

	if (rc)
		return rc;
	robot = doc.root;
	m->rate_num = o->rate_num;
	m->rate_den = o->rate_den;
	m->tick_hz = o->tick_hz;
	if (strcmp(robot->name, "robot"))
		rc = fail(&u, robot, "the root element is not <robot>%s%s", "", "");
	else
		rc = build(&u, m, robot, warn);
	if (!rc) {
		imp_note(m, "imported by strand import from %s (URDF robot '%s'): %d links, %d joints",
			 path, attr(robot, "name") ? attr(robot, "name") : "", u.nlinks, u.njoints);
		imp_note(m, "pivots and axes in the rest pose's coordinates (all joints at 0)");
		rc = imp_names(m, path, warn);
	}
	free(u.links);
	free(u.joints);
	xml_free(&doc);
	return rc;
}
