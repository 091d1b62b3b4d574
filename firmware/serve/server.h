/* SPDX-License-Identifier: MIT */
/*
 * server.h - strand serve's HTTP and WebSocket server (libwebsockets) on a
 * live session: the page at /, JSON-RPC 2.0 over a WebSocket at
 * /websocket and as POST /rpc, status pushed to every WebSocket client.
 *
 * One thread, the caller's, at normal priority: libwebsockets' event loop,
 * which also runs the session's service round every 5 ms. A slow client
 * gets the newest status when its socket can take it (libwebsockets calls
 * a client writable only once what it sent before has gone out), never a
 * queue of old ones, and never holds up the loop or another client.
 *
 * Security (README "Putting it on a network"): a token (--token-file) on
 * every request when given, compared in constant time (an Authorization
 * header, Bearer or Basic, or a one-shot ticket for a WebSocket); an Origin
 * other than the server's own refused; on loopback, a Host other than a
 * loopback name refused (DNS rebinding); POST /rpc only as
 * application/json (a foreign page cannot send that without a preflight,
 * which is never granted); one client controls at a time (the lease).
 */
#ifndef STRAND_SERVER_H
#define STRAND_SERVER_H

#include <signal.h>
#include <stdbool.h>
#include <stdio.h>

#include "live/live.h"

struct server_opts {
	const char *addr;   /* an IPv4 or IPv6 address, or "localhost" */
	int port;
	const char *token;  /* NULL: none (loopback only) */
	bool loopback;      /* addr is a loopback address */
	double lease_s;     /* an HTTP client's lease lapses after this idle (10) */
};

/* Serve until *stop (a signal) or the session has finished; the session's
 * service rounds run here. 0, or a negative errno when the server could
 * not start (err says why). */
int server_run(struct live *lv, const struct server_opts *o, volatile sig_atomic_t *stop,
	       FILE *err);

/* The page, built in (page.c). */
extern const char serve_page[];
extern const unsigned serve_page_len;

#endif /* STRAND_SERVER_H */
