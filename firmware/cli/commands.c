/* SPDX-License-Identifier: MIT */
/* commands.c - the `strand` dispatcher: the table of subcommands, --help
 * and --version. A new subcommand is a file cmd_<name>.c and a line here. */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "exitcode.h"
#include "rig/drv_gpio.h"

/* Every subcommand, in the order `strand --help` lists them. */
static const struct cli_cmd *const commands[] = {
	&cmd_check, &cmd_export, &cmd_plot, &cmd_info, &cmd_play, &cmd_serve, &cmd_dfmoco,
	&cmd_journal,
	&cmd_import,
	NULL,
};

static void main_help(FILE *out)
{
	size_t i;

	fprintf(out, "usage: strand <command> [options] SCENE.yaml\n"
		     "       strand --version | --help\n\n"
		     "Keyframed motion for servo rigs: check, export, plot and describe scene files,\n"
		     "and play them in real time, one camera trigger per frame.\n\n"
		     "commands:\n");
	for (i = 0; commands[i]; i++)
		fprintf(out, "  %-8s %s\n", commands[i]->name, commands[i]->summary);
	fprintf(out, "\n'strand <command> --help' describes a command.\n"
		     "exit codes: 0 ok, 1 limits violated, 2 invalid scene, 3 usage, 4 I/O,\n"
		     "            5 play stopped by a signal, 6 e-stop, 7 device fault,\n"
		     "            8 internal error (see the README)\n");
}

int cli_main(int argc, char **argv, FILE *out, FILE *err)
{
	size_t i;

	if (argc < 2) {
		main_help(err);
		return STRAND_EXIT_USAGE;
	}
	if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
		main_help(out);
		return STRAND_EXIT_OK;
	}
	if (!strcmp(argv[1], "--version")) {
		fprintf(out, "strand %s (libgpiod %s)\n", STRAND_VERSION, rig_gpio_lib_version());
		return STRAND_EXIT_OK;
	}
	for (i = 0; commands[i]; i++)
		if (!strcmp(argv[1], commands[i]->name))
			return commands[i]->run(commands[i], argc - 1, argv + 1, out, err);
	fprintf(err, "strand: unknown command '%s' (try 'strand --help')\n", argv[1]);
	return STRAND_EXIT_USAGE;
}
