/* SPDX-License-Identifier: MIT */
/*
 * fixmath_chain.c - how far libfixmath's Q16.16 lands from double on the
 * forward kinematics of a 5-joint revolute chain: the measurement behind
 * fix.h's choice of Q32.32 (the goal is 1 um and 1e-6 rad over +-100 m).
 *
 * The chain: joint i turns about z (i even) or y (i odd) by a random angle
 * in [-pi, pi], then a link runs along the joint's x axis. Link lengths are
 * random in [0.3, 0.9] m, then all scaled by one factor per pose so that
 * the reach (their sum) is uniform in [1, 100] m. With column vectors,
 *     R_i = R_(i-1) . Rot_axis(i)(theta_i),   p_i = p_(i-1) + R_i . (L_i, 0, 0)
 *
 * The Q16.16 chain gets the angles and lengths rounded to Q16.16
 * (fix16_from_dbl) and computes with fix16_sin, fix16_cos, fix16_mul and
 * fix16_add, as a libfixmath user would. The reference is the same chain in
 * double with libm.
 *
 * Prints, over N_POSES random poses, the worst
 *   BENCH libfixmath_chain_pos_err <m> m       |p_fix - p_ref| at the tip
 *   BENCH libfixmath_chain_rot_err <r> rad     largest angle between an axis
 *                                              of the tip frame and its
 *                                              reference
 *   BENCH libfixmath_chain_pos_err_reach2m     the same, poses reaching <= 2 m
 *   BENCH libfixmath_sincos_err                |fix16_sin - sin|, |fix16_cos - cos|
 * and, to separate the format from the library, the chain computed with
 * correctly rounded Q16.16 sines and cosines instead of fix16_sin/cos:
 *   BENCH q16_exact_trig_chain_{pos,rot}_err        against the exact inputs
 *   BENCH q16_exact_trig_chain_{pos,rot}_err_arith  against a reference fed the
 *                                                   rounded inputs: what the
 *                                                   products alone add
 *
 * Seen with Debian 12's libfixmath (0~20220222): fix16_sin is a Taylor
 * series whose x^11 term overflows Q16.16 once |x| > 2.58 rad (x^11 >
 * 32768), so its error jumps from ~2e-5 to ~8e-3 near +-pi, and that
 * dominates the chain's error.
 */
#define _XOPEN_SOURCE 700 /* erand48 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <libfixmath/fix16.h>

#define N_POSES 200000
#define N_JOINTS 5

/* The tip of the chain: rotation as three columns (the frame's axes) and
 * position. */
struct tip_dbl {
	double col[3][3];
	double p[3];
};

struct tip_fix {
	fix16_t col[3][3];
	fix16_t p[3];
};

/* Columns a, b of R become those of R . Rot(theta), for the rotation that
 * turns a toward b: a' = a cos + b sin, b' = b cos - a sin. About z that is
 * (a, b) = (x, y); about y it is (z, x). */
static void turn_dbl(double a[3], double b[3], double c, double s)
{
	int k;

	for (k = 0; k < 3; k++) {
		double ak = a[k];

		a[k] = ak * c + b[k] * s;
		b[k] = b[k] * c - ak * s;
	}
}

static void turn_fix(fix16_t a[3], fix16_t b[3], fix16_t c, fix16_t s)
{
	int k;

	for (k = 0; k < 3; k++) {
		fix16_t ak = a[k];

		a[k] = fix16_add(fix16_mul(ak, c), fix16_mul(b[k], s));
		b[k] = fix16_sub(fix16_mul(b[k], c), fix16_mul(ak, s));
	}
}

static void chain_dbl(struct tip_dbl *t, const double theta[N_JOINTS], const double len[N_JOINTS])
{
	int i, k;

	for (i = 0; i < 3; i++)
		for (k = 0; k < 3; k++)
			t->col[i][k] = i == k;
	t->p[0] = t->p[1] = t->p[2] = 0;
	for (i = 0; i < N_JOINTS; i++) {
		if (i % 2 == 0)
			turn_dbl(t->col[0], t->col[1], cos(theta[i]), sin(theta[i]));
		else
			turn_dbl(t->col[2], t->col[0], cos(theta[i]), sin(theta[i]));
		for (k = 0; k < 3; k++)
			t->p[k] += t->col[0][k] * len[i];
	}
}

/* The Q16.16 chain, given the cosines and sines of its joint angles. */
static void chain_fix(struct tip_fix *t, const fix16_t c[N_JOINTS], const fix16_t s[N_JOINTS],
		      const fix16_t len[N_JOINTS])
{
	int i, k;

	for (i = 0; i < 3; i++)
		for (k = 0; k < 3; k++)
			t->col[i][k] = i == k ? fix16_one : 0;
	t->p[0] = t->p[1] = t->p[2] = 0;
	for (i = 0; i < N_JOINTS; i++) {
		if (i % 2 == 0)
			turn_fix(t->col[0], t->col[1], c[i], s[i]);
		else
			turn_fix(t->col[2], t->col[0], c[i], s[i]);
		for (k = 0; k < 3; k++)
			t->p[k] = fix16_add(t->p[k], fix16_mul(t->col[0][k], len[i]));
	}
}

static double pos_err(const struct tip_fix *f, const struct tip_dbl *r)
{
	double dx = fix16_to_dbl(f->p[0]) - r->p[0];
	double dy = fix16_to_dbl(f->p[1]) - r->p[1];
	double dz = fix16_to_dbl(f->p[2]) - r->p[2];

	return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Largest angle between an axis of f and the same axis of r:
 * atan2(|a x b|, a . b), good at small angles, and meaningful when rounding
 * has left f not quite orthonormal. */
static double rot_err(const struct tip_fix *f, const struct tip_dbl *r)
{
	double worst = 0;
	int i;

	for (i = 0; i < 3; i++) {
		const double *b = r->col[i];
		double a[3] = { fix16_to_dbl(f->col[i][0]), fix16_to_dbl(f->col[i][1]),
				fix16_to_dbl(f->col[i][2]) };
		double cx = a[1] * b[2] - a[2] * b[1];
		double cy = a[2] * b[0] - a[0] * b[2];
		double cz = a[0] * b[1] - a[1] * b[0];
		double ang = atan2(sqrt(cx * cx + cy * cy + cz * cz),
				   a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);

		if (ang > worst)
			worst = ang;
	}
	return worst;
}

static void worst(double *w, double e)
{
	if (e > *w || isnan(e))
		*w = e;
}

int main(void)
{
	unsigned short seed[3] = { 0x5eed, 0x1234, 0xabcd };
	double pos = 0, rot = 0, pos_2m = 0, trig = 0, pos_x = 0, rot_x = 0, pos_xq = 0, rot_xq = 0;
	long n;

	for (n = 0; n < N_POSES; n++) {
		double theta[N_JOINTS], len[N_JOINTS], theta_q[N_JOINTS], len_q[N_JOINTS];
		fix16_t len_f[N_JOINTS], c[N_JOINTS], s[N_JOINTS], cx[N_JOINTS], sx[N_JOINTS];
		double sum = 0, reach = 1 + 99 * erand48(seed);
		struct tip_dbl ref, ref_q;
		struct tip_fix fix, fix_x;
		int i;

		for (i = 0; i < N_JOINTS; i++) {
			theta[i] = M_PI * (2 * erand48(seed) - 1);
			len[i] = 0.3 + 0.6 * erand48(seed);
			sum += len[i];
		}
		for (i = 0; i < N_JOINTS; i++) {
			fix16_t theta_f = fix16_from_dbl(theta[i]);

			len[i] *= reach / sum;
			len_f[i] = fix16_from_dbl(len[i]);
			theta_q[i] = fix16_to_dbl(theta_f);
			len_q[i] = fix16_to_dbl(len_f[i]);
			c[i] = fix16_cos(theta_f);
			s[i] = fix16_sin(theta_f);
			cx[i] = fix16_from_dbl(cos(theta_q[i]));
			sx[i] = fix16_from_dbl(sin(theta_q[i]));
			worst(&trig, fabs(fix16_to_dbl(c[i]) - cos(theta_q[i])));
			worst(&trig, fabs(fix16_to_dbl(s[i]) - sin(theta_q[i])));
		}
		chain_fix(&fix, c, s, len_f);
		chain_fix(&fix_x, cx, sx, len_f);
		chain_dbl(&ref, theta, len);
		chain_dbl(&ref_q, theta_q, len_q);
		worst(&pos, pos_err(&fix, &ref));
		worst(&rot, rot_err(&fix, &ref));
		if (reach <= 2)
			worst(&pos_2m, pos_err(&fix, &ref));
		worst(&pos_x, pos_err(&fix_x, &ref));
		worst(&rot_x, rot_err(&fix_x, &ref));
		worst(&pos_xq, pos_err(&fix_x, &ref_q));
		worst(&rot_xq, rot_err(&fix_x, &ref_q));
	}
	printf("BENCH libfixmath_chain_pos_err %.3g m\n", pos);
	printf("BENCH libfixmath_chain_rot_err %.3g rad\n", rot);
	printf("BENCH libfixmath_chain_pos_err_reach2m %.3g m\n", pos_2m);
	printf("BENCH libfixmath_sincos_err %.3g\n", trig);
	printf("BENCH q16_exact_trig_chain_pos_err %.3g m\n", pos_x);
	printf("BENCH q16_exact_trig_chain_rot_err %.3g rad\n", rot_x);
	printf("BENCH q16_exact_trig_chain_pos_err_arith %.3g m\n", pos_xq);
	printf("BENCH q16_exact_trig_chain_rot_err_arith %.3g rad\n", rot_xq);
	printf("BENCH libfixmath_chain_poses %d (%d joints, reach 1 to 100 m)\n", N_POSES,
	       N_JOINTS);
	return 0;
}
