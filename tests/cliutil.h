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

/* A new file /tmp/strand-test-XXXXXX<ext> holding len bytes of data; its
 * name in out (size bytes). The caller unlinks it. */
void tmp_file(char *out, size_t size, const char *ext, const void *data, size_t len);

/* `strand import` of a file (extension ext) holding data: exit 2 and one
 * line on stderr, starting with the file's name and containing want. */
void import_error(const char *ext, const void *data, size_t len, const char *want);

#endif /* CLIUTIL_H */
