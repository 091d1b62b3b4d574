/* SPDX-License-Identifier: MIT */
/* curve_portable.c - see curve_portable.h. */
#define MOT_NO_INT128 1
#define mot_acc_udiv cvp_acc_udiv_
#define mot_floordiv cvp_floordiv_
#define mot_muldiv cvp_muldiv_
#define mot_div cvp_div_
#define mot_recip_init cvp_recip_init_
#define mot_udiv_inv_init cvp_udiv_inv_init_
#define mot_sum_prod_wide cvp_sum_prod_wide_
#define mot_ease_init cvp_ease_init_
#define mot_ease_init_ratio cvp_ease_init_ratio_
#define mot_ease_apply cvp_ease_apply_
#define mot_ease_apply62 cvp_ease_apply62_
#define mot_ease_fused_init cvp_ease_fused_init_
#define mot_ease_span_init cvp_ease_span_init_
#define mot_curve_seg_count cvp_curve_seg_count_
#define mot_curve_init cvp_curve_init_
#define mot_curve_eval cvp_curve_eval_
#define mot_curve_integral cvp_curve_integral_
#define mot_curve_newton_iterations cvp_curve_newton_iterations_
#define mot_curve_bound cvp_curve_bound_
/* what the curve files share (motion/curve_priv.h) */
#define mot_cv_acc_sar cvp_cv_acc_sar_
#define mot_cv_acc_bitlen cvp_cv_acc_bitlen_
#define mot_cv_acc_round_shift cvp_cv_acc_round_shift_
#define mot_cv_acc_div_round cvp_cv_acc_div_round_
#define mot_cv_poly_prep cvp_cv_poly_prep_
#define mot_cv_poly_prep_pow cvp_cv_poly_prep_pow_
#define mot_cv_div_pow_round cvp_cv_div_pow_round_
#define mot_cv_locate cvp_cv_locate_
#define mot_cv_prep_interp cvp_cv_prep_interp_
#define mot_cv_prep_spline cvp_cv_prep_spline_
#define mot_cv_prep_bezier cvp_cv_prep_bezier_
#define mot_cv_prep_area cvp_cv_prep_area_
#define mot_cv_approx_eval cvp_cv_approx_eval_
#define mot_cv_eval_plain cvp_cv_eval_plain_
#define mot_cv_bezier_start cvp_cv_bezier_start_
#define mot_cv_tab_node cvp_cv_tab_node_
#define mot_cv_tab_fit cvp_cv_tab_fit_
#include "curve_portable.h"
#include "motion/curve.c"
#include "motion/curve_poly.c"
#include "motion/curve_locate.c"
#include "motion/curve_interp.c"
#include "motion/curve_integral.c"
#include "motion/curve_approx.c"
#include "motion/curve_solve.c"
#include "motion/curve_bezier.c"
#include "motion/ease.c"
#include "motion/fix.c"

#define CVP_MAXSEG 64

int cvp_eval(int kind, const struct mot_key *keys, uint32_t n, const struct mot_curve_opts *opts,
	     const int64_t *frames, int64_t *out, size_t m)
{
	struct mot_curve_seg seg[CVP_MAXSEG];
	struct mot_curve c;
	size_t i;
	int err = mot_curve_init(&c, (enum mot_interp)kind, keys, n, opts, seg, CVP_MAXSEG, NULL);

	for (i = 0; i < m && !err; i++)
		out[i] = mot_curve_eval(&c, NULL, frames[i], NULL);
	return err;
}

int cvp_integral(int kind, const struct mot_key *keys, uint32_t n, const int64_t *frames,
		 uint64_t *hi, uint64_t *lo, size_t m)
{
	struct mot_curve_opts o = { .integral = true };
	struct mot_curve_seg seg[CVP_MAXSEG];
	struct mot_curve c;
	size_t i;
	int err = mot_curve_init(&c, (enum mot_interp)kind, keys, n, &o, seg, CVP_MAXSEG, NULL);

	for (i = 0; i < m && !err; i++) {
		mot_acc a;

		err = mot_curve_integral(&a, &c, NULL, frames[i], NULL);
		hi[i] = mot_acc_hi(a);
		lo[i] = mot_acc_lo(a);
	}
	return err;
}
