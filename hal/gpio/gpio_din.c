/* SPDX-License-Identifier: MIT */
/*
 * gpio_din.c - e-stop, stop and camera-ready inputs on a GPIO chip (gpio.h).
 *
 * The event thread is the ring's only producer and the loop its only
 * consumer. The thread blocks in poll() on the lines' event descriptors
 * and an eventfd that stop() writes to end it; it never touches the
 * loop's state. It publishes each line's newest level (newest[], atomic)
 * as it pushes the line's edge, so that the loop sees an e-stop by level
 * even while its edge waits in the ring behind others (din.h). What it
 * must tell the loop besides edges (events lost, a read failing) it
 * latches in one atomic fault code.
 */
#include "gpio_priv.h"

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/eventfd.h>
#include <time.h>
#include <unistd.h>

#include "hal/clock.h"
#include "hal/ring.h"
#include "hal/rt.h"

/* With no event for this long, the thread reads the lines back anyway: a
 * lost edge is found within it even when no other edge follows. */
#define GPIO_DIN_READ_BACK_MS 50

struct gpio_din {
	struct hal_din base; /* first */
	struct gpio_req *req;
	uint32_t n;
	bool active_low[GPIO_LINE_MAX];
	bool sent[GPIO_LINE_MAX];  /* logical, the thread's: after the edges pushed */
	atomic_bool newest[GPIO_LINE_MAX]; /* sent[], for the loop to read */
	uint64_t corrected;        /* the thread's: edges made from a read-back */
	struct hal_ring ring;      /* struct hal_edge, thread -> loop */
	struct hal_edge *ring_buf;
	int wake_fd;               /* eventfd: stop() ends the thread */
	int fds[GPIO_LINE_MAX];
	uint32_t nfds;
	struct hal_sched sched;
	struct hal_thread thread;
	_Atomic int fault;         /* negative errno, 0: healthy; the thread's */
	char name[];
};

static struct gpio_din STRAND_RT *to_din(struct hal_din *d)
{
	return (struct gpio_din *)d;
}

static void latch(struct gpio_din *g, int code)
{
	int none = 0;

	atomic_compare_exchange_strong(&g->fault, &none, code);
}

/* Pass a line's level on to the loop when it changed. */
static void push(struct gpio_din *g, uint32_t line, bool asserted, int64_t ts_ns)
{
	struct hal_edge e = { .line = line, .asserted = asserted, .ts_ns = ts_ns };

	if (g->sent[line] == asserted)
		return;
	g->sent[line] = asserted;
	if (!hal_ring_push(&g->ring, &e))
		latch(g, -ENOBUFS);
	atomic_store(&g->newest[line], asserted);
}

/* Read what waits on fds[k] and pass it on; false when the thread must end. */
static bool forward(struct gpio_din *g, uint32_t k)
{
	struct gpio_line_event ev[16];
	int j, n;

	n = gpio_req_read(g->req, k, ev, 16);
	if (n < 0) {
		latch(g, n);
		return false;
	}
	for (j = 0; j < n; j++)
		if (ev[j].line < g->n)
			push(g, ev[j].line, ev[j].rising != g->active_low[ev[j].line], ev[j].ts_ns);
	return true;
}

/* Has the kernel more events for us? */
static bool pending(struct gpio_din *g)
{
	struct pollfd p[GPIO_LINE_MAX];
	uint32_t k;

	for (k = 0; k < g->nfds; k++)
		p[k] = (struct pollfd){ .fd = g->fds[k], .events = POLLIN };
	return poll(p, g->nfds, 0) > 0;
}

/*
 * When the kernel has no more events, the lines' levels must be what was
 * passed on: the kernel can get an edge wrong. The v1 ABI labels an edge
 * rising or falling by reading the line in its interrupt thread, which may
 * run after the line changed again, and an interrupt that comes while that
 * thread still runs for the previous one can be lost. A level that differs
 * becomes an edge of its own, dated now, so a lost or mislabelled edge
 * never leaves the loop's view of an e-stop wrong for longer than
 * GPIO_DIN_READ_BACK_MS. (An event that arrives between the two checks is
 * read first, next round.)
 */
static bool read_back(struct gpio_din *g)
{
	bool high[GPIO_LINE_MAX];
	int64_t now;
	uint32_t i;
	int rc;

	if (pending(g))
		return true;
	rc = gpio_req_get(g->req, high);
	if (rc) {
		latch(g, rc);
		return false;
	}
	if (pending(g))
		return true;
	now = hal_mono_ns();
	for (i = 0; i < g->n; i++)
		if ((high[i] != g->active_low[i]) != g->sent[i]) {
			g->corrected++;
			push(g, i, high[i] != g->active_low[i], now);
		}
	return true;
}

static void *event_thread(void *arg)
{
	struct gpio_din *g = arg;
	struct pollfd pfd[GPIO_LINE_MAX + 1];
	uint32_t k;

	/* (started with every signal blocked: hal/thread.h) */
	for (k = 0; k < g->nfds; k++)
		pfd[k] = (struct pollfd){ .fd = g->fds[k], .events = POLLIN };
	pfd[g->nfds] = (struct pollfd){ .fd = g->wake_fd, .events = POLLIN };
	for (;;) {
		if (poll(pfd, g->nfds + 1, GPIO_DIN_READ_BACK_MS) < 0) {
			if (errno == EINTR)
				continue;
			latch(g, -errno);
			return NULL;
		}
		if (pfd[g->nfds].revents)
			return NULL;
		for (k = 0; k < g->nfds; k++) {
			if (pfd[k].revents & (POLLERR | POLLHUP | POLLNVAL)) {
				latch(g, -EIO);
				return NULL;
			}
			if ((pfd[k].revents & POLLIN) && !forward(g, k))
				return NULL;
		}
		if (!read_back(g))
			return NULL;
	}
}

/* Edges queued in the kernel before the run are history: drop them, then
 * read the levels as they are. */
static int initial_levels(struct gpio_din *g)
{
	struct gpio_line_event ev[16];
	bool high[GPIO_LINE_MAX];
	struct pollfd p;
	uint32_t k, i;
	int rc;

	for (k = 0; k < g->nfds; k++) {
		p = (struct pollfd){ .fd = g->fds[k], .events = POLLIN };
		while (poll(&p, 1, 0) > 0 && (p.revents & POLLIN))
			if (gpio_req_read(g->req, k, ev, 16) < 0)
				break;
	}
	rc = gpio_req_get(g->req, high);
	if (rc)
		return rc;
	for (i = 0; i < g->n; i++) {
		g->sent[i] = high[i] != g->active_low[i];
		atomic_store(&g->newest[i], g->sent[i]);
	}
	return 0;
}

/* The event thread, as the plan schedules it (at the loop's priority: the
 * e-stop must not wait behind ordinary work). SCHED_FIFO refused, it runs
 * SCHED_OTHER; the plan's report says so. */
static int din_start(struct hal_din *d)
{
	struct gpio_din *g = to_din(d);
	char name[HAL_THREAD_NAME_MAX + 1];
	int rc;

	STRAND_ASSERT_NOT_RT();
	if (!g->req || g->thread.running)
		return g->req ? 0 : -EBADF;
	rc = initial_levels(g);
	if (rc)
		return rc;
	hal_thread_name(name, "strand-gpio-", g->name);
	return hal_thread_start(&g->thread, name, &g->sched, 0, event_thread, g);
}

static uint32_t STRAND_RT din_poll(struct hal_din *d, int64_t now_ns, struct hal_edge *ev,
				   uint32_t max)
{
	struct gpio_din *g = to_din(d);
	uint32_t n = 0;

	while (n < max && hal_ring_pop(&g->ring, &ev[n]))
		n++;
	return n;
}

static bool STRAND_RT din_level(struct hal_din *d, uint32_t line)
{
	struct gpio_din *g = to_din(d);

	return line < g->n && atomic_load(&g->newest[line]);
}

static int STRAND_RT din_fault(struct hal_din *d, struct hal_fault *f)
{
	struct gpio_din *g = to_din(d);
	int code = atomic_load(&g->fault);

	if (!code)
		return 0;
	f->code = code;
	f->channel = -1;
	f->detail = 0;
	switch (code) {
	case -ENOBUFS:
		f->cause = "input edges lost: the loop did not keep up with them";
		break;
	case -EIO:
		f->cause = "input lines gone (chip removed?)";
		break;
	default:
		f->cause = "reading input edges failed";
		break;
	}
	return code;
}

static int din_stop(struct hal_din *d)
{
	struct gpio_din *g = to_din(d);
	uint64_t one = 1;

	STRAND_ASSERT_NOT_RT();
	if (g->thread.running && write(g->wake_fd, &one, sizeof(one)) != sizeof(one))
		pthread_cancel(g->thread.id);
	hal_thread_join(&g->thread);
	gpio_req_close(g->req);
	g->req = NULL;
	return 0;
}

static void din_close(struct hal_din *d)
{
	struct gpio_din *g = to_din(d);

	STRAND_ASSERT_NOT_RT();
	din_stop(d);
	close(g->wake_fd);
	free(g->ring_buf);
	free(g);
}

static const struct hal_din_ops gpio_din_ops = {
	.start = din_start,
	.poll = din_poll,
	.level = din_level,
	.fault = din_fault,
	.stop = din_stop,
	.close = din_close,
};

int hal_gpio_din_open(struct hal_din **out, const struct hal_gpio_cfg *cfg, char *err,
		      size_t errsize)
{
	uint32_t i, cap = cfg->ring_cap ? cfg->ring_cap : HAL_GPIO_RING_DEFAULT;
	struct hal_gpio_req rq;
	struct gpio_din *g;
	char msg[256];
	int rc;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	rc = hal_gpio_req_init(&rq, cfg, GPIO_REQ_INPUT_EDGES, err, errsize);
	if (rc)
		return rc;
	g = calloc(1, sizeof(*g) + strlen(cfg->device) + 1);
	if (!g)
		goto nomem;
	strcpy(g->name, cfg->device);
	g->wake_fd = -1;
	g->ring_buf = calloc(cap, sizeof(*g->ring_buf));
	if (!g->ring_buf)
		goto nomem;
	rc = hal_ring_init(&g->ring, g->ring_buf, cap, sizeof(*g->ring_buf));
	if (rc) {
		snprintf(err, errsize, "device '%s': edge ring of %u: not a power of two",
			 cfg->device, cap);
		goto fail;
	}
	g->wake_fd = eventfd(0, EFD_CLOEXEC);
	if (g->wake_fd < 0) {
		rc = -errno;
		snprintf(err, errsize, "device '%s': eventfd: %s", cfg->device, strerror(errno));
		goto fail;
	}
	rc = gpio_req_open(&g->req, &rq.cfg, msg, sizeof(msg));
	if (rc) {
		snprintf(err, errsize, "device '%s': %s", cfg->device, msg);
		goto fail;
	}
	g->n = cfg->nlines;
	for (i = 0; i < g->n; i++)
		g->active_low[i] = cfg->lines[i].active_low;
	rc = hal_gpio_sleep_check(g->req, cfg, GPIO_REQ_INPUT_EDGES, NULL, err, errsize);
	if (rc)
		goto fail;
	g->nfds = gpio_req_fds(g->req, g->fds, GPIO_LINE_MAX);
	g->sched = cfg->sched;
	atomic_init(&g->fault, 0);
	g->base = (struct hal_din){ .ops = &gpio_din_ops, .name = g->name, .nlines = g->n };
	*out = &g->base;
	return 0;
nomem:
	rc = -ENOMEM;
	snprintf(err, errsize, "device '%s': out of memory", cfg->device);
fail:
	if (g) {
		gpio_req_close(g->req);
		if (g->wake_fd >= 0)
			close(g->wake_fd);
		free(g->ring_buf);
	}
	free(g);
	return rc;
}
