/* SPDX-License-Identifier: MIT */
/* main.c - the strand program (everything else is in cli.c and cmd_*.c, so
 * that the tests can run it in-process). */
#include <stdio.h>

#include "cli.h"
#include "exitcode.h"

int main(int argc, char **argv)
{
	int rc = cli_main(argc, argv, stdout, stderr);

	/* a full disk or a closed pipe shows up only when stdout is flushed */
	if (fflush(stdout) != 0 && rc == 0)
		rc = STRAND_EXIT_IO;
	return rc;
}
