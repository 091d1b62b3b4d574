/* SPDX-License-Identifier: MIT */
/* timecode.c - SMPTE timecode (see timecode.h). */
#include "timecode.h"

#include <errno.h>
#include <stdio.h>

#include "hal/rt.h"

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

int64_t STRAND_RT timecode_frame(const struct timecode *tc, uint32_t hh, uint32_t mm, uint32_t ss,
		       uint32_t ff)
{
	int64_t fps = tc->nominal, d = tc->drop, mins = (int64_t)hh * 60 + mm;

	if (hh > 23 || mm > 59 || ss > 59 || ff >= fps)
		return -1;
	if (d && ss == 0 && ff < d && mm % 10)
		return -1; /* skipped */
	/* every label, less those skipped in the minutes before this one
	 * (d in each minute that is not a tenth) */
	return ((mins * 60 + ss) * fps + ff) - d * (mins - mins / 10);
}

int64_t timecode_day(const struct timecode *tc)
{
	return (int64_t)tc->nominal * 86400 - (int64_t)tc->drop * (1440 - 144);
}

int timecode_parse(const struct timecode *tc, const char *s, int64_t *frame)
{
	unsigned hh, mm, ss, ff;
	char sep, end;

	if (sscanf(s, "%2u:%2u:%2u%c%2u%c", &hh, &mm, &ss, &sep, &ff, &end) != 5 ||
	    (sep != ':' && sep != ';' && sep != '.'))
		return -EINVAL;
	*frame = timecode_frame(tc, hh, mm, ss, ff);
	return *frame < 0 ? -EINVAL : 0;
}
