/* SPDX-License-Identifier: MIT */
/*
 * live_opts.h - the options of the commands that run a live session
 * (strand serve, strand dfmoco): where to listen, the clock, the loop
 * thread's scheduling, the jog's dead-man. One table of them and one
 * handler, so that they read and refuse alike in both.
 */
#ifndef STRAND_CLI_LIVE_OPTS_H
#define STRAND_CLI_LIVE_OPTS_H

#include <getopt.h>
#include <stdio.h>

#include "cli.h"
#include "live/live.h"

/* The options' numbers, above every command's own. */
enum {
	CLI_LIVE_CLOCK = 1024, CLI_LIVE_PRIORITY, CLI_LIVE_CPU, CLI_LIVE_NO_MLOCK,
	CLI_LIVE_DEADMAN,
};

/* Their entries of a getopt_long table. */
#define CLI_LIVE_OPTIONS                                                  \
	{ "clock", required_argument, NULL, CLI_LIVE_CLOCK },             \
	{ "priority", required_argument, NULL, CLI_LIVE_PRIORITY },       \
	{ "cpu", required_argument, NULL, CLI_LIVE_CPU },                 \
	{ "no-mlock", no_argument, NULL, CLI_LIVE_NO_MLOCK },             \
	{ "deadman", required_argument, NULL, CLI_LIVE_DEADMAN }

/* The loop thread's defaults, as strand play's (priority 80, memory
 * locked, PM QoS), into o. */
void cli_live_defaults(struct live_opts *o);

/* One of CLI_LIVE_*: -1 taken, the usage error's exit code, or -2 when
 * opt is none of them. */
int cli_live_opt(const struct cli_cmd *cmd, FILE *err, int opt, const char *arg,
		 struct live_opts *o);

/* --listen ADDRESS:PORT ("[::1]:4000" for IPv6) into addr and *port: -1,
 * or the usage error's exit code. */
int cli_listen_arg(const struct cli_cmd *cmd, FILE *err, const char *arg, char *addr,
		   size_t size, unsigned *port);

#endif /* STRAND_CLI_LIVE_OPTS_H */
