/* SPDX-License-Identifier: MIT */
/* dispatch.c - requests to commands, the lease, status as JSON (dispatch.h). */
#define _GNU_SOURCE
#include "dispatch.h"

#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>

#include "hal/clock.h"
#include "scene/timecode.h"

void dispatch_init(struct dispatch *d, struct live *lv, double lease_s)
{
	memset(d, 0, sizeof(*d));
	d->lv = lv;
	d->lease_ns = (int64_t)(lease_s * 1e9);
	d->http_ids = UINT64_C(1) << 62; /* apart from the connections' ids */
}

static json_t *jnum(double v)
{
	return isfinite(v) ? json_real(v) : json_null();
}

/* ---- status, info, events ---- */

static json_t *status_obj(struct dispatch *d, const struct live_snap *s)
{
	char tc[24] = "--:--:--:--";
	struct timecode t;
	json_t *o, *outs;
	uint32_t i;

	if (s->frame >= 0 && s->fps_num && s->fps_den) {
		timecode_init(&t, s->fps_num, s->fps_den);
		timecode_format(&t, s->frame, tc, sizeof(tc));
	}
	outs = json_array();
	for (i = 0; i < s->nout; i++) {
		const struct loop_live_out *x = &s->out[i];

		json_array_append_new(outs, json_pack("{s:o, s:o, s:o, s:o, s:b, s:b, s:b}",
			"sp", jnum(x->sp), "act", x->has_act ? jnum(x->act) : json_null(),
			"fe", x->has_act ? jnum(x->fe) : json_null(), "vel", jnum(x->vel),
			"off", x->off, "jog", x->jog, "has_act", x->has_act));
	}
	o = json_pack("{s:s, s:s, s:s, s:I, s:o, s:I, s:s, s:I, s:I, s:{s:o, s:o, s:o, s:I, s:I},"
		      " s:I, s:I, s:I, s:b, s:o}",
		      "state", live_state_name(s->state),
		      "loop", s->loop_state ? s->loop_state : "",
		      "reason", s->reason, "tick", (json_int_t)s->tick,
		      "t", jnum(s->t_ns / 1e9), "frame", (json_int_t)s->frame, "timecode", tc,
		      "fired", (json_int_t)s->fired, "total", (json_int_t)s->total,
		      "latency", "min_us", jnum(s->lat_min_ns / 1e3), "avg_us",
		      jnum(s->lat_avg_ns / 1e3), "max_us", jnum(s->lat_max_ns / 1e3),
		      "overruns", (json_int_t)s->overruns, "n", (json_int_t)s->lat_n,
		      "journal", (json_int_t)s->journal_frames, "serial", (json_int_t)s->serial,
		      "generation", (json_int_t)s->generation, "leased", d->holder != 0,
		      "outputs", outs);
	return o;
}

static char *notification(const char *method, json_t *params)
{
	json_t *o = json_pack("{s:s, s:s, s:o}", "jsonrpc", "2.0", "method", method, "params",
			      params);
	char *txt = o ? json_dumps(o, JSON_COMPACT | JSON_REAL_PRECISION(10)) : NULL;

	json_decref(o);
	return txt;
}

char *dispatch_status_text(struct dispatch *d, const struct live_snap *s, bool notify)
{
	json_t *o = status_obj(d, s);
	char *txt;

	if (!o)
		return NULL;
	if (notify)
		return notification("status", o);
	txt = json_dumps(o, JSON_COMPACT | JSON_REAL_PRECISION(10));
	json_decref(o);
	return txt;
}

char *dispatch_event_text(struct dispatch *d, const struct live_snap *s, enum live_state prev)
{
	const char *kind = s->state == LIVE_ESTOPPED ? "estop" :
			   s->state == LIVE_FAULTED ? "fault" : "state";

	return notification("event", json_pack("{s:s, s:s, s:s, s:s, s:I}", "kind", kind,
					       "state", live_state_name(s->state), "from",
					       live_state_name(prev), "reason", s->reason,
					       "frame", (json_int_t)s->frame));
}

struct keys_ctx {
	json_t *keys;
};

static void add_key(void *ctx, const char *channel, double frame)
{
	struct keys_ctx *k = ctx;
	json_t *a = json_object_get(k->keys, channel);

	if (!a) {
		a = json_array();
		json_object_set_new(k->keys, channel, a);
	}
	json_array_append_new(a, json_real(frame));
}

static json_t *info_obj(struct dispatch *d)
{
	struct live_out_info info[LOOP_LIVE_OUT_MAX];
	uint32_t n = live_outputs(d->lv, info, LOOP_LIVE_OUT_MAX), num, den, hz, i;
	int64_t first, last;
	const char *name, *path;
	struct keys_ctx k = { json_object() };
	json_t *outs = json_array(), *spaces = json_array();
	const char *targets[LOOP_LIVE_OUT_MAX];

	for (i = 0; i < n; i++)
		json_array_append_new(outs, json_pack("{s:s, s:s, s:o, s:o, s:o, s:o, s:b, s:b}",
			"channel", info[i].channel, "unit", info[i].unit, "min", jnum(info[i].min),
			"max", jnum(info[i].max), "vmax", jnum(info[i].vmax),
			"amax", jnum(info[i].amax), "jog", info[i].jog, "teach", info[i].teach));
	live_keys(d->lv, add_key, &k);
	live_span(d->lv, &first, &last, &num, &den, &hz, &name, &path);
	n = live_jog_targets(d->lv, targets, LOOP_LIVE_OUT_MAX);
	for (i = 0; i < n; i++)
		json_array_append_new(spaces, json_string(targets[i]));
	return json_pack("{s:s, s:s, s:I, s:I, s:I, s:I, s:I, s:o, s:o, s:o}", "scene", name,
			 "file", path, "first", (json_int_t)first, "last", (json_int_t)last,
			 "fps_num", (json_int_t)num, "fps_den", (json_int_t)den,
			 "tick_hz", (json_int_t)hz, "outputs", outs, "keys", k.keys,
			 "jog_targets", spaces);
}

/* ---- the lease ---- */

static bool holds(struct dispatch *d, uint64_t client, const struct rpc_req *r)
{
	if (d->holder && d->holder_http)
		return r->lease[0] && !strcmp(r->lease, d->http_lease);
	return d->holder == client;
}

static int lease_take(struct dispatch *d, uint64_t client, bool ws, const struct rpc_req *r,
		      json_t **res)
{
	unsigned char rnd[16];
	int i;

	if (d->holder && !holds(d, client, r))
		return RPC_NOT_LEASED;
	if (ws) {
		d->holder = client;
		d->holder_http = false;
		*res = json_pack("{s:s}", "lease", "connection");
		return 0;
	}
	if (!d->holder) {
		if (getrandom(rnd, sizeof(rnd), 0) != sizeof(rnd))
			return RPC_INTERNAL;
		for (i = 0; i < 16; i++)
			sprintf(d->http_lease + 2 * i, "%02x", rnd[i]);
		d->holder = ++d->http_ids;
		d->holder_http = true;
	}
	d->http_until = hal_mono_ns() + d->lease_ns;
	*res = json_pack("{s:s, s:f}", "lease", d->http_lease, "expires_s", d->lease_ns / 1e9);
	return 0;
}

void dispatch_gone(struct dispatch *d, uint64_t client)
{
	if (d->holder == client && !d->holder_http)
		d->holder = 0;
}

uint64_t dispatch_expire(struct dispatch *d, int64_t now)
{
	uint64_t who = d->holder;

	if (!who || !d->holder_http || now <= d->http_until)
		return 0;
	d->holder = 0;
	return who;
}

/* ---- the server's thread: admission ---- */

static char *answer(const struct rpc_req *r, int code, const char *msg, json_t *res)
{
	char *txt, *rtxt;

	if (!r->has_id) {
		json_decref(res);
		return NULL;
	}
	if (code) {
		json_decref(res);
		return rpc_error_text(r->id, code, msg[0] ? msg : "refused");
	}
	rtxt = res ? json_dumps(res, JSON_COMPACT | JSON_ENCODE_ANY | JSON_REAL_PRECISION(10)) :
		     NULL;
	json_decref(res);
	txt = rpc_result_text(r->id, rtxt ? rtxt : "null");
	free(rtxt);
	return txt;
}

/* The methods answered on the server's thread: 0 with *res, an error code
 * with msg, or 1: a command for the command thread. */
static int admit(struct dispatch *d, uint64_t client, bool ws, struct rpc_req *r, json_t **res,
		 char *msg, size_t size)
{
	struct live_snap snap;
	char ticket[33];
	int rc;

	*res = NULL;
	r->arrival_ns = hal_mono_ns();
	r->client = d->holder ? d->holder : client;
	if (rpc_controls(r->method)) {
		if (d->holder && !holds(d, client, r)) {
			snprintf(msg, size, "another client controls the rig: watch, or wait until "
				 "it gives the lease up");
			return RPC_NOT_LEASED;
		}
		if (!d->holder && ws) { /* a connection's first command takes it */
			d->holder = client;
			d->holder_http = false;
			r->client = client;
		}
		if (d->holder && d->holder_http)
			d->http_until = hal_mono_ns() + d->lease_ns;
	}
	switch (r->method) {
	case RPC_STATUS:
		live_snapshot(d->lv, &snap);
		*res = status_obj(d, &snap);
		return 0;
	case RPC_ESTOP:
		/* here, at once: never behind a command under way */
		live_estop(d->lv);
		*res = json_pack("{s:s}", "state", "e-stopped");
		return 0;
	case RPC_TICKET:
		if (!d->ticket || d->ticket(d->ticket_ctx, ticket)) {
			snprintf(msg, size, "no ticket: no randomness");
			return RPC_INTERNAL;
		}
		*res = json_pack("{s:s, s:i}", "ticket", ticket, "expires_s", 10);
		return 0;
	case RPC_LEASE_TAKE:
		rc = lease_take(d, client, ws, r, res);
		if (rc == RPC_NOT_LEASED)
			snprintf(msg, size, "another client controls the rig");
		return rc;
	case RPC_LEASE_RELEASE:
		*res = json_true();
		if (!d->holder || !holds(d, client, r))
			return 0;
		/* its jogs end: a command, as a client's going is */
		r->client = d->holder;
		d->holder = 0;
		return 1;
	default:
		return 1;
	}
}

char *dispatch_admit(struct dispatch *d, uint64_t client, bool ws, const char *buf, size_t len,
		     struct rpc_req **job)
{
	struct rpc_req *r = malloc(sizeof(*r));
	struct rpc_err e;
	json_t *res = NULL;
	char msg[LIVE_MSG], *txt;
	int code;

	*job = NULL;
	if (!r)
		return rpc_error_text("null", RPC_INTERNAL, "out of memory");
	if (rpc_decode(buf, len, r, &e)) {
		free(r);
		return rpc_error_text(e.id, e.code, e.msg);
	}
	msg[0] = 0;
	code = admit(d, client, ws, r, &res, msg, sizeof(msg));
	if (code == 1) {
		json_decref(res);
		*job = r;
		return NULL;
	}
	txt = answer(r, code, msg, res);
	free(r);
	return txt;
}

/* ---- the command thread ---- */

static int jog_output(struct dispatch *d, const struct rpc_req *r, uint32_t *out, char *msg,
		      size_t size)
{
	struct live_out_info info[LOOP_LIVE_OUT_MAX];
	uint32_t n = live_outputs(d->lv, info, LOOP_LIVE_OUT_MAX), i;

	if (r->out >= 0) {
		*out = (uint32_t)r->out;
		return 0;
	}
	for (i = 0; i < n; i++)
		if (!strcmp(info[i].channel, r->name)) {
			*out = i;
			return 0;
		}
	snprintf(msg, size, "no output '%s'", r->name);
	return -ENOENT;
}

/* Run a command: 0 with *res, or an error code with msg. */
static int run(struct dispatch *d, const struct rpc_req *r, json_t **res, char *msg, size_t size)
{
	struct live *lv = d->lv;
	struct live_snap snap;
	const char *nodes[RPC_NODES_MAX];
	int64_t lat;
	uint32_t out, i;
	int rc = 0;

	*res = NULL;
	switch (r->method) {
	case RPC_INFO:
		*res = info_obj(d);
		return 0;
	case RPC_PING:
		rc = live_ping(lv, r->arrival_ns, &lat, msg, size);
		if (!rc)
			*res = json_pack("{s:f}", "latency_us", lat / 1e3);
		break;
	case RPC_LEASE_RELEASE:
		live_client_gone(lv, r->client);
		*res = json_true();
		return 0;
	case RPC_ENABLE:
		rc = live_enable(lv, msg, size);
		break;
	case RPC_DISABLE:
		rc = live_disable(lv, msg, size);
		break;
	case RPC_STOP:
		rc = live_stop(lv, msg, size);
		break;
	case RPC_RESET:
		rc = live_reset(lv, msg, size);
		break;
	case RPC_JOG:
		if (r->space[0]) {
			rc = live_jog_space(lv, r->client, r->name, r->space, r->axis, r->speed,
					    r->seq, msg, size);
			break;
		}
		rc = jog_output(d, r, &out, msg, size);
		if (!rc)
			rc = live_jog(lv, r->client, out, r->speed, r->seq, msg, size);
		break;
	case RPC_GOTO:
		rc = live_goto(lv, r->frame, msg, size);
		break;
	case RPC_STEP:
		rc = live_step(lv, r->dir, msg, size);
		break;
	case RPC_MOVE:
		rc = live_move(lv, r->pose, r->npose, msg, size);
		break;
	case RPC_PLAY:
		rc = live_play(lv, &r->play, msg, size);
		break;
	case RPC_LOAD:
		rc = live_load(lv, r->name, msg, size);
		break;
	case RPC_SAVE:
		rc = live_save(lv, r->name[0] ? r->name : NULL, msg, size);
		break;
	case RPC_TEACH:
		for (i = 0; i < r->nnodes; i++)
			nodes[i] = r->nodes[i];
		rc = live_teach(lv, r->fframe, nodes, r->nnodes, msg, size);
		if (!rc)
			*res = json_pack("{s:s}", "done", msg);
		break;
	case RPC_TEACH_DELETE:
		rc = live_teach_delete(lv, r->name, r->fframe, msg, size);
		break;
	case RPC_TEACH_MOVE:
		rc = live_teach_move(lv, r->name, r->fframe, r->fto, msg, size);
		break;
	default:
		snprintf(msg, size, "%s: not a command", rpc_method_name(r->method));
		return RPC_INTERNAL;
	}
	if (rc)
		return RPC_REFUSED;
	if (!*res) {
		live_snapshot(lv, &snap);
		*res = json_pack("{s:s}", "state", live_state_name(snap.state));
	}
	return 0;
}

char *dispatch_run(struct dispatch *d, const struct rpc_req *r)
{
	json_t *res = NULL;
	char msg[LIVE_MSG];
	int code;

	msg[0] = 0;
	code = run(d, r, &res, msg, sizeof(msg));
	return answer(r, code, msg, res);
}
