/* SPDX-License-Identifier: MIT */
/* frames.c - step mode frame lists (see frames.h). */
#include "frames.h"
#include "hal/rt.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Frame numbers as --from and --to take them, and as many shots of one:
 * the core's frames are below 2^31 (README, "Numbers"). */
#define FRAMES_NUMBER_MAX INT32_MAX

/* A non-negative decimal at *p, at most FRAMES_NUMBER_MAX (*big when it
 * is more); advances *p. */
static bool number(const char **p, int64_t *out, bool *big)
{
	const char *s = *p;
	int64_t v = 0;

	if (!isdigit((unsigned char)*s))
		return false;
	while (isdigit((unsigned char)*s)) {
		v = v * 10 + (*s++ - '0');
		if (v > FRAMES_NUMBER_MAX) {
			*big = true;
			return false;
		}
	}
	*p = s;
	*out = v;
	return true;
}

int frames_parse(struct frame_list *fl, const char *spec, char *err, unsigned errsize)
{
	const char *p = spec;
	bool big = false;
	uint32_t n = 1, i = 0;

	fl->items = NULL;
	fl->n = 0;
	for (const char *c = spec; *c; c++)
		n += *c == ',';
	fl->items = calloc(n, sizeof(*fl->items));
	if (!fl->items) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	for (;;) {
		struct frame_item *it = &fl->items[i];

		if (!number(&p, &it->first, &big))
			goto bad;
		it->last = it->first;
		it->repeat = 1;
		if (p[0] == '.' && p[1] == '.') {
			p += 2;
			if (!number(&p, &it->last, &big))
				goto bad;
		}
		if (*p == 'x') {
			p++;
			if (!number(&p, &it->repeat, &big) || it->repeat < 1)
				goto bad;
		}
		i++;
		if (*p == '\0')
			break;
		if (*p != ',')
			goto bad;
		p++;
	}
	fl->n = i;
	return 0;
bad:
	if (big)
		snprintf(err, errsize, "--frames '%s': frame numbers and repeats go up to %d, at "
			 "column %u", spec, FRAMES_NUMBER_MAX, (unsigned)(p - spec) + 1);
	else
		snprintf(err, errsize,
		 "--frames '%s': expected N, A..B or NxK items separated by commas, at column %u",
		 spec, (unsigned)(p - spec) + 1);
	frames_free(fl);
	return -EINVAL;
}

int frames_range(struct frame_list *fl, int64_t first, int64_t last)
{
	fl->items = calloc(1, sizeof(*fl->items));
	if (!fl->items)
		return -ENOMEM;
	fl->items[0].first = first;
	fl->items[0].last = last;
	fl->items[0].repeat = 1;
	fl->n = 1;
	return 0;
}

void frames_free(struct frame_list *fl)
{
	free(fl->items);
	fl->items = NULL;
	fl->n = 0;
}

int64_t STRAND_RT frames_count(const struct frame_list *fl)
{
	int64_t total = 0;
	uint32_t i;

	for (i = 0; i < fl->n; i++) {
		const struct frame_item *it = &fl->items[i];
		int64_t span = it->last >= it->first ? it->last - it->first : it->first - it->last;

		/* each term is below 2^62; only a very long list can overflow */
		if (__builtin_add_overflow(total, (span + 1) * it->repeat, &total))
			return INT64_MAX;
	}
	return total;
}

bool STRAND_RT frames_next(const struct frame_list *fl, struct frame_iter *it, int64_t *frame)
{
	const struct frame_item *c;

	if (!it->started) {
		it->started = true;
		it->item = 0;
		it->shot = 0;
		if (fl->n == 0)
			return false;
		it->frame = fl->items[0].first;
		*frame = it->frame;
		return true;
	}
	if (it->item >= fl->n)
		return false;
	c = &fl->items[it->item];
	if (++it->shot < c->repeat) {
		*frame = it->frame;
		return true;
	}
	it->shot = 0;
	if (it->frame != c->last) {
		it->frame += c->last > c->first ? 1 : -1;
		*frame = it->frame;
		return true;
	}
	if (++it->item >= fl->n)
		return false;
	it->frame = fl->items[it->item].first;
	*frame = it->frame;
	return true;
}

int64_t frames_min(const struct frame_list *fl)
{
	int64_t m = INT64_MAX;
	uint32_t i;

	for (i = 0; i < fl->n; i++) {
		const struct frame_item *it = &fl->items[i];
		int64_t lo = it->first < it->last ? it->first : it->last;

		if (lo < m)
			m = lo;
	}
	return fl->n ? m : 0;
}

int64_t frames_max(const struct frame_list *fl)
{
	int64_t m = INT64_MIN;
	uint32_t i;

	for (i = 0; i < fl->n; i++) {
		const struct frame_item *it = &fl->items[i];
		int64_t hi = it->first > it->last ? it->first : it->last;

		if (hi > m)
			m = hi;
	}
	return fl->n ? m : 0;
}
