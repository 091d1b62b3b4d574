/* SPDX-License-Identifier: MIT */
/* source_path.c - straight lines between poses (see source_path.h). */
#include "source_path.h"

#include <errno.h>
#include <string.h>

#include "hal/rt.h"

static int path_lookup(struct play_source *s, const char *name, struct src_channel *info)
{
	struct source_path *p = (struct source_path *)s;
	uint32_t i;

	for (i = 0; i < p->n; i++)
		if (!strcmp(p->names[i], name)) {
			memset(info, 0, sizeof(*info));
			info->unit = p->units[i];
			return (int)i;
		}
	return -ENOENT;
}

static int path_select(struct play_source *s, const uint32_t *idx, uint32_t n)
{
	struct source_path *p = (struct source_path *)s;
	uint32_t i;

	if (n > p->n)
		return -EINVAL;
	for (i = 0; i < n; i++)
		if (idx[i] >= p->n)
			return -EINVAL;
	memcpy(p->sel, idx, n * sizeof(*idx));
	p->nsel = n;
	return 0;
}

static void STRAND_RT path_eval(struct play_source *s, mot_q32 frame, mot_q32 *out, uint32_t *sat)
{
	struct source_path *p = (struct source_path *)s;
	int64_t last = (int64_t)p->nkeys - 1, k;
	mot_q32 rel;
	uint32_t i;

	/* frames are below 2^31 (a journal's shot count): no overflow */
	rel = mot_sub_sat(frame, s->frame_first * MOT_Q32_ONE, sat);
	if (rel <= 0 || last <= 0) {
		for (i = 0; i < p->nsel; i++)
			out[i] = p->keys[0][p->sel[i]];
		return;
	}
	k = rel >> 32;
	if (k >= last) {
		for (i = 0; i < p->nsel; i++)
			out[i] = p->keys[last][p->sel[i]];
		return;
	}
	for (i = 0; i < p->nsel; i++) {
		mot_q32 a = p->keys[k][p->sel[i]], b = p->keys[k + 1][p->sel[i]];

		out[i] = mot_add_sat(a, mot_mul(mot_sub_sat(b, a, sat), rel & 0xffffffff, sat),
				     sat);
	}
}

static const struct play_source_ops path_ops = {
	.lookup = path_lookup,
	.select = path_select,
	.eval = path_eval,
};

int source_path_init(struct source_path *p, const char *name, uint32_t n,
		     const char *const *names, const enum src_unit *units, uint32_t num,
		     uint32_t den, uint32_t tick_hz, int64_t first, uint32_t nkeys)
{
	uint32_t i;

	memset(p, 0, sizeof(*p));
	if (n > SOURCE_PATH_CH_MAX || !nkeys || nkeys > SOURCE_PATH_KEYS_MAX ||
	    mot_timing_init(&p->s.timing, num, den, tick_hz))
		return -EINVAL;
	p->s.ops = &path_ops;
	p->s.name = name;
	p->s.frame_first = first;
	p->s.frame_last = first + nkeys - 1;
	p->n = n;
	p->names = names;
	p->units = units;
	p->nkeys = nkeys;
	for (i = 0; i < n; i++)
		p->sel[i] = i;
	p->nsel = n;
	return 0;
}
