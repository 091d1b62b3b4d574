/* SPDX-License-Identifier: MIT */
/* co_simbus.c - the simulated CAN bus (see co_simbus.h). */
#include "co_simbus.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/rt.h"

/* A drive's connection to the bus: the ctx of its send callback. */
struct port {
	struct co_simbus *b;
	struct co_slave *s;
	uint8_t node;
	int64_t next; /* when its timers next need it */
};

struct co_simbus {
	struct co_bus bus; /* first: the master's transport */
	struct hal_clock *clk;
	uint8_t state;     /* enum co_bus_state */
	bool bus_open;     /* the master's transport not closed yet */
	bool freed;        /* co_simbus_free called */
	struct port port[CO_NODE_MAX];
	uint32_t nslaves;
	/* the master's receive queue */
	struct co_frame *q;
	uint32_t qcap, qhead, qlen;
	uint64_t overflows;
	/* what the master sent while the drives were held (co_simbus_hold) */
	struct co_frame held[CO_SIMBUS_HELD];
	uint32_t nheld;
	bool hold;
	struct co_simbus_rec *log;
	uint64_t log_cap, nlog;
};

static struct co_simbus STRAND_RT *simbus_of(struct co_bus *bus)
{
	return (struct co_simbus *)bus; /* bus is the first member */
}

static void STRAND_RT record(struct co_simbus *b, const struct co_frame *f, int16_t from)
{
	struct co_simbus_rec *r;

	if (b->nlog >= b->log_cap)
		return;
	r = &b->log[b->nlog++];
	r->t = hal_clock_now(b->clk);
	r->f = *f;
	r->from = from;
}

/* A drive sends: logged and queued for the master. */
static int STRAND_RT slave_send(void *ctx, const struct co_frame *f, uint32_t n)
{
	struct port *p = ctx;
	struct co_simbus *b = p->b;
	uint32_t i;

	for (i = 0; i < n; i++) {
		record(b, &f[i], p->node);
		if (b->qlen == b->qcap) {
			b->overflows++;
			continue;
		}
		b->q[(b->qhead + b->qlen++) % b->qcap] = f[i];
	}
	return 0;
}

void STRAND_RT co_simbus_run(struct co_simbus *b, int64_t now)
{
	uint32_t i;

	for (i = 0; i < b->nslaves; i++)
		b->port[i].next = co_slave_poll(b->port[i].s, now);
}

/* ---- the master's transport ---- */

/* Every drive receives f now. */
static void STRAND_RT deliver(struct co_simbus *b, const struct co_frame *f, int64_t now)
{
	uint32_t k;

	for (k = 0; k < b->nslaves; k++) {
		struct port *p = &b->port[k];

		co_slave_rx(p->s, f, now);
		/* what it received may start a timer (a quick stop) */
		p->next = co_slave_poll(p->s, now);
	}
}

static int STRAND_RT sb_send(struct co_bus *bus, const struct co_frame *f, uint32_t n)
{
	struct co_simbus *b = simbus_of(bus);
	int64_t now = hal_clock_now(b->clk);
	uint32_t i;

	if (b->state == CO_BUS_OFF)
		return -ENETDOWN;
	co_simbus_run(b, now);
	for (i = 0; i < n; i++) {
		record(b, &f[i], -1);
		if (!b->hold)
			deliver(b, &f[i], now);
		else if (b->nheld < CO_SIMBUS_HELD)
			b->held[b->nheld++] = f[i];
		else
			b->overflows++;
	}
	return 0;
}

void co_simbus_hold(struct co_simbus *b, bool hold)
{
	b->hold = hold;
	if (!hold)
		co_simbus_deliver(b, b->nheld);
}

uint32_t co_simbus_deliver(struct co_simbus *b, uint32_t n)
{
	int64_t now = hal_clock_now(b->clk);
	uint32_t i;

	if (n > b->nheld)
		n = b->nheld;
	co_simbus_run(b, now);
	for (i = 0; i < n; i++)
		deliver(b, &b->held[i], now);
	memmove(b->held, b->held + n, (b->nheld - n) * sizeof(b->held[0]));
	b->nheld -= n;
	return n;
}

static int STRAND_RT sb_recv(struct co_bus *bus, struct co_frame *f, uint32_t max)
{
	struct co_simbus *b = simbus_of(bus);
	uint32_t n = 0;

	co_simbus_run(b, hal_clock_now(b->clk));
	while (n < max && b->qlen) {
		f[n++] = b->q[b->qhead];
		b->qhead = (b->qhead + 1) % b->qcap;
		b->qlen--;
	}
	return (int)n;
}

static enum co_bus_state STRAND_RT sb_state(struct co_bus *bus)
{
	return (enum co_bus_state)simbus_of(bus)->state;
}

static void sb_wait(struct co_bus *bus, int64_t until)
{
	struct co_simbus *b = simbus_of(bus);
	uint32_t i;

	STRAND_ASSERT_NOT_RT();
	if (b->qlen)
		return;
	for (i = 0; i < b->nslaves; i++)
		if (b->port[i].next < until)
			until = b->port[i].next;
	hal_clock_sleep_until(b->clk, until);
}

static void destroy(struct co_simbus *b)
{
	uint32_t i;

	for (i = 0; i < b->nslaves; i++)
		co_slave_free(b->port[i].s);
	free(b->q);
	free(b->log);
	free(b);
}

static void sb_close(struct co_bus *bus)
{
	struct co_simbus *b = simbus_of(bus);

	STRAND_ASSERT_NOT_RT();
	b->bus_open = false;
	if (b->freed)
		destroy(b);
}

static const struct co_bus_ops simbus_ops = {
	.send = sb_send,
	.recv = sb_recv,
	.state = sb_state,
	.wait = sb_wait,
	.close = sb_close,
};

/* ---- set-up ---- */

int co_simbus_new(struct co_simbus **out, struct hal_clock *clk, uint32_t queue,
		  uint64_t log_cap, char *err, size_t errsize)
{
	struct co_simbus *b = calloc(1, sizeof(*b));

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (b) {
		b->qcap = queue ? queue : 1;
		b->q = calloc(b->qcap, sizeof(*b->q));
		b->log = log_cap ? calloc(log_cap, sizeof(*b->log)) : NULL;
	}
	if (!b || !b->q || (log_cap && !b->log)) {
		if (b) {
			free(b->q);
			free(b->log);
		}
		free(b);
		snprintf(err, errsize, "simulated CAN bus: %s", strerror(ENOMEM));
		return -ENOMEM;
	}
	b->bus.ops = &simbus_ops;
	b->bus.name = "sim";
	b->clk = clk;
	b->log_cap = log_cap;
	b->bus_open = true;
	*out = b;
	return 0;
}

void co_simbus_free(struct co_simbus *b)
{
	STRAND_ASSERT_NOT_RT();
	if (!b)
		return;
	b->freed = true;
	if (!b->bus_open)
		destroy(b);
}

int co_simbus_add(struct co_slave **out, struct co_simbus *b, const struct co_slave_cfg *cfg,
		  bool off, char *err, size_t errsize)
{
	struct co_slave_cfg c = *cfg;
	struct port *p;
	int rc;

	STRAND_ASSERT_NOT_RT();
	if (out)
		*out = NULL;
	if (b->nslaves == CO_NODE_MAX || co_simbus_node(b, cfg->node)) {
		snprintf(err, errsize, "device '%s': simulated drive %u: %s",
			 cfg->name ? cfg->name : "", cfg->node, strerror(EINVAL));
		return -EINVAL;
	}
	p = &b->port[b->nslaves];
	c.send = slave_send;
	c.ctx = p;
	p->b = b;
	p->node = cfg->node;
	rc = co_slave_new(&p->s, &c, err, errsize);
	if (rc)
		return rc;
	b->nslaves++;
	p->next = INT64_MAX;
	if (!off) {
		int64_t now = hal_clock_now(b->clk);

		co_slave_power_on(p->s, now);
		p->next = co_slave_poll(p->s, now);
	}
	if (out)
		*out = p->s;
	return 0;
}

uint32_t co_simbus_count(const struct co_simbus *b)
{
	return b->nslaves;
}

struct co_slave *co_simbus_slave(struct co_simbus *b, uint32_t i)
{
	return i < b->nslaves ? b->port[i].s : NULL;
}

struct co_slave *co_simbus_node(struct co_simbus *b, uint8_t node)
{
	uint32_t i;

	for (i = 0; i < b->nslaves; i++)
		if (b->port[i].node == node)
			return b->port[i].s;
	return NULL;
}

struct co_bus *co_simbus_bus(struct co_simbus *b)
{
	return &b->bus;
}

void co_simbus_set_state(struct co_simbus *b, enum co_bus_state s)
{
	b->state = (uint8_t)s;
}

const struct co_simbus_rec *co_simbus_log(const struct co_simbus *b, uint64_t *n)
{
	*n = b->nlog;
	return b->log;
}

uint64_t co_simbus_overflows(const struct co_simbus *b)
{
	return b->overflows;
}
