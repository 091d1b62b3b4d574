/* SPDX-License-Identifier: MIT */
/*
 * can.c - strand-simdrive --can IFACE --node N: the simulated CiA 402 drive
 * (sim/co_slave.h, with the in-process drive's plant) on a real SocketCAN
 * interface. Unlike the Modbus mode it needs no scene: a CANopen master
 * tells the drive everything by SDO (mode, interpolation period, PDOs,
 * heartbeat); the plant's constants are options.
 *
 * The drive reads the frames addressed to it and runs on CLOCK_MONOTONIC,
 * woken by a frame or by its next timer (heartbeat, a quick stop's next
 * period).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <getopt.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/exitcode.h"
#include "cli/opt.h"
#include "hal/canopen/co_socketcan.h"
#include "hal/clock.h"
#include "sim/co_slave.h"
#include "simdrive.h"

static const char usage[] =
	"usage: strand-simdrive --can IFACE --node N [options]\n"
	"\n"
	"Answers as a CiA 402 servo drive with node-ID N on the SocketCAN interface IFACE:\n"
	"NMT with its boot-up message, an SDO server, RPDO1/TPDO1 as the master maps them,\n"
	"cyclic synchronous position (8) or velocity (9), the 402 state machine, heartbeat,\n"
	"emergency messages. Behind it strand's simulated drive, advanced one interpolation\n"
	"period (0x60C2) per SYNC. It prints one line once it listens, and runs until SIGINT\n"
	"or SIGTERM, then prints what it did.\n"
	"\n"
	"  --name TEXT           its device name, 0x1008 (default strand-simdrive)\n"
	"  --initial COUNTS      position at power-on (default 0)\n"
	"  --bandwidth HZ        position loop bandwidth (default 40)\n"
	"  --damping Z           (default 1)\n"
	"  --feedforward F       velocity feed-forward, 0 to 1 (default 0.9)\n"
	"  --fault CODE          the emergency code SIGUSR1 injects (default 0x2310,\n"
	"                        over-current); writing a code to 0x2000 does the same\n"
	"  --sync-log FILE       the CLOCK_MONOTONIC time (ns) each SYNC was received at,\n"
	"                        one a line: the SYNC period as a drive sees it\n"
	"  --quiet               no line when listening\n";

enum { OPT_CAN = 256, OPT_NODE, OPT_NAME, OPT_INITIAL, OPT_BW, OPT_DAMP, OPT_FF, OPT_FAULT,
       OPT_SYNC_LOG, OPT_QUIET };

static const struct option options[] = {
	{ "can", required_argument, NULL, OPT_CAN },
	{ "node", required_argument, NULL, OPT_NODE },
	{ "name", required_argument, NULL, OPT_NAME },
	{ "initial", required_argument, NULL, OPT_INITIAL },
	{ "bandwidth", required_argument, NULL, OPT_BW },
	{ "damping", required_argument, NULL, OPT_DAMP },
	{ "feedforward", required_argument, NULL, OPT_FF },
	{ "fault", required_argument, NULL, OPT_FAULT },
	{ "sync-log", required_argument, NULL, OPT_SYNC_LOG },
	{ "quiet", no_argument, NULL, OPT_QUIET },
	{ "help", no_argument, NULL, 'h' },
	{ NULL, 0, NULL, 0 },
};

static volatile sig_atomic_t stop_sig, fault_sig;

static void on_signal(int sig)
{
	if (sig == SIGUSR1)
		fault_sig = 1;
	else
		stop_sig = sig;
}

/* The drive's frames go straight out; one the interface refuses is lost,
 * as a real drive's would be. */
static int send_frames(void *ctx, const struct co_frame *f, uint32_t n)
{
	return co_bus_send(ctx, f, n);
}

struct can_opts {
	const char *iface, *name, *sync_log;
	long node;
	double initial, bandwidth, damping, feedforward, fault;
	bool quiet;
};

static int parse(struct can_opts *o, int argc, char **argv)
{
	static const struct rig_sim_desc none;
	struct sim_drive_channel plant;
	int opt;

	/* the plant of a twin whose scene says nothing, as `strand play --sim`
	 * makes it */
	rig_sim_plant(&none, &plant);
	o->name = "strand-simdrive";
	o->bandwidth = plant.bandwidth_hz;
	o->damping = plant.damping;
	o->feedforward = plant.feedforward;
	o->fault = 0x2310;
	while ((opt = getopt_long(argc, argv, "h", options, NULL)) != -1) {
		double v = 0;
		bool ok = true;

		switch (opt) {
		case OPT_CAN:
			o->iface = optarg;
			break;
		case OPT_NODE:
			ok = opt_double(optarg, 1, CO_NODE_MAX, &v) && v == (long)v;
			o->node = (long)v;
			break;
		case OPT_NAME:
			o->name = optarg;
			break;
		case OPT_INITIAL:
			ok = opt_double(optarg, INT32_MIN, INT32_MAX, &o->initial);
			break;
		case OPT_BW:
			ok = opt_double(optarg, 0.01, 10000, &o->bandwidth);
			break;
		case OPT_DAMP:
			ok = opt_double(optarg, 0.01, 100, &o->damping);
			break;
		case OPT_FF:
			ok = opt_double(optarg, 0, 1, &o->feedforward);
			break;
		case OPT_FAULT:
			ok = opt_double(optarg, 1, 0xffff, &o->fault) && o->fault == (long)o->fault;
			break;
		case OPT_SYNC_LOG:
			o->sync_log = optarg;
			break;
		case OPT_QUIET:
			o->quiet = true;
			break;
		case 'h':
			fputs(usage, stdout);
			return 0;
		default:
			fputs(usage, stderr);
			return STRAND_EXIT_USAGE;
		}
		if (!ok) {
			fprintf(stderr, "strand-simdrive: --%s %s: out of range\n",
				options[opt - OPT_CAN].name, optarg);
			return STRAND_EXIT_USAGE;
		}
	}
	if (optind != argc || !o->iface || !o->node) {
		fputs(usage, stderr);
		return STRAND_EXIT_USAGE;
	}
	return -1;
}

static void report(const struct co_slave_watch *w, uint8_t node)
{
	fprintf(stderr,
		"strand-simdrive: node %u: %s, NMT 0x%02x; %llu SYNCs, %llu RPDOs, %llu TPDOs, "
		"%llu heartbeats, %llu emergencies, %llu SDO requests; position %d\n",
		node, co402_state_name((enum co402_state)w->state), w->nmt,
		(unsigned long long)w->syncs, (unsigned long long)w->rpdos,
		(unsigned long long)w->tpdos, (unsigned long long)w->heartbeats,
		(unsigned long long)w->emcys, (unsigned long long)w->sdo_requests, w->actual);
}

/* What the drive takes from the bus: NMT and the default SYNC (0x000 to
 * 0x0ff, emergencies included), its RPDOs and SDO requests, and the SYNC's
 * identifier when 0x1005 moved it. So it wakes up for its own frames only,
 * not for every TPDO of the others. */
static int listen_to(struct co_bus *bus, uint8_t node, uint16_t sync_id)
{
	struct co_rx_filter f[7] = {
		{ 0x000, 0x700 },
		{ (uint16_t)(CO_ID_SDO_RX + node), 0x7ff },
		{ co_rpdo_id(1, node), 0x7ff },
		{ co_rpdo_id(2, node), 0x7ff },
		{ co_rpdo_id(3, node), 0x7ff },
		{ co_rpdo_id(4, node), 0x7ff },
		{ sync_id, 0x7ff },
	};

	return co_socketcan_filter(bus, f, sync_id > 0xff ? 7 : 6);
}

static int serve(struct co_bus *bus, struct co_slave *s, uint16_t fault, FILE *sync_log)
{
	struct pollfd p = { .fd = co_socketcan_fd(bus), .events = POLLIN };
	struct co_frame rx[CO_SOCKETCAN_BATCH];
	int64_t next = co_slave_poll(s, hal_mono_ns());
	uint16_t sync_id = co_slave_sync_id(s);

	while (!stop_sig) {
		int64_t now = hal_mono_ns(), wait = next - now;
		int n, i;

		if (fault_sig) {
			fault_sig = 0;
			co_slave_fault(s, fault, now);
		}
		if (wait > 0)
			poll(&p, 1, (int)(wait > 100000000 ? 100 : (wait + 999999) / 1000000));
		do {
			n = co_bus_recv(bus, rx, CO_SOCKETCAN_BATCH);
			now = hal_mono_ns();
			for (i = 0; i < n; i++) {
				if (sync_log && rx[i].id == sync_id)
					fprintf(sync_log, "%lld\n", (long long)now);
				co_slave_rx(s, &rx[i], now);
			}
		} while (n == CO_SOCKETCAN_BATCH);
		if (n < 0) {
			fprintf(stderr, "strand-simdrive: %s: %s\n", bus->name, strerror(-n));
			return STRAND_EXIT_IO;
		}
		next = co_slave_poll(s, hal_mono_ns());
		if (co_slave_sync_id(s) != sync_id) {
			sync_id = co_slave_sync_id(s);
			listen_to(bus, co_slave_node(s), sync_id);
		}
	}
	return 0;
}

int simdrive_can_main(int argc, char **argv)
{
	struct co_slave_cfg c = { 0 };
	struct can_opts o = { 0 };
	struct sigaction sa;
	struct co_slave *s;
	struct co_bus *bus;
	FILE *sync_log = NULL;
	char err[256];
	int rc = parse(&o, argc, argv);

	if (rc >= 0)
		return rc;
	if (co_socketcan_open(&bus, o.iface, NULL, 0, err, sizeof(err))) {
		fprintf(stderr, "strand-simdrive: %s\n", err);
		return STRAND_EXIT_IO;
	}
	rc = listen_to(bus, (uint8_t)o.node, CO_ID_SYNC);
	if (rc) {
		fprintf(stderr, "strand-simdrive: %s: receive filter: %s\n", o.iface, strerror(-rc));
		rc = STRAND_EXIT_IO;
		goto close_bus;
	}
	if (o.sync_log && !(sync_log = fopen(o.sync_log, "w"))) {
		fprintf(stderr, "strand-simdrive: %s: %s\n", o.sync_log, strerror(errno));
		rc = STRAND_EXIT_IO;
		goto close_bus;
	}
	c.node = (uint8_t)o.node;
	c.name = o.name;
	c.model.bandwidth_hz = o.bandwidth;
	c.model.damping = o.damping;
	c.model.feedforward = o.feedforward;
	c.initial = (int32_t)o.initial;
	c.send = send_frames;
	c.ctx = bus;
	if (co_slave_new(&s, &c, err, sizeof(err))) {
		fprintf(stderr, "strand-simdrive: %s\n", err);
		rc = STRAND_EXIT_INTERNAL;
		goto close_log;
	}
	memset(&sa, 0, sizeof(sa));
	sa.sa_handler = on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	sigaction(SIGUSR1, &sa, NULL);
	/* bound first: its boot-up message is the first thing it says */
	co_slave_power_on(s, hal_mono_ns());
	if (!o.quiet) {
		printf("strand-simdrive: CiA 402 drive, node %ld on %s, listening\n", o.node, o.iface);
		fflush(stdout);
	}
	rc = serve(bus, s, (uint16_t)o.fault, sync_log);
	report(co_slave_watch(s), c.node);
	co_slave_free(s);
close_log:
	if (sync_log)
		fclose(sync_log);
close_bus:
	co_bus_close(bus);
	return rc;
}
