/* SPDX-License-Identifier: MIT */
/*
 * cmd_dfmoco.c - `strand dfmoco SCENE`: Dragonframe's Arc workspace drives
 * the rig over DFMoco (dfmoco/dfm_session.h) on a serial line, a
 * pseudo-terminal or TCP; the options, the signals, the exit codes.
 */
#include <errno.h>
#include <getopt.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "dfmoco/dfm_port.h"
#include "dfmoco/dfm_run.h"
#include "dfmoco/dfm_session.h"
#include "exitcode.h"
#include "live_opts.h"
#include "live/live.h"

enum {
	OPT_SIM = 256, OPT_SERIAL, OPT_BAUD, OPT_PTY, OPT_LISTEN, OPT_PEER, OPT_JOURNAL,
	OPT_NO_JOURNAL,
};

static const struct option dfmoco_options[] = {
	{ "sim", no_argument, NULL, OPT_SIM },
	{ "serial", required_argument, NULL, OPT_SERIAL },
	{ "baud", required_argument, NULL, OPT_BAUD },
	{ "pty", required_argument, NULL, OPT_PTY },
	{ "listen", required_argument, NULL, OPT_LISTEN },
	{ "peer", required_argument, NULL, OPT_PEER },
	{ "journal", required_argument, NULL, OPT_JOURNAL },
	{ "no-journal", no_argument, NULL, OPT_NO_JOURNAL },
	CLI_LIVE_OPTIONS,
	{ "help", no_argument, NULL, 'h' },
	{ NULL, 0, NULL, 0 },
};

struct cli {
	const struct cli_cmd *cmd;
	FILE *err;
	struct live_opts o;
	const char *serial, *pty, *peer;
	char addr[64];
	unsigned port, baud, ports;
	bool no_journal;
	char journal[PATH_MAX];
};

static int on_opt(void *ctx, int opt, const char *arg)
{
	struct cli *c = ctx;
	long long v;
	int rc = cli_live_opt(c->cmd, c->err, opt, arg, &c->o);

	if (rc != -2)
		return rc;
	switch (opt) {
	case OPT_SIM:
		c->o.sim = true;
		return -1;
	case OPT_SERIAL:
	case OPT_PTY:
		*(opt == OPT_SERIAL ? &c->serial : &c->pty) = arg;
		c->ports++;
		return -1;
	case OPT_BAUD:
		if (!opt_long(arg, 1, 4000000, &v))
			return cli_usage(c->cmd, c->err, "--baud %s: a serial line's speed", arg);
		c->baud = (unsigned)v;
		return -1;
	case OPT_LISTEN:
		c->ports++;
		return cli_listen_arg(c->cmd, c->err, arg, c->addr, sizeof(c->addr), &c->port);
	case OPT_PEER:
		c->peer = arg;
		return -1;
	case OPT_JOURNAL:
		snprintf(c->journal, sizeof(c->journal), "%s", arg);
		return -1;
	case OPT_NO_JOURNAL:
		c->no_journal = true;
		return -1;
	default:
		return cli_usage(c->cmd, c->err, "unknown option");
	}
}

static volatile sig_atomic_t g_stop;

static void on_signal(int sig)
{
	g_stop = 1;
}

static void default_journal(char *buf, size_t size, const char *scene)
{
	const char *base = strrchr(scene, '/');
	char when[32];
	time_t now = time(NULL);
	struct tm tm;
	size_t n;

	base = base ? base + 1 : scene;
	n = strcspn(base, ".");
	localtime_r(&now, &tm);
	strftime(when, sizeof(when), "%Y%m%d-%H%M%S", &tm);
	snprintf(buf, size, "%.*s-dfmoco-%s.journal", (int)n, base, when);
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	struct cli c;
	struct cli_live_signals sigs;
	struct dfm_session *s = NULL;
	struct dfm_port p;
	struct live *lv = NULL;
	struct live_out_info info[LOOP_LIVE_OUT_MAX];
	char msg[LIVE_MSG];
	uint32_t i, n;
	int first, rc;

	memset(&c, 0, sizeof(c));
	c.cmd = cmd;
	c.err = err;
	cli_live_defaults(&c.o);
	c.o.deadman_ms = 500;
	c.baud = 57600;
	rc = cli_options(cmd, argc, argv, out, err, "h", dfmoco_options, on_opt, &c, &first);
	if (rc >= 0)
		return rc;
	if (argc - first != 1)
		return cli_usage(cmd, err, "one scene file, please");
	if (c.ports != 1)
		return cli_usage(cmd, err, "one of --serial DEVICE, --pty PATH or --listen "
				 "ADDRESS:PORT");
	if (c.peer && !c.port)
		return cli_usage(cmd, err, "--peer goes with --listen");
	if (c.port && !cli_is_loopback(c.addr) && !c.peer) {
		fprintf(err, "strand dfmoco: --listen %s: DFMoco has no authentication; beyond "
			"loopback give the Dragonframe computer's address with --peer ADDRESS\n",
			c.addr);
		return STRAND_EXIT_USAGE;
	}
	if (!c.no_journal) {
		if (!c.journal[0])
			default_journal(c.journal, sizeof(c.journal), argv[first]);
		c.o.journal_file = c.journal;
		c.o.journal_gomo = true;
	}
	rc = cli_live_open(&lv, argv[first], &c.o, err);
	if (rc)
		return rc;
	rc = c.serial ? dfm_port_serial(&p, c.serial, c.baud, msg, sizeof(msg)) :
	     c.pty ? dfm_port_pty(&p, c.pty, msg, sizeof(msg)) :
		     dfm_port_listen(&p, c.addr, c.port, c.peer, msg, sizeof(msg));
	if (rc) {
		fprintf(err, "strand dfmoco: %s\n", msg);
		live_close(lv);
		return STRAND_EXIT_IO;
	}
	s = malloc(sizeof(*s));
	if (!s) {
		dfm_port_close(&p);
		live_close(lv);
		return STRAND_EXIT_INTERNAL;
	}
	/* the drives on, as an Arduino's steppers are once powered: Dragonframe
	 * has no word for it (refused while an e-stop is held: hi retries) */
	if (live_enable(lv, msg, sizeof(msg)))
		fprintf(err, "strand dfmoco: %s\n", msg);
	dfm_session_init(s, lv, err);
	n = live_outputs(lv, info, LOOP_LIVE_OUT_MAX);
	fprintf(err, "strand dfmoco: DFMoco on %s, %u motor%s:", p.name, n, n == 1 ? "" : "s");
	for (i = 0; i < n; i++)
		fprintf(err, " %u=%s", i + 1, info[i].channel);
	fprintf(err, "%s%s\n", c.no_journal ? "" : "; journal ", c.no_journal ? "" : c.journal);
	g_stop = 0;
	cli_live_signals_catch(&sigs, on_signal);
	rc = dfm_run(s, &p, &g_stop, err);
	cli_live_signals_restore(&sigs);
	if (rc)
		fprintf(err, "strand dfmoco: %s: %s\n", p.name, strerror(-rc));
	dfm_port_close(&p);
	live_close(lv);
	free(s);
	if (rc)
		return STRAND_EXIT_IO;
	fprintf(err, "strand dfmoco: stopped; every drive disabled\n");
	return STRAND_EXIT_OK;
}

const struct cli_cmd cmd_dfmoco = {
	.name = "dfmoco",
	.summary = "let Dragonframe drive the rig over DFMoco (serial, pseudo-terminal or TCP)",
	.help = "usage: strand dfmoco SCENE.yaml [--sim] (--serial DEVICE [--baud 57600] |\n"
		"                                          --pty PATH | --listen ADDR:PORT)\n"
		"\n"
		"Answers DFMoco, the protocol Dragonframe's Arc workspace speaks to a motion\n"
		"controller, on the scene's rig: its outputs are the motors, numbered from 1 in\n"
		"the order the scene writes them, their counts the positions. Every move obeys\n"
		"the outputs' limits (one beyond them is refused, never clamped), the e-stop\n"
		"stops it, go-motion (bf, go) runs strand's go-motion, and every go-motion\n"
		"frame is journaled (README \"Dragonframe\").\n"
		"\n"
		"  --sim                 every device by its simulated twin\n"
		"  --serial DEVICE       a serial line: a USB adapter, or the USB gadget\n"
		"                        /dev/ttyGS0 (the Dragonframe computer sees a serial port)\n"
		"  --baud N              its speed (57600, as Dragonframe's DFMoco)\n"
		"  --pty PATH            a pseudo-terminal, linked at PATH\n"
		"  --listen ADDR:PORT    TCP, one client at a time; beyond loopback with --peer\n"
		"  --peer ADDR           the only client address taken\n"
		"  --journal FILE        the frame journal (SCENE-dfmoco-YYYYmmdd-HHMMSS.journal)\n"
		"  --no-journal          no journal\n"
		"  --clock real|virtual  the wall clock (default) or virtual time at its pace (tests)\n"
		"  --deadman MS          a jog stops without a repeated jm for MS (500)\n"
		"  --priority N, --cpu N, --no-mlock   as for strand play\n"
		"\n"
		"SIGINT or SIGTERM: the motion comes to rest, the drives are disabled, exit 0.\n"
		"exit codes: 0 stopped, 2 invalid scene, 3 usage, 4 the port or the journal,\n"
		"7 a device would not start, 8 internal.\n",
	.run = run,
};
