/* SPDX-License-Identifier: MIT */
/* pulse.c - a frame pulse on an input line as an external clock (pulse.h). */
#include "pulse.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rt.h"

#define PULSE_EDGES 16

struct pulse {
	struct hal_extclk base; /* first */
	struct hal_din *din;
	uint32_t line;
	struct hal_edge edges[PULSE_EDGES];
	char name[];
};

static struct pulse STRAND_RT *to_pulse(struct hal_extclk *c)
{
	return (struct pulse *)c;
}

static int pulse_start(struct hal_extclk *c)
{
	STRAND_ASSERT_NOT_RT();
	return hal_din_start(to_pulse(c)->din);
}

static uint32_t STRAND_RT pulse_poll(struct hal_extclk *c, int64_t now, struct hal_mark *m,
				     uint32_t max)
{
	struct pulse *p = to_pulse(c);
	uint32_t i, n, want, k = 0;

	/* no more edges than marks may be taken: each may be a rising one */
	while (k < max) {
		want = max - k < PULSE_EDGES ? max - k : PULSE_EDGES;
		n = hal_din_poll(p->din, now, p->edges, want);
		for (i = 0; i < n; i++)
			if (p->edges[i].line == p->line && p->edges[i].asserted)
				m[k++] = (struct hal_mark){ .t_ns = p->edges[i].ts_ns,
							    .avail_ns = p->edges[i].ts_ns };
		if (n < want)
			break;
	}
	return k;
}

static int STRAND_RT pulse_fault(struct hal_extclk *c, struct hal_fault *f)
{
	return hal_din_fault(to_pulse(c)->din, f);
}

static int pulse_stop(struct hal_extclk *c)
{
	STRAND_ASSERT_NOT_RT();
	return hal_din_stop(to_pulse(c)->din);
}

static void pulse_close(struct hal_extclk *c)
{
	struct pulse *p = to_pulse(c);

	STRAND_ASSERT_NOT_RT();
	hal_din_close(p->din);
	free(p);
}

static const struct hal_extclk_ops pulse_ops = {
	.start = pulse_start,
	.poll = pulse_poll,
	.fault = pulse_fault,
	.stop = pulse_stop,
	.close = pulse_close,
};

int hal_pulse_open(struct hal_extclk **out, struct hal_din *din, uint32_t line, const char *name,
		   char *err, size_t errsize)
{
	size_t len = strlen(name);
	struct pulse *p;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	p = calloc(1, sizeof(*p) + len + 1);
	if (!p) {
		hal_din_close(din);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	memcpy(p->name, name, len + 1);
	p->base.ops = &pulse_ops;
	p->base.name = p->name;
	p->base.labelled = false;
	p->din = din;
	p->line = line;
	*out = &p->base;
	return 0;
}
