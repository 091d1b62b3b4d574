/* SPDX-License-Identifier: MIT */
/* cliutil.c - the strand command in-process for the tests (see cliutil.h). */
#include "cliutil.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

