/* SPDX-License-Identifier: MIT */
/*
 * live_opts.h - the options of the commands that run a live session
 * (strand serve, strand dfmoco): where to listen, the clock, the loop
 * thread's scheduling, the jog's dead-man. One table of them and one
 * handler, so that they read and refuse alike in both; and what both do
 * around the session: open it, catch the signals that end it.
 */
#ifndef STRAND_CLI_LIVE_OPTS_H
#define STRAND_CLI_LIVE_OPTS_H

#include <getopt.h>
#include <signal.h>
#include <stdbool.h>
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

/* ADDR (as --listen gave it, brackets gone) names this machine only:
 * localhost, 127.0.0.0/8 or ::1. */
bool cli_is_loopback(const char *addr);

/* [init] live_open() with its message on err: 0, or the exit code of
 * its error (2 the scene, 4 the file, 7 a device, 8 memory). */
int cli_live_open(struct live **out, const char *scene, const struct live_opts *o, FILE *err);

/* SIGINT and SIGTERM to on_signal, SIGPIPE ignored (a client that goes
 * is a write error, not the end); restore puts SIGINT and SIGTERM back. */
struct cli_live_signals {
	struct sigaction old_int, old_term;
};
void cli_live_signals_catch(struct cli_live_signals *s, void (*on_signal)(int));
void cli_live_signals_restore(const struct cli_live_signals *s);

#endif /* STRAND_CLI_LIVE_OPTS_H */
