/* SPDX-License-Identifier: MIT */
/* scene.c - validating and evaluating a scene (see scene.h). */
#include "curve_priv.h"
#include "decomp.h"
#include "scene.h"
#include "trig.h"

#define ONE MOT_Q32_ONE

/* The inline paths below (a joint's curve, the kernels of the small case)
 * only where 128-bit integers are the compiler's: on the portable two-word
 * path their copies cost more code than they save time (a Cortex-M4), and
 * it is the one fix.h path the other builds check them against (make
 * check-cross). */
static const bool small_kernels = MOT_HAVE_INT128;

/* The kernels' loops over three rows or columns unrolled where they are
 * inlined (gcc -O2 keeps them loops): each entry's operands at fixed
 * offsets, no loop counter, and the products of one column free to overlap
 * the next's (a tenth fewer instructions and cycles per joint); kept loops
 * where code size is the point (the portable path). */
#if MOT_HAVE_INT128
#define UNROLL3 _Pragma("GCC unroll 3")
#else
#define UNROLL3
#endif

static const struct mot_mat mat_id = {
	{ { ONE, 0, 0 }, { 0, ONE, 0 }, { 0, 0, ONE }, { 0, 0, 0 } },
};

static bool in_range(int32_t idx, uint32_t n)
{
	return idx >= 0 && (uint32_t)idx < n;
}

static bool opt_in_range(int32_t idx, uint32_t n)
{
	return idx == -1 || in_range(idx, n);
}

static bool axis_is_unit(const mot_q32 a[3])
{
	/* |a|^2 within 2^-24 of 1, compared in Q64.64 */
	mot_acc n2 = mot_acc_mac(mot_acc_mac(mot_acc_mul(a[0], a[0]), a[1], a[1]), a[2], a[2]);
	int64_t q = mot_acc_round(n2, 64 - 24, NULL); /* Q40.24 */

	return q >= ((int64_t)1 << 24) - 1 && q <= ((int64_t)1 << 24) + 1;
}

void mot_node_prepare(struct mot_node *n)
{
	const mot_q32 *a = n->axis;
	bool tilted = n->kind == MOT_NODE_REVOLUTE && n->axis_id == MOT_AXIS_VEC;
	unsigned k;

	for (k = 0; k < 3; k++) {
		unsigned j = (k + 1) % 3, l = (k + 2) % 3;
		mot_acc sq = mot_acc_mac(mot_acc_mul(a[j], a[j]), a[l], a[l]);

		/* Q64.64 products rounded to Q2.62 */
		n->rot_sq[k] = tilted ? mot_acc_round(sq, 2, NULL) : 0;
		n->rot_pr[k] = tilted ? mot_acc_round(mot_acc_mul(a[j], a[l]), 2, NULL) : 0;
	}
}

/* The derived fields are those mot_node_prepare() gives. */
static bool node_prepared(const struct mot_node *n)
{
	struct mot_node p = *n;
	unsigned k;

	mot_node_prepare(&p);
	for (k = 0; k < 3; k++)
		if (p.rot_sq[k] != n->rot_sq[k] || p.rot_pr[k] != n->rot_pr[k])
			return false;
	return true;
}

int mot_scene_validate(const struct mot_scene *sc)
{
	uint32_t i, k;

	for (i = 0; i < sc->nnodes; i++) {
		const struct mot_node *n = &sc->nodes[i];

		if (n->parent < -1 || (n->parent >= 0 && (uint32_t)n->parent >= i))
			return MOT_E_PARENT;
		switch (n->kind) {
		case MOT_NODE_FREE:
			if (n->curve != -1 || n->spin != -1 || !opt_in_range(n->strand, sc->nfree))
				return MOT_E_KIND;
			break;
		case MOT_NODE_REVOLUTE:
		case MOT_NODE_PRISMATIC:
			if (n->strand != -1 || !opt_in_range(n->curve, sc->ncurves) ||
			    !opt_in_range(n->spin, sc->ncurves) || (n->curve >= 0 && n->spin >= 0))
				return MOT_E_KIND;
			if (n->spin >= 0 &&
			    (n->kind != MOT_NODE_REVOLUTE || !sc->curves[n->spin].integral))
				return MOT_E_KIND;
			if (n->axis_id > MOT_AXIS_VEC || !axis_is_unit(n->axis))
				return MOT_E_INVAL;
			if (n->axis_id != MOT_AXIS_VEC)
				for (k = 0; k < 3; k++)
					if (n->axis[k] != (k == n->axis_id ? MOT_Q32_ONE : 0))
						return MOT_E_INVAL;
			break;
		default:
			return MOT_E_KIND;
		}
		if (!node_prepared(n))
			return MOT_E_INVAL;
	}
	for (i = 0; i < sc->nfree; i++) {
		for (k = 0; k < MOT_FREE_NCHANNELS; k++)
			if (!opt_in_range(sc->free[i].channel[k], sc->ncurves))
				return MOT_E_INVAL;
		if (!opt_in_range(sc->free[i].rot, sc->nrot))
			return MOT_E_INVAL;
		for (k = 0; k < 4; k++)
			if (!opt_in_range(sc->free[i].quat[k], sc->ncurves) ||
			    (sc->free[i].quat[k] < 0) != (sc->free[i].quat[0] < 0))
				return MOT_E_INVAL;
		if (sc->free[i].rot >= 0 && sc->free[i].quat[0] >= 0)
			return MOT_E_INVAL;
	}
	if (sc->camera)
		for (k = 0; k < MOT_CAM_NCHANNELS; k++)
			if (!in_range(sc->camera->ch[k], sc->ncurves))
				return MOT_E_INVAL;
	for (i = 0; i < sc->nattrs; i++)
		if (!in_range(sc->attr_curve[i], sc->ncurves))
			return MOT_E_INVAL;
	for (i = 0; i < sc->nsys; i++)
		if ((uint64_t)sc->sys[i].out0 + sc->sys[i].nout > sc->nsysout)
			return MOT_E_INVAL;
	for (i = 0; i < sc->naims; i++) {
		const struct mot_aim *a = &sc->aims[i];

		if (a->src == MOT_AIM_SRC_NODE ? a->index >= sc->nnodes :
		    a->src != MOT_AIM_SRC_SYS || (uint64_t)a->index + 3 > sc->nsysout)
			return MOT_E_INVAL;
	}
	return MOT_OK;
}

/* The small case (see node_world below): every bound, and every result,
 * below 2^62 raw; an offset (pivot, translation) below 2^61, so that p + t
 * fits. */
#define SMALL_LIM ((uint64_t)1 << 62)
#define SMALL_OFFSET ((uint64_t)1 << 61)

/*
 * A pre-scale for the small kernels on x86-64: a factor known to be below
 * 2^(63 - PRE_SHIFT) raw (a revolute joint's sine or cosine; the pivot of
 * an axis joint where it is below 2 units, the memo's pre) is taken times
 * 2^PRE_SHIFT, and the sum it joins is rounded at 2^(32 + PRE_SHIFT)
 * instead of 2^32: the same exact sums, so the same bits (and, in the
 * small case, products below 2^125 and sums that fit). Why: the low word
 * of a 128-bit value shifted by 62 is a shift and an LEA of the high word
 * times 4, where a shift by 32 takes two shifts, an add and copies (fix.h's
 * mot_dw_shr()). make bench-ab on this project's Zen 3 VM, one set each:
 * the sines 2 to 3% off the arm's and the 1,000 joints' time, the pivots
 * 4 to 5% more off the arm's, 4% off the axis joints'. Elsewhere (ARM's
 * EXTR, or two 32-bit words) the shift costs the same either way and the
 * scaling would not pay: 0, and the copies that take it are left out.
 */
#if defined(__x86_64__)
#define PRE_SHIFT 30
#else
#define PRE_SHIFT 0
#endif

static uint64_t add_sat(uint64_t a, uint64_t b)
{
	return a + b < a ? UINT64_MAX : a + b;
}

/* ceil(a b / 2^32) or more for raw magnitudes, UINT64_MAX where that
 * does not fit */
static uint64_t mul_up(uint64_t a, uint64_t b)
{
	uint64_t lo, hi = mot_umul_hi(a, b, &lo);

	if (hi >> 32)
		return UINT64_MAX;
	return add_sat(hi << 32 | lo >> 32, 1);
}

/* A rotation as used, rounded, times a linear part of 2-norm below l, the
 * product rounded: below (1 + 2^-22) l + 3 (node_world's proof). */
static uint64_t lin_rot(uint64_t l)
{
	return l >= SMALL_LIM ? UINT64_MAX : l + (l >> 22) + 4;
}

static uint64_t max_u64(uint64_t a, uint64_t b)
{
	return a > b ? a : b;
}

/* ceil(sqrt(x)) */
static uint64_t sqrt_up(uint64_t x)
{
	uint64_t r = 0, b;

	for (b = (uint64_t)1 << 31; b; b >>= 1)
		if ((r + b) * (r + b) <= x)
			r += b;
	return r * r < x ? r + 1 : r;
}

/*
 * A bound on the 2-norm of a free node's S . H as free_linear() makes it
 * (raw): rows (sx, 0, 0), (sy hxy, sy, 0), (sz hxz, sz hyz, sz), each
 * product rounded once (a unit), the channels' values within their curves'
 * bounds (1 and 0 without a curve), B those bounds entry by entry. |A|_2^2
 * is the spectral radius of A^T A, at most its largest row sum, at most
 * B^T B's: row i sums B_ki r_k over k, r_k the sum of B's row k.
 */
static uint64_t scale_shear_bound(const struct mot_scene *sc, const struct mot_free_strand *fs)
{
	uint64_t b[6], e10, e20, e21, r0, r1, r2, g;
	unsigned k;

	for (k = 0; k < 6; k++) {
		int32_t c = fs->channel[MOT_FREE_SX + k];

		b[k] = c >= 0 ? mot_curve_bound(&sc->curves[c]) : k < 3 ? (uint64_t)ONE : 0;
	}
	e10 = add_sat(mul_up(b[1], b[3]), 1);
	e20 = add_sat(mul_up(b[2], b[4]), 1);
	e21 = add_sat(mul_up(b[2], b[5]), 1);
	r0 = b[0];
	r1 = add_sat(e10, b[1]);
	r2 = add_sat(add_sat(e20, e21), b[2]);
	g = add_sat(add_sat(mul_up(b[0], r0), mul_up(e10, r1)), mul_up(e20, r2));
	g = max_u64(g, add_sat(mul_up(b[1], r1), mul_up(e21, r2)));
	g = max_u64(g, mul_up(b[2], r2));
	/* sqrt(g 2^-32) 2^32 = sqrt(g) 2^16 */
	return g >= (uint64_t)1 << 62 ? UINT64_MAX : sqrt_up(g) << 16;
}

/*
 * A bound on the 2-norm of a node's W_lin (raw) from one on its parent's,
 * l, UINT64_MAX for none: the same for a prismatic joint or a free node
 * without rotation, scale or shear (W_lin = P_lin, copied), lin_rot() for a
 * rotation alone, and for a free node that scales or shears the bound of
 * its S . H times l, times the rotation's 1 + 2^-22 and with a unit an
 * entry of M's own rounding where it has one, and the product's rounding.
 */
static uint64_t lin_bound(const struct mot_scene *sc, const struct mot_node *n, uint64_t l)
{
	const struct mot_free_strand *fs;
	bool rot, shs = false;
	uint64_t a;
	unsigned k;

	switch (n->kind) {
	case MOT_NODE_REVOLUTE:
		return lin_rot(l);
	case MOT_NODE_PRISMATIC:
		return l;
	default:
		if (n->strand < 0)
			return l;
		fs = &sc->free[n->strand];
		rot = fs->rot >= 0 || fs->quat[0] >= 0;
		for (k = MOT_FREE_SX; k < MOT_FREE_NCHANNELS; k++)
			shs = shs || fs->channel[k] >= 0;
		if (!shs)
			return rot ? lin_rot(l) : l;
		a = scale_shear_bound(sc, fs);
		if (rot) /* M = (S . H) . R~ rounded: below (1 + 2^-22) a + 3 */
			a = lin_rot(a);
		return add_sat(mul_up(a, l), 3);
	}
}

/* The largest |t| component of a node over its whole timeline (raw), 0 for
 * a revolute joint. */
static uint64_t offset_bound(const struct mot_scene *sc, const struct mot_node *n)
{
	uint64_t b = 0;
	uint32_t k;

	switch (n->kind) {
	case MOT_NODE_REVOLUTE:
		return 0;
	case MOT_NODE_PRISMATIC:
		/* |v a_k| rounded, |a_k| <= 1 + 2^-25: one unit more than 2 |v| */
		b = n->curve >= 0 ? mot_curve_bound(&sc->curves[n->curve]) : (uint64_t)mot_abs(n->rest);
		return add_sat(add_sat(b, b), 1);
	default:
		if (n->strand < 0)
			return 0;
		for (k = MOT_FREE_TX; k <= MOT_FREE_TZ; k++) {
			int32_t c = sc->free[n->strand].channel[k];
			uint64_t v = c >= 0 ? mot_curve_bound(&sc->curves[c]) : 0;

			b = v > b ? v : b;
		}
		return b;
	}
}

/*
 * What a free strand's channels are, known from the scene (memo->free,
 * free_linear()): a rotation (a track or quaternion curves), a scale or
 * shear channel, and (bounds) whether every scale and shear value stays
 * below 2^40 raw over the whole timeline (its curve's bound; 1 and 0
 * without one), so that free_linear()'s sums need no test of the values.
 */
enum {
	FREE_ROT = 1,  /* a rotation track or four quaternion curves */
	FREE_SHS = 2,  /* a scale or shear channel */
	FREE_FITS = 4, /* every scale and shear below 2^40 raw (small_kernels) */
	FREE_UNIT = 8, /* its quaternions near unit: R(q) untested (small_kernels) */
	FREE_OWN = MOT_MEMO_FREE_OWN, /* channel_value() (small_kernels; scene.h) */
};

static unsigned free_flags(const struct mot_scene *sc, const struct mot_free_strand *fs,
			   bool bounds)
{
	unsigned f = fs->rot >= 0 || fs->quat[0] >= 0 ? FREE_ROT : 0, k;
	bool fits = small_kernels && bounds;

	for (k = MOT_FREE_SX; k < MOT_FREE_NCHANNELS; k++) {
		int32_t c = fs->channel[k];

		if (c < 0)
			continue;
		f |= FREE_SHS;
		fits = fits && mot_curve_bound(&sc->curves[c]) < (uint64_t)1 << 40;
	}
	/* a track of near-unit arcs (mot_rot_track's unit), or curves whose
	 * value is normalised (mot_quat_normalize(): unit within a few units,
	 * or the identity) */
	if (small_kernels && (fs->rot >= 0 ? sc->rot[fs->rot].unit : fs->quat[0] >= 0))
		f |= FREE_UNIT;
	return f | (fits ? FREE_FITS : 0) | (small_kernels && bounds ? FREE_OWN : 0);
}

/*
 * What the memo knows of a node before any evaluation: whether it is of the
 * small case, and bounds on its linear part and translation for its
 * children. Under a parent whose world translation is below B and linear
 * part below lp (2-norm, so every entry), the node's own below l, with a
 * pivot of 1-norm p1 and a translation below t a component: pos below
 * B + (p1 + 3 t) lp + 1 and W_t below that + p1 l + 1, raw.
 */
static void memo_prepare(struct mot_node_memo *m, const struct mot_scene *sc,
			 const struct mot_node *n, const struct mot_node_memo *up)
{
	uint64_t t = offset_bound(sc, n), p1 = 0, bt, sum;
	uint64_t lp = up ? up->lin : (uint64_t)ONE; /* the identity's */
	bool off = t < SMALL_OFFSET;
	uint32_t k;

	for (k = 0; k < 3; k++) {
		off = off && (uint64_t)mot_abs(n->pivot[k]) < SMALL_OFFSET;
		p1 = add_sat(p1, (uint64_t)mot_abs(n->pivot[k]));
	}
	m->prow = 0;
	for (k = 0; k < 3; k++)
		if (n->pivot[k])
			m->prow = n->pivot[(k + 1) % 3] || n->pivot[(k + 2) % 3] ? 3 : k;
	m->lin = lin_bound(sc, n, lp);
	m->free = n->kind == MOT_NODE_FREE && n->strand >= 0 ?
			  free_flags(sc, &sc->free[n->strand], true) :
			  0;
	bt = up ? up->bound : 0;
	/* (2 p1 + 3 t) max(lp, l) + 2 */
	sum = add_sat(add_sat(p1, p1), add_sat(add_sat(t, t), t));
	sum = add_sat(add_sat(bt, mul_up(sum, max_u64(lp, m->lin))), 2);
	m->small = lp < SMALL_LIM && m->lin < SMALL_LIM && off && sum < SMALL_LIM;
	m->bound = m->small ? sum : UINT64_MAX;
	m->pre = PRE_SHIFT && m->small;
	for (k = 0; k < 3; k++)
		m->pre = m->pre && (uint64_t)mot_abs(n->pivot[k]) < (uint64_t)1 << (63 - PRE_SHIFT);
}

/* ---- a joint's curve: the piece memo ----------------------------------------- */

/* How the memo evaluates its piece (struct mot_node_memo): curve.c's
 * piece_value() with what it decides per evaluation decided once (how),
 * and which of them the first pass takes inline (op: all but PIECE_WHOLE,
 * and a spin joint's). */
enum {
	PIECE_HELD,        /* no piece: the value `held` */
	PIECE_SHIFTED,     /* a hermite piece in s' (curve.h) */
	PIECE_LINEAR,      /* u = (f - f0) / (f1 - f0), linear */
	PIECE_CUBIC,       /* the same, hermite */
	PIECE_LINEAR_EASE, /* u eased, linear */
	PIECE_CUBIC_EASE,  /* u eased, hermite */
	PIECE_SLOW,        /* op only: the rest, out of line (joint_slow()) */
	PIECE_WHOLE,       /* how only: no piece, mot_curve_eval() every time */
	PIECE_SOLVE,       /* how only: no piece, the solve (c->solve) called straight */
	PIECE_WARP_SOLVE,  /* how only: the same at the strand-wide warped frame */
};

static void piece_forget(struct mot_node_memo *m)
{
	m->lo = MOT_Q32_MAX;
	m->hi = MOT_Q32_MIN;
	m->held = 0;
	m->piece = NULL;
	m->op = m->how = PIECE_HELD;
	m->warp = NULL;
	m->glo = MOT_Q32_MAX;
	m->ghi = MOT_Q32_MIN;
	m->arc = NULL;
	m->end = NULL;
	m->f0 = 0;
}

/* A joint the first pass never takes inline (PIECE_SLOW) has an empty span
 * (lo > hi): every frame is outside it, so the pass tests the span alone,
 * and joint_slow() goes by how (a span it learnt is not kept). */
static void slow_span(struct mot_node_memo *m)
{
	m->lo = MOT_Q32_MAX;
	m->hi = MOT_Q32_MIN;
}

/* The memo of a joint without a curve: its rest value, or a spin, always. */
static void piece_fixed(struct mot_node_memo *m, const struct mot_node *n)
{
	piece_forget(m);
	if (n->kind == MOT_NODE_FREE || n->curve >= 0)
		return;
	m->held = n->rest;
	m->op = m->how = n->spin >= 0 ? PIECE_SLOW : PIECE_HELD;
	if (m->op == PIECE_HELD) { /* always; a spin's span stays empty (slow_span()) */
		m->lo = MOT_Q32_MIN;
		m->hi = MOT_Q32_MAX;
	}
}

/*
 * What the memo knows of a curve at frame f, from mot_curve_eval()'s way
 * (curve.c's eval()): an interpolating curve holds its first value up to
 * its first key, its last from its last key, and between them, at the
 * frame or, under a strand-wide ease, at the warped frame g (which holds
 * the first or last value again at the span's ends), is the piece of the
 * key interval there, evaluated without any choice left. The span of the
 * first piece starts after the first key, which the held value covers.
 */
static void piece_learn(struct mot_node_memo *m, const struct mot_curve *c,
			struct mot_cursor *cur, mot_q32 f)
{
	const struct mot_curve_seg *s;
	mot_q32 *lo = &m->lo, *hi = &m->hi;

	piece_forget(m);
	if (!c->plain && (c->nkeys == 0 || (f > c->span_f0 && f < c->span_f1))) {
		/* an approximating kind, a compact curve, one key: the whole
		 * way inside the span, glo..ghi, which joint_slow() tests (every
		 * frame without a key); its held ends below */
		m->lo = MOT_Q32_MIN;
		m->hi = MOT_Q32_MAX;
		m->how = PIECE_WHOLE;
		/* curve.c's eval() without its tests: the solve at the frame, or
		 * at the warped frame under a strand-wide ease alone */
		if (c->solve)
			m->how = PIECE_SOLVE;
		else if (c->nkeys && c->kind >= MOT_INTERP_BSPLINE && c->span_ease &&
			 !c->seg_ease && !c->compact)
			m->how = PIECE_WARP_SOLVE;
		if (c->nkeys) {
			m->glo = c->span_f0 + 1;
			m->ghi = c->span_f1;
		} else {
			m->glo = MOT_Q32_MIN;
			m->ghi = MOT_Q32_MAX;
		}
		return;
	}
	if (f > c->span_f0 && f < c->span_f1 && c->span_ease) {
		/* the span's inside, raw; the rest at the warped frame */
		m->warp = c;
		m->lo = c->span_f0 + 1;
		m->hi = c->span_f1;
		f = span_warp(c, f);
		lo = &m->glo;
		hi = &m->ghi;
	}
	if (f <= c->span_f0) {
		*lo = MOT_Q32_MIN;
		*hi = c->span_f0 + 1; /* |span_f0| < 2^62 */
		m->held = c->keys[0].value;
		return;
	}
	if (f >= c->span_f1) {
		*lo = c->span_f1;
		*hi = MOT_Q32_MAX;
		m->held = c->keys[c->nkeys - 1].value;
		return;
	}
	s = &c->seg[locate_seg(c, cur, f)];
	*lo = s->f0 > c->span_f0 ? s->f0 : c->span_f0 + 1;
	*hi = s->f1;
	if (c->kind == MOT_INTERP_STEP) {
		m->held = s->vref;
		return;
	}
	m->piece = s;
	if (s->ush >= 0)
		m->how = PIECE_SHIFTED;
	else if (c->seg_ease && !mot_ease_is_identity(&s->ease))
		m->how = c->kind == MOT_INTERP_LINEAR ? PIECE_LINEAR_EASE : PIECE_CUBIC_EASE;
	else
		m->how = c->kind == MOT_INTERP_LINEAR ? PIECE_LINEAR : PIECE_CUBIC;
}

/* The first pass's own case (op): the memo's piece or held value at a frame
 * of its span, under a strand-wide ease at the warped frame; false where
 * the warped frame leaves the piece, or where the value leaves int64 as
 * value_of() would find (joint_slow() then learns again and goes the whole
 * way). */
static inline __attribute__((always_inline)) bool piece_fast(const struct mot_node_memo *m,
							     mot_q32 f, mot_q32 *out)
{
	const struct mot_curve_seg *s = m->piece;
	int64_t p, q;
	int sh;

	if (m->warp) {
		f = span_warp(m->warp, f);
		if (f < m->glo || f >= m->ghi)
			return false;
	}
	if (m->op == PIECE_HELD) {
		*out = m->held;
		return true;
	}
	if (m->op == PIECE_SHIFTED) {
		p = poly_eval(s->c, (f - s->f0) << s->ush);
	} else if (m->op == PIECE_LINEAR) {
		p = mul62(s->c[1], piece_u(f - s->f0, &s->inv_w));
	} else if (m->op == PIECE_CUBIC) {
		p = poly_eval(s->c, piece_u(f - s->f0, &s->inv_w));
	} else {
		int64_t u = eased_u(s, f - s->f0);

		p = m->op == PIECE_LINEAR_EASE ? mul62(s->c[1], u) : poly_eval(s->c, u);
	}
	/* round(p / 2^sh) = floor((floor(p / 2^(sh - 1)) + 1) / 2), with vsh in
	 * [1, 62] (curve_learn()): value_of()'s bits, no sum to overflow */
	sh = s->vsh;
	q = ((p >> (sh - 1)) + 1) >> 1;
	return !__builtin_add_overflow(s->vref, q, out);
}

/*
 * The piece a joint a few places on will read, asked for now (the first
 * pass): a piece sits wherever its curve's keys are, so the hardware's
 * prefetchers, which follow the nodes' and memos' arrays, do not bring it,
 * and its two lines (the polynomial, then the reciprocal and scales)
 * arrived from the second-level cache in the middle of the joint's chain.
 * Eight joints ahead, both lines: the 1,000 joints' first pass 9.9 -> 9.3
 * ns a joint on this project's VM (that pass timed alone, scene_count's
 * fastest of 40; the whole scene by make bench-time). A hint: no fault on
 * any address, a NULL piece included (integer arithmetic on its address,
 * so no pointer arithmetic on NULL), and no change to any result.
 */
#define PIECE_AHEAD 8
static inline __attribute__((always_inline)) void piece_prefetch(const struct mot_curve_seg *s)
{
	__builtin_prefetch(s);
	__builtin_prefetch((const void *)((uintptr_t)s + 64));
}

/*
 * The piece a joint will read: the memo's, or where the memo has none for
 * the whole span (an approximating, compact or eased curve, joint_slow()'s
 * way: 30% of the random nodes' evaluations), its cursor's piece, which
 * is the one the solve starts from. The address in integers: a curve
 * without pieces must not make pointer arithmetic on NULL.
 */
static inline __attribute__((always_inline)) void joint_prefetch(const struct mot_scene *sc,
								 const struct mot_eval *ev,
								 const struct mot_node *n,
								 const struct mot_node_memo *m)
{
	/* the memo's piece, the common case, in line (gcc put it out of line:
	 * two jumps a joint) */
	if (__builtin_expect(m->how >= PIECE_WHOLE && n->curve >= 0, 0))
		piece_prefetch((const struct mot_curve_seg *)(
			(uintptr_t)sc->curves[n->curve].seg +
			(uintptr_t)ev->cursors[n->curve].seg * sizeof(struct mot_curve_seg)));
	else
		piece_prefetch(m->piece);
}

/*
 * A revolute joint's sine and cosine of its new value, made two fresh
 * revolute joints later in the first pass (mot_scene_eval()): the value
 * comes at the end of a chain of products (the piece's cubic, each step
 * rounded), and the sine's chain (its table point, then five products) made
 * right after it left the joints behind waiting on both. Two joints on, the
 * value is there and the two chains overlap. The same bits.
 */
static inline __attribute__((always_inline)) void joint_sines(struct mot_node_memo *m)
{
#if MOT_HAVE_INT128
	struct mot_sc p = mot_sincos_in(m->value);
#else
	struct mot_sc p = mot_sincos_pair(m->value);
#endif

	m->s = p.s;
	m->c = p.c;
}

/* A frame outside the memo's span: learn the piece there, and the value
 * the whole way (out of line: joint_slow() then saves no register). */
static __attribute__((noinline)) mot_q32 curve_learn(const struct mot_curve *c,
						     struct mot_cursor *cur,
						     struct mot_node_memo *m, mot_q32 f,
						     uint32_t *sat)
{
	piece_learn(m, c, cur, f);
	/* a piece whose scale value_of() takes the wide way for: out of line */
	m->op = m->how >= PIECE_WHOLE || (m->piece && (m->piece->vsh < 1 || m->piece->vsh > 62)) ?
			PIECE_SLOW :
			m->how;
	if (m->op == PIECE_SLOW)
		slow_span(m);
	return mot_curve_eval(c, cur, f, sat);
}

int mot_eval_reset(struct mot_eval *ev, const struct mot_scene *sc)
{
	uint32_t i, n = mot_eval_cursor_count(sc);

	if (ev->ncursors < n || ev->nmemo < mot_eval_memo_count(sc))
		return MOT_E_CAPACITY;
	for (i = 0; i < n; i++) {
		ev->cursors[i].seg = 0;
		ev->cursors[i].key = 0;
	}
	for (i = 0; i < sc->nnodes; i++) {
		const struct mot_node *nd = &sc->nodes[i];
		struct mot_node_memo *m = &ev->memo[i];

		m->value = m->s = m->c = 0;
		m->moved = m->fresh = 1;
		piece_fixed(m, nd);
		memo_prepare(m, sc, nd, nd->parent >= 0 ? &ev->memo[nd->parent] : NULL);
	}
	for (i = 0; i < sc->nsys; i++)
		mot_system_eval_reset(&ev->sys[i]);
	ev->sat = 0;
	ev->memo_world = NULL;
	return MOT_OK;
}

/* The angle of a spin joint and its speed (kept out of the loop's way). */
static __attribute__((noinline)) mot_q32 spin_value(const struct mot_scene *sc,
						    struct mot_eval *ev,
						    const struct mot_node *n, mot_q32 frame,
						    mot_q32 *rpm)
{
	const struct mot_curve *c = &sc->curves[n->spin];
	struct mot_cursor *cur = &ev->cursors[n->spin];

	*rpm = mot_curve_eval(c, cur, frame, &ev->sat);
	return mot_add_sat(n->rest, mot_spin_turns(c, cur, &sc->timing, frame, &ev->sat),
			   &ev->sat);
}

/*
 * A spin joint's own memo, where 128-bit integers are the compiler's (the
 * first pass never takes it: its span lo..hi stays empty, and joint_slow()
 * comes here): between the frames glo (included) and ghi (excluded), a held
 * end or a piece of the rpm curve, which gives both the speed (piece_at()'s
 * bits: mot_curve_eval()'s) and the integral (the piece's area up to its
 * start plus cv_seg_integral(): mot_curve_integral()'s bits), whose turns
 * mot_spin_turns_of() makes. spin_value()'s bits without the curve's tests,
 * its two lookups of the piece (the speed's and the integral's) and four
 * calls; how says which (spin_learn()), held the held speed or, of a linear
 * piece, its change of value.
 */
enum {
	SPIN_FIRST,   /* to the first key: the speed held, the integral linear */
	SPIN_LAST,    /* from the last key, likewise */
	SPIN_STEP,    /* a step piece: likewise */
	SPIN_LINEAR,  /* a linear piece */
	SPIN_SHIFTED, /* a hermite piece in s' (curve.h) */
	SPIN_WHOLE,   /* spin_value(): one key, or a piece whose scale value_of()
		       * takes the wide way for */
};

/* A frame outside the spin's span: learn the held end or piece there, and
 * the value the whole way. Every frame of a one-key curve is SPIN_WHOLE's;
 * the held ends' spans stop 2^62 from their key, so that the offset fits
 * (|key frames| < 2^62: mot_curve_init()). */
static __attribute__((noinline)) mot_q32 spin_learn(const struct mot_scene *sc,
						    struct mot_eval *ev,
						    const struct mot_node *n,
						    struct mot_node_memo *m, mot_q32 frame,
						    mot_q32 *rpm)
{
	const struct mot_curve *c = &sc->curves[n->spin];
	const struct mot_curve_seg *s;
	uint32_t i;

	m->piece = NULL;
	m->how = SPIN_WHOLE;
	m->glo = MOT_Q32_MIN;
	m->ghi = MOT_Q32_MAX;
	if (!c->plain) {
		/* no piece: always the whole way */
	} else if (frame <= c->span_f0) {
		m->how = SPIN_FIRST;
		m->held = c->keys[0].value;
		m->glo = c->span_f0 - MOT_LEN_LIMIT;
		m->ghi = c->span_f0 + 1; /* e = 0: the first piece's area, the same */
	} else if (frame >= c->span_f1) {
		m->how = SPIN_LAST;
		m->held = c->keys[c->nkeys - 1].value;
		m->glo = c->span_f1;
		m->ghi = c->span_f1 + MOT_LEN_LIMIT;
	} else {
		i = locate_seg(c, &ev->cursors[n->spin], frame);
		s = &c->seg[i];
		m->piece = s;
		m->glo = s->f0 > c->span_f0 ? s->f0 : c->span_f0 + 1;
		m->ghi = s->f1;
		if (c->kind == MOT_INTERP_STEP) {
			m->how = SPIN_STEP;
			m->held = s->vref;
		} else if (s->plain) { /* vsh in [1, 62]; a hermite piece in s' */
			m->how = c->kind == MOT_INTERP_LINEAR ? SPIN_LINEAR : SPIN_SHIFTED;
			m->held = c->keys[i + 1].value - s->vref;
		}
	}
	return spin_value(sc, ev, n, frame, rpm);
}

static __attribute__((noinline)) mot_q32 spin_fast(const struct mot_scene *sc,
						   struct mot_eval *ev,
						   const struct mot_node *n,
						   struct mot_node_memo *m, mot_q32 frame,
						   mot_q32 *rpm)
{
	const struct mot_curve_seg *s = m->piece;
	const struct mot_curve *c = &sc->curves[n->spin];
	mot_q32 v = m->held;
	int64_t e, u, p;
	mot_acc a;

	if (frame < m->glo || frame >= m->ghi)
		return spin_learn(sc, ev, n, m, frame, rpm);
	switch (m->how) {
	case SPIN_FIRST:
		a = mot_acc_add(c->area_first, mot_acc_mul(v, frame - c->span_f0));
		break;
	case SPIN_LAST:
		a = mot_acc_add(c->area_last, mot_acc_mul(v, frame - c->span_f1));
		break;
	case SPIN_STEP:
		a = mot_acc_add(s->area, mot_acc_mul(v, frame - s->f0));
		break;
	case SPIN_LINEAR:
	case SPIN_SHIFTED:
		e = frame - s->f0;
		if (m->how == SPIN_LINEAR) {
			u = piece_u(e, &s->inv_w);
			p = mul62(s->c[1], u);
			a = cv_seg_integral(MOT_INTERP_LINEAR, s, v, e, u);
		} else {
			u = e << s->ush;
			p = poly_eval(s->c, u);
			a = cv_seg_integral(MOT_INTERP_HERMITE, s, 0, e, u);
		}
		a = mot_acc_add(s->area, a);
		/* value_of()'s bits, as piece_fast() */
		p = ((p >> (s->vsh - 1)) + 1) >> 1;
		if (__builtin_add_overflow(s->vref, p, &v))
			return spin_value(sc, ev, n, frame, rpm);
		break;
	default:
		return spin_value(sc, ev, n, frame, rpm);
	}
	*rpm = v;
	return mot_add_sat(n->rest, mot_spin_turns_of(a, &sc->timing, &ev->sat), &ev->sat);
}

/* The joint value of a joint node, and its spin speed (mot_node_local(),
 * and the first pass where 128-bit integers are not the compiler's). */
static inline __attribute__((always_inline)) mot_q32
joint_value(const struct mot_scene *sc, struct mot_eval *ev, const struct mot_node *n,
	    mot_q32 frame, mot_q32 *rpm)
{
	*rpm = 0;
	if (n->curve >= 0)
		return mot_curve_eval(&sc->curves[n->curve], &ev->cursors[n->curve], frame,
				      &ev->sat);
	if (n->spin >= 0)
		return spin_value(sc, ev, n, frame, rpm);
	return n->rest;
}

/*
 * A joint's value, and its spin speed, where the first pass does not take
 * the memo's value inline (mot_scene_eval()): a frame outside the memo's
 * span (every frame of a PIECE_SLOW joint's, which is empty: a spin, or the
 * whole curve as how says), or a warped frame that left its piece
 * (piece_fast() said so), learns the piece there and takes
 * mot_curve_eval(); inside the span of an approximating curve without
 * eases, or with the strand-wide one alone, the solve called straight
 * (curve.c's eval() without its call and tests). Where 128-bit integers are not the compiler's,
 * joint_value() alone: the memo's copies of the arithmetic would cost more
 * code than they save time (a Cortex-M4), and it is the path the other
 * builds check them against (make check-cross). The same bits every way.
 */
static __attribute__((noinline)) mot_q32 joint_slow(const struct mot_scene *sc,
						    struct mot_eval *ev,
						    const struct mot_node *n,
						    struct mot_node_memo *m, mot_q32 frame,
						    mot_q32 *rpm)
{
	const struct mot_curve *c;
	struct mot_cursor *cur;

	if (small_kernels && n->curve < 0 && n->spin >= 0)
		return spin_fast(sc, ev, n, m, frame, rpm);
	if (!small_kernels || n->curve < 0)
		return joint_value(sc, ev, n, frame, rpm);
	*rpm = 0;
	c = &sc->curves[n->curve];
	cur = &ev->cursors[n->curve];
	if (m->how < PIECE_WHOLE || frame < m->glo || frame >= m->ghi)
		return curve_learn(c, cur, m, frame, &ev->sat);
	/* strictly inside the span (glo..ghi): eval()'s way to the solve */
	if (m->how == PIECE_SOLVE)
		return mot_cv_approx_eval(c, cur, frame, NULL, &ev->sat);
	if (m->how == PIECE_WHOLE)
		return mot_curve_eval(c, cur, frame, &ev->sat);
	frame = span_warp(c, frame);
	if (frame <= c->span_f0)
		return c->keys[0].value;
	if (frame >= c->span_f1)
		return c->keys[c->nkeys - 1].value;
	return mot_cv_approx_eval(c, cur, frame, NULL, &ev->sat);
}

/* A rotation kept as four component curves: their value normalised (out
 * of line: free_quat()'s call of a track then needs no frame of its own). */
static __attribute__((noinline)) void quat_of_curves(struct mot_quat *q,
						     const struct mot_scene *sc,
						     struct mot_eval *ev, const int32_t qc[4],
						     mot_q32 frame)
{
	mot_q32 v[4];
	struct mot_quat raw;
	unsigned k;

	for (k = 0; k < 4; k++)
		v[k] = mot_curve_eval(&sc->curves[qc[k]], &ev->cursors[qc[k]], frame, &ev->sat);
	raw = (struct mot_quat){ v[0], v[1], v[2], v[3] };
	if (mot_quat_normalize(q, &raw, &ev->sat) != MOT_OK) {
		mot_quat_identity(q);
		ev->sat |= MOT_SAT_DOMAIN;
	}
}

/* A free node's rotation as a quaternion: its track's (the held end's
 * matrix made at init returned, as mot_rot_track_eval() returns it) or its
 * four curves'. */
static inline const struct mot_rot_q62 *free_quat(struct mot_quat *q,
						  const struct mot_scene *sc, struct mot_eval *ev,
						  const struct mot_free_strand *fs, mot_q32 g)
{
	if (fs->rot < 0) {
		quat_of_curves(q, sc, ev, fs->quat, g);
		return NULL;
	}
	return mot_rot_track_eval(q, &sc->rot[fs->rot], &ev->cursors[sc->ncurves + (uint32_t)fs->rot],
				  g, &ev->sat);
}

/*
 * A free node's rotation track by its memo (struct mot_node_memo): over the
 * span lo..hi of warped frames it learnt, a held end key (its matrix made
 * at init), or one key interval, whose t and slerp or squad are
 * mot_rot_track_eval()'s without its end tests, its search and its choices,
 * or the track the whole way (a compact one, an end whose matrix was not
 * made). The memo's how, for a free node: */
enum {
	ROT_END = 0,   /* the matrix `end` */
	ROT_SLERP = 1, /* the interval `arc`, a slerp */
	ROT_SQUAD = 2, /* the same, a squad */
	ROT_EASE = 4,  /* with one of those: its ease */
	ROT_WHOLE = 8, /* mot_rot_track_eval() */
};

/*
 * The track at g the whole way (out of line), and what the memo knows of it
 * there, learnt from mot_rot_track_eval()'s way: it holds its first key up
 * to it (the span's end after it) and its last from it, and between them
 * evaluates the interval [f(i), f(i+1)) its cursor is left on (strand.h),
 * the first after f(0). A miss, once an interval; or a span the memo takes
 * the whole way (ROT_WHOLE), every time.
 */
static __attribute__((noinline)) const struct mot_rot_q62 *
rot_learn(struct mot_quat *q, struct mot_node_memo *m, const struct mot_scene *sc,
	  struct mot_eval *ev, int32_t rot, mot_q32 g)
{
	const struct mot_rot_track *r = &sc->rot[rot];
	struct mot_cursor *cur = &ev->cursors[sc->ncurves + (uint32_t)rot];
	const struct mot_rot_q62 *held = mot_rot_track_eval(q, r, cur, g, &ev->sat);
	const struct mot_rot_key *k = r->keys;
	const uint32_t n = r->nkeys, i = cur->seg;

	if (m->how == ROT_WHOLE && g >= m->lo && g < m->hi)
		return held; /* known */

	m->how = held ? ROT_END : ROT_WHOLE;
	m->end = held;
	if (n == 1 || g <= k[0].frame) {
		m->lo = MOT_Q32_MIN;
		m->hi = n == 1 ? MOT_Q32_MAX : k[0].frame + 1; /* below k[1] */
	} else if (g >= k[n - 1].frame) {
		m->lo = k[n - 1].frame;
		m->hi = MOT_Q32_MAX;
	} else if (r->compact) {
		m->lo = k[0].frame + 1;
		m->hi = k[n - 1].frame;
	} else {
		m->lo = i ? k[i].frame : k[0].frame + 1;
		m->hi = k[i + 1].frame;
		m->f0 = k[i].frame;
		m->arc = &r->seg[i];
		m->how = (r->squad ? ROT_SQUAD : ROT_SLERP) |
			 (mot_ease_is_identity(&r->seg[i].ease) ? 0 : ROT_EASE);
	}
	return held;
}

/* The memo's rotation at g (held: its matrix, or NULL and q), learnt
 * where g leaves its span. */
static inline __attribute__((always_inline)) const struct mot_rot_q62 *
rot_value(struct mot_quat *q, const struct mot_scene *sc, struct mot_eval *ev,
	  struct mot_node_memo *m, int32_t rot, mot_q32 g)
{
	const struct mot_rot_seg *sg = m->arc;
	mot_q32 s;

	if (g < m->lo || g >= m->hi)
		return rot_learn(q, m, sc, ev, rot, g);
	if (m->how == ROT_END) /* most, in a random scene: tested first */
		return m->end;
	if (m->how == ROT_WHOLE)
		return rot_learn(q, m, sc, ev, rot, g);
	s = mot_rot_seg_t(sg, g - m->f0);
	if (m->how & ROT_EASE)
		s = mot_ease_apply(&sg->ease, s, &ev->sat);
	if (m->how & ROT_SQUAD)
		mot_squad_eval(q, &sg->arc, &sg->inner, s, &ev->sat);
	else
		mot_slerp_eval(q, &sg->arc, s, &ev->sat);
	return NULL;
}

/* What free_linear() made: no linear part (the identity, not written), a
 * lower-triangular one (S . H, its zeros written) or any. */
enum { FREE_LIN_NONE, FREE_LIN_TRI, FREE_LIN_FULL };

/*
 * A free node's channel curve at frame g (FREE_OWN): mot_curve_eval()'s
 * bits without its call and its dispatch, where 128-bit integers are the
 * compiler's. The held ends of any curve; an approximating curve's solve
 * called straight; of a plain curve without a strand-wide ease, the piece
 * the cursor holds inline (curve.c's piece_at(), eased or not, and for vsh
 * in [1, 62] piece_fast()'s rounding, which cannot overflow: the sum with
 * vref is tested instead), and eval_plain() called straight for any other
 * piece, which moves the cursor. The rest the whole way. (Random free
 * nodes' channels: about as many held ends, plain pieces and solves.)
 */
static inline __attribute__((always_inline)) mot_q32
channel_value(const struct mot_curve *c, struct mot_cursor *cur, mot_q32 g, uint32_t *sat)
{
	const struct mot_curve_seg *s;
	uint32_t j;
	int64_t p;
	mot_q32 v;

	if (c->solve) {
		if (g <= c->span_f0)
			return c->keys[0].value;
		if (g >= c->span_f1)
			return c->keys[c->nkeys - 1].value;
		return mot_cv_approx_eval(c, cur, g, NULL, sat);
	}
	if (!c->plain)
		return mot_curve_eval(c, cur, g, sat);
	if (g <= c->span_f0)
		return c->keys[0].value;
	if (g >= c->span_f1)
		return c->keys[c->nkeys - 1].value;
	j = cur->seg;
	s = &c->seg[j];
	if (j >= c->nseg || g < s->f0 || g >= s->f1 || c->span_ease)
		return mot_cv_eval_plain(c, cur, g, sat);
	if (c->kind == MOT_INTERP_STEP)
		return s->vref;
	if (s->vsh < 1 || s->vsh > 62)
		return mot_cv_eval_plain(c, cur, g, sat);
	if (s->ush >= 0) {
		p = poly_eval(s->c, (g - s->f0) << s->ush);
	} else {
		int64_t u = c->seg_ease && !mot_ease_is_identity(&s->ease) ?
				    eased_u(s, g - s->f0) :
				    piece_u(g - s->f0, &s->inv_w);

		p = c->kind == MOT_INTERP_LINEAR ? mul62(s->c[1], u) : poly_eval(s->c, u);
	}
	p = ((p >> (s->vsh - 1)) + 1) >> 1;
	if (__builtin_add_overflow(s->vref, p, &v))
		return mot_cv_eval_plain(c, cur, g, sat);
	return v;
}

/*
 * A free strand's nine channels at g, each at its rest value without a
 * curve: channel_value()'s (own) or mot_curve_eval()'s. A loop, one copy of
 * channel_value(): unrolled (nine copies) it took 18 instructions fewer a
 * random node (823 against 833 a node a tick, make bench-count) but 8 KB
 * more code on the scene's hot path, and callgrind's cache simulation had
 * five times the instruction cache misses of a random scene (37 thousand
 * to 184 thousand; 39 thousand this way).
 */
static inline __attribute__((always_inline)) void
free_channels(mot_q32 v[MOT_FREE_NCHANNELS], const struct mot_curve *curves,
	      struct mot_cursor *cursors, const struct mot_free_strand *fs, mot_q32 g, bool own,
	      uint32_t *sat)
{
	uint32_t k;

	for (k = 0; k < MOT_FREE_NCHANNELS; k++) {
		int32_t c = fs->channel[k];

		if (c < 0)
			v[k] = (k >= MOT_FREE_SX && k <= MOT_FREE_SZ) ? MOT_Q32_ONE : 0;
		else if (own)
			v[k] = channel_value(&curves[c], &cursors[c], g, sat);
		else
			v[k] = mot_curve_eval(&curves[c], &cursors[c], g, sat);
	}
}

/*
 * The linear part S . H . R and the translation (row 3) of a free node
 * (channels without keys at their rest values) in m, what free_flags()
 * says of its strand in `how`. Returns FREE_LIN_NONE when the node has no
 * rotation, scale or shear channel: its linear part is then the identity,
 * exactly, and only m's translation row is written; FREE_LIN_TRI when it
 * has no rotation.
 */
static unsigned free_linear(struct mot_mat *m, const struct mot_scene *sc, struct mot_eval *ev,
			    struct mot_node_memo *memo, const struct mot_free_strand *fs,
			    unsigned how, mot_q32 frame)
{
	mot_q32 *const t = m->m[3];
	struct mot_decomp d;
	mot_q32 v[MOT_FREE_NCHANNELS], g = frame;
	const bool rot = how & FREE_ROT, shs = how & FREE_SHS;
	bool fits;
	const struct mot_rot_q62 *held = NULL; /* R(d.rot), made at init */
	const struct mot_curve *const curves = sc->curves;
	struct mot_cursor *const cursors = ev->cursors;
	struct mot_rot_q62 r;
	uint64_t ov = 0;
	uint32_t k, j;

	if (fs->warp.on) /* most strands have none: not even the call */
		g = mot_warp_apply(&fs->warp, frame, &ev->sat);
	/* the call alone where asked for (free_local(), the tests) */
	if (small_kernels && (how & FREE_OWN))
		free_channels(v, curves, cursors, fs, g, true, &ev->sat);
	else
		free_channels(v, curves, cursors, fs, g, false, &ev->sat);
	for (k = 0; k < 3; k++)
		t[k] = v[MOT_FREE_TX + k];
	if (!rot && !shs)
		return FREE_LIN_NONE;
	/* What mot_mat_compose() would give, bit for bit, with the absent part
	 * left out: without a rotation track R = I and the linear part is S . H
	 * itself; without scale and shear channels it is R rounded once from
	 * Q2.62. */
	if (!rot) {
		const mot_q32 *sv = v + MOT_FREE_SX, *hv = v + MOT_FREE_HXY;

		if (small_kernels && (how & FREE_FITS)) {
			/* mot_mul()'s bits: the products below 2^80 */
			m->m[1][0] = mot_acc_round_ov(mot_acc_mul(sv[1], hv[0]), 32, &ov);
			m->m[2][0] = mot_acc_round_ov(mot_acc_mul(sv[2], hv[1]), 32, &ov);
			m->m[2][1] = mot_acc_round_ov(mot_acc_mul(sv[2], hv[2]), 32, &ov);
		} else {
			m->m[1][0] = mot_mul(sv[1], hv[0], &ev->sat);
			m->m[2][0] = mot_mul(sv[2], hv[1], &ev->sat);
			m->m[2][1] = mot_mul(sv[2], hv[2], &ev->sat);
		}
		m->m[0][0] = sv[0];
		m->m[1][1] = sv[1];
		m->m[2][2] = sv[2];
		m->m[0][1] = m->m[0][2] = m->m[1][2] = 0;
		return FREE_LIN_TRI;
	}
	/* a track's by the memo, a held end key's matrix without the call
	 * (its quaternion only where mot_mat_compose_r() takes it, below) */
	if (fs->rot >= 0)
		held = rot_value(&d.rot, sc, ev, memo, fs->rot, g);
	else
		held = free_quat(&d.rot, sc, ev, fs, g);
	/* scales and shears below 2^8 (every real one): S . H's products
	 * below 2^48 raw, its rows' sums with R below 2^113 and every entry
	 * below 2^51, so mot_mat_compose_r()'s tests are known to pass; the
	 * rotation made first only where that would make it. Known from the
	 * curves' bounds for most strands (FREE_FITS), else tested here. Where
	 * 128-bit integers are not the compiler's compose_r() does it all (one
	 * copy of the sums: less code, as the kernels above) */
	fits = !shs || (how & FREE_FITS) ||
	       (small_kernels &&
		(mot_mag(v[MOT_FREE_SX]) | mot_mag(v[MOT_FREE_SY]) | mot_mag(v[MOT_FREE_SZ]) |
		 mot_mag(v[MOT_FREE_HXY]) | mot_mag(v[MOT_FREE_HXZ]) | mot_mag(v[MOT_FREE_HYZ])) <
			(uint64_t)1 << 40);
	if (small_kernels && fits && !held && (how & FREE_UNIT)) {
		mot_quat_rot_q62_unit(r.r, &d.rot);
		held = &r;
	}
	if (fits && (held || mot_quat_to_rot_q62(r.r, &d.rot, &ev->sat) == MOT_OK)) {
		const int64_t(*rr)[3] = (held ? held : &r)->r;

		if (!shs) {
			for (k = 0; k < 3; k++)
				for (j = 0; j < 3; j++)
					m->m[k][j] = mot_acc_round_ov(mot_acc_from(rr[k][j], 0), 30,
								      &ov);
			return FREE_LIN_FULL; /* |r| < 2^63: ov stays 0 */
		}
		/* mot_mat_compose_r()'s bits without its tests (mot_mul()'s
		 * where it fits) */
		mot_compose_rows(m, v[MOT_FREE_SX],
				 mot_acc_round_ov(mot_acc_mul(v[MOT_FREE_SY], v[MOT_FREE_HXY]), 32, &ov),
				 v[MOT_FREE_SY],
				 mot_acc_round_ov(mot_acc_mul(v[MOT_FREE_SZ], v[MOT_FREE_HXZ]), 32, &ov),
				 mot_acc_round_ov(mot_acc_mul(v[MOT_FREE_SZ], v[MOT_FREE_HYZ]), 32, &ov),
				 v[MOT_FREE_SZ], rr, &ov);
		return FREE_LIN_FULL; /* ov stays 0 */
	}
	for (k = 0; k < 3; k++) {
		d.translate[k] = t[k];
		d.scale[k] = v[MOT_FREE_SX + k];
		d.shear[k] = v[MOT_FREE_HXY + k];
	}
	if (held) /* the same end, and its quaternion */
		free_quat(&d.rot, sc, ev, fs, g);
	mot_mat_compose_r(m, &d, held, &ev->sat);
	return FREE_LIN_FULL;
}

/*
 * The rotation of a revolute joint about a tilted unit axis a by an angle
 * with cosine c and sine s: the matrix of the quaternion (cos/2, a sin/2)
 * of FORMULAS section 4 multiplied out (Rodrigues' formula in the
 * row-vector convention),
 *     R[k][k] = 1 - (1 - c)(a_j^2 + a_l^2)
 *     R[j][l] = (1 - c) a_j a_l + s a_k,   R[l][j] = (1 - c) a_j a_l - s a_k
 * for (k, j, l) = (k, k+1, k+2) mod 3. The squares and products of the axis
 * are constant and prepared in Q2.62 (mot_node_prepare), so a tick costs
 * one sincos and nine products, each entry rounded once from Q34.94; the
 * quaternion route costs a half-angle sincos, three roundings of the
 * quaternion and fifteen products.
 */
/* The pair R[j][l], R[l][j] of tilted_rot()'s matrix for (k, j, l) = (k,
 * k+1, k+2) mod 3: one sum (1 - c) a_j a_l and one term s a_k, added and
 * subtracted, and the diagonal entry R[k][k]. Constants where inlined. */
static inline __attribute__((always_inline)) void tilted_pair(struct mot_mat *r,
							      const struct mot_node *n,
							      mot_q32 s, mot_q32 omc, unsigned k)
{
	const unsigned j = (k + 1) % 3, l = (k + 2) % 3;
	uint64_t ov = 0; /* terms below 2^96: never set */
	/* a_k in Q2.62, exactly (|a| <= 1 + 2^-25, validated) */
	mot_acc sym = mot_acc_mac(mot_acc_start(0, 62), omc, n->rot_pr[k]);
	mot_acc asym = mot_acc_mul(s, (int64_t)((uint64_t)n->axis[k] << 30));

	r->m[k][k] = mot_acc_floor_ov(mot_acc_sub(mot_acc_start(ONE, 62),
						  mot_acc_mul(omc, n->rot_sq[k])),
				      62, &ov);
	r->m[j][l] = mot_acc_floor_ov(mot_acc_add(sym, asym), 62, &ov);
	r->m[l][j] = mot_acc_floor_ov(mot_acc_sub(sym, asym), 62, &ov);
}

/* The rotation's rows 0..2 (row 3, the translation, is the caller's: the
 * kernels never read it) */
static inline __attribute__((always_inline)) void tilted_rot(struct mot_mat *r,
							     const struct mot_node *n, mot_q32 s,
							     mot_q32 c)
{
	mot_q32 omc = ONE - c; /* exact, in [0, 2] */
	unsigned k;

	if (small_kernels) {
		tilted_pair(r, n, s, omc, 0);
		tilted_pair(r, n, s, omc, 1);
		tilted_pair(r, n, s, omc, 2);
	} else {
		for (k = 0; k < 3; k++) /* one copy: less code */
			tilted_pair(r, n, s, omc, k);
	}
}

/* Local matrix of a free node: T(-p) . S . H . R . T(p) . T(t). */
static void free_local(struct mot_mat *out, const struct mot_scene *sc, struct mot_eval *ev,
		       const struct mot_node *n, mot_q32 frame)
{
	const struct mot_free_strand *fs;
	struct mot_node_memo m; /* a rotation track's: learnt, not kept */

	if (n->strand < 0) {
		mot_mat_identity(out);
		return;
	}
	fs = &sc->free[n->strand];
	piece_forget(&m);
	/* the values tested, not the curves' bounds made (mot_eval_reset()'s) */
	if (free_linear(out, sc, ev, &m, fs, free_flags(sc, fs, false), frame) == FREE_LIN_NONE) {
		/* T(-p) . T(p) . T(t) = T(t), exactly */
		mot_mat_translate(out, out->m[3]);
		return;
	}
	mot_mat_about_pivot(out, out, n->pivot, &ev->sat);
}

/*
 * World matrix W and pivot position of a node, from its parent's world
 * matrix P (the identity for a root). Every node's local matrix has the form
 * L = T(-p) . M . T(p) . T(t), with M its linear part (S.H.R of a free node,
 * the rotation of a revolute joint, the identity for a prismatic one) and t
 * its translation (zero for a revolute joint). The pivot is a fixed point of
 * T(-p) . M . T(p), so (p, 1) . L = (p + t, 1), and
 *     pos   = (p + t) . P_lin + P_t
 *     W_lin = M . P_lin
 *     W_t   = pos - p . W_lin            (pos = (p, 1) . W)
 * with W_t taken from pos's exact sum before it is rounded: three products a
 * column where forming L's translation p - p.M + t and then L . P costs six.
 * The rounded W maps the pivot onto pos within half an LSB, so a child's
 * position errs by its offset from this pivot times W's rounding, not by its
 * distance from the origin. Each entry is one sum of exact products rounded
 * once (fix.h's kernel); when a sum does not fit, node_world_sat() redoes
 * the node with the saturating sums, which give the same bits otherwise.
 *
 * Known bounds (the small case). Most nodes are known before the products
 * to need no overflow test at all. mot_eval_reset() bounds the 2-norm of
 * every node's W_lin once (memo_prepare, lin_bound), from the identity's 1
 * at a root down: |W_lin|_2 <= |M|_2 |P_lin|_2 + |E|_2, where E, W_lin's
 * rounding, is below a unit an entry (|E|_2 <= |E|_F < 3 units). A
 * rotation as the kernels use it, rounded, has |R|_2 below 1 + 2^-22:
 * about an axis sqrt(c^2 + s^2), within 2^-31 of 1 (the sine's error); a
 * tilted one with |a|^2 = 1 + d is normal, its eigenvalues 1 and
 * c - (1 - c) d +- i s |a|, of modulus below 1 + 2 |d| + 2^-31, |d| below
 * 3 2^-25 for the least exact axis mot_scene_validate() passes, plus its
 * entries' rounding (below 3 2^-32); a free node's from a quaternion unit
 * within a few units (mot_quat_normalize(), slerp; quat.h), and R(q) =
 * |q|^2 R(q/|q|) + (1 - |q|^2) I is within 2 ||q|^2 - 1| of a rotation's
 * norm. A free node that scales or shears has M =
 * (S . H) . R rounded once an entry, S . H's own products rounded once
 * (a unit each): |M|_2 <= |S.H|_2 (1 + 2^-22) + 3 units, |S.H|_2 at most
 * the mean of its largest column and row sums, from its channels' bounds
 * over the whole timeline (mot_curve_bound()); without a rotation M = S.H.
 * Each entry of a matrix is below its 2-norm, and the terms of an entry of
 * W_lin = M . P_lin sum to at most |M|_2 |P_lin|_2 in magnitude (a row of M
 * times a column of P, Cauchy-Schwarz); those of pos and W_t to at most
 * |p + t|_1 |P_lin|_2 + |p|_1 |W_lin|_2 beside P_t (memo_prepare()). Where
 * the parent's and the node's bounds, the node's pivot and translation
 * over the whole timeline (the curves' bounds) and that sum with P_t's
 * bound (its parent's, summed down the chain) are below 2^62 raw, p + t
 * fits, every sum stays below 2^95 (no wrap of 128 bits) and every result,
 * with or without P_t, below 2^62. The kernels below then drop the
 * tests, and P_t, whose share of each sum is a whole number of units of the
 * result, is added after the rounding instead of before: the same bits, a
 * fifth fewer instructions. The bounds hold whichever kernel a parent took:
 * where they hold nothing overflows, and the tested kernels give the same
 * bits.
 */

static void node_world_sat(struct mot_mat *w, mot_q32 pos[3], const struct mot_mat *par,
			   const struct mot_mat *m, const mot_q32 p[3], const mot_q32 t[3],
			   uint32_t *sat)
{
	mot_q32 r[4][3], q[3], np[3];
	unsigned i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++) {
			const mot_q32 y[3] = { par->m[0][j], par->m[1][j], par->m[2][j] };

			r[i][j] = mot_sum_prod(m->m[i], y, 3, sat);
		}
	for (j = 0; j < 3; j++)
		np[j] = mot_sub_sat(0, p[j], sat);
	for (j = 0; j < 3; j++) {
		const mot_q32 x[10] = { p[0], p[1], p[2], t[0], t[1], t[2], par->m[3][j],
					np[0], np[1], np[2] };
		const mot_q32 y[10] = { par->m[0][j], par->m[1][j], par->m[2][j], par->m[0][j],
					par->m[1][j], par->m[2][j], ONE, r[0][j], r[1][j], r[2][j] };

		q[j] = mot_sum_prod(x, y, 7, sat);
		r[3][j] = mot_sum_prod(x, y, 10, sat);
	}
	for (j = 0; j < 3; j++) {
		pos[j] = q[j];
		for (i = 0; i < 4; i++)
			w->m[i][j] = r[i][j];
	}
}

/*
 * The sums of one translation entry: start(P_t) + products, rounded, with
 * the overflow test; or, small, start(0) + products rounded and P_t added
 * after. Constant `small` where inlined: one of the two remains. ps: the
 * pivot's pre-scale (PRE_SHIFT; the small kernels only, 0 elsewhere), the sum
 * rounded at 2^(32 + ps).
 */
static inline __attribute__((always_inline)) mot_acc trans_start(mot_q32 yt, bool small,
								 unsigned ps)
{
	return mot_acc_start(small ? 0 : yt, 32 + ps);
}

static inline __attribute__((always_inline)) mot_q32 trans_end(mot_acc x, mot_q32 yt, bool small,
							       unsigned ps, uint64_t *ov)
{
	uint64_t unused = 0;

	if (small)
		return mot_acc_floor_ov(x, 32 + ps, &unused) + yt;
	return mot_acc_floor_ov(x, 32 + ps, ov);
}

/* v times 2^ps (PRE_SHIFT's pre-scale, |v| < 2^(63 - ps)) */
static inline __attribute__((always_inline)) int64_t prescale(mot_q32 v, unsigned ps)
{
	return (int64_t)((uint64_t)v << ps);
}

/* Any linear part M (free nodes, tilted joints); M must not alias W. W's
 * linear part first, row by row, then the translation sums column by
 * column, which read it back: few values live at once. A lower-triangular
 * M (tri: a free node's S . H without rotation) has exact zeros above its
 * diagonal, whose products are left out where it is inlined (the same
 * sums).
 *
 * Register pressure (gcc 12, x86_64; mot_scene_eval() has every kernel
 * inline): the translation sums read W_lin back from memory, not from
 * registers kept from the row sums, which gcc otherwise spills to the stack
 * beside their stores to W (nine more stores). An empty asm hides where
 * wl points (the same rows), or, with `fence`, a compiler barrier, whichever
 * counted fewer instructions (make bench-count: the barrier for free nodes
 * of the small case, the hidden pointer for tilted joints and the tested
 * kernel). In the tested kernel each overflow test is made where its sum
 * is (an empty asm on ov): otherwise gcc keeps all fifteen 128-bit sums for
 * one test at the end, spilled. Neither changes a result. */
static inline __attribute__((always_inline)) void
node_world_in(struct mot_mat *restrict w, mot_q32 *restrict pos, const struct mot_mat *restrict par,
	      const struct mot_mat *restrict m, const mot_q32 p[3], const mot_q32 t[3], bool small,
	      bool tri, bool fence, uint32_t *sat)
{
	const mot_q32(*restrict y)[3] = par->m;
	mot_q32(*wl)[3];
	mot_q32 q[3];
	uint64_t ov = 0, unused = 0;
	unsigned i, j;

	UNROLL3
	for (i = 0; i < 3; i++)
		ov |= (uint64_t)__builtin_add_overflow(p[i], t[i], &q[i]);
	UNROLL3
	for (i = 0; i < 3; i++) {
		const mot_q32 m0 = m->m[i][0], m1 = tri && i < 1 ? 0 : m->m[i][1];
		const mot_q32 m2 = tri && i < 2 ? 0 : m->m[i][2];

		UNROLL3
		for (j = 0; j < 3; j++) {
			w->m[i][j] = mot_sum3_ov(m0, y[0][j], m1, y[1][j], m2, y[2][j], 0, 32,
						 small ? &unused : &ov);
			if (!small)
				__asm__("" : "+r"(ov));
		}
	}
	wl = w->m;
	if (fence)
		__asm__("" ::: "memory");
	else
		__asm__("" : "+r"(wl));
	UNROLL3
	for (j = 0; j < 3; j++) {
		/* at most three products and an addend, then three more from a
		 * sum that fits (else ov is set already): no wrap goes unseen */
		mot_acc x = mot_acc_mac(trans_start(y[3][j], small, 0), q[0], y[0][j]);

		x = mot_acc_mac(mot_acc_mac(x, q[1], y[1][j]), q[2], y[2][j]);
		pos[j] = trans_end(x, y[3][j], small, 0, &ov);
		x = mot_acc_sub(x, mot_acc_mul(p[0], wl[0][j]));
		x = mot_acc_sub(x, mot_acc_mul(p[1], wl[1][j]));
		x = mot_acc_sub(x, mot_acc_mul(p[2], wl[2][j]));
		w->m[3][j] = trans_end(x, y[3][j], small, 0, &ov);
	}
	if (!small && ov)
		node_world_sat(w, pos, par, m, p, t, sat);
}

static void node_world(struct mot_mat *restrict w, mot_q32 *restrict pos,
		       const struct mot_mat *restrict par, const struct mot_mat *restrict m,
		       const mot_q32 p[3], const mot_q32 t[3], bool small, uint32_t *sat)
{
	if (small_kernels && small)
		node_world_in(w, pos, par, m, p, t, true, false, true, sat);
	else
		node_world_in(w, pos, par, m, p, t, false, false, false, sat);
}

/* A revolute joint about a tilted axis: its rotation, then node_world()
 * with t = 0. (The pivot's pre-scale, PRE_SHIFT, saved 3 instructions of
 * its 520 and no time measurably: left out.) */
static void tilted_world(struct mot_mat *restrict w, mot_q32 *restrict pos,
			 const struct mot_mat *restrict par, const struct mot_node *n, mot_q32 s,
			 mot_q32 c, bool small, uint32_t *sat)
{
	static const mot_q32 zero[3] = { 0, 0, 0 };
	struct mot_mat r;

	tilted_rot(&r, n, s, c);
	if (small_kernels && small) {
		node_world_in(w, pos, par, &r, n->pivot, zero, true, false, false, sat);
		return;
	}
	if (small_kernels)
		node_world_in(w, pos, par, &r, n->pivot, zero, false, false, false, sat);
	else /* one copy: less code */
		node_world(w, pos, par, &r, n->pivot, zero, false, sat);
}

/* M = I (prismatic joints, free nodes without rotation, scale or shear):
 * W = T(t) . P, P's linear part and translation t . P_lin + P_t, and
 * pos = W_t + p . P_lin. */
static inline __attribute__((always_inline)) void
translate_world_in(struct mot_mat *restrict w, mot_q32 *restrict pos,
		   const struct mot_mat *restrict par, const mot_q32 p[3], const mot_q32 t[3],
		   bool small, uint32_t *sat)
{
	const mot_q32(*y)[3] = par->m;
	uint64_t ov = 0;
	unsigned j;

	UNROLL3
	for (j = 0; j < 3; j++) {
		mot_acc x = mot_acc_mac(trans_start(y[3][j], small, 0), t[0], y[0][j]);

		x = mot_acc_mac(mot_acc_mac(x, t[1], y[1][j]), t[2], y[2][j]);
		w->m[3][j] = trans_end(x, y[3][j], small, 0, &ov);
		x = mot_acc_mac(mot_acc_mac(x, p[0], y[0][j]), p[1], y[1][j]);
		pos[j] = trans_end(mot_acc_mac(x, p[2], y[2][j]), y[3][j], small, 0, &ov);
		w->m[0][j] = y[0][j];
		w->m[1][j] = y[1][j];
		w->m[2][j] = y[2][j];
	}
	if (!small && ov)
		node_world_sat(w, pos, par, &mat_id, p, t, sat);
}

static void translate_world(struct mot_mat *restrict w, mot_q32 *restrict pos,
			    const struct mot_mat *restrict par, const mot_q32 p[3],
			    const mot_q32 t[3], bool small, uint32_t *sat)
{
	if (small_kernels && small)
		translate_world_in(w, pos, par, p, t, true, sat);
	else
		translate_world_in(w, pos, par, p, t, false, sat);
}

/* A prismatic joint along coordinate axis o by v: t = v e_o, and the two
 * zero products of each column are left out where it is inlined: W_t =
 * P_t + v P_o, a scaled row. */
static inline __attribute__((always_inline)) void
prismatic_in(struct mot_mat *restrict w, mot_q32 *restrict pos, const struct mot_mat *restrict par,
	     unsigned o, const mot_q32 p[3], mot_q32 v, bool small, uint32_t *sat)
{
	const mot_q32 tx[3] = { v, 0, 0 }, ty[3] = { 0, v, 0 }, tz[3] = { 0, 0, v };

	if (!small_kernels) /* one copy: less code */
		translate_world(w, pos, par, p, o == MOT_AXIS_X ? tx : o == MOT_AXIS_Y ? ty : tz, false,
				sat);
	else if (o == MOT_AXIS_X)
		translate_world_in(w, pos, par, p, tx, small, sat);
	else if (o == MOT_AXIS_Y)
		translate_world_in(w, pos, par, p, ty, small, sat);
	else
		translate_world_in(w, pos, par, p, tz, small, sat);
}

static void prismatic_world(struct mot_mat *restrict w, mot_q32 *restrict pos,
			    const struct mot_mat *restrict par, unsigned o, const mot_q32 p[3],
			    mot_q32 v, bool small, uint32_t *sat)
{
	if (small_kernels && small)
		prismatic_in(w, pos, par, o, p, v, true, sat);
	else
		prismatic_in(w, pos, par, o, p, v, false, sat);
}

/* t = v . axis, the offset of a prismatic joint */
static void joint_offset(mot_q32 t[3], mot_q32 v, const mot_q32 axis[3], uint32_t *sat)
{
	unsigned k;

	for (k = 0; k < 3; k++)
		t[k] = mot_mul(v, axis[k], sat);
}

/* A prismatic joint along a tilted axis: its offset, then translate_world().
 * In the small case the offset cannot leave its bound (memo_prepare()), so
 * its products are rounded without mot_mul()'s saturation (the same bits)
 * and the kernel is inline: one call where there were two and a switch. */
static __attribute__((noinline)) void
tilted_offset_world(struct mot_mat *restrict w, mot_q32 *restrict pos,
		    const struct mot_mat *restrict par, const struct mot_node *n, mot_q32 v, bool small,
		    uint32_t *sat)
{
	mot_q32 t[3];
	unsigned k;

	if (small_kernels && small) {
		uint64_t unused = 0;

		UNROLL3
		for (k = 0; k < 3; k++)
			t[k] = mot_acc_round_ov(mot_acc_mul(v, n->axis[k]), 32, &unused);
		translate_world_in(w, pos, par, n->pivot, t, true, sat);
		return;
	}
	joint_offset(t, v, n->axis, sat);
	translate_world(w, pos, par, n->pivot, t, small, sat);
}

/*
 * A revolute joint about a coordinate axis o: R mixes two rows (a, b) of
 * whatever follows it and leaves the third alone,
 *     Rz: (a, b) = (0, 1)   Rx: (1, 2)   Ry: (2, 0)
 * so W_lin costs 4 row products instead of 9, and in
 * W_t = pos - p . W_lin the term p_o P_o cancels: with
 * U = P_t + p_a P_a + p_b P_b, pos = U + p_o P_o and W_t = U - p_a W_a -
 * p_b W_b. Nine products a column.
 */
static const unsigned rev_rows[3][2] = { { 1, 2 }, { 2, 0 }, { 0, 1 } };

/* R about coordinate axis o as a matrix (the local matrix, the slow path) */
static void axis_rot(struct mot_mat *m, unsigned o, mot_q32 s, mot_q32 c)
{
	const unsigned a = rev_rows[o][0], b = rev_rows[o][1];

	*m = mat_id;
	m->m[a][a] = c;
	m->m[a][b] = s;
	m->m[b][a] = -s;
	m->m[b][b] = c;
}

/* W_lin: rows a and b of the parent turned into each other, row o kept;
 * s and c times 2^PRE_SHIFT, each sum rounded at 2^(32 + PRE_SHIFT) (a sine
 * or cosine is about 2^32 raw at most: the factor stays far below 2^63,
 * and a product with any entry below 2^125) */
static inline __attribute__((always_inline)) void
revolute_rows(struct mot_mat *restrict w, const struct mot_mat *restrict par, unsigned o,
	      mot_q32 s, mot_q32 c, bool small, uint64_t *ov)
{
	const unsigned a = rev_rows[o][0], b = rev_rows[o][1];
	const mot_q32(*restrict y)[3] = par->m;
	mot_q32(*restrict x)[3] = w->m;
	const int64_t cp = prescale(c, PRE_SHIFT), sp = prescale(s, PRE_SHIFT);
	uint64_t unused = 0;
	unsigned j;

	UNROLL3
	for (j = 0; j < 3; j++) {
		x[a][j] = mot_sum2_ov(cp, y[a][j], sp, y[b][j], 0, 32 + PRE_SHIFT,
				      small ? &unused : ov);
		x[b][j] = mot_sum2_ov(-sp, y[a][j], cp, y[b][j], 0, 32 + PRE_SHIFT,
				      small ? &unused : ov);
		x[o][j] = y[o][j];
	}
}

/* revolute_world() for rows (a, b) and axis row o, constants where it is
 * inlined (one copy per axis: the rows sit at fixed offsets). The rotated
 * rows first, then the translation sums, which read them back from W: fewer
 * values live at once than column by column. An empty asm hides where x
 * points (the same rows), else gcc 12 keeps a copy of each of the six
 * rotated entries, spilled to the stack beside its store to W and loaded
 * from there (make bench-count: 1,000 joints 365 -> 359 instructions a
 * joint, about 10 an axis joint with its pivot off the axes). */
static inline __attribute__((always_inline)) void
revolute_cols(struct mot_mat *restrict w, mot_q32 *restrict pos,
	      const struct mot_mat *restrict par, unsigned o, const mot_q32 p[3], mot_q32 s,
	      mot_q32 c, bool small, unsigned ps, uint64_t *ov)
{
	const unsigned a = rev_rows[o][0], b = rev_rows[o][1];
	const mot_q32(*restrict y)[3] = par->m;
	mot_q32(*restrict x)[3] = w->m;
	const int64_t pa = prescale(p[a], ps), pb = prescale(p[b], ps), po = prescale(p[o], ps);
	unsigned j;

	revolute_rows(w, par, o, s, c, small, ov);
	__asm__("" : "+r"(x));
	UNROLL3
	for (j = 0; j < 3; j++) {
		mot_acc u = mot_acc_mac(trans_start(y[3][j], small, ps), pa, y[a][j]);

		u = mot_acc_mac(u, pb, y[b][j]);
		/* U + p_o P_o fits, or ov is set: U - two products wraps visibly */
		pos[j] = trans_end(mot_acc_mac(u, po, y[o][j]), y[3][j], small, ps, ov);
		u = mot_acc_sub(u, mot_acc_mul(pa, x[a][j]));
		x[3][j] = trans_end(mot_acc_sub(u, mot_acc_mul(pb, x[b][j])), y[3][j], small, ps, ov);
	}
}

/*
 * The same for a pivot on one coordinate line, p = p_k e_k (a link along
 * an axis, the common case of a rig; p = 0 too), in the small case: the
 * other components' products are exact zeros, and of the sums above only
 * pos = P_t + p_k P_k and W_t = P_t + p_k (P_k - W_k) remain (W_o = P_o:
 * 0 for k = o), the difference exact (|entries| below 2^62 raw, the small
 * case's bound). Two products a column where there were five; the same
 * bits. k at run time, the axis a constant where inlined.
 */
static inline __attribute__((always_inline)) void
revolute_line(struct mot_mat *restrict w, mot_q32 *restrict pos,
	      const struct mot_mat *restrict par, unsigned o, unsigned k, mot_q32 pk, mot_q32 s,
	      mot_q32 c, unsigned ps)
{
	const mot_q32(*restrict y)[3] = par->m;
	mot_q32(*restrict x)[3] = w->m;
	uint64_t unused = 0;
	unsigned j;

	revolute_rows(w, par, o, s, c, true, &unused);
	pk = prescale(pk, ps);
	UNROLL3
	for (j = 0; j < 3; j++) {
		const mot_q32 yk = y[k][j], yt = y[3][j];

		pos[j] = trans_end(mot_acc_mac(trans_start(yt, true, ps), pk, yk), yt, true, ps,
				   &unused);
		x[3][j] = trans_end(mot_acc_mac(trans_start(yt, true, ps), pk, yk - x[k][j]), yt, true,
				    ps, &unused);
	}
}

static inline __attribute__((always_inline)) void
revolute_in(struct mot_mat *restrict w, mot_q32 *restrict pos, const struct mot_mat *restrict par,
	    unsigned o, const mot_q32 p[3], mot_q32 s, mot_q32 c, bool small, unsigned ps,
	    uint32_t *sat)
{
	uint64_t ov = 0;

	if (!small_kernels)
		revolute_cols(w, pos, par, o, p, s, c, small, 0, &ov); /* one copy: less code */
	else if (o == MOT_AXIS_X)
		revolute_cols(w, pos, par, MOT_AXIS_X, p, s, c, small, ps, &ov);
	else if (o == MOT_AXIS_Y)
		revolute_cols(w, pos, par, MOT_AXIS_Y, p, s, c, small, ps, &ov);
	else
		revolute_cols(w, pos, par, MOT_AXIS_Z, p, s, c, small, ps, &ov);
	if (!small && ov) {
		struct mot_mat m;
		static const mot_q32 zero[3] = { 0, 0, 0 };

		axis_rot(&m, o, s, c);
		node_world_sat(w, pos, par, &m, p, zero, sat);
	}
}

/* revolute_line() for the axis o (a constant in each copy) */
static inline __attribute__((always_inline)) void
revolute_line_in(struct mot_mat *restrict w, mot_q32 *restrict pos,
		 const struct mot_mat *restrict par, unsigned o, unsigned k, mot_q32 pk, mot_q32 s,
		 mot_q32 c, unsigned ps)
{
	if (o == MOT_AXIS_X)
		revolute_line(w, pos, par, MOT_AXIS_X, k, pk, s, c, ps);
	else if (o == MOT_AXIS_Y)
		revolute_line(w, pos, par, MOT_AXIS_Y, k, pk, s, c, ps);
	else
		revolute_line(w, pos, par, MOT_AXIS_Z, k, pk, s, c, ps);
}

static void revolute_world(struct mot_mat *restrict w, mot_q32 *restrict pos,
			   const struct mot_mat *restrict par, unsigned o, const mot_q32 p[3],
			   mot_q32 s, mot_q32 c, bool small, bool pre, unsigned prow, uint32_t *sat)
{
	if (PRE_SHIFT && small_kernels && small && pre) {
		if (prow < 3)
			revolute_line_in(w, pos, par, o, prow, p[prow], s, c, PRE_SHIFT);
		else
			revolute_in(w, pos, par, o, p, s, c, true, PRE_SHIFT, sat);
	} else if (small_kernels && small && prow < 3) {
		revolute_line_in(w, pos, par, o, prow, p[prow], s, c, 0);
	} else if (small_kernels && small) {
		revolute_in(w, pos, par, o, p, s, c, true, 0, sat);
	} else {
		revolute_in(w, pos, par, o, p, s, c, false, 0, sat);
	}
}

void mot_node_local(struct mot_mat *out, const struct mot_scene *sc, struct mot_eval *ev,
		    uint32_t node, mot_q32 frame, mot_q32 *value, mot_q32 *rpm)
{
	const struct mot_node *n = &sc->nodes[node];
	mot_q32 v = 0, r = 0, t[3], s, c;

	switch (n->kind) {
	case MOT_NODE_REVOLUTE:
		v = joint_value(sc, ev, n, frame, &r);
		mot_sincos(v, &s, &c);
		if (n->axis_id == MOT_AXIS_VEC) {
			tilted_rot(out, n, s, c);
			out->m[3][0] = out->m[3][1] = out->m[3][2] = 0;
		} else {
			axis_rot(out, n->axis_id, s, c);
		}
		mot_mat_about_pivot(out, out, n->pivot, &ev->sat);
		break;
	case MOT_NODE_PRISMATIC:
		v = joint_value(sc, ev, n, frame, &r);
		joint_offset(t, v, n->axis, &ev->sat);
		mot_mat_translate(out, t);
		break;
	default:
		free_local(out, sc, ev, n, frame);
		break;
	}
	if (value)
		*value = v;
	if (rpm)
		*rpm = r;
}

/*
 * Every node in index order, parents first, in two passes. The first takes
 * every joint's value and, for a revolute joint whose value changed, its
 * sine and cosine: work with no order between nodes, which the processor
 * overlaps from one joint to the next. The second makes the matrices,
 * each from its parent's. With a warm memo (scene.h) a joint whose value
 * is the one its matrix was made with keeps its sine and cosine, and, if
 * its parent did not move either, its matrix and position in the pose. A
 * free node without a strand follows its parent alone; one with a strand
 * is made anew. A node of the small case (above) whose parent's
 * translation and own offset are small takes the kernels without overflow
 * tests.
 */
void mot_scene_eval(const struct mot_scene *sc, struct mot_eval *ev, mot_q32 frame,
		    struct mot_pose *out)
{
	static const mot_q32 zero[3] = { 0, 0, 0 };
	struct mot_node_memo *memo = ev->memo, *m = memo;
	const bool warm = ev->memo_world == out->world && out->by == ev && !ev->sat;
	const struct mot_node *n = sc->nodes, *end = n + sc->nnodes;
	struct mot_mat *const world = out->world, *w = world;
	mot_q32(*pos)[3] = out->pos, *val = out->value, *rpm = out->rpm;
	struct mot_node_memo *due = NULL, *next = NULL; /* joint_sines() still to do */
	uint32_t i;

	for (; n < end; n++, m++, val++, rpm++) {
		mot_q32 v = 0;

		/* the spin speed straight into the pose (joint_slow() writes a
		 * spin joint's): a local whose address is taken lives on the
		 * stack, stored and loaded again every turn */
		*rpm = 0;
		if (small_kernels && n + PIECE_AHEAD < end)
			joint_prefetch(sc, ev, &n[PIECE_AHEAD], &m[PIECE_AHEAD]);
		if (n->kind != MOT_NODE_FREE) {
			if (!small_kernels || frame < m->lo || frame >= m->hi || !piece_fast(m, frame, &v))
				v = joint_slow(sc, ev, n, m, frame, rpm);
			m->fresh = !warm || v != m->value;
			if (m->fresh) {
				m->value = v;
				if (n->kind == MOT_NODE_REVOLUTE) {
					if (due)
						joint_sines(due);
					due = next;
					next = m;
				}
			}
		}
		*val = v;
	}
	if (due)
		joint_sines(due);
	if (next)
		joint_sines(next);
	for (n = sc->nodes, m = memo; n < end; n++, m++, w++, pos++) {
		const struct mot_mat *par = n->parent >= 0 ? &world[n->parent] : &mat_id;
		const bool still = warm && (n->parent < 0 || !memo[n->parent].moved);
		struct mot_mat local;
		const bool small = m->small;

		/* nothing moved: a joint with its value, a free node without a
		 * strand (one with a strand is made anew) */
		if (still && (n->kind != MOT_NODE_FREE ? !m->fresh : n->strand < 0)) {
			m->moved = 0;
			continue;
		}
		m->moved = 1;
		switch (n->kind) {
		case MOT_NODE_REVOLUTE:
			if (n->axis_id != MOT_AXIS_VEC)
				revolute_world(w, *pos, par, n->axis_id, n->pivot, m->s, m->c, small,
					       m->pre, m->prow, &ev->sat);
			else
				tilted_world(w, *pos, par, n, m->s, m->c, small, &ev->sat);
			break;
		case MOT_NODE_PRISMATIC:
			if (n->axis_id != MOT_AXIS_VEC) {
				prismatic_world(w, *pos, par, n->axis_id, n->pivot, m->value, small,
						&ev->sat);
			} else {
				tilted_offset_world(w, *pos, par, n, m->value, small, &ev->sat);
			}
			break;
		default:
			if (n->strand < 0) {
				translate_world(w, *pos, par, n->pivot, zero, small, &ev->sat);
				break;
			}
			switch (free_linear(&local, sc, ev, m, &sc->free[n->strand], m->free,
					    frame)) {
			case FREE_LIN_NONE:
				translate_world(w, *pos, par, n->pivot, local.m[3], small, &ev->sat);
				break;
			case FREE_LIN_TRI:
				if (small_kernels && small) {
					node_world_in(w, *pos, par, &local, n->pivot, local.m[3], true,
						      true, true, &ev->sat);
					break;
				}
				/* fall through */
			default:
				node_world(w, *pos, par, &local, n->pivot, local.m[3], small,
					   &ev->sat);
				break;
			}
			break;
		}
	}
	ev->memo_world = out->world;
	out->by = ev;
	if (sc->camera)
		mot_camera_eval(&out->cam, sc->camera, sc->curves, ev->cursors, frame, &ev->sat);
	if (sc->ncycles) {
		/* the frame a tick belongs to: floor of its frame time */
		int64_t fnum = frame >> 32;

		for (i = 0; i < sc->ncycles; i++)
			out->cycle[i] = mot_cycle_index(&sc->cycles[i], fnum);
	}
	for (i = 0; i < sc->nattrs; i++) {
		int32_t c = sc->attr_curve[i];

		out->attr[i] = mot_curve_eval(&sc->curves[c], &ev->cursors[c], frame, &ev->sat);
	}
	for (i = 0; i < sc->nsys; i++)
		mot_system_eval(&sc->sys[i], sc->curves, ev->cursors, &ev->sys[i], frame,
				out->sysout + sc->sys[i].out0, &ev->sat);
	for (i = 0; i < sc->naims; i++) {
		const struct mot_aim *a = &sc->aims[i];
		const mot_q32 *tgt = a->src == MOT_AIM_SRC_NODE ? out->pos[a->index] :
								  out->sysout + a->index;

		mot_aim_eval(a, tgt, frame, &out->aim[i][0], &out->aim[i][1], &ev->sat);
	}
}

int mot_scene_aims_init(const struct mot_scene *sc, struct mot_aim *aims, struct mot_eval *ev,
			struct mot_pose *out, struct mot_aim_march *m, uint32_t *bad)
{
	struct mot_scene tmp = *sc;
	uint32_t i, k, nfine;
	int err;

	tmp.naims = 0; /* the march evaluates the targets, not the aims */
	tmp.aims = NULL;
	*bad = 0;
	if (!sc->naims)
		return MOT_OK;
	err = mot_scene_validate(sc);
	if (err)
		return err;
	/* one march for all: they share the span and the grid */
	for (i = 0; i < sc->naims; i++) {
		if (aims[i].nref != aims[0].nref || aims[i].f0 != aims[0].f0 ||
		    aims[i].sub != aims[0].sub || !aims[i].pan_ref)
			return MOT_E_INVAL;
		m[i].have = false;
		m[i].prev = m[i].ref = 0;
	}
	nfine = (aims[0].nref - 1) * 4 + 1;
	mot_eval_reset(ev, sc);
	for (k = 0; k < nfine; k++) {
		mot_scene_eval(&tmp, ev, mot_aim_fine_frame(&aims[0], k, &ev->sat), out);
		for (i = 0; i < sc->naims; i++) {
			const mot_q32 *tgt = aims[i].src == MOT_AIM_SRC_NODE ?
						     out->pos[aims[i].index] :
						     out->sysout + aims[i].index;

			err = mot_aim_march(&aims[i], &m[i], k, tgt, &ev->sat);
			if (err) {
				*bad = i;
				return err;
			}
		}
	}
	mot_eval_reset(ev, sc);
	return MOT_OK;
}
