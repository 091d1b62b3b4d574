/* SPDX-License-Identifier: MIT */
/* pass.c - the frames and scene ticks of a pass (see pass.h). */
#include "pass.h"

void STRAND_RT pass_span(struct pass_span *s, const struct mot_timing *t, int64_t from,
			 int64_t to, bool ping_pong, int64_t p, int64_t lead, int64_t tail)
{
	s->dir = 1;
	s->first = from;
	s->last = to;
	if (ping_pong && to > from) {
		if (p % 2) {
			s->dir = -1;
			s->first = to - 1;
			s->last = from;
		} else if (p > 0) {
			s->first = from + 1;
		}
	}
	s->lo = s->dir > 0 ? s->first : s->last;
	s->hi = s->dir > 0 ? s->last : s->first;
	s->begin = mot_timing_trigger_tick(t, s->first) - s->dir * lead;
	s->end = mot_timing_trigger_tick(t, s->last) + s->dir * tail;
}
