/* SPDX-License-Identifier: MIT */
/* server.c - strand serve's HTTP and WebSocket server (server.h). */
#define _GNU_SOURCE
#include "server.h"

#include <errno.h>
#include <libwebsockets.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>

#include "hal/clock.h"
#include "dispatch.h"

#define OUTQ 32           /* answers and events waiting for one client */
#define JOBS_MAX 64       /* commands waiting for the command thread */
#define TICKETS 16
#define TICKET_NS 10000000000LL
#define PUSH_NS 20000000LL /* status to each client at most 50 times a second */

struct client {
	struct lws *wsi;
	uint64_t id;
	bool ws;
	bool authed;
	/* HTTP: the request and its answer */
	bool rpc, page, oversized;
	char *body;
	size_t blen;
	char *resp;
	size_t rlen;
	int status;
	const char *ctype;
	/* WebSocket */
	char *outq[OUTQ];
	unsigned qhead, qn;
	uint64_t sent_serial;
	int64_t sent_ns;
	bool listed;        /* in the server's list: a WebSocket, or HTTP waiting */
	struct client *next;
};

/* A command for the command thread, and its answer coming back. */
struct job {
	struct job *next;
	uint64_t client;      /* whose answer it is */
	struct rpc_req *r;    /* NULL: client `gone`'s jogs end */
	uint64_t gone;
	char *answer;         /* NULL: none (a notification) */
};

struct jobs {
	pthread_mutex_t mu;   /* held only to link and unlink */
	pthread_cond_t cv;
	struct job *head, *tail, *done;
	unsigned n;
	bool quit;
	pthread_t thread;
	bool started;
};

struct ticket {
	char t[33];
	int64_t until;
};

struct server {
	struct live *lv;
	struct server_opts o;
	struct lws_context *ctx;
	lws_sorted_usec_list_t sul;
	volatile sig_atomic_t *stop;
	struct client *clients;
	uint64_t next_id;
	struct dispatch d;
	struct ticket tickets[TICKETS];
	enum live_state last_state;
	char last_reason[LIVE_MSG];
	bool quitting, exit;
	struct jobs jobs;
};

/* ---- security ---- */

static bool same_secret(const char *a, const char *b)
{
	size_t na = strlen(a), nb = strlen(b), i;
	unsigned char d = (unsigned char)(na != nb);

	/* every byte of the longer, whatever matches: no early exit */
	for (i = 0; i < (na > nb ? na : nb); i++)
		d |= (unsigned char)(a[i < na ? i : 0] ^ b[i < nb ? i : 0]);
	return d == 0;
}

static int hdr(struct lws *wsi, enum lws_token_indexes t, char *buf, int size)
{
	buf[0] = 0;
	if (lws_hdr_total_length(wsi, t) >= size)
		return -1;
	return lws_hdr_copy(wsi, buf, size, t) < 0 ? -1 : 0;
}

/* The Authorization header carries the token: "Bearer T" or "Basic"
 * base64(user:T). */
static bool token_ok(struct server *s, struct lws *wsi)
{
	char h[512], dec[400], *colon;

	if (!s->o.token)
		return true;
	if (hdr(wsi, WSI_TOKEN_HTTP_AUTHORIZATION, h, sizeof(h)))
		return false;
	if (!strncmp(h, "Bearer ", 7))
		return same_secret(h + 7, s->o.token);
	if (!strncmp(h, "Basic ", 6) && lws_b64_decode_string(h + 6, dec, sizeof(dec)) > 0 &&
	    (colon = strchr(dec, ':')))
		return same_secret(colon + 1, s->o.token);
	return false;
}

static bool ticket_ok(struct server *s, struct lws *wsi)
{
	char arg[80], *t = NULL;
	int64_t now = hal_mono_ns();
	int i;

	for (i = 0; lws_hdr_copy_fragment(wsi, arg, sizeof(arg), WSI_TOKEN_HTTP_URI_ARGS, i) > 0;
	     i++)
		if (!strncmp(arg, "ticket=", 7))
			t = arg + 7;
	if (!t)
		return false;
	for (i = 0; i < TICKETS; i++) {
		if (s->tickets[i].until > now && same_secret(s->tickets[i].t, t)) {
			s->tickets[i].until = 0; /* one shot */
			return true;
		}
	}
	return false;
}

/* A new ticket into out (32 hex digits and a NUL): dispatch's callback. */
static int ticket_new(void *ctx, char out[33])
{
	struct server *s = ctx;
	unsigned char r[16];
	int i, slot = 0;

	if (getrandom(r, sizeof(r), 0) != sizeof(r))
		return -EIO;
	for (i = 0; i < 16; i++)
		sprintf(out + 2 * i, "%02x", r[i]);
	for (i = 1; i < TICKETS; i++)
		if (s->tickets[i].until < s->tickets[slot].until)
			slot = i;
	memcpy(s->tickets[slot].t, out, sizeof(s->tickets[slot].t));
	s->tickets[slot].until = hal_mono_ns() + TICKET_NS;
	return 0;
}

/* Host: on loopback, a loopback name (a page of another name resolving to
 * 127.0.0.1 is DNS rebinding); Origin, when a browser sends one: the
 * server's own page, http://<Host>. */
static const char *origin_refused(struct server *s, struct lws *wsi)
{
	char host[256], origin[300], want[300], *colon;

	if (hdr(wsi, WSI_TOKEN_HOST, host, sizeof(host)) || !host[0])
		return "no Host header";
	if (s->o.loopback) {
		char name[256];

		snprintf(name, sizeof(name), "%s", host);
		colon = name[0] == '[' ? strchr(name, ']') : strrchr(name, ':');
		if (colon && name[0] == '[')
			colon[1] = 0;
		else if (colon)
			*colon = 0;
		if (strcmp(name, "127.0.0.1") && strcmp(name, "localhost") && strcmp(name, "[::1]"))
			return "Host is not a loopback name";
	}
	if (lws_hdr_total_length(wsi, WSI_TOKEN_ORIGIN) <= 0)
		return NULL;
	if (hdr(wsi, WSI_TOKEN_ORIGIN, origin, sizeof(origin)))
		return "Origin too long";
	snprintf(want, sizeof(want), "http://%s", host);
	return strcmp(origin, want) ? "Origin is not this server's page" : NULL;
}

/* ---- answers ---- */

static void http_answer(struct client *c, int status, const char *ctype, char *body)
{
	free(c->resp);
	c->status = status;
	c->ctype = ctype;
	c->resp = body;
	c->rlen = body ? strlen(body) : 0;
	lws_callback_on_writable(c->wsi);
}

static int http_write(struct client *c)
{
	unsigned char hbuf[LWS_PRE + 1024], *start = hbuf + LWS_PRE, *p = start,
					     *end = hbuf + sizeof(hbuf) - 1;
	const char *body = c->page ? serve_page : c->resp;
	size_t n = c->page ? serve_page_len : c->rlen;
	unsigned char *out;

	if (lws_add_http_common_headers(c->wsi, (unsigned)c->status, c->ctype, n, &p, end))
		return 1;
	if (c->status == 401 &&
	    lws_add_http_header_by_token(c->wsi, WSI_TOKEN_HTTP_WWW_AUTHENTICATE,
					 (const unsigned char *)"Basic realm=\"strand\"", 20, &p,
					 end))
		return 1;
	if (lws_add_http_header_by_name(c->wsi, (const unsigned char *)"cache-control:",
					(const unsigned char *)"no-store", 8, &p, end) ||
	    lws_finalize_write_http_header(c->wsi, start, &p, end))
		return 1;
	out = malloc(LWS_PRE + n + 1);
	if (!out)
		return 1;
	memcpy(out + LWS_PRE, body, n);
	if (lws_write(c->wsi, out + LWS_PRE, n, LWS_WRITE_HTTP_FINAL) != (int)n) {
		free(out);
		return 1;
	}
	free(out);
	return lws_http_transaction_completed(c->wsi) ? -1 : 0;
}

static void ws_queue(struct client *c, char *msg)
{
	if (!msg)
		return;
	if (c->qn == OUTQ) {
		/* a client that sends and never reads: it goes */
		free(msg);
		lws_set_timeout(c->wsi, PENDING_TIMEOUT_CLOSE_SEND, LWS_TO_KILL_ASYNC);
		return;
	}
	c->outq[(c->qhead + c->qn++) % OUTQ] = msg;
	lws_callback_on_writable(c->wsi);
}

static int ws_send(struct lws *wsi, const char *msg, size_t n)
{
	unsigned char *buf = malloc(LWS_PRE + n);
	int rc;

	if (!buf)
		return -1;
	memcpy(buf + LWS_PRE, msg, n);
	rc = lws_write(wsi, buf + LWS_PRE, n, LWS_WRITE_TEXT);
	free(buf);
	return rc < (int)n ? -1 : 0;
}

static int ws_writable(struct server *s, struct client *c)
{
	struct live_snap snap;
	char *msg;
	int64_t now;
	int rc;

	if (lws_send_pipe_choked(c->wsi)) {
		lws_callback_on_writable(c->wsi);
		return 0;
	}
	if (c->qn) {
		char *m = c->outq[c->qhead];

		c->qhead = (c->qhead + 1) % OUTQ;
		c->qn--;
		rc = ws_send(c->wsi, m, strlen(m));
		free(m);
		if (c->qn)
			lws_callback_on_writable(c->wsi);
		return rc;
	}
	/* the newest status, at most every PUSH_NS: the timer asks again */
	now = hal_mono_ns();
	if (c->sent_serial && now - c->sent_ns < PUSH_NS)
		return 0;
	live_snapshot(s->lv, &snap);
	if (snap.serial == c->sent_serial && c->sent_serial)
		return 0;
	msg = dispatch_status_text(&s->d, &snap, true);
	if (!msg)
		return -1;
	rc = ws_send(c->wsi, msg, strlen(msg));
	free(msg);
	c->sent_serial = snap.serial;
	c->sent_ns = now;
	return rc;
}

/* ---- the command thread ---- */

static void *jobs_main(void *arg)
{
	struct server *s = arg;
	struct jobs *q = &s->jobs;
	struct job *j;

	for (;;) {
		pthread_mutex_lock(&q->mu);
		while (!q->head && !q->quit)
			pthread_cond_wait(&q->cv, &q->mu);
		j = q->head;
		if (!j) {
			pthread_mutex_unlock(&q->mu);
			return NULL;
		}
		q->head = j->next;
		if (!q->head)
			q->tail = NULL;
		pthread_mutex_unlock(&q->mu);
		if (j->r)
			j->answer = dispatch_run(&s->d, j->r);
		else
			live_client_gone(s->lv, j->gone);
		free(j->r);
		j->r = NULL;
		pthread_mutex_lock(&q->mu);
		q->n--;
		j->next = q->done;
		q->done = j;
		pthread_mutex_unlock(&q->mu);
		/* the server's thread delivers it (LWS_CALLBACK_EVENT_WAIT_CANCELLED) */
		lws_cancel_service(s->ctx);
	}
}

/* A job for the command thread: false when too many wait already. */
static bool jobs_push(struct server *s, uint64_t client, struct rpc_req *r, uint64_t gone)
{
	struct jobs *q = &s->jobs;
	struct job *j = calloc(1, sizeof(*j));

	if (!j)
		return false;
	j->client = client;
	j->r = r;
	j->gone = gone;
	pthread_mutex_lock(&q->mu);
	if (q->n >= JOBS_MAX && r) {
		pthread_mutex_unlock(&q->mu);
		free(j);
		return false;
	}
	q->n++;
	if (q->tail)
		q->tail->next = j;
	else
		q->head = j;
	q->tail = j;
	pthread_cond_signal(&q->cv);
	pthread_mutex_unlock(&q->mu);
	return true;
}

static struct client *find(struct server *s, uint64_t id)
{
	struct client *c;

	for (c = s->clients; c; c = c->next)
		if (c->id == id)
			return c;
	return NULL;
}

static void unlist(struct server *s, struct client *c)
{
	struct client **pp;

	if (!c->listed)
		return;
	for (pp = &s->clients; *pp; pp = &(*pp)->next)
		if (*pp == c) {
			*pp = c->next;
			break;
		}
	c->listed = false;
}

static void list_client(struct server *s, struct client *c)
{
	if (c->listed)
		return;
	c->next = s->clients;
	s->clients = c;
	c->listed = true;
}

/* The answers the command thread left, to their clients (gone: dropped). */
static void jobs_deliver(struct server *s)
{
	struct jobs *q = &s->jobs;
	struct job *j, *next;
	struct client *c;

	pthread_mutex_lock(&q->mu);
	j = q->done;
	q->done = NULL;
	pthread_mutex_unlock(&q->mu);
	for (; j; j = next) {
		next = j->next;
		c = j->answer ? find(s, j->client) : NULL;
		if (c && c->ws) {
			ws_queue(c, j->answer);
		} else if (c) {
			unlist(s, c);
			http_answer(c, 200, "application/json", j->answer);
		} else {
			free(j->answer);
		}
		free(j);
	}
}

static void jobs_stop(struct server *s)
{
	struct jobs *q = &s->jobs;
	struct job *j, *next;

	if (q->started) {
		pthread_mutex_lock(&q->mu);
		q->quit = true;
		pthread_cond_signal(&q->cv);
		pthread_mutex_unlock(&q->mu);
		pthread_join(q->thread, NULL);
	}
	for (j = q->head; j; j = next) {
		next = j->next;
		free(j->r);
		free(j);
	}
	for (j = q->done; j; j = next) {
		next = j->next;
		free(j->answer);
		free(j);
	}
	pthread_cond_destroy(&q->cv);
	pthread_mutex_destroy(&q->mu);
}

/* ---- the timer: the session's round, status, events ---- */

static void broadcast(struct server *s, char *msg)
{
	struct client *c;

	for (c = s->clients; c; c = c->next)
		if (c->ws)
			ws_queue(c, strdup(msg));
	free(msg);
}

static void tick(lws_sorted_usec_list_t *sul)
{
	struct server *s = lws_container_of(sul, struct server, sul);
	struct live_snap snap;
	struct client *c;
	int64_t now = hal_mono_ns();
	int ms = live_service(s->lv);
	uint64_t lapsed;

	live_snapshot(s->lv, &snap);
	if (snap.state != s->last_state || strcmp(snap.reason, s->last_reason)) {
		broadcast(s, dispatch_event_text(&s->d, &snap, s->last_state));
		s->last_state = snap.state;
		snprintf(s->last_reason, sizeof(s->last_reason), "%s", snap.reason);
	}
	for (c = s->clients; c; c = c->next)
		if (c->ws && snap.serial != c->sent_serial && now - c->sent_ns >= PUSH_NS)
			lws_callback_on_writable(c->wsi);
	lapsed = dispatch_expire(&s->d, now);
	if (lapsed)
		jobs_push(s, 0, NULL, lapsed);
	if (*s->stop && !s->quitting) {
		s->quitting = true;
		live_signal(s->lv, 1);
	}
	if (live_finished(s->lv) || (*s->stop >= 2)) {
		s->exit = true;
		lws_cancel_service(s->ctx);
		return;
	}
	lws_sul_schedule(s->ctx, 0, &s->sul, tick, (ms > 5 ? 5 : ms) * LWS_US_PER_MS);
}

/* ---- requests ---- */

/* A message's next bytes; past RPC_MAX_BYTES it is marked oversized and
 * the rest dropped. 0, or -1 out of memory (the connection goes). */
static int body_add(struct client *c, const void *in, size_t len)
{
	char *b;

	if (c->oversized || c->blen + len > RPC_MAX_BYTES) {
		c->oversized = true;
		return 0;
	}
	b = realloc(c->body, c->blen + len + 1);
	if (!b)
		return -1;
	c->body = b;
	memcpy(c->body + c->blen, in, len);
	c->blen += len;
	return 0;
}

/* A message: its answer now, or NULL when the command thread answers
 * (*queued) or nobody does (a notification). */
static char *handle(struct server *s, struct client *c, const char *buf, size_t len,
		    bool *queued)
{
	struct rpc_req *job;
	char *txt = dispatch_admit(&s->d, c->id, c->ws, buf, len, &job);

	*queued = false;
	if (!job)
		return txt;
	if (jobs_push(s, c->id, job, 0)) {
		*queued = job->has_id;
		return NULL;
	}
	txt = job->has_id ? rpc_error_text(job->id, RPC_REFUSED, "the server is busy: too many "
					   "commands wait for one that takes long (an enable, "
					   "a load); try again") : NULL;
	free(job);
	return txt;
}

static int callback(struct lws *wsi, enum lws_callback_reasons reason, void *user, void *in,
		    size_t len)
{
	struct server *s = lws_context_user(lws_get_context(wsi));
	struct client *c = user;
	const char *why;
	char uri[128], ctype[64], *txt;
	bool queued;

	switch (reason) {
	case LWS_CALLBACK_PROTOCOL_INIT:
		return 0;
	case LWS_CALLBACK_EVENT_WAIT_CANCELLED:
		if (s)
			jobs_deliver(s);
		return 0;
	case LWS_CALLBACK_HTTP:
		memset(c, 0, sizeof(*c));
		c->wsi = wsi;
		snprintf(uri, sizeof(uri), "%s", (const char *)in);
		if (!token_ok(s, wsi)) {
			http_answer(c, 401, "text/plain", strdup("401: the token is missing or "
								 "wrong\n"));
			return 0;
		}
		if ((why = origin_refused(s, wsi))) {
			char m[128];

			snprintf(m, sizeof(m), "403: %s\n", why);
			http_answer(c, 403, "text/plain", strdup(m));
			return 0;
		}
		if (lws_hdr_total_length(wsi, WSI_TOKEN_POST_URI) > 0) {
			if (strcmp(uri, "/rpc")) {
				http_answer(c, 404, "text/plain", strdup("404\n"));
				return 0;
			}
			hdr(wsi, WSI_TOKEN_HTTP_CONTENT_TYPE, ctype, sizeof(ctype));
			if (strncmp(ctype, "application/json", 16)) {
				http_answer(c, 415, "text/plain",
					    strdup("415: POST /rpc takes application/json\n"));
				return 0;
			}
			c->rpc = true;
			c->id = ++s->next_id;
			return 0; /* the body follows */
		}
		if (!strcmp(uri, "/") || !strcmp(uri, "/index.html")) {
			c->page = true;
			http_answer(c, 200, "text/html; charset=utf-8", NULL);
			return 0;
		}
		http_answer(c, 404, "text/plain", strdup("404\n"));
		return 0;
	case LWS_CALLBACK_HTTP_BODY:
		if (!c->rpc)
			return 0;
		return body_add(c, in, len);
	case LWS_CALLBACK_HTTP_BODY_COMPLETION:
		if (!c->rpc)
			return 0;
		if (c->oversized) {
			http_answer(c, 413, "application/json",
				    rpc_error_text("null", RPC_OVERSIZED, "message too large"));
			return 0;
		}
		txt = handle(s, c, c->body ? c->body : "", c->blen, &queued);
		if (queued) {
			/* the answer comes from the command thread: an enable may
			 * take seconds (a CANopen bus), more than lws's timeout */
			list_client(s, c);
			lws_set_timeout(wsi, PENDING_TIMEOUT_USER_OK, 120);
			return 0;
		}
		http_answer(c, 200, "application/json",
			    txt ? txt : strdup("")); /* a notification: nothing to say */
		return 0;
	case LWS_CALLBACK_HTTP_WRITEABLE:
		return http_write(c);
	case LWS_CALLBACK_CLOSED_HTTP:
	case LWS_CALLBACK_HTTP_DROP_PROTOCOL:
		if (c && !c->ws) {
			unlist(s, c);
			free(c->body);
			free(c->resp);
			c->body = c->resp = NULL;
		}
		return 0;
	case LWS_CALLBACK_FILTER_PROTOCOL_CONNECTION:
		if (!token_ok(s, wsi) && !ticket_ok(s, wsi)) {
			lws_return_http_status(wsi, 401, "the token is missing or wrong");
			return 1;
		}
		if ((why = origin_refused(s, wsi))) {
			lws_return_http_status(wsi, 403, why);
			return 1;
		}
		if (hdr(wsi, WSI_TOKEN_GET_URI, uri, sizeof(uri)) || strcmp(uri, "/websocket")) {
			lws_return_http_status(wsi, 404, NULL);
			return 1;
		}
		return 0;
	case LWS_CALLBACK_ESTABLISHED:
		memset(c, 0, sizeof(*c));
		c->wsi = wsi;
		c->ws = true;
		c->id = ++s->next_id;
		list_client(s, c);
		lws_callback_on_writable(wsi);
		return 0;
	case LWS_CALLBACK_RECEIVE:
		if (lws_is_first_fragment(wsi)) {
			c->blen = 0;
			c->oversized = false;
		}
		if (body_add(c, in, len))
			return -1;
		if (!lws_is_final_fragment(wsi) || lws_remaining_packet_payload(wsi))
			return 0;
		if (c->oversized)
			ws_queue(c, rpc_error_text("null", RPC_OVERSIZED, "message too large"));
		else
			ws_queue(c, handle(s, c, c->body ? c->body : "", c->blen, &queued));
		return 0;
	case LWS_CALLBACK_SERVER_WRITEABLE:
		return ws_writable(s, c);
	case LWS_CALLBACK_CLOSED:
		unlist(s, c);
		dispatch_gone(&s->d, c->id);
		/* its jogs end on the command thread, after what it sent */
		jobs_push(s, 0, NULL, c->id);
		while (c->qn) {
			free(c->outq[c->qhead]);
			c->qhead = (c->qhead + 1) % OUTQ;
			c->qn--;
		}
		free(c->body);
		c->body = NULL;
		return 0;
	default:
		return lws_callback_http_dummy(wsi, reason, user, in, len);
	}
}

static const struct lws_protocols protocols[] = {
	{ "strand", callback, sizeof(struct client), RPC_MAX_BYTES, 0, NULL, 0 },
	{ NULL, NULL, 0, 0, 0, NULL, 0 },
};

static void lws_log(int level, const char *line)
{
	fprintf(stderr, "strand serve: libwebsockets: %s", line);
}

int server_run(struct live *lv, const struct server_opts *o, volatile sig_atomic_t *stop,
	       FILE *err)
{
	struct lws_context_creation_info info;
	struct server *s = calloc(1, sizeof(*s));
	int rc = 0;

	if (!s)
		return -ENOMEM;
	s->lv = lv;
	s->o = *o;
	if (!(s->o.lease_s > 0))
		s->o.lease_s = 10;
	s->stop = stop;
	s->last_state = LIVE_DISABLED;
	dispatch_init(&s->d, lv, s->o.lease_s);
	s->d.ticket = ticket_new;
	s->d.ticket_ctx = s;
	pthread_mutex_init(&s->jobs.mu, NULL);
	pthread_cond_init(&s->jobs.cv, NULL);
	lws_set_log_level(LLL_ERR, lws_log);
	memset(&info, 0, sizeof(info));
	info.port = o->port;
	info.iface = o->addr;
	info.protocols = protocols;
	info.user = s;
	info.options = LWS_SERVER_OPTION_VALIDATE_UTF8;
	if (!strchr(o->addr, ':'))
		info.options |= LWS_SERVER_OPTION_DISABLE_IPV6;
	info.max_http_header_data = 4096;
	info.timeout_secs = 10;
	s->ctx = lws_create_context(&info);
	if (!s->ctx) {
		fprintf(err, "strand serve: cannot listen on %s:%d (in use, or not an address of "
			"this machine)\n", o->addr, o->port);
		jobs_stop(s);
		free(s);
		return -EADDRNOTAVAIL;
	}
	/* the command thread: created here, by a thread of normal priority
	 * (a thread inherits its creator's scheduling) */
	rc = pthread_create(&s->jobs.thread, NULL, jobs_main, s);
	if (rc) {
		fprintf(err, "strand serve: cannot start the command thread: %s\n", strerror(rc));
		lws_context_destroy(s->ctx);
		jobs_stop(s);
		free(s);
		return -rc;
	}
	s->jobs.started = true;
	fprintf(err, "strand serve: listening on http://%s%s%s:%d/\n",
		strchr(o->addr, ':') ? "[" : "", o->addr, strchr(o->addr, ':') ? "]" : "",
		o->port);
	fflush(err);
	lws_sul_schedule(s->ctx, 0, &s->sul, tick, 5 * LWS_US_PER_MS);
	while (!s->exit && !live_finished(lv) && *stop < 2)
		if (lws_service(s->ctx, 0) < 0)
			break;
	lws_sul_cancel(&s->sul);
	/* the command under way finishes (an enable, a load) before the
	 * session is closed under it */
	jobs_stop(s);
	lws_context_destroy(s->ctx);
	free(s);
	return 0;
}
