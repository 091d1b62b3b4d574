/* SPDX-License-Identifier: MIT */
/* rpc.c - JSON-RPC 2.0 requests decoded and checked, answers encoded (rpc.h). */
#include "rpc.h"

#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const method_names[RPC_NMETHODS] = {
	[RPC_STATUS] = "status",   [RPC_INFO] = "info",
	[RPC_PING] = "ping",       [RPC_LEASE_TAKE] = "lease.take",
	[RPC_LEASE_RELEASE] = "lease.release", [RPC_TICKET] = "ticket",
	[RPC_ENABLE] = "enable",   [RPC_DISABLE] = "disable",
	[RPC_STOP] = "stop",       [RPC_ESTOP] = "estop",
	[RPC_RESET] = "reset",     [RPC_JOG] = "jog",
	[RPC_GOTO] = "goto",       [RPC_STEP] = "step",
	[RPC_MOVE] = "move",       [RPC_PLAY] = "play",
	[RPC_LOAD] = "load",       [RPC_SAVE] = "save",
	[RPC_TEACH] = "teach",     [RPC_TEACH_DELETE] = "teach.delete",
	[RPC_TEACH_MOVE] = "teach.move",
};

/* The parameters each method takes (besides "lease"). */
static const char *const method_params[RPC_NMETHODS] = {
	[RPC_JOG] = "output node space axis speed seq",
	[RPC_GOTO] = "frame",
	[RPC_STEP] = "dir",
	[RPC_MOVE] = "pose",
	[RPC_PLAY] = "mode from to frames loop ping_pong passes duration settle exposure timeout "
		     "shutter",
	[RPC_LOAD] = "file",
	[RPC_SAVE] = "file",
	[RPC_TEACH] = "frame nodes",
	[RPC_TEACH_DELETE] = "node frame",
	[RPC_TEACH_MOVE] = "node from to",
};

const char *rpc_method_name(enum rpc_method m)
{
	return m < RPC_NMETHODS ? method_names[m] : "?";
}

bool rpc_controls(enum rpc_method m)
{
	return m >= RPC_ENABLE && m != RPC_ESTOP;
}

static int fail(struct rpc_err *e, int code, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

static int fail(struct rpc_err *e, int code, const char *fmt, ...)
{
	va_list ap;

	e->code = code;
	va_start(ap, fmt);
	vsnprintf(e->msg, sizeof(e->msg), fmt, ap);
	va_end(ap);
	return -1;
}

/* A whole-word member of a space-separated list. */
static bool listed(const char *list, const char *key)
{
	size_t n = strlen(key);
	const char *p = list;

	/* an empty name is no word (and strstr finds it everywhere: the
	 * fuzzer's hang of a server by {"params": {"": 0}}) */
	if (!n)
		return false;
	while (list && (p = strstr(p, key))) {
		if ((p == list || p[-1] == ' ') && (p[n] == ' ' || !p[n]))
			return true;
		p += n;
	}
	return false;
}

static int num(struct rpc_err *e, json_t *p, const char *key, double min, double max,
	       bool required, double *out)
{
	json_t *v = json_object_get(p, key);

	if (!v) {
		if (required)
			return fail(e, RPC_INVALID_PARAMS, "missing parameter '%s'", key);
		return 0;
	}
	if (!json_is_number(v))
		return fail(e, RPC_INVALID_PARAMS, "'%s': a number", key);
	*out = json_number_value(v);
	if (!(*out >= min && *out <= max))
		return fail(e, RPC_INVALID_PARAMS, "'%s' %.17g: outside %.17g to %.17g", key, *out,
			    min, max);
	return 0;
}

static int whole(struct rpc_err *e, json_t *p, const char *key, int64_t min, int64_t max,
		 bool required, int64_t *out)
{
	json_t *v = json_object_get(p, key);

	if (!v) {
		if (required)
			return fail(e, RPC_INVALID_PARAMS, "missing parameter '%s'", key);
		return 0;
	}
	if (!json_is_integer(v))
		return fail(e, RPC_INVALID_PARAMS, "'%s': a whole number", key);
	*out = json_integer_value(v);
	if (*out < min || *out > max)
		return fail(e, RPC_INVALID_PARAMS, "'%s' %lld: outside %lld to %lld", key,
			    (long long)*out, (long long)min, (long long)max);
	return 0;
}

static int flag(struct rpc_err *e, json_t *p, const char *key, bool *out)
{
	json_t *v = json_object_get(p, key);

	if (!v)
		return 0;
	if (!json_is_boolean(v))
		return fail(e, RPC_INVALID_PARAMS, "'%s': true or false", key);
	*out = json_is_true(v);
	return 0;
}

static int text(struct rpc_err *e, json_t *v, const char *key, char *out, size_t size)
{
	size_t n;

	if (!json_is_string(v))
		return fail(e, RPC_INVALID_PARAMS, "'%s': a string", key);
	n = json_string_length(v);
	if (!n || n >= size || memchr(json_string_value(v), 0, n))
		return fail(e, RPC_INVALID_PARAMS, "'%s': 1 to %zu characters, no NUL", key,
			    size - 1);
	memcpy(out, json_string_value(v), n + 1);
	return 0;
}

static int str(struct rpc_err *e, json_t *p, const char *key, bool required, char *out,
	       size_t size)
{
	json_t *v = json_object_get(p, key);

	if (!v) {
		if (required)
			return fail(e, RPC_INVALID_PARAMS, "missing parameter '%s'", key);
		return 0;
	}
	return text(e, v, key, out, size);
}

static int play_params(struct rpc_err *e, json_t *p, struct rpc_req *r)
{
	struct live_play *pl = &r->play;
	char mode[16] = "continuous";

	pl->settle_ms = 200;
	pl->exposure_ms = 100;
	pl->timeout_s = 10;
	if (str(e, p, "mode", false, mode, sizeof(mode)))
		return -1;
	if (strcmp(mode, "continuous") && strcmp(mode, "step"))
		return fail(e, RPC_INVALID_PARAMS, "'mode' %s: continuous or step", mode);
	pl->step = !strcmp(mode, "step");
	pl->has_from = json_object_get(p, "from") != NULL;
	pl->has_to = json_object_get(p, "to") != NULL;
	if (whole(e, p, "from", 0, INT32_MAX, false, &pl->from) ||
	    whole(e, p, "to", 0, INT32_MAX, false, &pl->to) ||
	    whole(e, p, "passes", 1, INT32_MAX, false, &pl->passes) ||
	    flag(e, p, "loop", &pl->loop) || flag(e, p, "ping_pong", &pl->ping_pong) ||
	    num(e, p, "duration", 1e-9, 1e9, false, &pl->duration_s) ||
	    num(e, p, "settle", 0, 1e12, false, &pl->settle_ms) ||
	    num(e, p, "exposure", 0, 1e12, false, &pl->exposure_ms) ||
	    num(e, p, "timeout", 1e-9, 1e9, false, &pl->timeout_s) ||
	    num(e, p, "shutter", 1e-9, 360, false, &pl->shutter) ||
	    str(e, p, "frames", false, r->frames, sizeof(r->frames)))
		return -1;
	pl->frames = r->frames[0] ? r->frames : NULL;
	return 0;
}

static int params(struct rpc_err *e, json_t *p, struct rpc_req *r)
{
	const char *key;
	json_t *v;
	size_t i;

	json_object_foreach(p, key, v) {
		if (strcmp(key, "lease") && !listed(method_params[r->method], key))
			return fail(e, RPC_INVALID_PARAMS, "%s takes no parameter '%.64s'",
				    method_names[r->method], key);
	}
	if (str(e, p, "lease", false, r->lease, sizeof(r->lease)))
		return -1;
	switch (r->method) {
	case RPC_JOG:
		v = json_object_get(p, "output");
		if (json_object_get(p, "node")) {
			if (v)
				return fail(e, RPC_INVALID_PARAMS, "'output' or 'node', not both");
			if (str(e, p, "node", true, r->name, sizeof(r->name)) ||
			    str(e, p, "space", true, r->space, sizeof(r->space)) ||
			    str(e, p, "axis", true, r->axis, sizeof(r->axis)))
				return -1;
			if (strcmp(r->space, "local") && strcmp(r->space, "world"))
				return fail(e, RPC_INVALID_PARAMS, "'space' %s: local or world",
					    r->space);
			if (!listed("x y z rx ry rz truck boom dolly tilt pan roll", r->axis))
				return fail(e, RPC_INVALID_PARAMS, "'axis' %s: x, y, z, rx, ry, "
					    "rz, truck, boom, dolly, tilt, pan or roll", r->axis);
		} else if (json_is_integer(v)) {
			if (json_integer_value(v) < 0 || json_integer_value(v) >= LOOP_LIVE_OUT_MAX)
				return fail(e, RPC_INVALID_PARAMS, "'output' %lld: 0 to %d",
					    (long long)json_integer_value(v),
					    LOOP_LIVE_OUT_MAX - 1);
			r->out = (int32_t)json_integer_value(v);
		} else if (v) {
			if (text(e, v, "output", r->name, sizeof(r->name)))
				return -1;
		} else {
			return fail(e, RPC_INVALID_PARAMS,
				    "missing parameter 'output' (or 'node')");
		}
		if (!r->space[0] && (json_object_get(p, "space") || json_object_get(p, "axis")))
			return fail(e, RPC_INVALID_PARAMS, "'space' and 'axis' go with 'node'");
		{
			int64_t seq = 0;

			if (num(e, p, "speed", -1, 1, true, &r->speed) ||
			    whole(e, p, "seq", 1, INT64_C(1) << 53, true, &seq))
				return -1;
			r->seq = (uint64_t)seq;
		}
		return 0;
	case RPC_GOTO:
		return whole(e, p, "frame", 0, INT32_MAX, true, &r->frame);
	case RPC_STEP: {
		int64_t d = 0;

		if (whole(e, p, "dir", -1, 1, true, &d))
			return -1;
		if (!d)
			return fail(e, RPC_INVALID_PARAMS, "'dir': 1 or -1");
		r->dir = (int)d;
		return 0;
	}
	case RPC_MOVE:
		v = json_object_get(p, "pose");
		if (!json_is_array(v) || json_array_size(v) > LOOP_LIVE_OUT_MAX ||
		    !json_array_size(v))
			return fail(e, RPC_INVALID_PARAMS, "'pose': an array of 1 to %d numbers "
				    "(null: where an output stands)", LOOP_LIVE_OUT_MAX);
		r->npose = (uint32_t)json_array_size(v);
		for (i = 0; i < r->npose; i++) {
			json_t *x = json_array_get(v, i);

			if (json_is_null(x))
				r->pose[i] = NAN;
			else if (json_is_number(x) && isfinite(json_number_value(x)) &&
				 fabs(json_number_value(x)) < 1e15)
				r->pose[i] = json_number_value(x);
			else
				return fail(e, RPC_INVALID_PARAMS, "'pose'[%zu]: a number or null",
					    i);
		}
		return 0;
	case RPC_PLAY:
		return play_params(e, p, r);
	case RPC_LOAD:
		return str(e, p, "file", true, r->name, sizeof(r->name));
	case RPC_SAVE:
		return str(e, p, "file", false, r->name, sizeof(r->name));
	case RPC_TEACH:
		if (num(e, p, "frame", 0, 1073741823, true, &r->fframe))
			return -1;
		v = json_object_get(p, "nodes");
		if (!v)
			return 0;
		if (!json_is_array(v) || json_array_size(v) > RPC_NODES_MAX || !json_array_size(v))
			return fail(e, RPC_INVALID_PARAMS, "'nodes': an array of 1 to %d names",
				    RPC_NODES_MAX);
		r->nnodes = (uint32_t)json_array_size(v);
		for (i = 0; i < r->nnodes; i++)
			if (text(e, json_array_get(v, i), "nodes", r->nodes[i], RPC_NAME_MAX))
				return -1;
		return 0;
	case RPC_TEACH_DELETE:
		return str(e, p, "node", true, r->name, sizeof(r->name)) ||
		       num(e, p, "frame", 0, 1073741823, true, &r->fframe);
	case RPC_TEACH_MOVE:
		return str(e, p, "node", true, r->name, sizeof(r->name)) ||
		       num(e, p, "from", 0, 1073741823, true, &r->fframe) ||
		       num(e, p, "to", 0, 1073741823, true, &r->fto);
	default:
		return 0;
	}
}

int rpc_decode(const char *buf, size_t len, struct rpc_req *r, struct rpc_err *e)
{
	json_error_t je;
	json_t *root, *v, *p;
	const char *m;
	char *idtext;
	int rc = -1, i;

	memset(r, 0, sizeof(*r));
	r->out = -1;
	memset(e, 0, sizeof(*e));
	snprintf(e->id, sizeof(e->id), "null");
	if (len > RPC_MAX_BYTES)
		return fail(e, RPC_OVERSIZED, "message of %zu bytes: at most %d", len,
			    RPC_MAX_BYTES);
	root = json_loadb(buf, len, JSON_REJECT_DUPLICATES, &je);
	if (!root)
		return fail(e, RPC_PARSE_ERROR, "not JSON: %s at line %d column %d", je.text,
			    je.line, je.column);
	if (!json_is_object(root)) {
		fail(e, RPC_INVALID_REQUEST, "a request is an object (batches are not taken)");
		goto out;
	}
	v = json_object_get(root, "id");
	if (v) {
		if (!json_is_string(v) && !json_is_integer(v) && !json_is_null(v)) {
			fail(e, RPC_INVALID_REQUEST, "'id': a string, a whole number or null");
			goto out;
		}
		idtext = json_dumps(v, JSON_ENCODE_ANY | JSON_COMPACT);
		if (!idtext || strlen(idtext) >= sizeof(r->id)) {
			free(idtext);
			fail(e, RPC_INVALID_REQUEST, "'id': at most %zu characters",
			     sizeof(r->id) - 3);
			goto out;
		}
		snprintf(r->id, sizeof(r->id), "%s", idtext);
		snprintf(e->id, sizeof(e->id), "%s", idtext);
		free(idtext);
		r->has_id = true;
	}
	json_object_foreach(root, m, v) {
		if (strcmp(m, "jsonrpc") && strcmp(m, "method") && strcmp(m, "params") &&
		    strcmp(m, "id")) {
			fail(e, RPC_INVALID_REQUEST, "unknown member '%.64s'", m);
			goto out;
		}
	}
	v = json_object_get(root, "jsonrpc");
	if (!json_is_string(v) || strcmp(json_string_value(v), "2.0")) {
		fail(e, RPC_INVALID_REQUEST, "'jsonrpc' must be \"2.0\"");
		goto out;
	}
	v = json_object_get(root, "method");
	if (!json_is_string(v)) {
		fail(e, RPC_INVALID_REQUEST, "'method': a string");
		goto out;
	}
	m = json_string_value(v);
	for (i = 0; i < RPC_NMETHODS; i++)
		if (!strcmp(m, method_names[i]))
			break;
	if (i == RPC_NMETHODS) {
		fail(e, RPC_METHOD_NOT_FOUND, "no method '%.64s'", m);
		goto out;
	}
	r->method = (enum rpc_method)i;
	p = json_object_get(root, "params");
	if (p && !json_is_object(p)) {
		fail(e, RPC_INVALID_PARAMS, "'params': an object of named parameters");
		goto out;
	}
	if (!p)
		p = json_object();
	else
		json_incref(p);
	rc = params(e, p, r) ? -1 : 0;
	json_decref(p);
out:
	json_decref(root);
	return rc;
}

char *rpc_error_text(const char *id, int code, const char *msg)
{
	json_t *o = json_pack("{s:s, s:{s:i, s:s}}", "jsonrpc", "2.0", "error", "code", code,
			      "message", msg);
	json_t *idv = json_loads(id, JSON_DECODE_ANY, NULL);
	char *s;

	if (!o)
		return NULL;
	json_object_set_new(o, "id", idv ? idv : json_null());
	s = json_dumps(o, JSON_COMPACT);
	json_decref(o);
	return s;
}

char *rpc_result_text(const char *id, const char *result)
{
	size_t n = strlen(id) + strlen(result) + 40;
	char *s = malloc(n);

	if (s)
		snprintf(s, n, "{\"jsonrpc\":\"2.0\",\"id\":%s,\"result\":%s}", id, result);
	return s;
}
