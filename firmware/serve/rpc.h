/* SPDX-License-Identifier: MIT */
/*
 * rpc.h - strand serve's JSON-RPC 2.0 messages: a request decoded and
 * checked whole before anything is done (method, every parameter's type
 * and range, no unknown parameter), and the answers encoded. The decoder
 * is pure: bytes in, a struct rpc_req or a JSON-RPC error out (fuzzed:
 * tests/fuzz/fuzz_rpc.c). JSON by jansson: 64-bit integers, doubles parsed
 * as doubles, duplicate keys refused.
 *
 * Methods and their parameters (README "strand serve" lists them):
 *
 *   status, info, ping, lease.take, lease.release, ticket
 *   enable, disable, stop, estop, reset
 *   jog       {output: index or channel name, speed: -1..1, seq: 1..2^53}
 *             or {node: "camera" or a free node's name, space: local|world,
 *              axis: x|y|z|rx|ry|rz|truck|boom|dolly|tilt|pan|roll, speed, seq}
 *   goto      {frame: 0..2^31-1}
 *   step      {dir: 1 or -1}
 *   move      {pose: [values, file units; null: where it stands]}
 *   play      {mode: continuous|step, from, to, frames, loop, ping_pong,
 *              passes, duration, settle, exposure, timeout}
 *   load      {file}          save {file?}
 *   teach     {frame, nodes?: [names]}
 *   teach.delete {node, frame}    teach.move {node, from, to}
 *
 * Every method takes an optional "lease" (a string of lease.take's) for
 * clients without a connection of their own (POST /rpc).
 */
#ifndef STRAND_RPC_H
#define STRAND_RPC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "live/live.h"

/* The largest message taken, over HTTP or a WebSocket. */
#define RPC_MAX_BYTES 65536
#define RPC_NAME_MAX 128
#define RPC_NODES_MAX 32

/* JSON-RPC 2.0's error codes, and strand's (-32000 and below). */
enum rpc_code {
	RPC_PARSE_ERROR = -32700,
	RPC_INVALID_REQUEST = -32600,
	RPC_METHOD_NOT_FOUND = -32601,
	RPC_INVALID_PARAMS = -32602,
	RPC_INTERNAL = -32603,
	RPC_REFUSED = -32000,    /* the command was refused: the message says why */
	RPC_NOT_LEASED = -32001, /* another client controls the rig */
	RPC_OVERSIZED = -32002,
};

enum rpc_method {
	RPC_STATUS, RPC_INFO, RPC_PING, RPC_LEASE_TAKE, RPC_LEASE_RELEASE, RPC_TICKET,
	RPC_ENABLE, RPC_DISABLE, RPC_STOP, RPC_ESTOP, RPC_RESET,
	RPC_JOG, RPC_GOTO, RPC_STEP, RPC_MOVE, RPC_PLAY,
	RPC_LOAD, RPC_SAVE, RPC_TEACH, RPC_TEACH_DELETE, RPC_TEACH_MOVE,
	RPC_NMETHODS,
};

struct rpc_req {
	enum rpc_method method;
	bool has_id;          /* a notification has none: no answer */
	char id[80];          /* the id as JSON text ("1", "\"a\"", "null") */
	char lease[40];       /* "" when not given */
	uint64_t client;      /* who sends it: the lease holder's id (dispatch) */
	int64_t arrival_ns;   /* hal_mono_ns() when the server had it whole (dispatch) */
	/* jog */
	int32_t out;          /* -1: by name */
	char name[RPC_NAME_MAX]; /* jog's channel, load/save's file, teach's node */
	double speed;
	uint64_t seq;
	char space[8];        /* jog of a node or the camera: "local" or "world", else "" */
	char axis[8];         /* ... x y z rx ry rz, or truck boom dolly tilt pan roll */
	/* goto, step, teach, teach.delete, teach.move */
	int64_t frame;
	double fframe, fto;
	int dir;
	/* move */
	uint32_t npose;
	double pose[LOOP_LIVE_OUT_MAX];
	/* play */
	struct live_play play;
	char frames[256];
	/* teach */
	uint32_t nnodes;
	char nodes[RPC_NODES_MAX][RPC_NAME_MAX];
};

struct rpc_err {
	int code;             /* enum rpc_code */
	char msg[256];
	char id[80];          /* the id when it could be read, else "null" */
};

/* Decode one request. 0, or -1 with *e set (the answer to send). */
int rpc_decode(const char *buf, size_t len, struct rpc_req *r, struct rpc_err *e);

const char *rpc_method_name(enum rpc_method m);

/* Methods that move the rig or change the scene: they need the lease. */
bool rpc_controls(enum rpc_method m);

/* The answers, as JSON text (malloc'd, NULL when out of memory). */
char *rpc_error_text(const char *id, int code, const char *msg);
/* result: JSON text of the result value */
char *rpc_result_text(const char *id, const char *result);

#endif /* STRAND_RPC_H */
