/* SPDX-License-Identifier: MIT */
/* sim_gpio.c - the simulated GPIO chip (see sim_gpio.h). */
#include "sim_gpio.h"

#include <errno.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/ring.h"
#include "hal/rt.h"

#define INJECT_CAP 64

struct sched_edge {
	int64_t at_ns;
	uint32_t line;
	bool asserted;
};

struct sim_out {
	bool active_low;
	bool staged; /* logical */
	bool level;  /* physical */
	sim_gpio_listener fn;
	void *ctx;
};

struct sim_in {
	bool active_low;
	bool asserted; /* after the edges polled */
	bool newest;   /* after every edge due by the last poll (din.h: level) */
};

struct sim_gpio {
	struct hal_dout dout; /* the HAL views, each with its ops first */
	struct hal_din din;
	struct hal_clock *clk;
	struct sim_out *out;
	struct sim_in *in;
	struct sim_gpio_edge *rec;
	uint64_t rec_cap, nedges;
	/* scheduled input edges, sorted by time; touched by one thread */
	struct sched_edge *q;
	uint32_t qlen, qcap;
	struct hal_ring inject;
	struct sched_edge inject_buf[INJECT_CAP];
};

static struct sim_gpio STRAND_RT *of_dout(struct hal_dout *d)
{
	return (struct sim_gpio *)((char *)d - offsetof(struct sim_gpio, dout));
}

static struct sim_gpio STRAND_RT *of_din(struct hal_din *d)
{
	return (struct sim_gpio *)((char *)d - offsetof(struct sim_gpio, din));
}

/* ---- outputs ---- */

static int go_start(struct hal_dout *d)
{
	struct sim_gpio *g = of_dout(d);
	uint32_t i;

	STRAND_ASSERT_NOT_RT();
	for (i = 0; i < d->nlines; i++) {
		g->out[i].staged = false;
		g->out[i].level = g->out[i].active_low;
	}
	return 0;
}

static void STRAND_RT go_set(struct hal_dout *d, uint32_t line, bool asserted)
{
	of_dout(d)->out[line].staged = asserted;
}

static int STRAND_RT go_commit(struct hal_dout *d, int64_t tick)
{
	struct sim_gpio *g = of_dout(d);
	int64_t now = 0;
	bool have_now = false;
	uint32_t i;

	for (i = 0; i < d->nlines; i++) {
		struct sim_out *o = &g->out[i];
		bool level = o->staged != o->active_low;
		struct sim_gpio_edge e;

		if (level == o->level)
			continue;
		if (!have_now) {
			now = hal_clock_now(g->clk);
			have_now = true;
		}
		o->level = level;
		e.line = i;
		e.level = level;
		e.asserted = o->staged;
		e.tick = tick;
		e.ts_ns = now;
		if (g->nedges < g->rec_cap)
			g->rec[g->nedges] = e;
		g->nedges++;
		if (o->fn)
			o->fn(o->ctx, &e);
	}
	return 0;
}

static int STRAND_RT go_fault(struct hal_dout *d, struct hal_fault *f)
{
	return 0;
}

static int go_stop(struct hal_dout *d)
{
	uint32_t i;

	STRAND_ASSERT_NOT_RT();
	for (i = 0; i < d->nlines; i++)
		go_set(d, i, false);
	return go_commit(d, -1);
}

static void go_close(struct hal_dout *d)
{
	STRAND_ASSERT_NOT_RT();
}

static const struct hal_dout_ops sim_dout_ops = {
	.start = go_start,
	.set = go_set,
	.commit = go_commit,
	.fault = go_fault,
	.stop = go_stop,
	.close = go_close,
};

/* ---- inputs ---- */

static int gi_start(struct hal_din *d)
{
	STRAND_ASSERT_NOT_RT();
	return 0;
}

/* Insert keeping the queue sorted by time (stable: equal times keep their
 * order). The queue is short: a handful of frames in flight. */
static int STRAND_RT q_insert(struct sim_gpio *g, const struct sched_edge *e)
{
	uint32_t i;

	if (g->qlen == g->qcap)
		return -ENOSPC;
	for (i = g->qlen; i > 0 && g->q[i - 1].at_ns > e->at_ns; i--)
		g->q[i] = g->q[i - 1];
	g->q[i] = *e;
	g->qlen++;
	return 0;
}

static uint32_t STRAND_RT gi_poll(struct hal_din *d, int64_t now_ns, struct hal_edge *ev,
				  uint32_t max)
{
	struct sim_gpio *g = of_din(d);
	struct sched_edge e;
	uint32_t n = 0, k = 0, j;

	while (hal_ring_pop(&g->inject, &e)) {
		e.at_ns = now_ns;
		if (q_insert(g, &e))
			break; /* full: the edge is lost; the queue is sized so it is not */
	}
	while (k < g->qlen && n < max && g->q[k].at_ns <= now_ns) {
		struct sched_edge *s = &g->q[k++];
		struct sim_in *in = &g->in[s->line];

		in->newest = s->asserted;
		if (in->asserted == s->asserted)
			continue; /* no change, no edge */
		in->asserted = s->asserted;
		ev[n].line = s->line;
		ev[n].asserted = s->asserted;
		ev[n].ts_ns = s->at_ns;
		n++;
	}
	/* edges due but beyond max wait for the next poll; their levels are
	 * the lines' newest now (a scan of the queue, which is short) */
	for (j = k; j < g->qlen && g->q[j].at_ns <= now_ns; j++)
		g->in[g->q[j].line].newest = g->q[j].asserted;
	if (k) {
		memmove(g->q, g->q + k, (g->qlen - k) * sizeof(*g->q));
		g->qlen -= k;
	}
	return n;
}

static bool STRAND_RT gi_level(struct hal_din *d, uint32_t line)
{
	return of_din(d)->in[line].newest;
}

static int STRAND_RT gi_fault(struct hal_din *d, struct hal_fault *f)
{
	return 0;
}

static int gi_stop(struct hal_din *d)
{
	STRAND_ASSERT_NOT_RT();
	return 0;
}

static void gi_close(struct hal_din *d)
{
	STRAND_ASSERT_NOT_RT();
}

static const struct hal_din_ops sim_din_ops = {
	.start = gi_start,
	.poll = gi_poll,
	.level = gi_level,
	.fault = gi_fault,
	.stop = gi_stop,
	.close = gi_close,
};

int sim_gpio_new(struct sim_gpio **out, const char *name, uint32_t nout, uint32_t nin,
		 struct hal_clock *clk, uint32_t queue_cap, char *err, size_t errsize)
{
	struct sim_gpio *g = calloc(1, sizeof(*g));

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (g) {
		g->out = calloc(nout ? nout : 1, sizeof(*g->out));
		g->in = calloc(nin ? nin : 1, sizeof(*g->in));
		g->qcap = queue_cap ? queue_cap : 16;
		g->q = calloc(g->qcap, sizeof(*g->q));
	}
	if (!g || !g->out || !g->in || !g->q) {
		sim_gpio_free(g);
		snprintf(err, errsize, "device '%s': simulated GPIO: %s", name, strerror(ENOMEM));
		return -ENOMEM;
	}
	hal_ring_init(&g->inject, g->inject_buf, INJECT_CAP, sizeof(g->inject_buf[0]));
	g->dout.ops = &sim_dout_ops;
	g->dout.name = name;
	g->dout.nlines = nout;
	g->din.ops = &sim_din_ops;
	g->din.name = name;
	g->din.nlines = nin;
	g->clk = clk;
	*out = g;
	return 0;
}

void sim_gpio_free(struct sim_gpio *g)
{
	STRAND_ASSERT_NOT_RT();
	if (!g)
		return;
	free(g->out);
	free(g->in);
	free(g->q);
	free(g);
}

struct hal_dout *sim_gpio_dout(struct sim_gpio *g)
{
	return &g->dout;
}

struct hal_din *sim_gpio_din(struct sim_gpio *g)
{
	return &g->din;
}

void sim_gpio_out_polarity(struct sim_gpio *g, uint32_t line, bool active_low)
{
	g->out[line].active_low = active_low;
	g->out[line].level = active_low;
}

void sim_gpio_in_polarity(struct sim_gpio *g, uint32_t line, bool active_low)
{
	g->in[line].active_low = active_low;
}

void sim_gpio_record(struct sim_gpio *g, struct sim_gpio_edge *buf, uint64_t cap)
{
	g->rec = buf;
	g->rec_cap = buf ? cap : 0;
}

uint64_t sim_gpio_edges(const struct sim_gpio *g)
{
	return g->nedges;
}

void sim_gpio_listen(struct sim_gpio *g, uint32_t line, sim_gpio_listener fn, void *ctx)
{
	g->out[line].fn = fn;
	g->out[line].ctx = ctx;
}

bool sim_gpio_out_level(const struct sim_gpio *g, uint32_t line)
{
	return g->out[line].level;
}

int STRAND_RT sim_gpio_schedule(struct sim_gpio *g, uint32_t line, int64_t at_ns, bool asserted)
{
	struct sched_edge e = { .at_ns = at_ns, .line = line, .asserted = asserted };

	if (line >= g->din.nlines)
		return -EINVAL;
	return q_insert(g, &e);
}

bool sim_gpio_inject(struct sim_gpio *g, uint32_t line, bool asserted)
{
	struct sched_edge e = { .at_ns = 0, .line = line, .asserted = asserted };

	return line < g->din.nlines && hal_ring_push(&g->inject, &e);
}
