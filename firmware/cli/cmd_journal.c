/* SPDX-License-Identifier: MIT */
/* cmd_journal.c - `strand journal FILE`: a frame journal as CSV (journal.h). */
#include <getopt.h>

#include "cli.h"
#include "exitcode.h"
#include "journal/journal.h"

/* only --help, which cli_options answers itself */
static int no_opt(void *ctx, int opt, const char *arg)
{
	return -1;
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	static const struct option opts[] = { { "help", no_argument, NULL, 'h' }, { 0 } };
	char msg[512];
	int first, rc;

	rc = cli_options(cmd, argc, argv, out, err, "h", opts, no_opt, NULL, &first);
	if (rc >= 0)
		return rc;
	if (argc - first != 1)
		return cli_usage(cmd, err, "expected one journal file");
	if (journal_csv(argv[first], out, msg, sizeof(msg))) {
		fprintf(err, "strand journal: %s\n", msg);
		return STRAND_EXIT_IO;
	}
	return STRAND_EXIT_OK;
}

const struct cli_cmd cmd_journal = {
	.name = "journal",
	.summary = "print the frame journal of a strand play run as CSV",
	.help = "usage: strand journal FILE\n"
		"\n"
		"Prints a frame journal written by strand play as CSV: a header row, then one\n"
		"row per trigger edge: frame, timecode (SMPTE; drop-frame at 30000/1001 and\n"
		"60000/1001), tick, trigger (its index), state (fired; armed for the one frame a\n"
		"kill caught between its record and its edge), due_ns (when its tick was due),\n"
		"mono_ns (CLOCK_MONOTONIC right after the edge went out), late_us, wall (UTC),\n"
		"ferr and ferr_channel (the worst following error while the frame lasted), then\n"
		"every output's setpoint in the scene file's units (degrees for angles).\n"
		"\n"
		"exit codes: 0 ok, 3 usage, 4 the file cannot be read or is not a journal.\n",
	.run = run,
};
