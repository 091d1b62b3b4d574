/* SPDX-License-Identifier: MIT */
/*
 * digest.c - one 64-bit digest of a long deterministic workload through the
 * motion core, printed as the line "DIGEST <16 hex digits>".
 *
 * The core promises the same bits on every target. `make check-cross` builds
 * this program natively, natively with MOT_NO_INT128, for aarch64 and for
 * armhf (run under qemu-user), and requires the four digests to be equal.
 * Whatever would break the promise shows here: an implementation-defined
 * shift, a 32-bit path that rounds differently, a compiler's liberty with a
 * division. No digest is stored: only the agreement between targets is
 * checked, so adding a workload changes the digest and that is expected.
 *
 * Every value a workload produces goes into the digest, status words and
 * error codes included (FNV-1a over the 8 bytes of each value, taken
 * least-significant first, so byte order does not matter). Each workload
 * draws from its own generator seeded from its name: adding a workload
 * leaves the inputs of the others unchanged. `digest -v` prints the digest
 * of each workload, to find the one that differs.
 *
 * Adding a workload (trig, curves, matrices, whole-scene evaluation):
 *   1. Write `static void wl_<name>(struct dg *d)`: draw inputs with
 *      dg_i64() / dg_u64() / dg_range(), call the core, dg_put() every
 *      result. Keep it to a few hundred thousand calls: it runs under qemu.
 *   2. Add it to workloads[] at the end of the file.
 * The scene workloads build scenes in code (tests/synth.c through
 * firmware/scene_build.c, no files: the program also runs where there are
 * none), play them over many ticks with the cursors a real loop uses, and
 * put every pose and the status words. They cover the loader's conversion
 * from doubles too, which is why firmware/ is built with -ffp-contract=off.
 */
#include <inttypes.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "motion/curve.h"
#include "motion/decomp.h"
#include "motion/ease.h"
#include "motion/fix.h"
#include "motion/mat.h"
#include "motion/quat.h"
#include "motion/rng.h"
#include "motion/system.h"
#include "motion/trig.h"
#include "scene/scene_desc.h"
#include "tests/synth.h"

#define ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

#define FNV_OFFSET 0xcbf29ce484222325ull
#define FNV_PRIME 0x100000001b3ull

/* A workload's digest and its generator. */
struct dg {
	uint64_t h;   /* FNV-1a state */
	uint64_t n;   /* values put */
	uint64_t rng; /* splitmix64 state */
};

static void dg_put(struct dg *d, uint64_t v)
{
	int i;

	for (i = 0; i < 8; i++) {
		d->h ^= (v >> (8 * i)) & 0xff;
		d->h *= FNV_PRIME;
	}
	d->n++;
}

static void dg_put_acc(struct dg *d, mot_acc x)
{
	dg_put(d, mot_acc_hi(x));
	dg_put(d, mot_acc_lo(x));
}

/* splitmix64 (Steele, Lea, Flood 2014): the same sequence everywhere. */
static uint64_t dg_u64(struct dg *d)
{
	uint64_t z = (d->rng += 0x9e3779b97f4a7c15ull);

	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
	return z ^ (z >> 31);
}

/* An int64 of random bit length (0 to 63, uniformly): small values,
 * Q32.32-sized ones and the extremes all occur often. */
static int64_t dg_i64(struct dg *d)
{
	unsigned shift = (unsigned)(dg_u64(d) & 63);

	return (int64_t)dg_u64(d) >> shift;
}

/* n values of dg_i64(). (C leaves the order of evaluation of function
 * arguments and of initializer lists open: draw one value per statement.) */
static void dg_fill(struct dg *d, int64_t *v, int n)
{
	int k;

	for (k = 0; k < n; k++)
		v[k] = dg_i64(d);
}

/* Uniform in [lo, hi] (hi - lo < 2^63). */
static int64_t dg_range(struct dg *d, int64_t lo, int64_t hi)
{
	return lo + (int64_t)(dg_u64(d) % ((uint64_t)(hi - lo) + 1));
}

/* ---- fix.h / fix.c ------------------------------------------------------- */

#define N_FIX (1 << 19)

/* Products, sums, dot products and the small helpers of fix.h. */
static void wl_fix_mul(struct dg *d)
{
	long i;

	for (i = 0; i < N_FIX; i++) {
		mot_q32 a[3], b[3];
		uint32_t sat = 0;

		dg_fill(d, a, 3);
		dg_fill(d, b, 3);
		dg_put(d, (uint64_t)mot_mul(a[0], b[0], &sat));
		dg_put(d, (uint64_t)mot_dot3(a, b, &sat));
		dg_put(d, (uint64_t)mot_add_sat(a[1], b[1], &sat));
		dg_put(d, (uint64_t)mot_sub_sat(a[2], b[2], &sat));
		dg_put(d, (uint64_t)mot_abs(a[0]));
		dg_put(d, mot_clz64((uint64_t)b[0]));
		dg_put(d, sat);
	}
}

/* 128-bit accumulation and rounding at every shift. */
static void wl_fix_acc(struct dg *d)
{
	long i;

	for (i = 0; i < N_FIX; i++) {
		int64_t v[5];
		unsigned shift = (unsigned)dg_range(d, 1, 126);
		unsigned up = (unsigned)(dg_u64(d) & 63);
		uint32_t sat = 0;
		mot_acc p;

		dg_fill(d, v, 5);
		p = mot_acc_mul(v[0], v[1]);
		p = mot_acc_mac(p, v[2], v[3]);
		p = mot_acc_sub(p, mot_acc_from(v[4], up));
		dg_put_acc(d, p);
		dg_put(d, (uint64_t)mot_acc_round(p, shift, &sat));
		dg_put(d, (uint64_t)mot_acc_round(mot_acc_neg(p), MOT_Q32_FRAC, &sat));
		dg_put(d, sat);
	}
}

/* 128 / 64 division, in range and overflowing. */
static void wl_fix_udiv(struct dg *d)
{
	long i;

	for (i = 0; i < N_FIX; i++) {
		unsigned shift = (unsigned)(dg_u64(d) & 63);
		uint64_t dv = dg_u64(d) >> shift;
		uint64_t hi = dg_u64(d), lo = dg_u64(d), rem = 0;
		uint32_t sat = 0;

		/* one in sixteen overflows (hi >= d), the rest fit */
		if ((i & 15) && dv)
			hi %= dv;
		dg_put(d, mot_acc_udiv(mot_acc_make(hi, lo), dv, &rem, &sat));
		dg_put(d, rem);
		dg_put(d, sat);
	}
}

/* Rounded divisions: muldiv, div, ratio, floordiv; bad divisors included. */
static void wl_fix_div(struct dg *d)
{
	long i;

	for (i = 0; i < N_FIX; i++) {
		int64_t a = dg_i64(d), m = dg_i64(d), b = dg_i64(d);
		unsigned shift = (unsigned)dg_range(d, 1, 63);
		int64_t pos = (int64_t)(dg_u64(d) >> shift) | 1;
		int64_t rem = 0;
		uint32_t sat = 0;

		if ((i & 63) == 0)
			b = (i & 64) ? 0 : MOT_Q32_MIN;
		dg_put(d, (uint64_t)mot_muldiv(a, m, (i & 31) ? pos : -pos, &sat));
		dg_put(d, (uint64_t)mot_div(a, b, &sat));
		dg_put(d, (uint64_t)mot_q32_ratio(m, pos, &sat));
		dg_put(d, (uint64_t)mot_floordiv(a, pos, &rem));
		dg_put(d, (uint64_t)rem);
		dg_put(d, sat);
	}
}

/* Prepared reciprocals, each used for a few ratios. */
static void wl_fix_recip(struct dg *d)
{
	long i;
	int j;

	for (i = 0; i < N_FIX / 4; i++) {
		struct mot_recip r = { 0, 0 };
		int64_t dv = dg_i64(d);
		uint32_t sat = 0;

		dg_put(d, (uint64_t)mot_recip_init(&r, dv));
		dg_put(d, (uint64_t)r.m);
		dg_put(d, r.shift);
		if (dv <= 0)
			continue;
		for (j = 0; j < 4; j++)
			dg_put(d, (uint64_t)mot_recip_ratio(dg_i64(d), &r, &sat));
		dg_put(d, sat);
	}
}

/* ---- trig.c -------------------------------------------------------------- */

#define N_TRIG (1 << 16)

static void wl_trig(struct dg *d)
{
	long i;

	for (i = 0; i < N_TRIG; i++) {
		mot_q32 turns = dg_i64(d), x = dg_i64(d), y = dg_i64(d), s, c;
		/* around [-1, 1], a little outside on purpose */
		mot_q32 u = dg_range(d, -MOT_Q32_ONE - (1 << 20), MOT_Q32_ONE + (1 << 20));
		mot_q32 v[3];
		uint32_t sat = 0;

		dg_fill(d, v, 3);
		v[0] >>= 2;
		v[1] >>= 2;
		v[2] >>= 2;
		mot_sincos(turns, &s, &c);
		dg_put(d, (uint64_t)s);
		dg_put(d, (uint64_t)c);
		dg_put(d, (uint64_t)mot_sin(x));
		dg_put(d, (uint64_t)mot_cos(x));
		dg_put(d, (uint64_t)mot_atan2(y, x));
		dg_put(d, (uint64_t)mot_acos(u, &sat));
		dg_put(d, (uint64_t)mot_sqrt(x, &sat));
		dg_put(d, (uint64_t)mot_rsqrt(y, &sat));
		dg_put(d, mot_isqrt_acc(mot_acc_mul(x, y), &sat));
		dg_put(d, (uint64_t)mot_norm3(v, &sat));
		dg_put(d, sat);
	}
}

/* ---- ease.c -------------------------------------------------------------- */

#define N_EASE (1 << 14)

static void wl_ease(struct dg *d)
{
	long i;
	int j;

	for (i = 0; i < N_EASE; i++) {
		struct mot_ease e;
		/* a + b <= 1 mostly; one in eight is invalid */
		mot_q32 a = dg_range(d, 0, MOT_Q32_HALF), b = dg_range(d, 0, MOT_Q32_HALF);
		uint32_t sat = 0;
		int rc;

		if ((i & 7) == 0)
			b += MOT_Q32_HALF + 1;
		rc = mot_ease_init(&e, a, b, &sat);
		dg_put(d, (uint64_t)rc);
		if (rc != MOT_OK)
			continue;
		for (j = 0; j < 16; j++) {
			mot_q32 s = dg_range(d, -MOT_Q32_ONE / 8, MOT_Q32_ONE + MOT_Q32_ONE / 8);

			dg_put(d, (uint64_t)mot_ease_apply(&e, s, &sat));
		}
		dg_put(d, sat);
	}
}

/* ---- helpers of the geometry workloads (mat, quat, decomp) ------------------ */

/* An angle for them: +-1000 turns. (trig's own workload covers the whole
 * int64 range.) */
#define DG_TURNS MOT_Q32_INT(1000)

static inline void dg_put_vec(struct dg *d, const mot_q32 v[3])
{
	dg_put(d, (uint64_t)v[0]);
	dg_put(d, (uint64_t)v[1]);
	dg_put(d, (uint64_t)v[2]);
}

static inline void dg_put_mat(struct dg *d, const struct mot_mat *m)
{
	int r;

	for (r = 0; r < 4; r++)
		dg_put_vec(d, m->m[r]);
}

static inline void dg_vec(struct dg *d, mot_q32 v[3], mot_q32 lim)
{
	int k;

	for (k = 0; k < 3; k++)
		v[k] = dg_range(d, -lim, lim);
}


/* ---- mat.c --------------------------------------------------------------- */

#define N_MAT (1 << 13)

/* A random affine matrix: Euler rotation, scale 0.1 to 10, translation. */
static void dg_mat(struct dg *d, struct mot_mat *m, uint32_t *sat)
{
	struct mot_mat r, s;
	mot_q32 e[3], k[3];
	int j;

	dg_vec(d, e, MOT_Q32_INT(2));
	for (j = 0; j < 3; j++)
		k[j] = dg_range(d, MOT_Q32_ONE / 10, MOT_Q32_INT(10));
	mot_mat_euler(&r, e, sat);
	mot_mat_scale(&s, k);
	mot_mat_mul(m, &s, &r, sat);
	dg_vec(d, m->m[3], MOT_Q32_INT(1000));
}

static void wl_mat(struct dg *d)
{
	long i;

	for (i = 0; i < N_MAT; i++) {
		struct mot_mat a, b, m, t;
		mot_q32 p[3], v[3], h[3], out[3];
		uint32_t sat = 0;

		dg_mat(d, &a, &sat);
		dg_mat(d, &b, &sat);
		dg_vec(d, p, MOT_Q32_INT(1000));
		dg_vec(d, h, MOT_Q32_ONE);
		dg_vec(d, v, MOT_Q32_INT(1000));
		mot_mat_mul(&m, &a, &b, &sat);
		dg_put_mat(d, &m);
		dg_put(d, (uint64_t)mot_mat_det(&m, &sat));
		mot_mat_identity(&t); /* what a failed inverse leaves */
		dg_put(d, (uint64_t)mot_mat_inverse(&t, &m, &sat));
		dg_put_mat(d, &t);
		mot_mat_apply(out, p, &m, &sat);
		dg_put_vec(d, out);
		mot_mat_apply_dir(out, p, &m, &sat);
		dg_put_vec(d, out);
		/* unit axes: rows of rotations */
		mot_mat_rot_z(&t, dg_range(d, -DG_TURNS, DG_TURNS));
		dg_put_mat(d, &t);
		mot_mat_rot_axis(&t, t.m[0], dg_range(d, -DG_TURNS, DG_TURNS), &sat);
		dg_put_mat(d, &t);
		mot_mat_rot_axis(&t, t.m[1], dg_range(d, -DG_TURNS, DG_TURNS), &sat);
		dg_put_mat(d, &t);
		mot_mat_shear(&t, h);
		mot_mat_edit_local(&m, &t, p, &sat);
		mot_mat_edit_world(&m, &b, v, &sat);
		dg_put_mat(d, &m);
		mot_mat_to_local(&m, p, &sat);
		mot_mat_to_world(&m, v, &sat);
		mot_mat_about_pivot(&t, &m, p, &sat);
		dg_put_mat(d, &t);
		dg_put(d, sat);
	}
}

/* ---- quat.c -------------------------------------------------------------- */

#define N_QUAT (1 << 13)

static void dg_put_quat(struct dg *d, const struct mot_quat *q)
{
	dg_put(d, (uint64_t)q->w);
	dg_put(d, (uint64_t)q->x);
	dg_put(d, (uint64_t)q->y);
	dg_put(d, (uint64_t)q->z);
}

static void dg_quat(struct dg *d, struct mot_quat *q, uint32_t *sat)
{
	mot_q32 e[3];

	dg_vec(d, e, DG_TURNS);
	mot_quat_from_euler(q, e, sat);
}

static void wl_quat(struct dg *d)
{
	long i;
	int j;

	for (i = 0; i < N_QUAT; i++) {
		struct mot_quat a, b, c, s0, s1, q;
		struct mot_slerp sl;
		struct mot_mat m;
		mot_q32 axis[3];
		uint32_t sat = 0;

		dg_vec(d, axis, MOT_Q32_INT(100));
		dg_quat(d, &a, &sat);
		dg_quat(d, &b, &sat);
		dg_quat(d, &c, &sat);
		/* nearly equal keys now and then, for the nlerp fallback */
		if ((i & 7) == 0) {
			b = a;
			b.x += dg_range(d, -4096, 4096);
		}
		q.w = 0;
		q.x = axis[0];
		q.y = axis[1];
		q.z = axis[2];
		dg_put(d, (uint64_t)mot_quat_normalize(&q, &q, &sat));
		axis[0] = q.x;
		axis[1] = q.y;
		axis[2] = q.z;
		mot_quat_from_axis_angle(&q, axis, dg_range(d, -DG_TURNS, DG_TURNS), &sat);
		dg_put_quat(d, &q);
		mot_quat_mul(&q, &a, &b, &sat);
		dg_put_quat(d, &q);
		dg_put(d, (uint64_t)mot_quat_dot(&a, &b, &sat));
		mot_quat_to_mat(&m, &q, &sat);
		mot_quat_from_mat(&q, &m, &sat);
		dg_put_quat(d, &q);
		mot_slerp_prepare(&sl, &a, &b, &sat);
		mot_squad_inner(&s0, &a, &b, &c, &sat);
		mot_squad_inner(&s1, &b, &c, &a, &sat);
		for (j = 0; j < 8; j++) {
			mot_q32 t = dg_range(d, 0, MOT_Q32_ONE);

			mot_slerp_eval(&q, &sl, t, &sat);
			dg_put_quat(d, &q);
			mot_quat_slerp(&q, &b, &c, t, &sat);
			dg_put_quat(d, &q);
			mot_quat_squad(&q, &b, &c, &s0, &s1, t, &sat);
			dg_put_quat(d, &q);
		}
		dg_put(d, sat);
	}
}

/* ---- decomp.c ------------------------------------------------------------ */

#define N_DECOMP (1 << 13)

static void wl_decomp(struct dg *d)
{
	long i;
	int j;

	for (i = 0; i < N_DECOMP; i++) {
		struct mot_decomp in, out;
		struct mot_mat m, r;
		mot_q32 e[3];
		uint32_t sat = 0;

		dg_vec(d, e, DG_TURNS);
		for (j = 0; j < 3; j++) {
			in.scale[j] = dg_range(d, MOT_Q32_ONE / 10, MOT_Q32_INT(10));
			in.shear[j] = dg_range(d, -MOT_Q32_ONE, MOT_Q32_ONE);
			in.translate[j] = dg_range(d, -MOT_Q32_INT(1000), MOT_Q32_INT(1000));
		}
		if (i & 1)
			in.scale[i & 2] = -in.scale[i & 2]; /* a reflection */
		if ((i & 63) == 0)
			in.scale[1] = 0; /* singular */
		mot_quat_from_euler(&in.rot, e, &sat);
		mot_mat_compose(&m, &in, &sat);
		memset(&out, 0, sizeof(out));
		memset(&r, 0, sizeof(r));
		dg_put(d, (uint64_t)mot_mat_decompose(&out, &r, &m, &sat));
		for (j = 0; j < 3; j++) {
			dg_put(d, (uint64_t)out.scale[j]);
			dg_put(d, (uint64_t)out.shear[j]);
			dg_put(d, (uint64_t)out.translate[j]);
		}
		dg_put(d, (uint64_t)out.rot.w);
		dg_put(d, (uint64_t)out.rot.x);
		dg_put(d, (uint64_t)out.rot.y);
		dg_put(d, (uint64_t)out.rot.z);
		dg_put_mat(d, &r);
		dg_put(d, sat);
	}
}

/* ---- curve*.c ------------------------------------------------------------ */

#define N_CURVE 192
#define CURVE_KEYS 12
#define CURVE_SEGS 64

/* One random curve of each kind, sampled tick by tick with a cursor and at
 * random frames without one. */
static void wl_curve(struct dg *d)
{
	static const enum mot_interp kinds[] = {
		MOT_INTERP_STEP,    MOT_INTERP_LINEAR, MOT_INTERP_HERMITE,
		MOT_INTERP_BSPLINE, MOT_INTERP_BETA,   MOT_INTERP_BEZIER,
	};
	long i;

	for (i = 0; i < N_CURVE; i++) {
		enum mot_interp kind = kinds[i % ARRAY_SIZE(kinds)];
		bool interp = kind <= MOT_INTERP_HERMITE;
		struct mot_key keys[CURVE_KEYS];
		struct mot_curve_seg seg[CURVE_SEGS];
		struct mot_curve_opts opts;
		struct mot_cursor cur = { 0, 0 };
		struct mot_curve c;
		mot_q32 f = -MOT_Q32_INT(5), tick;
		uint32_t n = 2 + (uint32_t)(dg_u64(d) % (CURVE_KEYS - 1)), nseg, k;
		uint32_t sat = 0;
		int rc;

		for (k = 0; k < n; k++) {
			f += dg_range(d, MOT_Q32_ONE / 4, MOT_Q32_INT(50));
			keys[k].frame = f;
			keys[k].value = dg_range(d, -MOT_Q32_INT(1000), MOT_Q32_INT(1000));
			keys[k].ease_in = (i & 2) ? dg_range(d, 0, MOT_Q32_ONE / 2) : 0;
			keys[k].ease_out = (i & 2) ? dg_range(d, 0, MOT_Q32_ONE / 2) : 0;
		}
		memset(&opts, 0, sizeof(opts));
		opts.beta1 = dg_range(d, MOT_Q32_ONE / 2, MOT_Q32_INT(3));
		opts.beta2 = dg_range(d, 0, MOT_Q32_INT(5));
		opts.integral = interp && !(i & 2);
		if (i & 4) {
			opts.ease_in_frames = (f - keys[0].frame) / 4;
			opts.ease_out_frames = (f - keys[0].frame) / 4;
			opts.integral = false;
		}
		nseg = mot_curve_seg_count(kind, n);
		dg_put(d, nseg);
		if (nseg > CURVE_SEGS)
			continue;
		rc = mot_curve_init(&c, kind, keys, n, &opts, seg, nseg, &sat);
		dg_put(d, (uint64_t)rc);
		if (rc != MOT_OK)
			continue;
		tick = dg_range(d, MOT_Q32_ONE / 2, MOT_Q32_INT(4));
		for (f = keys[0].frame - MOT_Q32_INT(3); f < keys[n - 1].frame + MOT_Q32_INT(3);
		     f += tick) {
			mot_acc area = mot_acc_zero();

			dg_put(d, (uint64_t)mot_curve_eval(&c, &cur, f, &sat));
			dg_put(d, (uint64_t)mot_curve_eval(&c, NULL,
							   dg_range(d, keys[0].frame, keys[n - 1].frame),
							   &sat));
			if (opts.integral) {
				dg_put(d, (uint64_t)mot_curve_integral(&area, &c, &cur, f, &sat));
				dg_put_acc(d, area);
			}
		}
		dg_put(d, sat);
	}
}

/* What the importers added: hermite curves with explicit tangents, compact
 * step and linear curves, compact slerp tracks. */
static void wl_curve_keys(struct dg *d)
{
	long i;

	for (i = 0; i < N_CURVE / 2; i++) {
		struct mot_key keys[CURVE_KEYS];
		struct mot_tangent tan[CURVE_KEYS];
		struct mot_rot_key rk[CURVE_KEYS];
		struct mot_curve_seg seg[CURVE_SEGS];
		struct mot_curve_opts opts;
		struct mot_cursor cur = { 0, 0 }, rcur = { 0, 0 };
		struct mot_curve c;
		struct mot_rot_track rt;
		enum mot_interp kind = (i % 3 == 0) ? MOT_INTERP_HERMITE :
				       (i % 3 == 1) ? MOT_INTERP_LINEAR : MOT_INTERP_STEP;
		mot_q32 f = -MOT_Q32_INT(5), tick;
		uint32_t n = 2 + (uint32_t)(dg_u64(d) % (CURVE_KEYS - 1)), k, sat = 0;
		int rc;

		for (k = 0; k < n; k++) {
			f += dg_range(d, MOT_Q32_ONE / 4, MOT_Q32_INT(50));
			keys[k].frame = rk[k].frame = f;
			keys[k].value = dg_range(d, -MOT_Q32_INT(1000), MOT_Q32_INT(1000));
			keys[k].ease_in = keys[k].ease_out = rk[k].ease_in = rk[k].ease_out = 0;
			tan[k].in = dg_range(d, -MOT_Q32_INT(100), MOT_Q32_INT(100));
			tan[k].out = dg_range(d, -MOT_Q32_INT(100), MOT_Q32_INT(100));
			tan[k].set = (uint32_t)(dg_u64(d) % 4);
			dg_quat(d, &rk[k].q, &sat);
		}
		memset(&opts, 0, sizeof(opts));
		opts.tangents = kind == MOT_INTERP_HERMITE ? tan : NULL;
		opts.compact = kind != MOT_INTERP_HERMITE;
		rc = mot_curve_init(&c, kind, keys, n, &opts, opts.compact ? NULL : seg,
				    opts.compact ? 0 : CURVE_SEGS, &sat);
		dg_put(d, (uint64_t)rc);
		rc = mot_rot_track_init_compact(&rt, rk, n);
		dg_put(d, (uint64_t)rc);
		tick = dg_range(d, MOT_Q32_ONE / 2, MOT_Q32_INT(4));
		for (f = keys[0].frame - MOT_Q32_INT(3); f < keys[n - 1].frame + MOT_Q32_INT(3);
		     f += tick) {
			struct mot_quat q;
			mot_q32 at = dg_range(d, keys[0].frame, keys[n - 1].frame);

			dg_put(d, (uint64_t)mot_curve_eval(&c, &cur, f, &sat));
			dg_put(d, (uint64_t)mot_curve_eval(&c, NULL, at, &sat));
			mot_rot_track_eval(&q, &rt, &rcur, f, &sat);
			dg_put_quat(d, &q);
		}
		dg_put(d, sat);
	}
}

/* ---- whole scenes ----------------------------------------------------------- */

static void put_pose(struct dg *d, const struct mot_scene *sc, const struct mot_pose *p)
{
	uint32_t i, r, c;

	for (i = 0; i < sc->nnodes; i++) {
		for (r = 0; r < 4; r++)
			for (c = 0; c < 3; c++)
				dg_put(d, (uint64_t)p->world[i].m[r][c]);
		for (c = 0; c < 3; c++)
			dg_put(d, (uint64_t)p->pos[i][c]);
		dg_put(d, (uint64_t)p->value[i]);
		dg_put(d, (uint64_t)p->rpm[i]);
	}
	if (sc->camera) {
		dg_put(d, (uint64_t)p->cam.pan);
		dg_put(d, (uint64_t)p->cam.tilt);
		dg_put(d, (uint64_t)p->cam.roll);
		for (r = 0; r < 4; r++)
			for (c = 0; c < 3; c++)
				dg_put(d, (uint64_t)p->cam.m.m[r][c]);
	}
	for (i = 0; i < sc->ncycles; i++)
		dg_put(d, (uint64_t)p->cycle[i]);
	for (i = 0; i < sc->nattrs; i++)
		dg_put(d, (uint64_t)p->attr[i]);
}

/* Play a described scene tick by tick from `from` for n ticks (every
 * `step`), as the loop does. */
static void play(struct dg *d, const struct scene_desc *desc, int64_t from, int64_t n, int64_t step)
{
	struct scene_built b;
	struct scene_build_err e;
	struct mot_eval ev;
	struct mot_pose p;
	int64_t k;
	int err = scene_build(&b, desc, &e);

	dg_put(d, (uint64_t)err);
	if (err)
		return;
	if (scene_eval_new(&ev, &b.sc) || scene_pose_new(&p, &b.sc)) {
		fprintf(stderr, "digest: out of memory\n");
		exit(1);
	}
	for (k = from; k < from + n; k += step) {
		mot_scene_eval(&b.sc, &ev, mot_timing_tick_frame(&b.sc.timing, k), &p);
		put_pose(d, &b.sc, &p);
	}
	dg_put(d, ev.sat);
	scene_pose_free(&p);
	scene_eval_free(&ev);
	scene_built_free(&b);
}

static void wl_scene_arm(struct dg *d)
{
	struct synth s;

	synth_robot_arm(&s, 60.0, 240);
	play(d, &s.d, -100, 10300, 1);
	synth_free(&s);
}

static void wl_scene_random(struct dg *d)
{
	uint64_t seed;

	for (seed = 1; seed <= 3; seed++) {
		struct synth s;

		synth_random(&s, seed, 150, 96);
		play(d, &s.d, -300, 4300, 3);
		synth_free(&s);
	}
}

/* ---- systems: surfaces, particles, flocks ---------------------------------------- */

/* A system built by hand over 30 s at 25 fps and 1 kHz, evaluated at
 * every 17th tick of the first 20 s, then at 100 random ticks (seeks from
 * checkpoints), every value put: a fraction of a second natively, under
 * qemu a few. */
struct dg_sys {
	struct mot_timing t;
	struct mot_system sys;
	struct mot_sys_eval ev;
	void *block, *ckpt;
	mot_q32 *out;
	struct mot_curve curves[4];
	struct mot_key keys[4][4];
	struct mot_curve_seg seg[4][8];
};

static void dg_sys_run(struct dg *d, struct dg_sys *s, struct mot_steps *steps, uint32_t sbytes)
{
	uint32_t sat = 0, i;
	size_t bytes;
	int64_t k;

	if (steps) {
		dg_put(d, (uint64_t)mot_steps_init(steps, &s->t, 0, MOT_Q32_INT(750), 50, 1, 16,
						   sbytes));
		s->ckpt = calloc(mot_steps_ckpt_count(steps), steps->state_bytes);
		steps->ckpt = s->ckpt;
	}
	bytes = mot_system_eval_bytes(&s->sys);
	s->block = aligned_alloc(64, (bytes + 63) & ~(size_t)63);
	if (!s->block || (steps && !s->ckpt)) {
		fprintf(stderr, "digest: out of memory\n");
		exit(1);
	}
	mot_system_eval_init(&s->ev, &s->sys, s->block, bytes);
	dg_put(d, (uint64_t)mot_system_init(&s->sys, s->curves, 4, &s->ev, &sat));
	s->out = calloc(s->sys.nout ? s->sys.nout : 1, sizeof(*s->out));
	for (k = 0; k < 20000 + 100; k++) {
		int64_t tick = k < 20000 ? k : dg_range(d, 0, 30000);

		if (k < 20000 && k % 17)
			continue;
		mot_system_eval(&s->sys, s->curves, NULL, &s->ev, mot_timing_tick_frame(&s->t, tick),
				s->out, &sat);
		for (i = 0; i < s->sys.nout; i++)
			dg_put(d, (uint64_t)s->out[i]);
	}
	dg_put(d, sat);
	free(s->block);
	free(s->ckpt);
	free(s->out);
}

/* Curve c: n keys every 100 frames with random values in +-lim. */
static void dg_sys_curve(struct dg *d, struct dg_sys *s, int c, enum mot_interp kind,
			 int64_t lim)
{
	uint32_t k, sat = 0;

	for (k = 0; k < 4; k++)
		s->keys[c][k] = (struct mot_key){ MOT_Q32_INT(250 * (int)k), dg_range(d, -lim, lim),
						  0, 0 };
	dg_put(d, (uint64_t)mot_curve_init(&s->curves[c], kind, s->keys[c], 4, NULL, s->seg[c], 8,
					   &sat));
}

static void wl_sys_surface(struct dg *d)
{
	static struct mot_surface_w wu[40], wv[40];
	static int32_t curve[10 * 7 * 3];
	static mot_q32 rest[10 * 7 * 3], fixed[40 * 40 * 3];
	int basis;

	for (basis = 0; basis < 2; basis++) {
		struct dg_sys s;
		struct mot_surface sf;
		uint32_t i;

		memset(&s, 0, sizeof(s));
		mot_timing_init(&s.t, 25, 1, 1000);
		memset(&sf, 0, sizeof(sf));
		sf.basis = (uint32_t)basis;
		sf.ncu = basis ? 9 : 10;
		sf.ncv = 7;
		sf.nsu = 19;
		sf.nsv = 13;
		sf.curve = curve;
		sf.rest = rest;
		sf.wu = wu;
		sf.wv = wv;
		sf.fixed = fixed;
		dg_sys_curve(d, &s, 0, MOT_INTERP_HERMITE, MOT_Q32_INT(2));
		dg_sys_curve(d, &s, 1, MOT_INTERP_BSPLINE, MOT_Q32_INT(2));
		dg_sys_curve(d, &s, 2, MOT_INTERP_BETA, MOT_Q32_INT(2));
		dg_sys_curve(d, &s, 3, MOT_INTERP_LINEAR, MOT_Q32_INT(2));
		for (i = 0; i < sf.ncu * sf.ncv * 3; i++) {
			rest[i] = dg_range(d, -MOT_Q32_INT(10), MOT_Q32_INT(10));
			curve[i] = i % 3 == 1 ? (int32_t)(i % 4) : -1;
		}
		s.sys.kind = MOT_SYS_SURFACE;
		s.sys.surface = &sf;
		dg_sys_run(d, &s, NULL, 0);
	}
}

static void wl_sys_particles(struct dg *d)
{
	static const mot_q32 lattice[16][3] = {
		{ 0, 0, 0 }, { 1LL << 31, 0, 0 }, { 2LL << 31, 0, 0 }, { 3LL << 31, 0, 0 },
		{ 0, 0, 1LL << 31 }, { 1LL << 31, 0, 1LL << 31 }, { 2LL << 31, 0, 1LL << 31 },
		{ 3LL << 31, 0, 1LL << 31 }, { 0, 0, 2LL << 31 }, { 1LL << 31, 0, 2LL << 31 },
		{ 2LL << 31, 0, 2LL << 31 }, { 3LL << 31, 0, 2LL << 31 }, { 0, 0, 3LL << 31 },
		{ 1LL << 31, 0, 3LL << 31 }, { 2LL << 31, 0, 3LL << 31 }, { 3LL << 31, 0, 3LL << 31 },
	};
	struct mot_spring springs[24];
	struct mot_pin pins[2] = { { 0, { -1, 0, -1 } }, { 3, { -1, -1, -1 } } };
	int variant;

	for (variant = 0; variant < 3; variant++) {
		struct dg_sys s;
		struct mot_particles ps;
		uint32_t i, ns = 0;
		int k;

		memset(&s, 0, sizeof(s));
		mot_timing_init(&s.t, 25, 1, 1000);
		memset(&ps, 0, sizeof(ps));
		for (k = 0; k < MOT_PC_COUNT; k++) {
			ps.curve[k] = -1;
			ps.value[k] = dg_range(d, -MOT_Q32_INT(2), MOT_Q32_INT(2));
		}
		dg_sys_curve(d, &s, 0, MOT_INTERP_HERMITE, MOT_Q32_ONE / 4);
		dg_sys_curve(d, &s, 1, MOT_INTERP_LINEAR, MOT_Q32_INT(1));
		dg_sys_curve(d, &s, 2, MOT_INTERP_STEP, MOT_Q32_INT(200));
		dg_sys_curve(d, &s, 3, MOT_INTERP_BSPLINE, MOT_Q32_ONE);
		ps.seed = dg_u64(d);
		ps.gravity[1] = -dg_range(d, MOT_Q32_INT(5), MOT_Q32_INT(10));
		if (variant < 2) {
			/* a fountain: scripted, then Newtonian with every force */
			ps.motion = variant ? MOT_PARTICLES_NEWTON : MOT_PARTICLES_SCRIPTED;
			ps.npool = 48;
			ps.emit = true;
			ps.curve[MOT_PC_RATE] = 2;
			ps.value[MOT_PC_SPREAD] = MOT_Q32_INT(30);
			ps.value[MOT_PC_LIFE_LO] = MOT_Q32_ONE / 2;
			ps.value[MOT_PC_LIFE_HI] = MOT_Q32_INT(2);
			ps.value[MOT_PC_VEL_LO + 1] = MOT_Q32_INT(3);
			ps.value[MOT_PC_VEL_HI + 1] = MOT_Q32_INT(6);
			ps.curve[MOT_PC_AGE_ALPHA] = 3;
			ps.drag = variant ? MOT_Q32_ONE / 5 : 0;
			ps.ground = variant;
			ps.restitution = MOT_Q32_ONE / 2;
			ps.pair_radius = variant ? MOT_Q32_ONE / 3 : 0;
			ps.pair_strength = MOT_Q32_INT(3);
		} else {
			/* a 4 x 4 cloth, two corners pinned, one waved */
			ps.motion = MOT_PARTICLES_NEWTON;
			ps.npool = 16;
			ps.rest = lattice;
			for (i = 0; i < 16; i++) {
				if (i % 4 < 3)
					springs[ns++] = (struct mot_spring){ i, i + 1, MOT_Q32_ONE / 2 };
				if (i < 12)
					springs[ns++] = (struct mot_spring){ i, i + 4, MOT_Q32_ONE / 2 };
			}
			ps.springs = springs;
			ps.nsprings = ns;
			ps.pins = pins;
			ps.npins = 2;
			ps.spring_k = MOT_Q32_INT(300);
			ps.spring_c = MOT_Q32_ONE;
			ps.drag = MOT_Q32_ONE / 10;
		}
		s.sys.kind = MOT_SYS_PARTICLES;
		s.sys.particles = &ps;
		dg_sys_run(d, &s, &ps.steps, mot_particles_state_bytes(ps.npool));
		dg_put(d, (uint64_t)ps.dropped);
		dg_put(d, (uint64_t)ps.first_drop);
		dg_put(d, (uint64_t)ps.peak);
	}
}

static void wl_sys_flock(struct dg *d)
{
	struct mot_obstacle obst[2];
	struct dg_sys s;
	struct mot_flock f;
	int k;

	memset(&s, 0, sizeof(s));
	mot_timing_init(&s.t, 25, 1, 1000);
	memset(&f, 0, sizeof(f));
	dg_sys_curve(d, &s, 0, MOT_INTERP_HERMITE, MOT_Q32_INT(8));
	dg_sys_curve(d, &s, 1, MOT_INTERP_LINEAR, MOT_Q32_INT(3));
	dg_sys_curve(d, &s, 2, MOT_INTERP_BEZIER, MOT_Q32_INT(8));
	f.n = 60;
	f.seed = dg_u64(d);
	f.start_r = MOT_Q32_INT(4);
	f.start_v[0] = MOT_Q32_ONE;
	f.start_dv = MOT_Q32_ONE / 2;
	f.radius = MOT_Q32_INT(2);
	f.sep = MOT_Q32_ONE * 3 / 4;
	f.max_neighbours = 8;
	f.w_sep = MOT_Q32_INT(6);
	f.w_coh = MOT_Q32_INT(1);
	f.w_ali = MOT_Q32_INT(2);
	f.w_goal = MOT_Q32_INT(2);
	f.w_obst = MOT_Q32_INT(10);
	f.goal = MOT_FLOCK_GOAL_POINT;
	for (k = 0; k < 3; k++) {
		f.goal_ch[k] = k;
		obst[0].c[k] = dg_range(d, -MOT_Q32_INT(3), MOT_Q32_INT(3));
		obst[1].c[k] = dg_range(d, -MOT_Q32_INT(3), MOT_Q32_INT(3));
	}
	obst[0].r = MOT_Q32_ONE;
	obst[1].r = MOT_Q32_ONE / 2;
	f.obst = obst;
	f.nobst = 2;
	f.margin = MOT_Q32_ONE;
	f.vmax = MOT_Q32_INT(3);
	f.amax = MOT_Q32_INT(5);
	s.sys.kind = MOT_SYS_FLOCK;
	s.sys.flock = &f;
	dg_sys_run(d, &s, &f.steps, mot_flock_state_bytes(f.n));
}

static void wl_rng(struct dg *d)
{
	struct mot_rng r;
	long i;

	mot_rng_seed(&r, dg_u64(d));
	for (i = 0; i < 100000; i++) {
		dg_put(d, mot_rng_u64(&r));
		dg_put(d, (uint64_t)mot_rng_sym(&r));
	}
}

/* ---- the list -------------------------------------------------------------- */

struct workload {
	const char *name;
	void (*run)(struct dg *d);
};

static const struct workload workloads[] = {
	{ "fix_mul", wl_fix_mul },
	{ "fix_acc", wl_fix_acc },
	{ "fix_udiv", wl_fix_udiv },
	{ "fix_div", wl_fix_div },
	{ "fix_recip", wl_fix_recip },
	{ "trig", wl_trig },
	{ "ease", wl_ease },
	{ "mat", wl_mat },
	{ "quat", wl_quat },
	{ "decomp", wl_decomp },
	{ "curve", wl_curve },
	{ "curve_keys", wl_curve_keys },
	{ "scene_arm", wl_scene_arm },
	{ "scene_random", wl_scene_random },
	{ "rng", wl_rng },
	{ "sys_surface", wl_sys_surface },
	{ "sys_particles", wl_sys_particles },
	{ "sys_flock", wl_sys_flock },
};

int main(int argc, char **argv)
{
	bool verbose = argc > 1 && strcmp(argv[1], "-v") == 0;
	struct dg all = { FNV_OFFSET, 0, 0 };
	size_t i, k;

	for (i = 0; i < ARRAY_SIZE(workloads); i++) {
		const char *name = workloads[i].name;
		struct dg d = { FNV_OFFSET, 0, FNV_OFFSET };

		for (k = 0; name[k]; k++)
			d.rng = (d.rng ^ (uint8_t)name[k]) * FNV_PRIME;
		workloads[i].run(&d);
		dg_put(&all, d.h);
		dg_put(&all, d.n);
		if (verbose)
			printf("workload %-10s %016" PRIx64 " %10" PRIu64 " values\n", name, d.h, d.n);
	}
	printf("DIGEST %016" PRIx64 "\n", all.h);
	return 0;
}
