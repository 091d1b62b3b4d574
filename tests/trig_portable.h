/* SPDX-License-Identifier: MIT */
/* trig_portable.h - trig.c compiled with MOT_NO_INT128 (the path armhf and
 * Cortex-M take), callable from a test built with __int128. */
#ifndef TRIG_PORTABLE_H
#define TRIG_PORTABLE_H

#include <stdint.h>

void trigp_sincos(int64_t turns, int64_t *s, int64_t *c);
void trigp_sincos64(uint64_t phase, int64_t *s, int64_t *c);
int64_t trigp_atan2(int64_t y, int64_t x);
int64_t trigp_atan2_unit_q62(int64_t y, int64_t x);
int64_t trigp_acos(int64_t x, uint32_t *sat);
int64_t trigp_sqrt(int64_t x, uint32_t *sat);
int64_t trigp_rsqrt(int64_t x, uint32_t *sat);
uint64_t trigp_isqrt(uint64_t hi, uint64_t lo, uint32_t *sat);
int64_t trigp_norm3(const int64_t v[3], uint32_t *sat);

#endif
