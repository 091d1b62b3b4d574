/* SPDX-License-Identifier: MIT */
/* cli.c - what the subcommands share: usage errors, scene errors, option
 * parsing (the dispatcher is commands.c). */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "check/run_check.h"
#include "exitcode.h"
#include "opt.h"
#include "plan/gomo.h"
#include "play/rt.h"

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

int cli_limits_usage(const struct cli_cmd *cmd, FILE *err, const struct lim_run *r)
{
	char msg[160];

	return run_check_options(r, msg, sizeof(msg)) ? cli_usage(cmd, err, "%s", msg) : -1;
}

int cli_shutter_arg(const struct cli_cmd *cmd, FILE *err, const char *arg, mot_q32 *s)
{
	double a;

	if (!opt_double(arg, 0, 360, &a) || !gomo_shutter_of_angle(a, s))
		return cli_usage(cmd, err, "--shutter %s: a shutter angle in degrees, above 0 and "
				 "at most 360", arg);
	return -1;
}

int cli_shutter_usage(const struct cli_cmd *cmd, FILE *err, const struct mot_timing *t,
		      mot_q32 s)
{
	char msg[200];

	return run_check_shutter(t, s, msg, sizeof(msg)) ? cli_usage(cmd, err, "%s", msg) : -1;
}

int cli_rt_option(const struct cli_cmd *cmd, FILE *err, const char *name, const char *arg,
		  struct rt_opts *rt)
{
	long long v;

	if (!strcmp(name, "no-mlock")) {
		rt->lock_memory = false;
	} else if (!strcmp(name, "priority")) {
		if (!opt_long(arg, 0, 99, &v))
			return cli_usage(cmd, err, "--priority %s: 0 to 99", arg);
		rt->priority = (int)v;
	} else {
		if (!opt_long(arg, 0, 1023, &v))
			return cli_usage(cmd, err, "--cpu %s: a CPU number", arg);
		rt->cpu = (int)v;
	}
	return -1;
}
