/* SPDX-License-Identifier: MIT */
/*
 * fuzz_rpc.c - libFuzzer on strand serve's JSON-RPC decoder (serve/rpc.h):
 * any message gives a request checked whole or one JSON-RPC error, never a
 * crash, a leak or a read outside the message; and what the server would
 * answer is valid JSON that jansson reads back.
 */
#include <jansson.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "serve/rpc.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void answer_reads_back(char *txt)
{
	json_t *j = txt ? json_loads(txt, 0, NULL) : NULL;

	if (txt && !j)
		abort(); /* an answer that is not JSON */
	json_decref(j);
	free(txt);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct rpc_req *r = malloc(sizeof(*r));
	struct rpc_err e;

	if (!r)
		return 0;
	if (rpc_decode((const char *)data, size, r, &e)) {
		if (e.code > -32000 && e.code != RPC_PARSE_ERROR && e.code != RPC_INVALID_REQUEST &&
		    e.code != RPC_METHOD_NOT_FOUND && e.code != RPC_INVALID_PARAMS)
			abort(); /* an error code JSON-RPC does not define */
		answer_reads_back(rpc_error_text(e.id, e.code, e.msg));
	} else {
		if (r->method >= RPC_NMETHODS || r->npose > LOOP_LIVE_OUT_MAX ||
		    r->nnodes > RPC_NODES_MAX || !memchr(r->name, 0, sizeof(r->name)))
			abort();
		/* a notification (no id) is never answered */
		if (r->has_id) {
			answer_reads_back(rpc_result_text(r->id, "{\"state\":\"enabled\"}"));
			answer_reads_back(rpc_error_text(r->id, RPC_REFUSED, r->name));
		}
	}
	free(r);
	return 0;
}
