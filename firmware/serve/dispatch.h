/* SPDX-License-Identifier: MIT */
/*
 * dispatch.h - a decoded request to the live session's command, and the
 * lease: one client controls at a time. A WebSocket client takes it with
 * lease.take or with its first command that needs it, and keeps it until
 * lease.release or until it goes; a client of POST /rpc takes it with
 * lease.take, which answers a lease string to give as "lease" with each
 * command, and loses it after the server's lease time without one. The
 * others watch: status, info, ping and estop (accepted from any client).
 */
#ifndef STRAND_DISPATCH_H
#define STRAND_DISPATCH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "live/live.h"
#include "rpc.h"

struct dispatch {
	struct live *lv;
	int64_t lease_ns;
	uint64_t holder;        /* client id, 0: nobody */
	bool holder_http;
	char http_lease[33];
	int64_t http_until;
	uint64_t http_ids;
};

void dispatch_init(struct dispatch *d, struct live *lv, double lease_s);
void dispatch_free(struct dispatch *d);

/* The answer to one message (malloc'd JSON text), or NULL for a
 * notification. client: the connection's id; ticket: a fresh ticket for
 * the method ticket (its answer). */
char *dispatch(struct dispatch *d, uint64_t client, bool ws, const char *buf, size_t len,
	       const char *ticket);
bool dispatch_is_ticket(const char *buf, size_t len);
/* A WebSocket client went: its jogs end, its lease is free. */
void dispatch_gone(struct dispatch *d, uint64_t client);
/* An HTTP lease unused for its time lapses. */
void dispatch_expire(struct dispatch *d, int64_t now_ns);

/* A status notification, an event notification (the state changed). */
char *dispatch_status_text(struct dispatch *d, const struct live_snap *s, bool notification);
char *dispatch_event_text(struct dispatch *d, const struct live_snap *s, enum live_state prev);

#endif /* STRAND_DISPATCH_H */
