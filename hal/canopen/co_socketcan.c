/* SPDX-License-Identifier: MIT */
/* co_socketcan.c - the CANopen transport on SocketCAN (see co_socketcan.h). */
#define _GNU_SOURCE
#include "co_socketcan.h"

#include <errno.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "hal/clock.h"
#include "hal/rt.h"

struct co_socketcan {
	struct co_bus bus; /* first: the transport */
	int fd;
	uint8_t state;     /* enum co_bus_state */
	char name[IF_NAMESIZE];
	/* sendmmsg/recvmmsg vectors, set up once: nothing is made per call */
	struct can_frame tx[CO_SOCKETCAN_BATCH], rx[CO_SOCKETCAN_BATCH];
	struct iovec txv[CO_SOCKETCAN_BATCH], rxv[CO_SOCKETCAN_BATCH];
	struct mmsghdr txm[CO_SOCKETCAN_BATCH], rxm[CO_SOCKETCAN_BATCH];
};

static struct co_socketcan STRAND_RT *sc_of(struct co_bus *b)
{
	return (struct co_socketcan *)b; /* bus is the first member */
}

static int STRAND_RT sc_send(struct co_bus *b, const struct co_frame *f, uint32_t n)
{
	struct co_socketcan *s = sc_of(b);
	uint32_t i, done = 0;
	int rc;

	if (n > CO_SOCKETCAN_BATCH)
		return -EMSGSIZE;
	for (i = 0; i < n; i++) {
		struct can_frame *c = &s->tx[i];

		c->can_id = f[i].id & CAN_SFF_MASK;
		c->can_dlc = f[i].len;
		memcpy(c->data, f[i].data, 8);
	}
	while (done < n) {
		rc = sendmmsg(s->fd, s->txm + done, n - done, MSG_DONTWAIT);
		if (rc < 0)
			return errno == EINTR ? -EAGAIN : -errno;
		done += (uint32_t)rc;
	}
	return 0;
}

enum co_bus_state STRAND_RT co_socketcan_error_state(enum co_bus_state prev, uint32_t can_id,
						     const uint8_t *data)
{
	if (can_id & CAN_ERR_BUSOFF)
		return CO_BUS_OFF;
	if (can_id & CAN_ERR_RESTARTED)
		return CO_BUS_ACTIVE;
	if (!(can_id & CAN_ERR_CRTL))
		return prev;
	/* data[1]: the controller's problem, from its error counters */
	if (data[1] & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE))
		return CO_BUS_PASSIVE;
	if (data[1] & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING))
		return CO_BUS_WARNING;
	if (data[1] & CAN_ERR_CRTL_ACTIVE)
		return CO_BUS_ACTIVE;
	return prev;
}

static int STRAND_RT sc_recv(struct co_bus *b, struct co_frame *f, uint32_t max)
{
	struct co_socketcan *s = sc_of(b);
	uint32_t n = 0;
	int rc, i;

	if (max > CO_SOCKETCAN_BATCH)
		max = CO_SOCKETCAN_BATCH;
	rc = recvmmsg(s->fd, s->rxm, max, MSG_DONTWAIT, NULL);
	if (rc < 0)
		return errno == EAGAIN || errno == EINTR ? 0 : -errno;
	for (i = 0; i < rc; i++) {
		const struct can_frame *c = &s->rx[i];

		if (c->can_id & CAN_ERR_FLAG) {
			s->state = (uint8_t)co_socketcan_error_state(
				(enum co_bus_state)s->state, c->can_id, c->data);
			continue;
		}
		if (c->can_id & (CAN_EFF_FLAG | CAN_RTR_FLAG) || s->rxm[i].msg_len < CAN_MTU)
			continue;
		f[n].id = (uint16_t)(c->can_id & CAN_SFF_MASK);
		f[n].len = c->can_dlc > 8 ? 8 : c->can_dlc;
		memcpy(f[n].data, c->data, 8);
		n++;
	}
	return (int)n;
}

static enum co_bus_state STRAND_RT sc_state(struct co_bus *b)
{
	return (enum co_bus_state)sc_of(b)->state;
}

static void sc_wait(struct co_bus *b, int64_t until)
{
	struct co_socketcan *s = sc_of(b);
	struct pollfd p = { .fd = s->fd, .events = POLLIN };
	int64_t now = hal_mono_ns(), ms;

	STRAND_ASSERT_NOT_RT();
	if (until <= now)
		return;
	ms = (until - now + 999999) / 1000000;
	poll(&p, 1, ms > 1000 ? 1000 : (int)ms);
}

static void sc_close(struct co_bus *b)
{
	struct co_socketcan *s = sc_of(b);

	STRAND_ASSERT_NOT_RT();
	close(s->fd);
	free(s);
}

static const struct co_bus_ops socketcan_ops = {
	.send = sc_send,
	.recv = sc_recv,
	.state = sc_state,
	.wait = sc_wait,
	.close = sc_close,
};

/* The message (fmt has the interface's name, then the errno's text), and
 * nothing left open. */
static int fail(struct co_socketcan *s, int code, char *err, size_t size, const char *fmt,
		const char *ifname)
{
	snprintf(err, size, fmt, ifname, strerror(code));
	if (s) {
		if (s->fd >= 0)
			close(s->fd);
		free(s);
	}
	return -code;
}

/* CAN_RAW_FILTER from ours: the identifier's bits, and a data frame with
 * an 11-bit identifier (no remote request, no extended frame). */
static int set_filter(int fd, const struct co_rx_filter *flt, uint32_t n)
{
	struct can_filter *k = calloc(n ? n : 1, sizeof(*k));
	uint32_t i;
	int rc = 0;

	if (!k)
		return -ENOMEM;
	for (i = 0; i < n; i++) {
		k[i].can_id = flt[i].id & CAN_SFF_MASK;
		k[i].can_mask = (flt[i].mask & CAN_SFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG;
	}
	if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, k, (socklen_t)(n * sizeof(*k))) < 0)
		rc = -errno;
	free(k);
	return rc;
}

int co_socketcan_filter(struct co_bus *b, const struct co_rx_filter *flt, uint32_t n)
{
	STRAND_ASSERT_NOT_RT();
	return set_filter(sc_of(b)->fd, flt, n);
}

int co_socketcan_open(struct co_bus **out, const char *ifname, const struct co_rx_filter *flt,
		      uint32_t n, char *err, size_t size)
{
	can_err_mask_t errs = CAN_ERR_CRTL | CAN_ERR_BUSOFF | CAN_ERR_RESTARTED;
	struct sockaddr_can addr = { .can_family = AF_CAN };
	struct co_socketcan *s;
	uint32_t i;
	int rc;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (strlen(ifname) >= IF_NAMESIZE)
		return fail(NULL, EINVAL, err, size, "CAN interface '%s': %s (name too long)", ifname);
	s = calloc(1, sizeof(*s));
	if (!s)
		return fail(NULL, ENOMEM, err, size, "CAN interface '%s': %s", ifname);
	s->fd = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
	if (s->fd < 0)
		return fail(s, errno, err, size,
			    "CAN interface '%s': no CAN socket: %s (is the can-raw module loaded?)",
			    ifname);
	addr.can_ifindex = (int)if_nametoindex(ifname);
	if (!addr.can_ifindex)
		return fail(s, errno, err, size,
			    "CAN interface '%s': %s (see `ip link show type can`)", ifname);
	if (flt && (rc = set_filter(s->fd, flt, n)) < 0)
		return fail(s, -rc, err, size, "CAN interface '%s': receive filter: %s", ifname);
	if (setsockopt(s->fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errs, sizeof(errs)) < 0)
		return fail(s, errno, err, size, "CAN interface '%s': error frames: %s", ifname);
	if (bind(s->fd, (struct sockaddr *)&addr, sizeof(addr)) < 0)
		return fail(s, errno, err, size, "CAN interface '%s': bind: %s (is it up?)", ifname);
	for (i = 0; i < CO_SOCKETCAN_BATCH; i++) {
		s->txv[i].iov_base = &s->tx[i];
		s->txv[i].iov_len = CAN_MTU;
		s->txm[i].msg_hdr.msg_iov = &s->txv[i];
		s->txm[i].msg_hdr.msg_iovlen = 1;
		s->rxv[i].iov_base = &s->rx[i];
		s->rxv[i].iov_len = CAN_MTU;
		s->rxm[i].msg_hdr.msg_iov = &s->rxv[i];
		s->rxm[i].msg_hdr.msg_iovlen = 1;
	}
	snprintf(s->name, sizeof(s->name), "%s", ifname);
	s->bus.ops = &socketcan_ops;
	s->bus.name = s->name;
	*out = &s->bus;
	return 0;
}

int co_socketcan_fd(struct co_bus *b)
{
	return sc_of(b)->fd;
}
