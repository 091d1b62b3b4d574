/* SPDX-License-Identifier: MIT */
/* fix_portable.h - fix.h's operations compiled with MOT_NO_INT128 (the path
 * armhf and Cortex-M take), callable from a test built with __int128. */
#ifndef FIX_PORTABLE_H
#define FIX_PORTABLE_H

#include <stdint.h>

void fixp_mul(int64_t a, int64_t b, uint64_t *hi, uint64_t *lo);
int64_t fixp_round(int64_t a, int64_t b, unsigned shift, uint32_t *sat);
uint64_t fixp_udiv(uint64_t hi, uint64_t lo, uint64_t d, uint64_t *rem);
/* mot_udiv_inv_init() then mot_udiv_by_inv() (hi < d) */
uint64_t fixp_udiv_by_inv(uint64_t hi, uint64_t lo, uint64_t d, uint64_t *rem);
int64_t fixp_muldiv(int64_t a, int64_t m, int64_t d);
int64_t fixp_sum3_ov(const int64_t a[3], const int64_t b[3], int64_t c, unsigned shift,
		     uint64_t *ov);

#endif
