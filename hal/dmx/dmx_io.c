/* SPDX-License-Identifier: MIT */
/*
 * dmx_io.c - a DMX device's socket and I/O thread (see dmx.h): one UDP
 * packet per universe per frame, to the destination the scene names.
 */
#define _GNU_SOURCE
#include "dmx_priv.h"

#include <arpa/inet.h>
#include <errno.h>
#include <netdb.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "hal/clock.h"

static int resolve(struct dmx_drv *m, const char *host, uint16_t port, struct sockaddr_in *sa)
{
	struct addrinfo hints, *res = NULL;
	int rc;

	memset(&hints, 0, sizeof(hints));
	hints.ai_family = AF_INET;
	hints.ai_socktype = SOCK_DGRAM;
	rc = getaddrinfo(host, NULL, &hints, &res);
	if (rc || !res) {
		snprintf(m->io_text, sizeof(m->io_text), "%s: cannot resolve '%s': %s", m->where,
			 host, gai_strerror(rc));
		return -EHOSTUNREACH;
	}
	memcpy(sa, res->ai_addr, sizeof(*sa));
	sa->sin_port = htons(port);
	freeaddrinfo(res);
	return 0;
}

int dmx_io_open(struct dmx_drv *m)
{
	const struct dmx_desc *d = m->d;
	uint16_t port = d->port ? d->port :
			d->protocol == DMX_E131 ? DMX_E131_PORT : DMX_ARTNET_PORT;
	bool group = !strcmp(d->destination, "multicast");
	unsigned char ttl = (unsigned char)(d->ttl ? d->ttl : 1);
	int one = 1, rc = 0;
	uint32_t u;

	m->fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
	if (m->fd < 0) {
		rc = -errno;
		snprintf(m->io_text, sizeof(m->io_text), "%s: cannot open a UDP socket: %s",
			 m->where, strerror(errno));
		return rc;
	}
	/* a unicast destination may be a broadcast one (Art-Net's 2.255.255.255) */
	setsockopt(m->fd, SOL_SOCKET, SO_BROADCAST, &one, sizeof(one));
	if (setsockopt(m->fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof(ttl)) < 0)
		rc = -errno;
	if (!rc && d->interface) {
		struct in_addr ifa;

		if (inet_pton(AF_INET, d->interface, &ifa) != 1) {
			snprintf(m->io_text, sizeof(m->io_text), "%s: interface '%s' is not an "
				 "IPv4 address", m->where, d->interface);
			return -EINVAL;
		}
		if (setsockopt(m->fd, IPPROTO_IP, IP_MULTICAST_IF, &ifa, sizeof(ifa)) < 0) {
			rc = -errno;
			snprintf(m->io_text, sizeof(m->io_text), "%s: cannot send from %s: %s",
				 m->where, d->interface, strerror(errno));
			return rc;
		}
	}
	for (u = 0; !rc && u < m->nu; u++) {
		char host[32];

		if (group) {
			/* sACN's group for the universe (E1.31 section 9.3.1) */
			snprintf(host, sizeof(host), "239.255.%u.%u", d->universes[u] >> 8,
				 d->universes[u] & 0xff);
			rc = resolve(m, host, port, &m->dest[u]);
		} else {
			rc = resolve(m, d->destination, port, &m->dest[u]);
		}
	}
	return rc;
}

void dmx_io_close(struct dmx_drv *m)
{
	if (m->fd >= 0)
		close(m->fd);
	m->fd = -1;
}

int dmx_io_send(struct dmx_drv *m, const struct dmx_frame *f, uint8_t options)
{
	const struct dmx_desc *d = m->d;
	uint32_t u;
	int rc = 0;

	for (u = 0; u < m->nu; u++) {
		size_t len;

		if (d->protocol == DMX_E131)
			len = dmx_e131_packet(m->pkt, m->cid, d->source_name ? d->source_name : "strand",
					      d->priority, m->seq[u], options, d->universes[u],
					      f->img[u], DMX_SLOTS);
		else
			len = dmx_artnet_packet(m->pkt, (uint8_t)(m->seq[u] % 255 + 1),
						d->universes[u], f->img[u], DMX_SLOTS);
		/* a sequence per universe, forward on every packet */
		m->seq[u]++;
		if (sendto(m->fd, m->pkt, len, 0, (const struct sockaddr *)&m->dest[u],
			   sizeof(m->dest[u])) < 0) {
			rc = -errno;
			m->errors++;
			continue;
		}
		m->packets++;
	}
	return rc;
}

/* A send error: the message, then the code (release), for the loop. */
static void io_fail(struct dmx_drv *m, int rc)
{
	if (atomic_load(&m->io_error))
		return;
	snprintf(m->io_text, sizeof(m->io_text), "%s: send failed: %s", m->where, strerror(-rc));
	atomic_store_explicit(&m->io_error, rc, memory_order_release);
}

void *dmx_io_main(void *arg)
{
	struct dmx_drv *m = arg;
	const struct dmx_frame *f;
	struct timespec ts;
	bool done = false;
	int64_t t;
	int rc, i;

	while (!atomic_load(&m->quit) && !done) {
		t = hal_mono_ns() + DMX_IDLE_NS;
		ts.tv_sec = t / 1000000000;
		ts.tv_nsec = t % 1000000000;
		rc = sem_clockwait(&m->wake, CLOCK_MONOTONIC, &ts);
		if (atomic_load(&m->terminate)) {
			/* E1.31 6.2.6: three packets with Stream_Terminated set */
			for (i = 0; m->d->protocol == DMX_E131 && m->have_last && i < 3; i++)
				dmx_io_send(m, m->last, DMX_E131_TERMINATED);
			done = true;
			continue;
		}
		f = hal_slot_take(&m->slot);
		if (!f && rc && m->have_last) {
			/* a second without a frame: say it again */
			f = m->last;
			m->resends++;
		}
		if (!f)
			continue;
		rc = dmx_io_send(m, f, 0);
		if (rc)
			io_fail(m, rc);
		if (f != m->last)
			memcpy(m->last, f, m->frame_size);
		m->have_last = true;
		m->sent++;
		atomic_store_explicit(&m->sent_tick, f->tick, memory_order_release);
	}
	atomic_store(&m->sent_tick, INT64_MAX); /* nothing more to wait for */
	return NULL;
}
