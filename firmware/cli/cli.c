/* SPDX-License-Identifier: MIT */
/* cli.c - the `strand` dispatcher and the helpers its subcommands share. */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "exitcode.h"

/* Every subcommand, in the order `strand --help` lists them. */
static const struct cli_cmd *const commands[] = {
	&cmd_check, &cmd_export, &cmd_plot, &cmd_info, &cmd_play, &cmd_journal, NULL,
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
		fprintf(out, "strand %s\n", STRAND_VERSION);
		return STRAND_EXIT_OK;
	}
	for (i = 0; commands[i]; i++)
		if (!strcmp(argv[1], commands[i]->name))
			return commands[i]->run(commands[i], argc - 1, argv + 1, out, err);
	fprintf(err, "strand: unknown command '%s' (try 'strand --help')\n", argv[1]);
	return STRAND_EXIT_USAGE;
}

int cli_usage(const struct cli_cmd *cmd, FILE *err, const char *fmt, ...)
{
	va_list ap;

	fprintf(err, "strand %s: ", cmd->name);
	va_start(ap, fmt);
	vfprintf(err, fmt, ap);
	va_end(ap);
	fprintf(err, "\nTry 'strand %s --help'.\n", cmd->name);
	return STRAND_EXIT_USAGE;
}

int cli_scene_error(FILE *err, const char *path, const struct load_err *e)
{
	if (e->line)
		fprintf(err, "%s:%u:%u: %s\n", path, e->line, e->col, e->msg);
	else
		fprintf(err, "%s: %s\n", path, e->msg);
	switch (e->code) {
	case -EINVAL:
	case -ERANGE:
	case -EBADMSG:
	case -EFBIG:
		return STRAND_EXIT_SCENE;
	case -ENOMEM:
		return STRAND_EXIT_INTERNAL;
	default:
		return STRAND_EXIT_IO;
	}
}

int cli_open_scene(const char *path, struct scene_file *sf, struct scene_built *b, FILE *err)
{
	struct load_err e;

	memset(b, 0, sizeof(*b));
	if (scene_file_load(sf, path, &e))
		return cli_scene_error(err, path, &e);
	if (scene_file_build(sf, b, &e)) {
		scene_file_free(sf);
		return cli_scene_error(err, path, &e);
	}
	return STRAND_EXIT_OK;
}

int cli_options(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err,
		const char *shortopts, const struct option *longopts,
		int (*on_opt)(void *ctx, int opt, const char *arg), void *ctx, int *first)
{
	char spec[64];
	int c, rc;

	/* ':': report a missing argument as ':'; options may follow operands */
	snprintf(spec, sizeof(spec), ":%s", shortopts);
	optind = 0; /* glibc: a full reset, so that a second call parses afresh */
	opterr = 0;
	while ((c = getopt_long(argc, argv, spec, longopts, NULL)) != -1) {
		switch (c) {
		case 'h':
			fputs(cmd->help, out);
			return STRAND_EXIT_OK;
		case ':':
			return cli_usage(cmd, err, "option '%s' needs a value", argv[optind - 1]);
		case '?':
			return cli_usage(cmd, err, "unknown option '%s'", argv[optind - 1]);
		default:
			rc = on_opt(ctx, c, optarg);
			if (rc >= 0)
				return rc;
		}
	}
	*first = optind;
	return -1;
}

static int no_opt(void *ctx, int opt, const char *arg)
{
	return -1;
}

int cli_scene_args(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err,
		   const struct option *longopts,
		   int (*on_opt)(void *ctx, int opt, const char *arg), void *ctx,
		   const char **path, struct scene_file *sf, struct scene_built *b)
{
	int first, rc;

	rc = cli_options(cmd, argc, argv, out, err, "ho:", longopts, on_opt ? on_opt : no_opt,
			 ctx, &first);
	if (rc >= 0)
		return rc;
	if (argc - first != 1)
		return cli_usage(cmd, err, "expected one scene file");
	*path = argv[first];
	rc = cli_open_scene(*path, sf, b, err);
	return rc ? rc : -1;
}

bool cli_parse_long(const char *s, long long min, long long max, long long *out)
{
	char *end;

	errno = 0;
	*out = strtoll(s, &end, 10);
	return *s && !*end && !errno && *out >= min && *out <= max;
}
