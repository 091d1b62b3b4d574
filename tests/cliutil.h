/* SPDX-License-Identifier: MIT */
/*
 * cliutil.h - the strand command run in-process with its output captured,
 * and the example scenes every suite plays, for the CLI tests.
 */
#ifndef CLIUTIL_H
#define CLIUTIL_H

#include <stddef.h>

extern const char *const cli_examples[];
#define NEXAMPLES 9

struct run {
	int rc;
	char *out, *err;
	size_t out_len, err_len;
};

/* Run `strand args...` (args split at spaces) with its output captured. */
void strand(struct run *r, const char *args);
void run_free(struct run *r);

#endif /* CLIUTIL_H */
