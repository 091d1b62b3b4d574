/* SPDX-License-Identifier: MIT */
/*
 * cmd_serve.c - `strand serve SCENE`: the rig under live control from a
 * browser or any JSON-RPC client (live/live.h, serve/server.h): the
 * options, the token, the signals, the exit codes.
 */
#include <errno.h>
#include <getopt.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "exitcode.h"
#include "live_opts.h"
#include "live/live.h"
#include "serve/server.h"

enum {
	OPT_SIM = 256, OPT_LISTEN, OPT_TOKEN_FILE, OPT_DATA, OPT_FORCE, OPT_LAT_HIST, OPT_JOURNAL,
};

static const struct option serve_options[] = {
	{ "sim", no_argument, NULL, OPT_SIM },
	{ "listen", required_argument, NULL, OPT_LISTEN },
	{ "token-file", required_argument, NULL, OPT_TOKEN_FILE },
	{ "data", required_argument, NULL, OPT_DATA },
	{ "force", no_argument, NULL, OPT_FORCE },
	CLI_LIVE_OPTIONS,
	{ "latency-hist", required_argument, NULL, OPT_LAT_HIST },
	{ "journal", required_argument, NULL, OPT_JOURNAL },
	{ "help", no_argument, NULL, 'h' },
	{ NULL, 0, NULL, 0 },
};

struct cli {
	const struct cli_cmd *cmd;
	FILE *err;
	struct live_opts o;
	char addr[64];
	unsigned port;
	const char *token_file;
};

static int on_opt(void *ctx, int opt, const char *arg)
{
	struct cli *c = ctx;
	int rc = cli_live_opt(c->cmd, c->err, opt, arg, &c->o);

	if (rc != -2)
		return rc;
	switch (opt) {
	case OPT_SIM:
		c->o.sim = true;
		return -1;
	case OPT_LISTEN:
		return cli_listen_arg(c->cmd, c->err, arg, c->addr, sizeof(c->addr), &c->port);
	case OPT_TOKEN_FILE:
		c->token_file = arg;
		return -1;
	case OPT_DATA:
		c->o.data_dir = arg;
		return -1;
	case OPT_FORCE:
		c->o.force = true;
		return -1;
	case OPT_LAT_HIST:
		c->o.lat_hist = arg;
		return -1;
	case OPT_JOURNAL:
		c->o.journal = arg;
		return -1;
	default:
		return cli_usage(c->cmd, c->err, "unknown option");
	}
}

/* The token: the file's first line, at least 16 characters. */
static int read_token(struct cli *c, char *tok, size_t size)
{
	FILE *f = fopen(c->token_file, "r");
	size_t n;

	if (!f) {
		fprintf(c->err, "strand serve: %s: %s\n", c->token_file, strerror(errno));
		return STRAND_EXIT_IO;
	}
	if (!fgets(tok, (int)size, f))
		tok[0] = 0;
	fclose(f);
	n = strcspn(tok, "\r\n");
	tok[n] = 0;
	if (n < 16 || strchr(tok, ' ')) {
		fprintf(c->err, "strand serve: %s: the token must be one line of at least 16 "
			"characters without spaces (head -c 24 /dev/urandom | base64)\n",
			c->token_file);
		return STRAND_EXIT_USAGE;
	}
	return 0;
}

static volatile sig_atomic_t g_stop;

static void on_signal(int sig)
{
	g_stop = g_stop + 1;
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	struct cli c;
	struct server_opts so;
	struct cli_live_signals sigs;
	struct live *lv = NULL;
	char token[256];
	int first, rc;

	memset(&c, 0, sizeof(c));
	c.cmd = cmd;
	c.err = err;
	cli_live_defaults(&c.o);
	snprintf(c.addr, sizeof(c.addr), "127.0.0.1");
	c.port = 7125;
	rc = cli_options(cmd, argc, argv, out, err, "h", serve_options, on_opt, &c, &first);
	if (rc >= 0)
		return rc;
	if (argc - first > 1)
		return cli_usage(cmd, err, "one scene file at most (or none: load one later)");
	memset(&so, 0, sizeof(so));
	so.addr = c.addr;
	so.port = c.port;
	so.loopback = cli_is_loopback(c.addr);
	if (!so.loopback && !c.token_file) {
		fprintf(err, "strand serve: --listen %s is not a loopback address: a server that "
			"moves machinery on a network needs --token-file\n", c.addr);
		return STRAND_EXIT_USAGE;
	}
	if (c.token_file) {
		rc = read_token(&c, token, sizeof(token));
		if (rc)
			return rc;
		so.token = token;
	}
	rc = cli_live_open(&lv, argc > first ? argv[first] : NULL, &c.o, err);
	if (rc)
		return rc;
	g_stop = 0;
	cli_live_signals_catch(&sigs, on_signal);
	rc = server_run(lv, &so, &g_stop, err);
	live_close(lv);
	cli_live_signals_restore(&sigs);
	if (rc)
		return STRAND_EXIT_IO;
	fprintf(err, "strand serve: stopped; every drive disabled\n");
	return STRAND_EXIT_OK;
}

const struct cli_cmd cmd_serve = {
	.name = "serve",
	.summary = "control the rig live from a browser or a JSON-RPC client",
	.help = "usage: strand serve [SCENE.yaml] [options]\n"
		"\n"
		"Opens the scene's rig (the drives disabled), runs the real-time loop while they\n"
		"are enabled, and serves the console page at http://ADDRESS:PORT/, JSON-RPC 2.0\n"
		"over a WebSocket at /websocket and as POST /rpc (README \"strand serve\").\n"
		"Without SCENE it waits for a client to load one of the data folder.\n"
		"\n"
		"  --sim                 every device by its simulated twin\n"
		"  --listen ADDR:PORT    where to listen (127.0.0.1:7125); an address other than\n"
		"                        loopback needs --token-file\n"
		"  --token-file FILE     every request must present this token (Authorization:\n"
		"                        Bearer TOKEN, or Basic with any user name)\n"
		"  --data DIR            where load and save find scene files (the scene's\n"
		"                        folder, or the working directory without one)\n"
		"  --clock real|virtual  the wall clock (default) or virtual time (tests)\n"
		"  --deadman MS          a jog stops without a refresh for MS (250)\n"
		"  --journal DIR         each play segment's journal,\n"
		"                        DIR/SCENE-DATE-TIME-N.journal\n"
		"  --latency-hist FILE   each run's wake-up latency histogram (as cyclictest's)\n"
		"  --priority N, --cpu N, --no-mlock, --force   as for strand play\n"
		"\n"
		"SIGINT or SIGTERM: the motion comes to rest, the drives are disabled, exit 0.\n"
		"exit codes: 0 stopped, 2 invalid scene, 3 usage, 4 I/O (cannot listen),\n"
		"7 a device would not start, 8 internal.\n",
	.run = run,
};
