/* SPDX-License-Identifier: MIT */
/* cliutil.c - the strand command in-process for the tests (see cliutil.h). */
#include "cliutil.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <setjmp.h>
#include <cmocka.h>

#include "cli/cli.h"

const char *const cli_examples[NEXAMPLES] = {
	"examples/robot_arm.yaml",  "examples/propeller.yaml", "examples/camera_move.yaml",
	"examples/cycled_data.yaml", "examples/curves.yaml", "examples/kinetic_surface.yaml",
	"examples/fountain_lights.yaml", "examples/flock_heads.yaml", "examples/cloth_winches.yaml",
};

void strand(struct run *r, const char *args)
{
	char *argv[32], buf[1024], *save = NULL, *tok;
	int argc = 0;
	FILE *out, *err;

	snprintf(buf, sizeof(buf), "strand %s", args);
	for (tok = strtok_r(buf, " ", &save); tok && argc < 31; tok = strtok_r(NULL, " ", &save))
		argv[argc++] = tok;
	argv[argc] = NULL;
	out = open_memstream(&r->out, &r->out_len);
	err = open_memstream(&r->err, &r->err_len);
	assert_non_null(out);
	assert_non_null(err);
	r->rc = cli_main(argc, argv, out, err);
	fclose(out);
	fclose(err);
}

void run_free(struct run *r)
{
	free(r->out);
	free(r->err);
}


void tmp_file(char *out, size_t size, const char *ext, const void *data, size_t len)
{
	char path[] = "/tmp/strand-test-XXXXXX";
	int fd = mkstemp(path);
	FILE *f;

	assert_true(fd >= 0);
	close(fd);
	snprintf(out, size, "%s%s", path, ext);
	assert_int_equal(rename(path, out), 0);
	f = fopen(out, "wb");
	assert_non_null(f);
	assert_int_equal(fwrite(data, 1, len, f), len);
	fclose(f);
}

void import_error(const char *ext, const void *data, size_t len, const char *want)
{
	char path[64], args[128];
	struct run r;

	tmp_file(path, sizeof(path), ext, data, len);
	snprintf(args, sizeof(args), "import %s", path);
	strand(&r, args);
	unlink(path);
	if (r.rc != 2 || !strstr(r.err, want))
		fprintf(stderr, "import of %s: exit %d: %s", want, r.rc, r.err);
	assert_int_equal(r.rc, 2);
	assert_non_null(strstr(r.err, want));
	assert_true(!strncmp(r.err, path, strlen(path)));
	assert_int_equal(strchr(r.err, '\n') - r.err + 1, (long)strlen(r.err));
	run_free(&r);
}
