/* SPDX-License-Identifier: MIT */
/*
 * dispatch.h - a decoded request to the live session's command, and the
 * lease: one client controls at a time. A WebSocket client takes it with
 * lease.take or with its first command that needs it, and keeps it until
 * lease.release or until it goes; a client of POST /rpc takes it with
 * lease.take, which answers a lease string to give as "lease" with each
 * command, and loses it after the server's lease time without one. The
 * others watch: status, info, ping and estop (accepted from any client).
 *
 * Two threads: the server's admits each message (dispatch_admit) and
 * answers what needs no command at once; the command thread runs the rest
 * one after the other (dispatch_run), so that a command that takes long
 * (an enable, a load) holds up neither the status nor another client's
 * e-stop.
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
	/* a one-shot ticket for a WebSocket (32 hex digits): the server's */
	int (*ticket)(void *ctx, char out[33]);
	void *ticket_ctx;
};

void dispatch_init(struct dispatch *d, struct live *lv, double lease_s);

/*
 * [the server's thread] A message decoded and checked whole, the lease
 * looked at, and the methods that need no command of the session answered
 * at once: status, ticket, lease.take, lease.release, and estop, which
 * reaches the loop here and never waits behind a command. Returns the
 * answer (malloc'd JSON text), or NULL: then *job is the command for
 * dispatch_run (malloc'd; the caller's to pass on and free), or NULL for a
 * notification answered already.
 */
char *dispatch_admit(struct dispatch *d, uint64_t client, bool ws, const char *buf, size_t len,
		     struct rpc_req **job);

/* [the command thread] Run an admitted command on the session: its answer
 * (malloc'd), or NULL for a notification. Commands take as long as the
 * session's (an enable starts the drives: seconds on a CANopen bus). */
char *dispatch_run(struct dispatch *d, const struct rpc_req *r);

/* [the server's thread] A WebSocket client went: its lease is free. Its
 * jogs are ended by live_client_gone, a command (the caller's to run on
 * the command thread). */
void dispatch_gone(struct dispatch *d, uint64_t client);
/* [the server's thread] An HTTP lease unused for its time lapses: the
 * client whose jogs must end (live_client_gone), or 0. */
uint64_t dispatch_expire(struct dispatch *d, int64_t now_ns);

/* A status notification, an event notification (the state changed): from
 * a snapshot alone (the server's thread). */
char *dispatch_status_text(struct dispatch *d, const struct live_snap *s, bool notification);
char *dispatch_event_text(struct dispatch *d, const struct live_snap *s, enum live_state prev);

#endif /* STRAND_DISPATCH_H */
