/* SPDX-License-Identifier: MIT */
/*
 * scene_desc.c - the range check shared by the loader and the builder: what
 * a number of the user's must satisfy to become a Q32.32 of the core. Kept
 * apart from scene_build.c so that the loader (and its tests) can use it
 * without linking the core.
 */
#include "scene_desc.h"

#include <math.h>

bool sd_to_q32(double v, mot_q32 *out)
{
	/* |v| < 2^30 keeps sums of a few terms inside Q32.32 (fix.h) */
	if (!isfinite(v) || fabs(v) >= 1073741824.0)
		return false;
	*out = (mot_q32)llround(v * 4294967296.0);
	return true;
}

bool sd_deg_to_turns(double deg, mot_q32 *out)
{
	return sd_to_q32(deg / 360.0, out);
}
