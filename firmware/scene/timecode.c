/* SPDX-License-Identifier: MIT */
/* timecode.c - SMPTE timecode (see timecode.h). */
#include "timecode.h"

#include <stdio.h>

void timecode_init(struct timecode *tc, uint32_t num, uint32_t den)
{
	uint64_t nominal = ((uint64_t)num + den / 2) / den;

	tc->nominal = nominal ? (uint32_t)nominal : 1;
	tc->drop = 0;
	if (den == 1001 && (num == 30000 || num == 60000))
		tc->drop = num / 15000; /* 2 at 29.97, 4 at 59.94 */
}

void timecode_format(const struct timecode *tc, int64_t f, char *buf, unsigned size)
{
	uint64_t n, fps = tc->nominal, day = fps * 86400;
	const char *sign = "";

	if (f < 0) {
		sign = "-";
		n = (uint64_t)-(f + 1) + 1;
	} else {
		n = (uint64_t)f;
	}
	if (tc->drop) {
		/* Frames in ten minutes and in a minute that drops labels; add
		 * back the labels skipped before frame n (the standard
		 * conversion, e.g. SMPTE RP 201 / Wikipedia "SMPTE timecode"). */
		uint64_t d = tc->drop, per_min = fps * 60 - d, per_10 = fps * 600 - 9 * d;
		uint64_t tens = n / per_10, rem = n % per_10;

		n += 9 * d * tens;
		if (rem > d)
			n += d * ((rem - d) / per_min);
	}
	n %= day; /* labels in a day, the dropped ones included */
	snprintf(buf, size, "%s%02u:%02u:%02u%c%02u", sign, (unsigned)(n / (fps * 3600)),
		 (unsigned)(n / (fps * 60) % 60), (unsigned)(n / fps % 60), tc->drop ? ';' : ':',
		 (unsigned)(n % fps));
}
