/* SPDX-License-Identifier: MIT */
/*
 * dbl_scene.c - the double twin of motion/scene.c and strand.c (see
 * dbl_scene.h): built like scene_build.c, evaluated like mot_scene_eval().
 */
#include "dbl_scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- the block ------------------------------------------------------------------ */

/* A bump allocator over the one block; sizes here are multiples of 8. */
struct pool {
	char *base;
	size_t used;
};

static void *take(struct pool *p, size_t n)
{
	void *r = p->base + p->used;

	p->used += (n + 7) & ~(size_t)7;
	return r;
}

static size_t rot_size(const struct sd_free *f)
{
	uint32_t nseg = f->nrot > 1 ? f->nrot - 1 : 1;

	return ((f->nrot * sizeof(double) + 7) & ~(size_t)7) + nseg * sizeof(struct dbl_rot_seg);
}

static size_t curve_size(const struct sd_curve *c)
{
	return c->nkeys ? (dbl_curve_size(c) + 7) & ~(size_t)7 : 0;
}

/* What the scene needs, in scene_build.c's order. */
static size_t count(struct dbl_scene *sc, const struct scene_desc *d)
{
	size_t bytes = 0;
	uint32_t i, k;

	sc->ncurves = sc->nrot = sc->nfree = 0;
	for (i = 0; i < d->nnodes; i++) {
		const struct sd_node *n = &d->nodes[i];

		if (n->kind != MOT_NODE_FREE) {
			sc->ncurves += (n->value.nkeys > 0) + (n->spin.nkeys > 0);
			bytes += curve_size(&n->value) + curve_size(&n->spin);
			continue;
		}
		if (!n->has_free)
			continue;
		sc->nfree++;
		for (k = 0; k < MOT_FREE_NCHANNELS; k++) {
			sc->ncurves += n->free.ch[k].nkeys > 0;
			bytes += curve_size(&n->free.ch[k]);
		}
		if (n->free.nrot) {
			sc->nrot++;
			bytes += rot_size(&n->free);
		}
	}
	return bytes + d->nnodes * sizeof(struct dbl_node) +
	       sc->ncurves * sizeof(struct dbl_curve) + sc->nrot * sizeof(struct dbl_rot) +
	       sc->nfree * sizeof(struct dbl_free);
}

/* ---- rotation tracks (strand.c) ----------------------------------------------------- */

static void quat_align(struct dbl_quat *out, const struct dbl_quat *a, const struct dbl_quat *b)
{
	*out = *b;
	if (dbl_quat_dot(a, b) < 0)
		*out = (struct dbl_quat){ -b->w, -b->x, -b->y, -b->z };
}

static int rot_init(struct dbl_rot *r, const struct sd_free *f, struct pool *p)
{
	struct dbl_quat prev, cur, next, s_cur, s_next, *q;
	uint32_t n = f->nrot, i, k;

	r->n = n;
	r->squad = f->squad;
	r->frame = take(p, n * sizeof(double));
	r->seg = take(p, (n > 1 ? n - 1 : 1) * sizeof(struct dbl_rot_seg));
	q = calloc(n, sizeof(*q));
	if (!q)
		return -1;
	/* normalised in double, then quantised: scene_build.c's build_rot() */
	for (i = 0; i < n; i++) {
		const double *kq = f->rot[i].q;
		double len = sqrt(kq[0] * kq[0] + kq[1] * kq[1] + kq[2] * kq[2] + kq[3] * kq[3]);
		double c[4];

		for (k = 0; k < 4; k++)
			if (!(len > 1e-9) || !dbl_quantize(kq[k] / len, &c[k]))
				goto fail;
		q[i] = (struct dbl_quat){ c[0], c[1], c[2], c[3] };
		if (!dbl_quantize(f->rot[i].frame, &r->frame[i]))
			goto fail;
	}
	r->q0 = q[0];
	cur = prev = s_cur = q[0];
	for (i = 0; i + 1 < n; i++) {
		struct dbl_rot_seg *sg = &r->seg[i];
		double a, b;

		quat_align(&next, &cur, &q[i + 1]);
		if (!dbl_quantize(f->rot[i].ease_out, &a) ||
		    !dbl_quantize(f->rot[i + 1].ease_in, &b))
			goto fail;
		dbl_ease_init(&sg->ease, a, b);
		sg->inv_h = 1 / (r->frame[i + 1] - r->frame[i]);
		dbl_slerp_prepare(&sg->arc, &cur, &next);
		if (r->squad) {
			struct dbl_quat after = next;

			if (i == 0)
				dbl_squad_inner(&s_cur, &prev, &cur, &next);
			if (i + 2 < n)
				quat_align(&after, &next, &q[i + 2]);
			dbl_squad_inner(&s_next, &cur, &next, &after);
			dbl_slerp_prepare(&sg->inner, &s_cur, &s_next);
			s_cur = s_next;
		} else {
			sg->inner = sg->arc;
		}
		prev = cur;
		cur = next;
	}
	/* the quaternions rot_eval() holds */
	dbl_quat_to_mat(&r->end[0], n == 1 ? &r->q0 : &r->seg[0].arc.a);
	dbl_quat_to_mat(&r->end[1], n == 1 ? &r->q0 : &r->seg[n - 2].arc.b);
	free(q);
	return 0;
fail:
	free(q);
	return -1;
}

static uint32_t rot_find(const struct dbl_rot *r, struct dbl_cursor *cur, double f)
{
	const double *k = r->frame;
	uint32_t lo = 0, hi = r->n - 1, i = cur->seg;

	if (i + 1 < r->n && k[i] <= f) {
		if (f < k[i + 1])
			return i;
		if (i + 2 < r->n && f < k[i + 2]) {
			cur->seg = i + 1;
			return i + 1;
		}
	}
	while (hi - lo > 1) {
		uint32_t mid = lo + (hi - lo) / 2;

		if (k[mid] <= f)
			lo = mid;
		else
			hi = mid;
	}
	cur->seg = lo;
	return lo;
}

/* the rotation, and its matrix made at init where an end key is held
 * (NULL elsewhere) */
static const struct dbl_mat *rot_eval(struct dbl_quat *out, const struct dbl_rot *r,
				      struct dbl_cursor *cur, double f)
{
	const struct dbl_rot_seg *sg;
	struct dbl_quat qa, qb;
	struct dbl_slerp outer;
	double s;

	if (r->n == 1 || f <= r->frame[0]) {
		*out = r->n == 1 ? r->q0 : r->seg[0].arc.a;
		return &r->end[0];
	}
	if (f >= r->frame[r->n - 1]) {
		*out = r->seg[r->n - 2].arc.b;
		return &r->end[1];
	}
	sg = &r->seg[rot_find(r, cur, f)];
	s = (f - r->frame[sg - r->seg]) * sg->inv_h;
	s = s > 1 ? 1 : s;
	if (!dbl_ease_is_identity(&sg->ease))
		s = dbl_ease_apply(&sg->ease, s);
	dbl_slerp_eval(&qa, &sg->arc, s);
	if (!r->squad) {
		*out = qa;
		return NULL;
	}
	dbl_slerp_eval(&qb, &sg->inner, s);
	dbl_slerp_prepare(&outer, &qa, &qb);
	dbl_slerp_eval(out, &outer, 2 * s * (1 - s));
	return NULL;
}

/* ---- building -------------------------------------------------------------------- */

static int curve_take(struct dbl_scene *sc, uint32_t *ci, int32_t *idx, const struct sd_curve *c,
		      double scale, bool integral, struct pool *p)
{
	*idx = -1;
	if (!c->nkeys)
		return 0;
	if (dbl_curve_init(&sc->curves[*ci], c, scale, integral, take(p, curve_size(c))))
		return -1;
	*idx = (int32_t)(*ci)++;
	return 0;
}

static int warp_init(struct dbl_warp *w, const struct sd_free *f)
{
	double lo = INFINITY, hi = -INFINITY, e_in, e_out;
	uint32_t k;

	for (k = 0; k < MOT_FREE_NCHANNELS; k++) {
		const struct sd_curve *c = &f->ch[k];

		if (c->nkeys) {
			lo = fmin(lo, c->keys[0].frame);
			hi = fmax(hi, c->keys[c->nkeys - 1].frame);
		}
	}
	if (f->nrot) {
		lo = fmin(lo, f->rot[0].frame);
		hi = fmax(hi, f->rot[f->nrot - 1].frame);
	}
	if (lo > hi)
		lo = hi = 0;
	if (!dbl_quantize(lo, &w->f0) || !dbl_quantize(hi, &w->f1) ||
	    !dbl_quantize(f->ease_in, &e_in) || !dbl_quantize(f->ease_out, &e_out))
		return -1;
	w->on = (e_in != 0 || e_out != 0) && w->f1 > w->f0;
	if (w->on)
		dbl_ease_init(&w->ease, e_out / (w->f1 - w->f0), e_in / (w->f1 - w->f0));
	return 0;
}

static int node_init(struct dbl_scene *sc, uint32_t i, const struct sd_node *sn, uint32_t *ci,
		     uint32_t *ri, uint32_t *fi, struct pool *p)
{
	struct dbl_node *n = &sc->nodes[i];
	double scale = sn->kind == MOT_NODE_REVOLUTE ? 1.0 / 360.0 : 1.0;
	double len = sqrt(sn->axis[0] * sn->axis[0] + sn->axis[1] * sn->axis[1] +
			  sn->axis[2] * sn->axis[2]);
	uint32_t k;

	n->parent = sn->parent;
	n->kind = sn->kind;
	n->axis_id = sn->axis_id;
	n->curve = n->spin = n->strand = -1;
	for (k = 0; k < 3; k++) {
		if (!dbl_quantize(sn->pivot[k], &n->pivot[k]))
			return -1;
		if (sn->kind == MOT_NODE_FREE)
			n->axis[k] = 0;
		else if (sn->axis_id != MOT_AXIS_VEC)
			n->axis[k] = k == (uint32_t)sn->axis_id;
		else if (!(len > 1e-9) || !dbl_quantize(sn->axis[k] / len, &n->axis[k]))
			return -1;
	}
	n->prow = 0;
	for (k = 0; k < 3; k++)
		if (n->pivot[k] != 0)
			n->prow = n->pivot[(k + 1) % 3] != 0 || n->pivot[(k + 2) % 3] != 0 ? 3 : k;
	if (!dbl_quantize(sn->rest * scale, &n->rest))
		return -1;
	for (k = 0; k < 3; k++) {
		const double *a = n->axis;
		uint32_t j = (k + 1) % 3, l = (k + 2) % 3;
		bool tilted = sn->kind == MOT_NODE_REVOLUTE && sn->axis_id == MOT_AXIS_VEC;

		n->rot_sq[k] = tilted ? a[j] * a[j] + a[l] * a[l] : 0;
		n->rot_pr[k] = tilted ? a[j] * a[l] : 0;
	}
	if (sn->kind != MOT_NODE_FREE)
		return curve_take(sc, ci, &n->curve, &sn->value, scale, false, p) ||
			       curve_take(sc, ci, &n->spin, &sn->spin, 1.0, true, p) ?
			       -1 : 0;
	if (!sn->has_free)
		return 0;
	{
		struct dbl_free *f = &sc->free[*fi];

		for (k = 0; k < MOT_FREE_NCHANNELS; k++)
			if (curve_take(sc, ci, &f->ch[k], &sn->free.ch[k], 1.0, false, p))
				return -1;
		f->rot = -1;
		if (sn->free.nrot) {
			if (rot_init(&sc->rot[*ri], &sn->free, p))
				return -1;
			f->rot = (int32_t)(*ri)++;
		}
		if (warp_init(&f->warp, &sn->free))
			return -1;
		n->strand = (int32_t)(*fi)++;
	}
	return 0;
}

int dbl_scene_new(struct dbl_scene *sc, const struct scene_desc *d)
{
	struct pool p = { NULL, 0 };
	uint32_t i, ci = 0, ri = 0, fi = 0;
	size_t size;

	memset(sc, 0, sizeof(*sc));
	if (d->has_camera || d->ncycles || d->nattrs)
		return -1;
	size = count(sc, d);
	p.base = aligned_alloc(64, (size + 63) & ~(size_t)63);
	if (!p.base)
		return -1;
	sc->block = p.base;
	sc->rate_num = d->rate_num;
	sc->rate_den = d->rate_den;
	sc->nnodes = d->nnodes;
	sc->nodes = take(&p, d->nnodes * sizeof(*sc->nodes));
	sc->curves = take(&p, sc->ncurves * sizeof(*sc->curves));
	sc->rot = take(&p, sc->nrot * sizeof(*sc->rot));
	sc->free = take(&p, sc->nfree * sizeof(*sc->free));
	for (i = 0; i < d->nnodes; i++) {
		if (d->nodes[i].parent >= (int32_t)i ||
		    node_init(sc, i, &d->nodes[i], &ci, &ri, &fi, &p)) {
			dbl_scene_free(sc);
			return -1;
		}
	}
	return 0;
}

void dbl_scene_free(struct dbl_scene *sc)
{
	free(sc->block);
	memset(sc, 0, sizeof(*sc));
}

int dbl_eval_new(struct dbl_eval *ev, const struct dbl_scene *sc)
{
	ev->cursors = calloc(sc->ncurves + sc->nrot + 1, sizeof(*ev->cursors));
	ev->memo = calloc(sc->nnodes + 1, sizeof(*ev->memo));
	ev->memo_world = NULL;
	if (ev->cursors && ev->memo)
		return 0;
	dbl_eval_free(ev);
	return -1;
}

void dbl_eval_free(struct dbl_eval *ev)
{
	free(ev->cursors);
	free(ev->memo);
	ev->cursors = NULL;
	ev->memo = NULL;
}

int dbl_pose_new(struct dbl_pose *p, const struct dbl_scene *sc)
{
	size_t n = sc->nnodes ? sc->nnodes : 1;

	p->world = calloc(n, sizeof(*p->world));
	p->pos = calloc(n, sizeof(*p->pos));
	p->value = calloc(n, sizeof(*p->value));
	p->rpm = calloc(n, sizeof(*p->rpm));
	if (p->world && p->pos && p->value && p->rpm)
		return 0;
	dbl_pose_free(p);
	return -1;
}

void dbl_pose_free(struct dbl_pose *p)
{
	free(p->world);
	free(p->pos);
	free(p->value);
	free(p->rpm);
	memset(p, 0, sizeof(*p));
}

/* ---- evaluation (scene.c) ------------------------------------------------------------ */

static double joint_value(const struct dbl_scene *sc, struct dbl_eval *ev,
			  const struct dbl_node *n, struct dbl_memo *m, double f, double *rpm)
{
	*rpm = 0;
	if (n->curve >= 0) {
		/* scene.c's piece memo */
		double v;

		if (f >= m->piece.lo && f < m->piece.hi) {
			if (dbl_piece_at(&m->piece, f, &v))
				return v;
			if (m->piece.whole)
				return dbl_curve_eval(&sc->curves[n->curve],
						      &ev->cursors[n->curve], f);
		}
		dbl_piece_learn(&m->piece, &sc->curves[n->curve], &ev->cursors[n->curve], f);
		return dbl_curve_eval(&sc->curves[n->curve], &ev->cursors[n->curve], f);
	}
	if (n->spin >= 0) {
		const struct dbl_curve *c = &sc->curves[n->spin];
		struct dbl_cursor *cur = &ev->cursors[n->spin];

		/* turns = integral(rpm df) * den / (60 num): strand.c's spin */
		*rpm = dbl_curve_eval(c, cur, f);
		return n->rest +
		       dbl_curve_integral(c, cur, f) * sc->rate_den / (60.0 * sc->rate_num);
	}
	return n->rest;
}

static double warp_apply(const struct dbl_warp *w, double f)
{
	double span = w->f1 - w->f0;

	if (!w->on || f <= w->f0 || f >= w->f1)
		return f;
	return w->f0 + dbl_ease_apply(&w->ease, (f - w->f0) / span) * span;
}

/* scene.c's free_linear(): S . H . R and t; false when the node has no
 * rotation, scale or shear channel (the linear part is the identity) */
static bool free_linear(struct dbl_mat *m, double t[3], const struct dbl_scene *sc,
			struct dbl_eval *ev, const struct dbl_free *fs, double frame)
{
	struct dbl_decomp d;
	const struct dbl_mat *held; /* R(d.rot), made at init */
	double v[MOT_FREE_NCHANNELS], g = warp_apply(&fs->warp, frame);
	bool rot = fs->rot >= 0, shs = false;
	uint32_t k;

	for (k = 0; k < MOT_FREE_NCHANNELS; k++) {
		int32_t c = fs->ch[k];

		if (c >= 0) {
			v[k] = dbl_curve_eval(&sc->curves[c], &ev->cursors[c], g);
			shs = shs || k >= MOT_FREE_SX;
		} else {
			v[k] = k >= MOT_FREE_SX && k <= MOT_FREE_SZ;
		}
	}
	for (k = 0; k < 3; k++)
		t[k] = v[MOT_FREE_TX + k];
	if (!rot && !shs)
		return false;
	if (!rot) {
		/* S . H */
		const double *sv = v + MOT_FREE_SX, *hv = v + MOT_FREE_HXY;

		*m = (struct dbl_mat){ { { sv[0], 0, 0 },
					 { sv[1] * hv[0], sv[1], 0 },
					 { sv[2] * hv[1], sv[2] * hv[2], sv[2] },
					 { t[0], t[1], t[2] } } };
		return true;
	}
	held = rot_eval(&d.rot, &sc->rot[fs->rot], &ev->cursors[sc->ncurves + (uint32_t)fs->rot],
			g);
	if (!shs) {
		/* R */
		if (held)
			*m = *held;
		else
			dbl_quat_to_mat(m, &d.rot);
		for (k = 0; k < 3; k++)
			m->m[3][k] = t[k];
		return true;
	}
	for (k = 0; k < 3; k++) {
		d.translate[k] = t[k];
		d.scale[k] = v[MOT_FREE_SX + k];
		d.shear[k] = v[MOT_FREE_HXY + k];
	}
	if (held)
		dbl_mat_compose_r(m, &d, held);
	else
		dbl_mat_compose(m, &d);
	return true;
}

/* scene.c's tilted_rot(): Rodrigues on the prepared squares and products */
static void tilted_rot(struct dbl_mat *r, const struct dbl_node *n, double s, double c)
{
	const double *a = n->axis, *sq = n->rot_sq, *pr = n->rot_pr;
	double omc = 1 - c;

	*r = (struct dbl_mat){ {
		{ 1 - omc * sq[0], omc * pr[2] + s * a[2], omc * pr[1] - s * a[1] },
		{ omc * pr[2] - s * a[2], 1 - omc * sq[1], omc * pr[0] + s * a[0] },
		{ omc * pr[1] + s * a[1], omc * pr[0] - s * a[0], 1 - omc * sq[2] },
		{ 0, 0, 0 },
	} };
}

/* scene.c's node_world(): pos = (p + t) . P_lin + P_t, W_lin = M . P_lin,
 * W_t = pos - p . W_lin */
static void node_world(struct dbl_mat *w, double pos[3], const struct dbl_mat *par,
		       const struct dbl_mat *m, const double p[3], const double t[3])
{
	const double q[3] = { p[0] + t[0], p[1] + t[1], p[2] + t[2] };
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++)
			w->m[i][j] = m->m[i][0] * par->m[0][j] + m->m[i][1] * par->m[1][j] +
				     m->m[i][2] * par->m[2][j];
	for (j = 0; j < 3; j++) {
		pos[j] = q[0] * par->m[0][j] + q[1] * par->m[1][j] + q[2] * par->m[2][j] +
			 par->m[3][j];
		w->m[3][j] = pos[j] - (p[0] * w->m[0][j] + p[1] * w->m[1][j] + p[2] * w->m[2][j]);
	}
}

/* scene.c's translate_world(): W = T(t) . P, pos = W_t + p . P_lin */
static void translate_world(struct dbl_mat *w, double pos[3], const struct dbl_mat *par,
			    const double p[3], const double t[3])
{
	int j;

	for (j = 0; j < 3; j++) {
		double y0 = par->m[0][j], y1 = par->m[1][j], y2 = par->m[2][j];

		w->m[3][j] = t[0] * y0 + t[1] * y1 + t[2] * y2 + par->m[3][j];
		pos[j] = w->m[3][j] + p[0] * y0 + p[1] * y1 + p[2] * y2;
		w->m[0][j] = y0;
		w->m[1][j] = y1;
		w->m[2][j] = y2;
	}
}

/* scene.c's revolute_world(): R mixes rows a and b of the parent; with
 * U = P_t + p_a P_a + p_b P_b, pos = U + p_o P_o and W_t = U - p_a W_a - p_b W_b */
static void revolute_world(struct dbl_mat *w, double pos[3], const struct dbl_mat *par,
			   unsigned o, const double p[3], double s, double c, unsigned prow)
{
	static const unsigned ab[3][2] = { { 1, 2 }, { 2, 0 }, { 0, 1 } };
	const unsigned a = ab[o][0], b = ab[o][1];
	unsigned j;

	if (prow < 3) {
		/* scene.c's revolute_line(): p = p_k e_k, pos = P_t + p_k P_k and
		 * W_t = P_t + p_k (P_k - W_k) */
		for (j = 0; j < 3; j++) {
			double pa = par->m[a][j], pb = par->m[b][j];

			w->m[a][j] = c * pa + s * pb;
			w->m[b][j] = c * pb - s * pa;
			w->m[o][j] = par->m[o][j];
		}
		for (j = 0; j < 3; j++) {
			double pk = par->m[prow][j];

			pos[j] = par->m[3][j] + p[prow] * pk;
			w->m[3][j] = par->m[3][j] + p[prow] * (pk - w->m[prow][j]);
		}
		return;
	}
	for (j = 0; j < 3; j++) {
		double pa = par->m[a][j], pb = par->m[b][j];
		double wa = c * pa + s * pb, wb = c * pb - s * pa;
		double u = par->m[3][j] + p[a] * pa + p[b] * pb;

		pos[j] = u + p[o] * par->m[o][j];
		w->m[3][j] = u - p[a] * wa - p[b] * wb;
		w->m[a][j] = wa;
		w->m[b][j] = wb;
		w->m[o][j] = par->m[o][j];
	}
}

/* scene.c's mot_scene_eval(), memo, two passes and all */
void dbl_scene_eval(const struct dbl_scene *sc, struct dbl_eval *ev, double frame,
		    struct dbl_pose *out)
{
	static const struct dbl_mat id = { { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0, 0, 0 } } };
	static const double zero[3] = { 0, 0, 0 };
	const bool warm = ev->memo_world == out->world;
	uint32_t i, k;

	for (i = 0; i < sc->nnodes; i++) {
		/* scene.c's first pass: joint values, sines and cosines */
		const struct dbl_node *n = &sc->nodes[i];
		struct dbl_memo *m = &ev->memo[i];
		double v = 0, r = 0;

		if (n->kind != MOT_NODE_FREE) {
			v = joint_value(sc, ev, n, m, frame, &r);
			m->fresh = !warm || v != m->value;
			if (m->fresh) {
				m->value = v;
				if (n->kind == MOT_NODE_REVOLUTE)
					sincos(2 * M_PI * v, &m->s, &m->c);
			}
		}
		out->value[i] = v;
		out->rpm[i] = r;
	}
	for (i = 0; i < sc->nnodes; i++) {
		const struct dbl_node *n = &sc->nodes[i];
		const struct dbl_mat *par = n->parent >= 0 ? &out->world[n->parent] : &id;
		const bool still = warm && (n->parent < 0 || !ev->memo[n->parent].moved);
		struct dbl_memo *m = &ev->memo[i];
		struct dbl_mat *w = &out->world[i], local;
		double *pos = out->pos[i], t[3];

		m->moved = true;
		switch (n->kind) {
		case MOT_NODE_REVOLUTE:
			if (still && !m->fresh) {
				m->moved = false;
			} else if (n->axis_id != MOT_AXIS_VEC) {
				revolute_world(w, pos, par, n->axis_id, n->pivot, m->s, m->c, n->prow);
			} else {
				tilted_rot(&local, n, m->s, m->c);
				node_world(w, pos, par, &local, n->pivot, zero);
			}
			break;
		case MOT_NODE_PRISMATIC:
			if (still && !m->fresh) {
				m->moved = false;
				break;
			}
			for (k = 0; k < 3; k++)
				t[k] = m->value * n->axis[k];
			translate_world(w, pos, par, n->pivot, t);
			break;
		default:
			if (n->strand < 0) {
				if (still)
					m->moved = false;
				else
					translate_world(w, pos, par, n->pivot, zero);
			} else if (!free_linear(&local, t, sc, ev, &sc->free[n->strand], frame)) {
				translate_world(w, pos, par, n->pivot, t);
			} else {
				node_world(w, pos, par, &local, n->pivot, t);
			}
			break;
		}
	}
	ev->memo_world = out->world;
}
