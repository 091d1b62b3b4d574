/* SPDX-License-Identifier: MIT */
/* gpio_dout.c - camera trigger outputs on a GPIO chip (gpio.h). */
#include "gpio_priv.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/rt.h"

struct gpio_dout {
	struct hal_dout base; /* first */
	struct gpio_req *req;
	uint32_t n;
	bool active_low[GPIO_LINE_MAX];
	bool staged[GPIO_LINE_MAX]; /* logical, for the next commit */
	bool high[GPIO_LINE_MAX];   /* physical, as last applied */
	struct hal_fault fault;     /* code 0: healthy */
	char name[];
};

static struct gpio_dout STRAND_RT *to_dout(struct hal_dout *d)
{
	return (struct gpio_dout *)d;
}

/* Every line to its staged level: one ioctl when something changed. */
static int STRAND_RT apply(struct gpio_dout *g, bool force)
{
	bool high[GPIO_LINE_MAX];
	bool changed = force;
	uint32_t i;
	int rc;

	for (i = 0; i < g->n; i++) {
		high[i] = g->staged[i] != g->active_low[i];
		changed |= high[i] != g->high[i];
	}
	if (!changed)
		return 0;
	rc = gpio_req_set(g->req, high);
	if (rc) {
		if (!g->fault.code)
			g->fault = (struct hal_fault){ .code = rc, .channel = -1,
						       .cause = "setting the output lines failed" };
		return rc;
	}
	memcpy(g->high, high, sizeof(high));
	return 0;
}

static int dout_start(struct hal_dout *d)
{
	struct gpio_dout *g = to_dout(d);

	STRAND_ASSERT_NOT_RT();
	if (!g->req)
		return -EBADF;
	memset(g->staged, 0, sizeof(g->staged));
	return apply(g, true);
}

static void STRAND_RT dout_set(struct hal_dout *d, uint32_t line, bool asserted)
{
	struct gpio_dout *g = to_dout(d);

	if (line < g->n)
		g->staged[line] = asserted;
}

static int STRAND_RT dout_commit(struct hal_dout *d, int64_t tick)
{
	struct gpio_dout *g = to_dout(d);

	if (g->fault.code)
		return g->fault.code;
	return apply(g, false);
}

static int STRAND_RT dout_fault(struct hal_dout *d, struct hal_fault *f)
{
	struct gpio_dout *g = to_dout(d);

	if (g->fault.code)
		*f = g->fault;
	return g->fault.code;
}

/* Deasserted, then released: what the line does after that is the chip's
 * and the wiring's business (a pull resistor should hold it deasserted). */
static int dout_stop(struct hal_dout *d)
{
	struct gpio_dout *g = to_dout(d);
	int rc;

	STRAND_ASSERT_NOT_RT();
	if (!g->req)
		return 0;
	memset(g->staged, 0, sizeof(g->staged));
	rc = apply(g, true);
	gpio_req_close(g->req);
	g->req = NULL;
	return rc;
}

static void dout_close(struct hal_dout *d)
{
	struct gpio_dout *g = to_dout(d);

	STRAND_ASSERT_NOT_RT();
	gpio_req_close(g->req);
	free(g);
}

static const struct hal_dout_ops gpio_dout_ops = {
	.start = dout_start,
	.set = dout_set,
	.commit = dout_commit,
	.fault = dout_fault,
	.stop = dout_stop,
	.close = dout_close,
};

int hal_gpio_dout_open(struct hal_dout **out, const struct hal_gpio_cfg *cfg, char *err,
		       size_t errsize)
{
	struct hal_gpio_req rq;
	struct gpio_dout *g;
	char msg[256];
	uint32_t i;
	int e;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	e = hal_gpio_req_init(&rq, cfg, GPIO_REQ_OUTPUT, err, errsize);
	if (e)
		return e;
	g = calloc(1, sizeof(*g) + strlen(cfg->device) + 1);
	if (!g) {
		snprintf(err, errsize, "device '%s': out of memory", cfg->device);
		return -ENOMEM;
	}
	strcpy(g->name, cfg->device);
	e = gpio_req_open(&g->req, &rq.cfg, msg, sizeof(msg));
	if (e) {
		snprintf(err, errsize, "device '%s': %s", cfg->device, msg);
		free(g);
		return e;
	}
	g->n = cfg->nlines;
	for (i = 0; i < g->n; i++) {
		g->active_low[i] = cfg->lines[i].active_low;
		g->high[i] = rq.initial[i]; /* deasserted from the request on */
	}
	e = hal_gpio_sleep_check(g->req, cfg, GPIO_REQ_OUTPUT, g->high, err, errsize);
	if (e) {
		gpio_req_close(g->req);
		free(g);
		return e;
	}
	g->base = (struct hal_dout){ .ops = &gpio_dout_ops, .name = g->name, .nlines = g->n };
	*out = &g->base;
	return 0;
}
