/* SPDX-License-Identifier: MIT */
/* co_axis.c - CANopen drives behind the HAL axis interface (see co_axis.h). */
#include "co_axis.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/rt.h"

struct co_axis {
	struct hal_axis ax; /* first: the HAL view */
	struct co_master m;
	struct co_bus *bus;
	struct hal_clock *clk;
	const struct hal_cancel *cancel; /* the start's, or NULL */
	uint8_t bus_state;  /* enum co_bus_state, as last told to the master */
	bool started;
	struct hal_fault hf;
	char msg[256];      /* a start or stop failure in words ([init] only) */
	char emcy[96];      /* "emergency 0x2310 (its class)", composed in fault() */
	struct co_node *nodes;
	struct co_frame *cycle;
	struct co_frame rx[CO_AXIS_RX_BATCH];
};

static struct co_axis STRAND_RT *axis_of(struct hal_axis *ax)
{
	return (struct co_axis *)ax; /* ax is the first member */
}

static int STRAND_RT bus_send(void *ctx, const struct co_frame *f, uint32_t n)
{
	return co_bus_send(((struct co_axis *)ctx)->bus, f, n);
}

/* Everything received so far, up to a tick's worth, then the bus state. */
static void STRAND_RT drain(struct co_axis *a, int64_t now)
{
	uint32_t total = 0;
	enum co_bus_state st;
	int n, i;

	do {
		n = co_bus_recv(a->bus, a->rx, CO_AXIS_RX_BATCH);
		for (i = 0; i < n; i++)
			co_master_rx(&a->m, &a->rx[i], now);
		total += n > 0 ? (uint32_t)n : 0;
	} while (n == CO_AXIS_RX_BATCH && total < CO_AXIS_RX_MAX_PER_TICK);
	/* an interface that went away is off the bus as far as we can tell */
	st = n < 0 ? CO_BUS_OFF : co_bus_state(a->bus);
	if (st != a->bus_state) {
		a->bus_state = (uint8_t)st;
		co_master_bus(&a->m, st);
	}
}

/* Run the master's timers until it leaves phase `during`, or, when
 * `cancellable`, until the run's cancel request comes: the start waits
 * seconds for boot-ups and enabling, and a signal then must not wait
 * behind them. Woken at least every HAL_CANCEL_POLL_NS to look (a signal
 * to this thread ends the wait at once; one to another does not). The stop
 * is not cancellable: it is the way out. */
static void run_until_not(struct co_axis *a, enum co_master_phase during, bool cancellable)
{
	int64_t now = hal_clock_now(a->clk), next;

	cancellable = cancellable && a->cancel;
	while (co_master_phase(&a->m) == during) {
		if (cancellable && hal_cancelled(a->cancel))
			break;
		drain(a, now);
		next = co_master_poll(&a->m, now);
		if (co_master_phase(&a->m) != during)
			break;
		if (cancellable && next - now > HAL_CANCEL_POLL_NS)
			next = now + HAL_CANCEL_POLL_NS;
		co_bus_wait(a->bus, next);
		now = hal_clock_now(a->clk);
	}
}

static void describe(struct co_axis *a)
{
	struct co_fault f;

	if (co_master_fault(&a->m, &f))
		co_master_describe(&a->m, &f, a->msg, sizeof(a->msg));
}

static int ca_stop(struct hal_axis *ax);

static int ca_start(struct hal_axis *ax)
{
	struct co_axis *a = axis_of(ax);
	struct co_fault f;
	int rc;

	STRAND_ASSERT_NOT_RT();
	a->started = true;
	/* what came before the start (boot-ups of drives powered on since
	 * the interface opened) is not an answer to anything of this run */
	while (co_bus_recv(a->bus, a->rx, CO_AXIS_RX_BATCH) == CO_AXIS_RX_BATCH)
		;
	co_master_start(&a->m, hal_clock_now(a->clk));
	run_until_not(a, CO_MASTER_STARTING, true);
	if (co_master_phase(&a->m) == CO_MASTER_RUNNING)
		return 0;
	rc = co_master_fault(&a->m, &f);
	if (!rc && hal_cancelled(a->cancel)) {
		/* asked to stop (a signal): the drives enabled so far, and
		 * those on their way, are shut down as after any failed start */
		snprintf(a->msg, sizeof(a->msg), "start given up (a stop was asked for)");
		rc = -ECANCELED;
	} else {
		describe(a);
	}
	/* leave no drive enabled behind: shut down those that got that far */
	ca_stop(ax);
	return rc ? rc : -EIO;
}

static int STRAND_RT ca_input(struct hal_axis *ax, int64_t tick)
{
	struct co_axis *a = axis_of(ax);
	int64_t now = hal_clock_now(a->clk);

	drain(a, now);
	co_master_poll(&a->m, now);
	return co_master_fault(&a->m, NULL);
}

static bool STRAND_RT ca_actual(struct hal_axis *ax, uint32_t ch, int64_t *counts)
{
	struct co_axis *a = axis_of(ax);
	int i = co_master_index(&a->m, (uint8_t)ch);

	return ch <= CO_NODE_MAX && i >= 0 && co_master_actual(&a->m, (uint32_t)i, counts);
}

static void STRAND_RT ca_set(struct hal_axis *ax, uint32_t ch, const struct hal_setpoint *sp)
{
	struct co_axis *a = axis_of(ax);
	int i = ch <= CO_NODE_MAX ? co_master_index(&a->m, (uint8_t)ch) : -1;

	if (i < 0)
		return;
	co_master_stage(&a->m, (uint32_t)i,
			co_master_mode(&a->m, (uint32_t)i) == CO402_MODE_CSV ? sp->vel : sp->pos);
}

static int STRAND_RT ca_commit(struct hal_axis *ax, int64_t tick)
{
	struct co_axis *a = axis_of(ax);

	co_master_cycle(&a->m, hal_clock_now(a->clk));
	return co_master_fault(&a->m, NULL);
}

/* "emergency 0x2310 (current, device output side)": four hex digits and a
 * static class, put together by hand in the loop's thread, where printf
 * has no place. */
static const char STRAND_RT *emcy_text(struct co_axis *a, uint16_t code)
{
	static const char head[] = "emergency 0x", hex[] = "0123456789ABCDEF";
	const char *cls = co_emcy_class(code);
	size_t n = sizeof(head) - 1, len = strlen(cls);
	int i;

	memcpy(a->emcy, head, n);
	for (i = 12; i >= 0; i -= 4)
		a->emcy[n++] = hex[(code >> i) & 0xf];
	a->emcy[n++] = ' ';
	a->emcy[n++] = '(';
	if (len > sizeof(a->emcy) - n - 2)
		len = sizeof(a->emcy) - n - 2;
	memcpy(a->emcy + n, cls, len);
	n += len;
	a->emcy[n++] = ')';
	a->emcy[n] = '\0';
	return a->emcy;
}

static int STRAND_RT ca_fault(struct hal_axis *ax, struct hal_fault *hf)
{
	struct co_axis *a = axis_of(ax);
	struct co_fault f;
	int code = co_master_fault(&a->m, &f);

	if (!code)
		return 0;
	hf->code = code;
	hf->channel = f.node ? f.node : -1;
	/* a start or stop failure was put in words by [init] code; in the
	 * loop only static text */
	hf->cause = a->msg[0] ? a->msg :
		    f.kind == CO_FAULT_EMCY ? emcy_text(a, (uint16_t)f.detail) : co_fault_cause(&f);
	hf->detail = f.kind == CO_FAULT_EMCY || f.kind == CO_FAULT_SDO ? f.detail : 0;
	return code;
}

static void STRAND_RT ca_disable(struct hal_axis *ax)
{
	struct co_axis *a = axis_of(ax);

	co_master_disable(&a->m, hal_clock_now(a->clk));
}

static int ca_stop(struct hal_axis *ax)
{
	struct co_axis *a = axis_of(ax);

	STRAND_ASSERT_NOT_RT();
	if (!a->started)
		return 0;
	co_master_stop(&a->m, hal_clock_now(a->clk));
	run_until_not(a, CO_MASTER_STOPPING, false);
	if (co_master_phase(&a->m) == CO_MASTER_STOPPED)
		return 0;
	if (!a->msg[0])
		describe(a);
	return -EIO;
}

static void ca_close(struct hal_axis *ax)
{
	struct co_axis *a = axis_of(ax);

	STRAND_ASSERT_NOT_RT();
	co_bus_close(a->bus);
	free(a->nodes);
	free(a->cycle);
	free(a);
}

static const struct hal_axis_ops co_axis_ops = {
	.start = ca_start,
	.input = ca_input,
	.actual = ca_actual,
	.set = ca_set,
	.commit = ca_commit,
	.fault = ca_fault,
	.disable = ca_disable,
	.stop = ca_stop,
	.close = ca_close,
};

int co_axis_new(struct hal_axis **out, const struct co_axis_cfg *cfg, char *err, size_t errsize)
{
	struct co_master_cfg mc = cfg->master;
	struct co_axis *a = calloc(1, sizeof(*a));
	int rc = -ENOMEM;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (a) {
		a->nodes = calloc(cfg->ndrives ? cfg->ndrives : 1, sizeof(*a->nodes));
		a->cycle = calloc(cfg->ndrives + 1, sizeof(*a->cycle));
	}
	if (!a || !a->nodes || !a->cycle) {
		if (a) {
			free(a->nodes);
			free(a->cycle);
		}
		free(a);
		co_bus_close(cfg->bus);
		goto fail;
	}
	a->ax.ops = &co_axis_ops;
	a->ax.name = cfg->name;
	a->ax.nch = CO_NODE_MAX + 1;
	a->bus = cfg->bus;
	a->clk = cfg->clk;
	a->cancel = cfg->cancel;
	mc.send = bus_send;
	mc.ctx = a;
	rc = co_master_init(&a->m, &mc, cfg->drives, a->nodes, a->cycle, cfg->ndrives);
	if (rc) {
		ca_close(&a->ax);
		goto fail;
	}
	*out = &a->ax;
	return 0;
fail:
	snprintf(err, errsize, "device '%s': CANopen master: %s", cfg->name, strerror(-rc));
	return rc;
}

struct co_master *co_axis_master(struct hal_axis *ax)
{
	return &axis_of(ax)->m;
}
