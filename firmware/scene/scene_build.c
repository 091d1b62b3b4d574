/* SPDX-License-Identifier: MIT */
/*
 * scene_build.c - a scene description (doubles, the user's units) into the
 * core's scene (Q32.32, turns), in one block.
 *
 * The build runs twice over the same layout code: first with a measuring
 * arena to learn the exact size, then into one allocation of that size. The
 * fill step runs only on the second pass. Every conversion is range-checked;
 * nothing is clamped.
 */
#include "scene_desc.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "motion/arena.h"
#include "scene_build_priv.h"


/* Count what the scene needs (independent of the arena). */
static void count(const struct scene_desc *d, struct layout *l)
{
	uint32_t i, k;

	l->ncurves = l->nrot = l->nfree = 0;
	for (i = 0; i < d->nnodes; i++) {
		const struct sd_node *n = &d->nodes[i];

		if (n->kind == MOT_NODE_FREE) {
			if (!n->has_free)
				continue;
			l->nfree++;
			for (k = 0; k < MOT_FREE_NCHANNELS; k++)
				l->ncurves += curve_used(&n->free.ch[k]);
			l->nrot += n->free.nrot > 0;
			l->ncurves += 4 * curve_used(&n->free.quat[0]);
		} else {
			l->ncurves += curve_used(&n->value) + curve_used(&n->spin);
		}
	}
	if (d->has_camera)
		l->ncurves += MOT_CAM_NCHANNELS;
	l->ncurves += d->nattrs;
	l->ncurves += sb_sys_curves(d);
}

/* One curve: key array, segment array, init. `scale` converts values
 * (1 for units, 1/360 for degrees). */
int sb_curve(struct layout *l, struct mot_curve *c, const struct sd_curve *sc, double scale,
	     bool integral, uint32_t *bad_key)
{
	uint32_t nseg = sc->compact ? 0 : mot_curve_seg_count(sc->interp, sc->nkeys), i;
	bool tangents = false;
	struct mot_key *keys = ALLOC(l->a, struct mot_key, sc->nkeys);
	struct mot_curve_seg *seg = nseg ? ALLOC(l->a, struct mot_curve_seg, nseg) : NULL;
	struct mot_tangent *tan = NULL;
	struct mot_curve_opts o;
	uint32_t sat = 0;
	int err;

	for (i = 0; i < sc->nkeys; i++)
		tangents = tangents || sc->keys[i].tan_set;
	if (!l->a->base)
		return 0;
	if (!keys || (nseg && !seg))
		return MOT_E_CAPACITY;
	/* the tangents are read at init only: a scratch array */
	if (tangents && !(tan = calloc(sc->nkeys, sizeof(*tan))))
		return MOT_E_CAPACITY;
	for (i = 0; i < sc->nkeys; i++) {
		const struct sd_key *k = &sc->keys[i];

		*bad_key = i;
		if (!sd_to_q32(k->frame, &keys[i].frame) ||
		    !sd_to_q32(k->value * scale, &keys[i].value) ||
		    !sd_to_q32(k->ease_in, &keys[i].ease_in) ||
		    !sd_to_q32(k->ease_out, &keys[i].ease_out) ||
		    (tan && (!sd_to_q32(k->tan_in * scale, &tan[i].in) ||
			     !sd_to_q32(k->tan_out * scale, &tan[i].out)))) {
			free(tan);
			return MOT_E_RANGE;
		}
		if (tan)
			tan[i].set = k->tan_set;
	}
	*bad_key = UINT32_MAX;
	memset(&o, 0, sizeof(o));
	if (!sd_to_q32(sc->beta1, &o.beta1) || !sd_to_q32(sc->beta2, &o.beta2) ||
	    !sd_to_q32(sc->ease_in, &o.ease_in_frames) ||
	    !sd_to_q32(sc->ease_out, &o.ease_out_frames))
		return MOT_E_RANGE;
	o.integral = integral;
	o.tangents = tan;
	o.compact = sc->compact;
	err = mot_curve_init(c, sc->interp, keys, sc->nkeys, &o, seg, nseg, &sat);
	free(tan);
	return err;
}

static int build_rot(struct layout *l, struct mot_rot_track *r, const struct sd_free *f,
		     uint32_t *bad_key)
{
	struct mot_rot_key *keys = ALLOC(l->a, struct mot_rot_key, f->nrot);
	struct mot_rot_seg *seg = f->rot_compact ? NULL :
				  ALLOC(l->a, struct mot_rot_seg, f->nrot > 1 ? f->nrot - 1 : 1);
	uint32_t i, sat = 0;

	if (!l->a->base)
		return 0;
	if (!keys || (!f->rot_compact && !seg))
		return MOT_E_CAPACITY;
	for (i = 0; i < f->nrot; i++) {
		const struct sd_rot_key *k = &f->rot[i];
		double n = sqrt(k->q[0] * k->q[0] + k->q[1] * k->q[1] + k->q[2] * k->q[2] +
				k->q[3] * k->q[3]);

		*bad_key = i;
		if (!(n > 1e-9))
			return MOT_E_INVAL;
		if (!sd_to_q32(k->frame, &keys[i].frame) ||
		    !sd_to_q32(k->q[0] / n, &keys[i].q.w) || !sd_to_q32(k->q[1] / n, &keys[i].q.x) ||
		    !sd_to_q32(k->q[2] / n, &keys[i].q.y) || !sd_to_q32(k->q[3] / n, &keys[i].q.z) ||
		    !sd_to_q32(k->ease_in, &keys[i].ease_in) ||
		    !sd_to_q32(k->ease_out, &keys[i].ease_out))
			return MOT_E_RANGE;
	}
	*bad_key = UINT32_MAX;
	if (f->rot_compact)
		return f->squad ? MOT_E_INVAL : mot_rot_track_init_compact(r, keys, f->nrot);
	return mot_rot_track_init(r, keys, f->nrot, f->squad, seg, f->nrot > 1 ? f->nrot - 1 : 1,
				  &sat);
}

/* Span of every key of a free strand, for its strand-wide ease. */
static void free_span(const struct sd_free *f, double *lo, double *hi)
{
	uint32_t k;

	*lo = INFINITY;
	*hi = -INFINITY;
	for (k = 0; k < MOT_FREE_NCHANNELS; k++) {
		const struct sd_curve *c = &f->ch[k];

		if (c->nkeys) {
			*lo = fmin(*lo, c->keys[0].frame);
			*hi = fmax(*hi, c->keys[c->nkeys - 1].frame);
		}
	}
	if (f->nrot) {
		*lo = fmin(*lo, f->rot[0].frame);
		*hi = fmax(*hi, f->rot[f->nrot - 1].frame);
	}
	for (k = 0; k < 4; k++) {
		const struct sd_curve *c = &f->quat[k];

		if (c->nkeys) {
			*lo = fmin(*lo, c->keys[0].frame);
			*hi = fmax(*hi, c->keys[c->nkeys - 1].frame);
		}
	}
	if (*lo > *hi)
		*lo = *hi = 0;
}

int sb_err(struct scene_build_err *e, int code, int node, const char *what, uint32_t key)
{
	if (e) {
		e->code = code;
		e->node = node;
		e->what = what;
		e->key = key;
	}
	return code;
}

const char *const sd_free_names[MOT_FREE_NCHANNELS] = {
	"translate.x", "translate.y", "translate.z", "scale.x",  "scale.y",
	"scale.z",     "shear.hxy",   "shear.hxz",   "shear.hyz",
};

const char *const sd_quat_names[4] = { "rotation.w", "rotation.x", "rotation.y", "rotation.z" };

const char *const sd_cam_names[MOT_CAM_NCHANNELS] = {
	"camera.eye.x",     "camera.eye.y",     "camera.eye.z", "camera.look_at.x",
	"camera.look_at.y", "camera.look_at.z", "camera.twist",
};

/* The whole layout (and, on the real pass, the fill). */
static int layout_all(struct layout *l, const struct scene_desc *d, struct scene_build_err *e)
{
	struct mot_arena *a = l->a;
	bool fill = a->base != NULL;
	uint32_t i, k, ci = 0, ri = 0, fi = 0, bad = UINT32_MAX, sat = 0;
	int err;

	l->sc = ALLOC(a, struct mot_scene, 1);
	l->nodes = ALLOC(a, struct mot_node, d->nnodes ? d->nnodes : 1);
	l->curves = ALLOC(a, struct mot_curve, l->ncurves ? l->ncurves : 1);
	l->rot = ALLOC(a, struct mot_rot_track, l->nrot ? l->nrot : 1);
	l->free = ALLOC(a, struct mot_free_strand, l->nfree ? l->nfree : 1);
	l->camera = d->has_camera ? ALLOC(a, struct mot_camera, 1) : NULL;
	l->cycles = ALLOC(a, struct mot_cycle, d->ncycles ? d->ncycles : 1);
	l->attr_curve = ALLOC(a, int32_t, d->nattrs ? d->nattrs : 1);
	if (fill && a->failed)
		return sb_err(e, MOT_E_CAPACITY, -1, "scene", UINT32_MAX);

	if (fill) {
		err = mot_timing_init(&l->sc->timing, d->rate_num, d->rate_den, d->tick_hz);
		if (err)
			return sb_err(e, err, -1, "timing", UINT32_MAX);
	}
	for (i = 0; i < d->nnodes; i++) {
		const struct sd_node *sn = &d->nodes[i];
		struct mot_node *n = fill ? &l->nodes[i] : NULL;
		double scale = sn->kind == MOT_NODE_REVOLUTE ? 1.0 / 360.0 : 1.0;

		if (n) {
			double len = sqrt(sn->axis[0] * sn->axis[0] + sn->axis[1] * sn->axis[1] +
					  sn->axis[2] * sn->axis[2]);

			n->parent = sn->parent;
			n->kind = sn->kind;
			n->axis_id = sn->axis_id;
			n->curve = n->spin = n->strand = -1;
			for (k = 0; k < 3; k++) {
				if (!sd_to_q32(sn->pivot[k], &n->pivot[k]))
					return sb_err(e, MOT_E_RANGE, (int)i, "pivot", UINT32_MAX);
				if (sn->kind == MOT_NODE_FREE)
					n->axis[k] = 0;
				else if (sn->axis_id != MOT_AXIS_VEC)
					n->axis[k] = k == (uint32_t)sn->axis_id ? MOT_Q32_ONE : 0;
				else if (!(len > 1e-9) || !sd_to_q32(sn->axis[k] / len, &n->axis[k]))
					return sb_err(e, MOT_E_INVAL, (int)i, "axis", UINT32_MAX);
			}
			if (!sd_to_q32(sn->rest * scale, &n->rest))
				return sb_err(e, MOT_E_RANGE, (int)i, "rest", UINT32_MAX);
			mot_node_prepare(n);
		}
		if (sn->kind != MOT_NODE_FREE) {
			if (curve_used(&sn->value)) {
				err = sb_curve(l, fill ? &l->curves[ci] : NULL, &sn->value, scale,
						  false, &bad);
				if (err)
					return sb_err(e, err, (int)i, "value", bad);
				if (n)
					n->curve = (int32_t)ci;
				ci++;
			}
			if (curve_used(&sn->spin)) {
				err = sb_curve(l, fill ? &l->curves[ci] : NULL, &sn->spin, 1.0, true,
						  &bad);
				if (err)
					return sb_err(e, err, (int)i, "spin", bad);
				if (n)
					n->spin = (int32_t)ci;
				ci++;
			}
			continue;
		}
		if (!sn->has_free)
			continue;
		{
			const struct sd_free *sf = &sn->free;
			struct mot_free_strand *fs = fill ? &l->free[fi] : NULL;
			double lo, hi;
			mot_q32 qlo, qhi, qin, qout;

			for (k = 0; k < MOT_FREE_NCHANNELS; k++) {
				if (fs)
					fs->channel[k] = -1;
				if (!curve_used(&sf->ch[k]))
					continue;
				err = sb_curve(l, fill ? &l->curves[ci] : NULL, &sf->ch[k], 1.0,
						  false, &bad);
				if (err)
					return sb_err(e, err, (int)i, sd_free_names[k], bad);
				if (fs)
					fs->channel[k] = (int32_t)ci;
				ci++;
			}
			for (k = 0; k < 4; k++) {
				if (fs)
					fs->quat[k] = -1;
				if (!curve_used(&sf->quat[0]))
					continue;
				if (sf->nrot || !curve_used(&sf->quat[k]))
					return sb_err(e, MOT_E_INVAL, (int)i, sd_quat_names[k],
						      UINT32_MAX);
				err = sb_curve(l, fill ? &l->curves[ci] : NULL, &sf->quat[k], 1.0,
					       false, &bad);
				if (err)
					return sb_err(e, err, (int)i, sd_quat_names[k], bad);
				if (fs)
					fs->quat[k] = (int32_t)ci;
				ci++;
			}
			if (fs)
				fs->rot = -1;
			if (sf->nrot) {
				err = build_rot(l, fill ? &l->rot[ri] : NULL, sf, &bad);
				if (err)
					return sb_err(e, err, (int)i, "rotation", bad);
				if (fs)
					fs->rot = (int32_t)ri;
				ri++;
			}
			if (fs) {
				free_span(sf, &lo, &hi);
				if (!sd_to_q32(lo, &qlo) || !sd_to_q32(hi, &qhi) ||
				    !sd_to_q32(sf->ease_in, &qin) || !sd_to_q32(sf->ease_out, &qout))
					return sb_err(e, MOT_E_RANGE, (int)i, "ease", UINT32_MAX);
				err = mot_warp_init(&fs->warp, qlo, qhi, qout, qin, &sat);
				if (err)
					return sb_err(e, err, (int)i, "ease", UINT32_MAX);
				n->strand = (int32_t)fi;
			}
			fi++;
		}
	}
	if (d->has_camera) {
		uint32_t nref;
		mot_q32 *ref;
		mot_q32 qin, qout;

		for (k = 0; k < MOT_CAM_NCHANNELS; k++) {
			double scale = k == MOT_CAM_TWIST ? 1.0 / 360.0 : 1.0;

			err = sb_curve(l, fill ? &l->curves[ci] : NULL, &d->camera.ch[k], scale,
					  false, &bad);
			if (err)
				return sb_err(e, err, -1, sd_cam_names[k], bad);
			if (fill)
				l->camera->ch[k] = (int32_t)ci;
			ci++;
		}
		nref = mot_camera_ref_count(d->camera.ch[0].nkeys);
		ref = ALLOC(a, mot_q32, nref);
		if (fill) {
			const struct sd_curve *c0 = &d->camera.ch[0];
			mot_q32 qlo = 0, qhi = 0;

			if (!ref)
				return sb_err(e, MOT_E_CAPACITY, -1, "camera", UINT32_MAX);
			if (c0->nkeys == 0)
				return sb_err(e, MOT_E_NOKEYS, -1, "camera", UINT32_MAX);
			if (!sd_to_q32(c0->keys[0].frame, &qlo) ||
			    !sd_to_q32(c0->keys[c0->nkeys - 1].frame, &qhi) ||
			    !sd_to_q32(d->camera.ease_in, &qin) || !sd_to_q32(d->camera.ease_out, &qout))
				return sb_err(e, MOT_E_RANGE, -1, "camera", UINT32_MAX);
			err = mot_warp_init(&l->camera->warp, qlo, qhi, qout, qin, &sat);
			if (err)
				return sb_err(e, err, -1, "camera.ease", UINT32_MAX);
			err = mot_camera_init(l->camera, l->curves, ref, nref, &sat);
			if (err)
				return sb_err(e, err, -1, "camera", UINT32_MAX);
		}
	}
	for (i = 0; i < d->nattrs; i++) {
		err = sb_curve(l, fill ? &l->curves[ci] : NULL, &d->attrs[i].curve, 1.0, false,
				  &bad);
		if (err)
			return sb_err(e, err, -1, d->attrs[i].name, bad);
		if (fill)
			l->attr_curve[i] = (int32_t)ci;
		ci++;
	}
	err = sb_systems(l, d, &ci, e);
	if (err || !fill)
		return err;
	for (i = 0; i < d->ncycles; i++) {
		const struct sd_cycle *c = &d->cycles[i];

		err = mot_cycle_init(&l->cycles[i], c->first, c->last, c->skip, c->mode,
				     c->frames_per_step, c->start_frame);
		if (err)
			return sb_err(e, err, -1, c->name, UINT32_MAX);
	}
	l->sc->nnodes = d->nnodes;
	l->sc->nodes = l->nodes;
	l->sc->ncurves = l->ncurves;
	l->sc->curves = l->curves;
	l->sc->nrot = l->nrot;
	l->sc->rot = l->rot;
	l->sc->nfree = l->nfree;
	l->sc->free = l->free;
	l->sc->camera = l->camera;
	l->sc->ncycles = d->ncycles;
	l->sc->cycles = l->cycles;
	l->sc->nattrs = d->nattrs;
	l->sc->attr_curve = l->attr_curve;
	err = mot_scene_validate(l->sc);
	if (err)
		return sb_err(e, err, -1, "hierarchy", UINT32_MAX);
	/* the systems run over their span once every curve is in place,
	 * then the aims march over the whole scene */
	err = sb_systems_init(l, d, e);
	if (!err)
		err = sb_aims_init(l, d, e);
	return err;
}

int scene_build(struct scene_built *out, const struct scene_desc *d, struct scene_build_err *e)
{
	struct mot_arena a;
	struct layout l;
	size_t size;
	void *block;
	int err;

	memset(out, 0, sizeof(*out));
	sb_err(e, 0, -1, NULL, UINT32_MAX);
	count(d, &l);
	mot_arena_init(&a, NULL, 0);
	l.a = &a;
	err = layout_all(&l, d, e);
	if (err)
		return err;
	size = (a.used + 63) & ~(size_t)63;
	block = aligned_alloc(64, size ? size : 64);
	if (!block)
		return sb_err(e, -ENOMEM, -1, "scene", UINT32_MAX);
	mot_arena_init(&a, block, size);
	err = layout_all(&l, d, e);
	if (err) {
		free(block);
		return err;
	}
	mot_arena_seal(&a);
	out->sc = *l.sc;
	out->block = block;
	out->block_size = a.used;
	return 0;
}

void scene_built_free(struct scene_built *b)
{
	free(b->block);
	b->block = NULL;
}

/* Each system's part of an evaluation in one block after the array of
 * struct mot_sys_eval (system.h). */
static int sys_eval_new(struct mot_eval *ev, const struct mot_scene *sc)
{
	size_t head = ((size_t)(sc->nsys ? sc->nsys : 1) * sizeof(*ev->sys) + 63) & ~(size_t)63;
	size_t size = head, off;
	unsigned char *block;
	uint32_t i;

	for (i = 0; i < sc->nsys; i++)
		size += (mot_system_eval_bytes(&sc->sys[i]) + 63) & ~(size_t)63;
	block = aligned_alloc(64, size);
	if (!block)
		return -ENOMEM;
	ev->sys = (struct mot_sys_eval *)(void *)block;
	for (i = 0, off = head; i < sc->nsys; i++) {
		size_t n = mot_system_eval_bytes(&sc->sys[i]);

		mot_system_eval_init(&ev->sys[i], &sc->sys[i], block + off, n);
		off += (n + 63) & ~(size_t)63;
	}
	return 0;
}

int scene_eval_new(struct mot_eval *ev, const struct mot_scene *sc)
{
	uint32_t n = mot_eval_cursor_count(sc);

	memset(ev, 0, sizeof(*ev));
	ev->cursors = calloc(n ? n : 1, sizeof(*ev->cursors));
	ev->memo = calloc(sc->nnodes ? sc->nnodes : 1, sizeof(*ev->memo));
	if (!ev->cursors || !ev->memo || sys_eval_new(ev, sc)) {
		scene_eval_free(ev);
		return -ENOMEM;
	}
	ev->ncursors = n;
	ev->nmemo = mot_eval_memo_count(sc);
	return mot_eval_reset(ev, sc);
}

void scene_eval_free(struct mot_eval *ev)
{
	free(ev->cursors);
	free(ev->memo);
	free(ev->sys);
	ev->cursors = NULL;
	ev->memo = NULL;
	ev->sys = NULL;
}

int scene_pose_new(struct mot_pose *p, const struct mot_scene *sc)
{
	size_t n = sc->nnodes ? sc->nnodes : 1;

	memset(p, 0, sizeof(*p));
	p->world = calloc(n, sizeof(*p->world));
	p->pos = calloc(n, sizeof(*p->pos));
	p->value = calloc(n, sizeof(*p->value));
	p->rpm = calloc(n, sizeof(*p->rpm));
	p->cycle = calloc(sc->ncycles ? sc->ncycles : 1, sizeof(*p->cycle));
	p->attr = calloc(sc->nattrs ? sc->nattrs : 1, sizeof(*p->attr));
	p->sysout = calloc(sc->nsysout ? sc->nsysout : 1, sizeof(*p->sysout));
	p->aim = calloc(sc->naims ? sc->naims : 1, sizeof(*p->aim));
	if (!p->world || !p->pos || !p->value || !p->rpm || !p->cycle || !p->attr || !p->sysout ||
	    !p->aim) {
		scene_pose_free(p);
		return -ENOMEM;
	}
	return 0;
}

void scene_pose_free(struct mot_pose *p)
{
	free(p->world);
	free(p->pos);
	free(p->value);
	free(p->rpm);
	free(p->cycle);
	free(p->attr);
	free(p->sysout);
	free(p->aim);
	memset(p, 0, sizeof(*p));
}
