/* SPDX-License-Identifier: MIT */
/* fix_portable.c - see fix_portable.h. The portable path of fix.h and a
 * private copy of fix.c, both without __int128. */
#define MOT_NO_INT128 1
#define mot_acc_udiv fixp_acc_udiv_
#define mot_floordiv fixp_floordiv_
#define mot_muldiv fixp_muldiv_
#define mot_div fixp_div_
#define mot_recip_init fixp_recip_init_
#define mot_udiv_inv_init fixp_udiv_inv_init_
#define mot_sum_prod_wide fixp_sum_prod_wide_
#include "fix_portable.h"
#include "motion/fix.c"

void fixp_mul(int64_t a, int64_t b, uint64_t *hi, uint64_t *lo)
{
	mot_acc p = mot_acc_mul(a, b);

	*hi = mot_acc_hi(p);
	*lo = mot_acc_lo(p);
}

int64_t fixp_round(int64_t a, int64_t b, unsigned shift, uint32_t *sat)
{
	return mot_acc_round(mot_acc_mul(a, b), shift, sat);
}

uint64_t fixp_udiv(uint64_t hi, uint64_t lo, uint64_t d, uint64_t *rem)
{
	return fixp_acc_udiv_(mot_acc_make(hi, lo), d, rem, NULL);
}

uint64_t fixp_udiv_by_inv(uint64_t hi, uint64_t lo, uint64_t d, uint64_t *rem)
{
	struct mot_udiv_inv in;

	fixp_udiv_inv_init_(&in, d);
	return mot_udiv_by_inv(hi, lo, &in, rem);
}

int64_t fixp_muldiv(int64_t a, int64_t m, int64_t d)
{
	return fixp_muldiv_(a, m, d, NULL);
}

int64_t fixp_sum3_ov(const int64_t a[3], const int64_t b[3], int64_t c, unsigned shift,
		     uint64_t *ov)
{
	return mot_sum3_ov(a[0], b[0], a[1], b[1], a[2], b[2], c, shift, ov);
}
