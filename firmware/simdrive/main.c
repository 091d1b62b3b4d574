/* SPDX-License-Identifier: MIT */
/*
 * main.c - strand-simdrive's command line: the scene, the device, its
 * simulated twin (simdrive.h), then the Modbus server until a signal.
 */
#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/exitcode.h"
#include "simdrive.h"

static const char usage[] =
	"usage: strand-simdrive SCENE.yaml [--device NAME] [options]\n"
	"       strand-simdrive --can IFACE --node N [options]   (--can --help)\n"
	"\n"
	"Plays one device of the scene's rig with strand's simulated drive behind a real\n"
	"Modbus server: TCP on the device's host and port, or RTU on a pseudo-terminal\n"
	"linked at the device's serial port. The register map is the scene's. It prints\n"
	"one line when it serves, and runs until SIGINT or SIGTERM.\n"
	"\n"
	"  --device NAME         the device (default: the first Modbus device)\n"
	"  --listen HOST:PORT    TCP: listen there instead (port 0: any; the line says which)\n"
	"  --pty PATH            RTU: link PATH to the pseudo-terminal instead\n"
	"  --log FILE            one line per setpoint write: W N TICK VALUE... (TICK from\n"
	"                        the heartbeat register, -1 without), E 1|0 per enable\n"
	"  --wire-time           RTU: answer after the time a real line at the scene's baud\n"
	"                        rate takes for the request and the answer\n"
	"faults, each after N setpoint writes:\n"
	"  --silent-after N      stop answering\n"
	"  --late-after N        answer --late-ms MS (default 100) late\n"
	"  --exception-after N   answer with exception --exception CODE (default 4)\n"
	"  --die-after N         exit at once (the connection drops, the line goes quiet)\n"
	"  --drop-after N        close the connection once, then accept a new one (TCP)\n"
	"  --trip-after N        the drive trips: its status register shows the fault\n"
	"  --quiet               no line when serving\n";

enum {
	OPT_DEVICE = 256, OPT_LISTEN, OPT_PTY, OPT_LOG, OPT_WIRE, OPT_SILENT, OPT_LATE,
	OPT_LATE_MS, OPT_EXC, OPT_EXC_CODE, OPT_DIE, OPT_DROP, OPT_TRIP, OPT_QUIET,
};

static const struct option options[] = {
	{ "device", required_argument, NULL, OPT_DEVICE },
	{ "listen", required_argument, NULL, OPT_LISTEN },
	{ "pty", required_argument, NULL, OPT_PTY },
	{ "log", required_argument, NULL, OPT_LOG },
	{ "wire-time", no_argument, NULL, OPT_WIRE },
	{ "silent-after", required_argument, NULL, OPT_SILENT },
	{ "late-after", required_argument, NULL, OPT_LATE },
	{ "late-ms", required_argument, NULL, OPT_LATE_MS },
	{ "exception-after", required_argument, NULL, OPT_EXC },
	{ "exception", required_argument, NULL, OPT_EXC_CODE },
	{ "die-after", required_argument, NULL, OPT_DIE },
	{ "drop-after", required_argument, NULL, OPT_DROP },
	{ "trip-after", required_argument, NULL, OPT_TRIP },
	{ "quiet", no_argument, NULL, OPT_QUIET },
	{ "help", no_argument, NULL, 'h' },
	{ NULL, 0, NULL, 0 },
};

static volatile sig_atomic_t stop_sig;

static void on_signal(int sig)
{
	stop_sig = sig;
}

static int parse(struct simdrive *sd, int argc, char **argv)
{
	struct mb_server_faults *f = &sd->mb.faults;
	long long v;
	int opt;

	f->late_ms = 100;
	f->exception = 4;
	while ((opt = getopt_long(argc, argv, "h", options, NULL)) != -1) {
		const char *name = NULL;

		switch (opt) {
		case OPT_DEVICE:
			sd->device = optarg;
			break;
		case OPT_LISTEN:
			sd->mb.listen = optarg;
			break;
		case OPT_PTY:
			sd->mb.pty = optarg;
			break;
		case OPT_LOG:
			sd->mb.log = fopen(optarg, "w");
			if (!sd->mb.log) {
				fprintf(stderr, "strand-simdrive: %s: %s\n", optarg, strerror(errno));
				return STRAND_EXIT_IO;
			}
			break;
		case OPT_WIRE:
			f->wire_time = true;
			break;
		case OPT_QUIET:
			sd->mb.quiet = true;
			break;
		case OPT_LATE_MS:
			if (!opt_long(optarg, 1, 60000, &v))
				name = "--late-ms";
			f->late_ms = (double)v;
			break;
		case OPT_EXC_CODE:
			if (!opt_long(optarg, 1, 255, &v))
				name = "--exception";
			f->exception = (int)v;
			break;
		case OPT_SILENT:
		case OPT_LATE:
		case OPT_EXC:
		case OPT_DIE:
		case OPT_DROP:
		case OPT_TRIP:
			if (!opt_long(optarg, 1, INT64_MAX, &v)) {
				name = "a fault's count";
				break;
			}
			*(opt == OPT_SILENT ? &f->silent_after : opt == OPT_LATE ? &f->late_after :
			  opt == OPT_EXC ? &f->exception_after : opt == OPT_DIE ? &f->die_after :
			  opt == OPT_DROP ? &f->drop_after : &f->trip_after) = v;
			break;
		case 'h':
			fputs(usage, stdout);
			return 0;
		default:
			fputs(usage, stderr);
			return STRAND_EXIT_USAGE;
		}
		if (name) {
			fprintf(stderr, "strand-simdrive: %s %s: out of range\n", name, optarg);
			return STRAND_EXIT_USAGE;
		}
	}
	if (optind != argc - 1) {
		fputs(usage, stderr);
		return STRAND_EXIT_USAGE;
	}
	sd->scene_path = argv[optind];
	return -1;
}

/* The scene, its outputs bound, the device's twin: the drive that
 * `strand play --sim` would make for it (drv_sim.h). */
static int setup(struct simdrive *sd)
{
	struct load_err le;
	char msg[512];
	uint32_t i, k;
	int32_t ax = -1;
	int rc;

	if (scene_file_load(&sd->sf, sd->scene_path, &le) ||
	    (sd->have_sf = true, scene_file_build(&sd->sf, &sd->b, &le)))
		return cli_scene_error(stderr, sd->scene_path, &le);
	sd->have_b = true;
	for (k = 0; k < sd->sf.rig.ndevices; k++) {
		const struct rig_device_desc *dd = &sd->sf.rig.devices[k];

		if (rig_modbus_desc(dd) && (!sd->device || !strcmp(sd->device, dd->name))) {
			sd->dd = dd;
			break;
		}
	}
	if (!sd->dd) {
		fprintf(stderr, "%s: no Modbus device%s%s in devices:\n", sd->scene_path,
			sd->device ? " named " : "", sd->device ? sd->device : "");
		return STRAND_EXIT_SCENE;
	}
	if (source_scene_init(&sd->src, &sd->sf.desc, &sd->b.sc)) {
		fprintf(stderr, "strand-simdrive: out of memory\n");
		return STRAND_EXIT_INTERNAL;
	}
	sd->have_src = true;
	rc = rig_bind(&sd->rig, &sd->sf.rig, &sd->src.s, msg, sizeof(msg));
	if (rc) {
		fprintf(stderr, "%s: %s\n", sd->scene_path, msg);
		return rc == -ENOMEM ? STRAND_EXIT_INTERNAL : STRAND_EXIT_SCENE;
	}
	sd->have_rig = true;
	ax = sd->rig.dev[k].axis;
	if (ax < 0) {
		fprintf(stderr, "%s: device '%s' drives no output\n", sd->scene_path, sd->dd->name);
		return STRAND_EXIT_SCENE;
	}
	sd->mb.tick_hz = sd->src.s.timing.tick_hz;
	rc = rig_sim_drive_new(&sd->drive, &sd->rig, k, sd->mb.tick_hz, msg, sizeof(msg));
	if (rc) {
		fprintf(stderr, "%s: %s\n", sd->scene_path, msg);
		return rc == -ENOMEM ? STRAND_EXIT_INTERNAL : STRAND_EXIT_SCENE;
	}
	sd->mb.name = sd->dd->name;
	sd->mb.d = rig_modbus_desc(sd->dd);
	sd->mb.drive = sd->drive;
	sd->mb.nch = sim_drive_axis(sd->drive)->nch;
	sd->velocity = calloc(sd->mb.nch ? sd->mb.nch : 1, sizeof(*sd->velocity));
	if (!sd->velocity) {
		fprintf(stderr, "strand-simdrive: out of memory\n");
		return STRAND_EXIT_INTERNAL;
	}
	for (i = 0; i < sd->rig.nout; i++)
		if (sd->rig.out[i].dev == (uint32_t)ax)
			sd->velocity[sd->rig.out[i].ch] = sd->rig.out[i].vel_mode;
	sd->mb.velocity = sd->velocity;
	return -1;
}

int main(int argc, char **argv)
{
	struct simdrive sd;
	int rc;

	/* a CANopen drive needs no scene: its master configures it */
	for (rc = 1; rc < argc; rc++)
		if (!strcmp(argv[rc], "--can") || !strncmp(argv[rc], "--can=", 6))
			return simdrive_can_main(argc, argv);
	memset(&sd, 0, sizeof(sd));
	rc = parse(&sd, argc, argv);
	if (rc < 0)
		rc = setup(&sd);
	if (rc < 0) {
		struct sigaction sa;
		char err[512];

		memset(&sa, 0, sizeof(sa));
		sa.sa_handler = on_signal;
		sigaction(SIGINT, &sa, NULL);
		sigaction(SIGTERM, &sa, NULL);
		signal(SIGPIPE, SIG_IGN);
		sd.mb.stop = &stop_sig;
		rc = mb_server_run(&sd.mb, err, sizeof(err));
		if (rc)
			fprintf(stderr, "strand-simdrive: %s\n", err);
		rc = rc == 0 ? STRAND_EXIT_OK : rc == -ENOMEM ? STRAND_EXIT_INTERNAL : STRAND_EXIT_IO;
	}
	if (sd.mb.log)
		fclose(sd.mb.log);
	free(sd.velocity);
	if (sd.drive)
		hal_axis_close(sim_drive_axis(sd.drive));
	if (sd.have_rig)
		rig_free(&sd.rig);
	if (sd.have_src)
		source_scene_free(&sd.src);
	if (sd.have_b)
		scene_built_free(&sd.b);
	if (sd.have_sf)
		scene_file_free(&sd.sf);
	return rc;
}
