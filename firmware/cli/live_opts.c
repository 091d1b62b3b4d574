/* SPDX-License-Identifier: MIT */
/* live_opts.c - the live session's options (see live_opts.h). */
#include "live_opts.h"

#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <string.h>

#include "exitcode.h"

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

bool cli_is_loopback(const char *addr)
{
	struct in_addr a4;
	struct in6_addr a6;

	if (!strcmp(addr, "localhost"))
		return true;
	if (inet_pton(AF_INET, addr, &a4) == 1)
		return (ntohl(a4.s_addr) >> 24) == 127;
	return inet_pton(AF_INET6, addr, &a6) == 1 && IN6_IS_ADDR_LOOPBACK(&a6);
}

int cli_live_open(struct live **out, const char *scene, const struct live_opts *o, FILE *err)
{
	char msg[LIVE_MSG];
	int rc = live_open(out, scene, o, msg, sizeof(msg));

	if (!rc)
		return 0;
	fprintf(err, "%s\n", msg);
	return rc == -EINVAL || rc == -ERANGE || rc == -EBADMSG ? STRAND_EXIT_SCENE :
	       rc == -ENOMEM ? STRAND_EXIT_INTERNAL : rc == -ENOENT ? STRAND_EXIT_IO :
	       STRAND_EXIT_FAULT;
}

void cli_live_signals_catch(struct cli_live_signals *s, void (*on_signal)(int))
{
	struct sigaction sa;

	memset(&sa, 0, sizeof(sa));
	sa.sa_handler = on_signal;
	sigemptyset(&sa.sa_mask);
	sigaction(SIGINT, &sa, &s->old_int);
	sigaction(SIGTERM, &sa, &s->old_term);
	signal(SIGPIPE, SIG_IGN);
}

void cli_live_signals_restore(const struct cli_live_signals *s)
{
	sigaction(SIGINT, &s->old_int, NULL);
	sigaction(SIGTERM, &s->old_term, NULL);
}
