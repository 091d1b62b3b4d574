/* SPDX-License-Identifier: MIT */
/* load_timing.c - the `timing:` section of a scene file (FORMULAS section 5). */
#include "load_priv.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#define TICK_HZ_DEFAULT 1000
#define FRAME_LIMIT 1073741823LL /* |frame| < 2^30, as every Q32.32 input */

/* "24" or "30000/1001": digits, optionally a slash and digits. */
static int frame_rate(struct ld *l, const yaml_node_t *n, uint32_t *num, uint32_t *den)
{
	const char *s = n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value : "";
	size_t len = n && n->type == YAML_SCALAR_NODE ? n->data.scalar.length : 0;
	unsigned long long v[2] = { 0, 1 };
	size_t i = 0, part = 0, digits = 0;
	char buf[64];

	for (; i < len; i++) {
		if (s[i] >= '0' && s[i] <= '9') {
			if (v[part] > MOT_RATE_MAX)
				break;
			v[part] = v[part] * 10 + (unsigned)(s[i] - '0');
			digits++;
		} else if (s[i] == '/' && part == 0 && digits) {
			part = 1;
			v[1] = 0;
			digits = 0;
		} else {
			break;
		}
	}
	if (i != len || !digits)
		return ld_fail(l, n, -EINVAL,
			       "frame_rate must be a whole number or a ratio like \"30000/1001\", found %s",
			       ld_describe(n, buf, sizeof(buf)));
	if (v[0] == 0 || v[1] == 0)
		return ld_fail(l, n, -EINVAL, "frame rate %s must be above zero",
			       ld_describe(n, buf, sizeof(buf)));
	if (v[0] > MOT_RATE_MAX || v[1] > MOT_RATE_MAX)
		return ld_fail(l, n, -ERANGE,
			       "frame rate %s is outside the core's range (numerator and denominator up to %u)",
			       ld_describe(n, buf, sizeof(buf)), (unsigned)MOT_RATE_MAX);
	*num = (uint32_t)v[0];
	*den = (uint32_t)v[1];
	return 0;
}

int ld_timing(struct ld *l, yaml_node_t *n)
{
	static const char *const keys[] = { "tick_hz", "frame_rate", "frames", NULL };
	enum { TICK_HZ, FRAME_RATE, FRAMES };
	yaml_node_t *v[3];
	yaml_node_item_t *it;
	long long hz = TICK_HZ_DEFAULT, f[2];
	size_t count, i;
	int err;

	l->mk->timing = ld_mark_of(n);
	err = ld_map_req(l, n, "timing", keys, v, YML_REQ(FRAME_RATE) | YML_REQ(FRAMES));
	if (err)
		return err;
	if (v[TICK_HZ]) {
		err = ld_int(l, v[TICK_HZ], 1, MOT_TICK_HZ_MAX, &hz);
		if (err)
			return err;
	}
	l->d->tick_hz = (uint32_t)hz;
	err = frame_rate(l, v[FRAME_RATE], &l->d->rate_num, &l->d->rate_den);
	if (err)
		return err;
	/* at most one frame per tick, so that a tick fires at most one trigger */
	if ((uint64_t)l->d->rate_num > (uint64_t)hz * l->d->rate_den)
		return ld_fail(l, v[FRAME_RATE], -EINVAL,
			       "frame rate %u/%u is faster than tick_hz %lld (at most one frame per tick)",
			       l->d->rate_num, l->d->rate_den, hz);

	err = ld_seq(l, v[FRAMES], "frames", &it, &count);
	if (err)
		return err;
	if (count != 2)
		return ld_fail(l, v[FRAMES], -EINVAL,
			       "frames takes two whole numbers [first, last], found %zu items", count);
	for (i = 0; i < 2; i++) {
		err = ld_int(l, ld_node(l, it[i]), -FRAME_LIMIT, FRAME_LIMIT, &f[i]);
		if (err)
			return err;
	}
	if (f[1] < f[0])
		return ld_fail(l, ld_node(l, it[1]), -EINVAL,
			       "the last frame %lld is before the first frame %lld", f[1], f[0]);
	l->d->frame_first = (double)f[0];
	l->d->frame_last = (double)f[1];
	return 0;
}
