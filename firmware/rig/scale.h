/* SPDX-License-Identifier: MIT */
/*
 * scale.h - scene units to device counts, per output channel.
 *
 * The loop's setpoints are the core's Q32.32 values in core units (turns for
 * angles, the scene's unit for lengths, rpm for spin speeds). A channel's
 * scale is counts per core unit (a scene file says counts per degree or per
 * unit; the rig converts once) and an offset in counts:
 *
 *     counts = round(value * per_unit) + offset
 *
 * computed exactly in 128 bits: a setpoint is the same count on every
 * machine and at every hour of a run. per_unit is Q32.32, so a scale has
 * 2^-32 count resolution and may be up to 2^31 counts per unit (a 23-bit
 * encoder behind a 100:1 gear is 2^29.6 counts per turn). Feedback goes the
 * other way only for diagnosis (following error), in double precision.
 *
 * Everything here is [rt].
 */
#ifndef HAL_SCALE_H
#define HAL_SCALE_H

#include <stdint.h>

#include "motion/fix.h"
#include "hal/rt.h"
#include "scene/num.h"

struct hal_scale {
	mot_q32 per_unit; /* counts per core unit, Q32.32, non-zero */
	int64_t offset;   /* counts at value 0 */
	double per_unit_d; /* the same as a double, for diagnosis */
};

/* Device counts of a core value; saturation is ORed into *sat. */
static inline int64_t STRAND_RT hal_scale_counts(const struct hal_scale *s, mot_q32 value, uint32_t *sat)
{
	return mot_add_sat(mot_acc_round(mot_acc_mul(value, s->per_unit), 64, sat), s->offset,
			   sat);
}

/* Counts per second of a speed in core units per second, rounded to
 * nearest; beyond int64_t it saturates and NaN gives 0, either ORed into
 * *sat as hal_scale_counts does. */
static inline int64_t STRAND_RT hal_scale_rate(const struct hal_scale *s, double units_per_s,
					       uint32_t *sat)
{
	return num_sat_i64(units_per_s * s->per_unit_d, INT64_MIN, INT64_MAX, sat);
}

/* A count difference (setpoint minus actual) in core units. */
static inline double STRAND_RT hal_scale_delta_units(const struct hal_scale *s, int64_t dcounts)
{
	return (double)dcounts / s->per_unit_d;
}

#endif /* HAL_SCALE_H */
