/* SPDX-License-Identifier: MIT */
/*
 * cli.h - the `strand` command: a table of subcommands and what they share.
 *
 * A subcommand is a struct cli_cmd in its own file (cmd_<name>.c), listed
 * once in commands.c's table; `strand --help` and the dispatcher read the table,
 * so adding one (play, journal, ...) is a new file and a line there. Every
 * subcommand writes through the streams it is given, never stdout/stderr
 * directly, so the tests run them in-process. Exit codes: exitcode.h.
 */
#ifndef STRAND_CLI_H
#define STRAND_CLI_H

#include <stdbool.h>
#include <stdio.h>

#include "load/load.h"
#include "opt.h"

#define STRAND_VERSION "0.1.0"

struct cli_cmd {
	const char *name;
	const char *summary; /* one line for `strand --help` */
	const char *help;    /* the whole `strand <name> --help` text */
	/* argv[0] is the subcommand's name; returns an exit code */
	int (*run)(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err);
};

/* The whole program: `strand [--help|--version] <command> [args]`. */
int cli_main(int argc, char **argv, FILE *out, FILE *err);

/* "strand <cmd>: <message>" and a hint to --help on err; STRAND_EXIT_USAGE. */
int cli_usage(const struct cli_cmd *cmd, FILE *err, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

struct lim_run;
struct rt_opts;

/* --priority N, --cpu N or --no-mlock (name without the dashes) of strand
 * play and strand serve into rt: -1, or the usage error's exit code. */
int cli_rt_option(const struct cli_cmd *cmd, FILE *err, const char *name, const char *arg,
		  struct rt_opts *rt);

/* The run's options against each other (check/run_check.h): -1 when they
 * agree, else the usage error's exit code, said on err. */
int cli_limits_usage(const struct cli_cmd *cmd, FILE *err, const struct lim_run *r);
/* --shutter ANGLE (degrees, 0 < ANGLE <= 360) into *s, the fraction of a
 * frame go-motion exposes (plan/gomo.h): -1, or the usage error's exit
 * code, said on err. */
int cli_shutter_arg(const struct cli_cmd *cmd, FILE *err, const char *arg, mot_q32 *s);
/* The shutter against the scene's timing (run_check_shutter): -1, or the
 * usage error's exit code. */
int cli_shutter_usage(const struct cli_cmd *cmd, FILE *err, const struct mot_timing *t,
		      mot_q32 s);

/* A scene file's error as the one line `file:line:column: message` (or
 * `file: message` when it has no position), and the exit code it means. */
int cli_scene_error(FILE *err, const char *path, const struct load_err *e);

/* Load and build a scene file, reporting any error on err: an exit code. */
int cli_open_scene(const char *path, struct scene_file *sf, struct scene_built *b, FILE *err);

/*
 * Parse options with getopt_long (state reset on each call), handling
 * --help itself. `longopts` must include {"help", no_argument, 0, 'h'}.
 * Calls on_opt for every other option; afterwards *first is the index of
 * the first operand. Returns -1 to go on, else the exit code to return.
 */
struct option;
int cli_options(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err,
		const char *shortopts, const struct option *longopts,
		int (*on_opt)(void *ctx, int opt, const char *arg), void *ctx, int *first);

/*
 * The usual start of a subcommand: options (on_opt may be NULL when there
 * are none but --help), then exactly one operand, the scene file, loaded and
 * built. Returns -1 with *path, sf and b ready (free them), else the exit
 * code to return.
 */
int cli_scene_args(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err,
		   const struct option *longopts,
		   int (*on_opt)(void *ctx, int opt, const char *arg), void *ctx,
		   const char **path, struct scene_file *sf, struct scene_built *b);

/* The exit code of a run of the loop that ended with report r (exitcode.h):
 * chosen by how it ended, never by its message. */
struct loop_report;
int cli_play_exit(const struct loop_report *r);

extern const struct cli_cmd cmd_check, cmd_export, cmd_plot, cmd_info, cmd_play, cmd_journal,
	cmd_import, cmd_serve, cmd_dfmoco;

#endif /* STRAND_CLI_H */
