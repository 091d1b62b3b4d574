/* SPDX-License-Identifier: MIT */
/* live_opts.c - the live session's options (see live_opts.h). */
#include "live_opts.h"

#include <string.h>

void cli_live_defaults(struct live_opts *o)
{
	o->rt.priority = 80;
	o->rt.cpu = -1;
	o->rt.lock_memory = true;
	o->rt.pm_qos = true;
	o->rt.name = "strand-rt";
}

int cli_live_opt(const struct cli_cmd *cmd, FILE *err, int opt, const char *arg,
		 struct live_opts *o)
{
	double d;

	switch (opt) {
	case CLI_LIVE_CLOCK:
		if (strcmp(arg, "real") && strcmp(arg, "virtual"))
			return cli_usage(cmd, err, "--clock %s: real or virtual", arg);
		/* a person, a browser or Dragonframe waits: every tick at the
		 * wall's pace */
		o->virtual_clock = o->pace_all = !strcmp(arg, "virtual");
		return -1;
	case CLI_LIVE_PRIORITY:
	case CLI_LIVE_CPU:
	case CLI_LIVE_NO_MLOCK:
		/* as strand play's */
		return cli_rt_option(cmd, err, opt == CLI_LIVE_PRIORITY ? "priority" :
					   opt == CLI_LIVE_CPU ? "cpu" : "no-mlock", arg, &o->rt);
	case CLI_LIVE_DEADMAN:
		if (!opt_double(arg, 10, 10000, &d))
			return cli_usage(cmd, err, "--deadman %s: 10 to 10000 ms", arg);
		o->deadman_ms = d;
		return -1;
	default:
		return -2;
	}
}

int cli_listen_arg(const struct cli_cmd *cmd, FILE *err, const char *arg, char *addr,
		   size_t size, unsigned *port)
{
	const char *colon = strrchr(arg, ':');
	long long v;

	if (!colon || colon == arg || (size_t)(colon - arg) >= size ||
	    !opt_long(colon + 1, 1, 65535, &v))
		return cli_usage(cmd, err, "--listen %s: ADDRESS:PORT", arg);
	if (arg[0] == '[' && colon[-1] == ']')
		snprintf(addr, size, "%.*s", (int)(colon - arg - 2), arg + 1);
	else
		snprintf(addr, size, "%.*s", (int)(colon - arg), arg);
	*port = (unsigned)v;
	return -1;
}
