/* SPDX-License-Identifier: MIT */
/*
 * fuzz_dfmoco.c - libFuzzer on DFMoco's line reader (dfmoco/dfm_parse.c):
 * any bytes, split into lines as the port's are, each line parsed. Every
 * line the parser takes must say itself again: printed back in the
 * protocol's form and parsed anew, the same command; and none takes more
 * arguments than its command does.
 */
#include <assert.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "dfmoco/dfm_parse.h"

static void on_line(void *ctx, const char *line, size_t len, bool overlong)
{
	struct dfm_cmd c, again;
	char msg[160], text[DFM_LINE_MAX + 1];
	size_t n;
	uint32_t i;
	int rc;

	(void)ctx;
	assert(len <= DFM_LINE_MAX + 1);
	rc = dfm_parse(line, len, &c, msg, sizeof(msg));
	assert(rc == 0 || rc == -EINVAL || rc == -E2BIG);
	if (rc || overlong)
		return;
	assert(c.kind < DFM_NKINDS && c.nargs <= DFM_ARGS_MAX);
	n = (size_t)snprintf(text, sizeof(text), "%s", dfm_name(c.kind));
	for (i = 0; i < c.nargs; i++)
		n += (size_t)snprintf(text + n, sizeof(text) - n, " %d", c.arg[i]);
	assert(n < sizeof(text));
	assert(dfm_parse(text, n, &again, msg, sizeof(msg)) == 0);
	assert(again.kind == c.kind && again.nargs == c.nargs);
	assert(!memcmp(again.arg, c.arg, c.nargs * sizeof(c.arg[0])));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct dfm_lines l;

	memset(&l, 0, sizeof(l));
	dfm_lines_feed(&l, (const char *)data, size, on_line, NULL);
	return 0;
}
