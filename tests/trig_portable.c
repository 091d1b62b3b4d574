/* SPDX-License-Identifier: MIT */
/* trig_portable.c - see trig_portable.h. A private copy of trig.c on fix.h's
 * portable two-word path. */
#define MOT_NO_INT128 1
#define mot_sincos trigp_sincos
#define mot_sincos_pair trigp_sincos_pair_
#define mot_sincos64 trigp_sincos64_
#define mot_sin trigp_sin_
#define mot_cos trigp_cos_
#define mot_atan2 trigp_atan2
#define mot_atan2_unit_q62 trigp_atan2_unit_q62
#define mot_acos trigp_acos
#define mot_sqrt trigp_sqrt
#define mot_rsqrt trigp_rsqrt
#define mot_isqrt_acc trigp_isqrt_acc_
#define mot_isqrt_acc_inv trigp_isqrt_acc_inv_
#define mot_isqrt_acc_inv_near trigp_isqrt_acc_inv_near_
#define mot_norm3 trigp_norm3
#include "motion/trig.c"
#include "trig_portable.h"

uint64_t trigp_isqrt(uint64_t hi, uint64_t lo, uint32_t *sat)
{
	return trigp_isqrt_acc_(mot_acc_make(hi, lo), sat);
}

void trigp_sincos64(uint64_t phase, int64_t *s, int64_t *c)
{
	struct mot_sc r = trigp_sincos64_(phase);

	*s = r.s;
	*c = r.c;
}
