/* SPDX-License-Identifier: MIT */
/* play_cli.c - strand play and strand journal (see play_cli.h). */
#define _GNU_SOURCE
#include "play_cli.h"

#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "exitcode.h"
#include "frames.h"
#include "journal.h"
#include "play.h"
#include "rig_auto.h"
#include "source_scene.h"

static const char play_usage[] =
	"usage: strand play SCENE [options]\n"
	"\n"
	"Plays SCENE on its rig in real time, firing one camera trigger per frame.\n"
	"\n"
	"  --sim                 every device of the scene by its simulated twin\n"
	"  --mode MODE           continuous (default) or step (shoot-move-shoot)\n"
	"  --from F, --to F      the frames to fire (default: the scene's span)\n"
	"  --frames SPEC         step mode: frames as 0..240, 1,5,9 or 12x5 (reshoot)\n"
	"  --loop                play the range again and again\n"
	"  --ping-pong           forwards, backwards, forwards, ...\n"
	"  --passes N            with --loop or --ping-pong: stop after N passes\n"
	"  --duration S          a controlled stop after S seconds\n"
	"  --settle MS           step mode: in position this long before the shot (default 200)\n"
	"  --exposure MS         step mode: hold still this long after it (default 100),\n"
	"                        unless a camera_ready input paces the shots\n"
	"  --timeout S           step mode: for in position and camera ready (default 10)\n"
	"  --journal FILE        the frame journal (default SCENE-YYYYmmdd-HHMMSS.journal)\n"
	"  --no-journal          no journal\n"
	"  --telemetry FILE      JSON lines of the loop's state, ten a second\n"
	"  --clock real|virtual  the wall clock (default) or virtual time, as fast as it computes\n"
	"  --priority N          SCHED_FIFO priority of the loop (default 80; 0: none)\n"
	"  --cpu N               pin the loop to CPU N\n"
	"  --no-mlock            do not lock memory\n"
	"  --force               play a scene that strand check rejects; setpoints beyond a\n"
	"                        limit are clamped to it instead of stopping the run\n"
	"  --camera-log FILE     the simulated camera logs its exposures there (tests)\n"
	"  --latency-hist FILE   the wake-up latency histogram (us count), for make bench\n"
	"  --quiet               no status line, no summary\n"
	"\n"
	"Exit: 0 done, 2 scene, 3 usage, 4 file, 5 stopped by SIGINT/SIGTERM, 6 e-stop,\n"
	"7 device fault or following error, 8 internal.\n";

static struct play *g_play;
static volatile sig_atomic_t g_sigints;

static void on_signal(int sig)
{
	if (sig == SIGINT)
		g_sigints++;
	if (g_play)
		play_signal(g_play, sig, sig == SIGINT ? g_sigints : 1);
}

static int usage_error(const char *fmt, const char *arg)
{
	fprintf(stderr, "strand play: ");
	fprintf(stderr, fmt, arg);
	fprintf(stderr, "\n(strand play --help for the options)\n");
	return STRAND_EXIT_USAGE;
}

static bool parse_i64(const char *s, int64_t *out)
{
	char *end;
	long long v;

	errno = 0;
	v = strtoll(s, &end, 10);
	if (errno || end == s || *end)
		return false;
	*out = v;
	return true;
}

static bool parse_double(const char *s, double *out)
{
	char *end;
	double v;

	errno = 0;
	v = strtod(s, &end);
	if (errno || end == s || *end || !isfinite(v) || v < 0)
		return false;
	*out = v;
	return true;
}

static void default_journal(char *buf, size_t size, const char *scene)
{
	time_t now = time(NULL);
	struct tm tm;
	char when[32];

	localtime_r(&now, &tm);
	strftime(when, sizeof(when), "%Y%m%d-%H%M%S", &tm);
	snprintf(buf, size, "%s-%s.journal", scene, when);
}

enum {
	OPT_SIM = 256, OPT_MODE, OPT_FROM, OPT_TO, OPT_FRAMES, OPT_LOOP, OPT_PING_PONG,
	OPT_PASSES, OPT_DURATION, OPT_SETTLE, OPT_EXPOSURE, OPT_TIMEOUT, OPT_JOURNAL,
	OPT_NO_JOURNAL, OPT_TELEMETRY, OPT_CLOCK, OPT_PRIORITY, OPT_CPU, OPT_NO_MLOCK,
	OPT_FORCE, OPT_CAMERA_LOG, OPT_LAT_HIST, OPT_QUIET, OPT_HELP,
};

static const struct option play_options[] = {
	{ "sim", no_argument, NULL, OPT_SIM },
	{ "mode", required_argument, NULL, OPT_MODE },
	{ "from", required_argument, NULL, OPT_FROM },
	{ "to", required_argument, NULL, OPT_TO },
	{ "frames", required_argument, NULL, OPT_FRAMES },
	{ "loop", no_argument, NULL, OPT_LOOP },
	{ "ping-pong", no_argument, NULL, OPT_PING_PONG },
	{ "passes", required_argument, NULL, OPT_PASSES },
	{ "duration", required_argument, NULL, OPT_DURATION },
	{ "settle", required_argument, NULL, OPT_SETTLE },
	{ "exposure", required_argument, NULL, OPT_EXPOSURE },
	{ "timeout", required_argument, NULL, OPT_TIMEOUT },
	{ "journal", required_argument, NULL, OPT_JOURNAL },
	{ "no-journal", no_argument, NULL, OPT_NO_JOURNAL },
	{ "telemetry", required_argument, NULL, OPT_TELEMETRY },
	{ "clock", required_argument, NULL, OPT_CLOCK },
	{ "priority", required_argument, NULL, OPT_PRIORITY },
	{ "cpu", required_argument, NULL, OPT_CPU },
	{ "no-mlock", no_argument, NULL, OPT_NO_MLOCK },
	{ "force", no_argument, NULL, OPT_FORCE },
	{ "camera-log", required_argument, NULL, OPT_CAMERA_LOG },
	{ "latency-hist", required_argument, NULL, OPT_LAT_HIST },
	{ "quiet", no_argument, NULL, OPT_QUIET },
	{ "help", no_argument, NULL, OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

struct cli {
	struct play_opts o;
	const char *scene;
	const char *frames;
	const char *lat_hist;
	bool have_from, have_to, no_journal, quiet, step;
	int64_t from, to;
	double duration_s, settle_ms, exposure_ms, timeout_s;
	char journal[PATH_MAX];
};

static int parse(struct cli *c, int argc, char **argv)
{
	int opt;
	int64_t v;

	memset(c, 0, sizeof(*c));
	c->o.rt.priority = 80;
	c->o.rt.cpu = -1;
	c->o.rt.lock_memory = true;
	c->o.rt.pm_qos = true;
	c->o.rt.name = "strand-rt";
	c->settle_ms = 200;
	c->exposure_ms = 100;
	c->timeout_s = 10;
	optind = 1;
	while ((opt = getopt_long(argc, argv, "h", play_options, NULL)) != -1) {
		switch (opt) {
		case OPT_SIM:
			c->o.rig.sim = true;
			break;
		case OPT_MODE:
			if (strcmp(optarg, "continuous") && strcmp(optarg, "step"))
				return usage_error("--mode %s: continuous or step", optarg);
			c->step = !strcmp(optarg, "step");
			break;
		case OPT_FROM:
		case OPT_TO:
			if (!parse_i64(optarg, &v) || v < 0)
				return usage_error("--from/--to %s: a frame number", optarg);
			if (opt == OPT_FROM) {
				c->from = v;
				c->have_from = true;
			} else {
				c->to = v;
				c->have_to = true;
			}
			break;
		case OPT_FRAMES:
			c->frames = optarg;
			break;
		case OPT_LOOP:
			c->o.loop.loop = true;
			break;
		case OPT_PING_PONG:
			c->o.loop.ping_pong = true;
			break;
		case OPT_PASSES:
			if (!parse_i64(optarg, &v) || v < 1)
				return usage_error("--passes %s: a count of 1 or more", optarg);
			c->o.loop.passes = v;
			break;
		case OPT_DURATION:
			if (!parse_double(optarg, &c->duration_s) || c->duration_s == 0)
				return usage_error("--duration %s: seconds", optarg);
			break;
		case OPT_SETTLE:
			if (!parse_double(optarg, &c->settle_ms))
				return usage_error("--settle %s: milliseconds", optarg);
			break;
		case OPT_EXPOSURE:
			if (!parse_double(optarg, &c->exposure_ms))
				return usage_error("--exposure %s: milliseconds", optarg);
			break;
		case OPT_TIMEOUT:
			if (!parse_double(optarg, &c->timeout_s) || c->timeout_s == 0)
				return usage_error("--timeout %s: seconds", optarg);
			break;
		case OPT_JOURNAL:
			snprintf(c->journal, sizeof(c->journal), "%s", optarg);
			break;
		case OPT_NO_JOURNAL:
			c->no_journal = true;
			break;
		case OPT_TELEMETRY:
			c->o.telemetry_path = optarg;
			break;
		case OPT_CLOCK:
			if (strcmp(optarg, "real") && strcmp(optarg, "virtual"))
				return usage_error("--clock %s: real or virtual", optarg);
			c->o.virtual_clock = !strcmp(optarg, "virtual");
			break;
		case OPT_PRIORITY:
			if (!parse_i64(optarg, &v) || v < 0 || v > 99)
				return usage_error("--priority %s: 0 to 99", optarg);
			c->o.rt.priority = (int)v;
			break;
		case OPT_CPU:
			if (!parse_i64(optarg, &v) || v < 0 || v >= CPU_SETSIZE)
				return usage_error("--cpu %s: a CPU number", optarg);
			c->o.rt.cpu = (int)v;
			break;
		case OPT_NO_MLOCK:
			c->o.rt.lock_memory = false;
			break;
		case OPT_FORCE:
			c->o.loop.force = true;
			break;
		case OPT_CAMERA_LOG:
			c->o.rig.camera_log = optarg;
			break;
		case OPT_LAT_HIST:
			c->lat_hist = optarg;
			break;
		case OPT_QUIET:
			c->quiet = true;
			break;
		case OPT_HELP:
		case 'h':
			fputs(play_usage, stdout);
			return -1;
		default:
			return usage_error("%s", "unknown option");
		}
	}
	if (optind != argc - 1)
		return usage_error("%s", optind >= argc ? "which scene?" : "one scene only");
	c->scene = argv[optind];
	if (c->frames && !c->step)
		return usage_error("%s", "--frames is for --mode step");
	if (c->step && (c->o.loop.loop || c->o.loop.ping_pong))
		return usage_error("%s", "--loop and --ping-pong are for continuous mode");
	if (c->o.loop.loop && c->o.loop.ping_pong)
		return usage_error("%s", "--loop or --ping-pong, not both");
	if (c->o.loop.passes && !c->o.loop.loop && !c->o.loop.ping_pong)
		return usage_error("%s", "--passes goes with --loop or --ping-pong");
	return 0;
}

/* The histogram as cyclictest -h writes its own: "us count" lines. */
static int write_hist(const char *path, const struct lat_stats *s)
{
	FILE *f = fopen(path, "w");
	uint32_t i;

	if (!f)
		return -errno;
	fprintf(f, "# strand wake-up latency, 1 us buckets\n");
	for (i = 0; i < LAT_HIST_US; i++)
		if (s->hist[i])
			fprintf(f, "%06u %06u\n", i, s->hist[i]);
	fprintf(f, "# Total: %lld\n# Overflow: %lld\n# Max Latencies: %.3f\n", (long long)s->n,
		(long long)s->overflow, s->n ? s->max_ns / 1000.0 : 0.0);
	return fclose(f) ? -errno : 0;
}

static int prepare_exit(enum play_stage st)
{
	switch (st) {
	case PLAY_STAGE_START:
		return STRAND_EXIT_FAULT;
	case PLAY_STAGE_JOURNAL:
		return STRAND_EXIT_IO;
	default:
		return STRAND_EXIT_SCENE;
	}
}

int play_main(int argc, char **argv, play_load_fn load, play_check_fn check)
{
	struct cli c;
	struct play_scene ps;
	struct scene_built built;
	struct scene_build_err berr;
	struct source_scene src;
	struct rig_auto ra;
	struct frame_list fl = { 0 };
	const struct rig_desc *rig;
	struct sigaction sa;
	struct play p;
	char err[512];
	int rc, code;
	uint32_t hz;

	rc = parse(&c, argc, argv);
	if (rc)
		return rc < 0 ? STRAND_EXIT_OK : rc;
	memset(&ps, 0, sizeof(ps));
	rc = load(c.scene, &ps, err, sizeof(err));
	if (rc) {
		fprintf(stderr, "%s\n", err);
		return rc == -ENOENT || rc == -EIO || rc == -EACCES ? STRAND_EXIT_IO :
								       STRAND_EXIT_SCENE;
	}
	code = STRAND_EXIT_SCENE;
	memset(&built, 0, sizeof(built));
	memset(&ra, 0, sizeof(ra));
	memset(&src, 0, sizeof(src));
	memset(&p, 0, sizeof(p));
	if (check) {
		rc = check(&ps);
		if (rc && !c.o.loop.force) {
			fprintf(stderr, "strand play: %s: strand check rejects this scene; "
				"--force plays it anyway, clamping setpoints to the limits\n", c.scene);
			code = rc > 0 ? STRAND_EXIT_VIOLATION : STRAND_EXIT_SCENE;
			goto out;
		}
	}
	rc = scene_build(&built, ps.desc, &berr);
	if (rc) {
		fprintf(stderr, "%s: cannot build the scene (error %d at node %d, %s)\n", c.scene,
			berr.code, berr.node, berr.what ? berr.what : "?");
		goto out;
	}
	rc = source_scene_init(&src, ps.desc, &built.sc);
	if (rc) {
		fprintf(stderr, "strand play: %s\n", strerror(-rc));
		code = STRAND_EXIT_INTERNAL;
		goto out;
	}
	rig = ps.rig;
	if (!rig || (!rig->noutputs && !rig->ntriggers)) {
		if (!c.o.rig.sim) {
			fprintf(stderr, "%s: the scene describes no rig (devices:, outputs:, "
				"triggers:); play it on a simulated one with --sim\n", c.scene);
			goto out;
		}
		rc = rig_auto_build(&ra, ps.desc, &src.s);
		if (rc) {
			fprintf(stderr, "%s: simulated rig: %s\n", c.scene, strerror(-rc));
			goto out;
		}
		rig = &ra.d;
	}
	hz = src.s.timing.tick_hz;
	c.o.loop.from = c.have_from ? c.from : src.s.frame_first;
	c.o.loop.to = c.have_to ? c.to : src.s.frame_last;
	c.o.loop.settle_ticks = llround(c.settle_ms * hz / 1000);
	c.o.loop.exposure_ticks = llround(c.exposure_ms * hz / 1000);
	c.o.loop.in_position_timeout_ticks = llround(c.timeout_s * hz);
	c.o.loop.ready_timeout_ticks = llround(c.timeout_s * hz);
	c.o.loop.max_ticks = llround(c.duration_s * hz);
	c.o.loop.status_every = hz / 10 ? hz / 10 : 1;
	if (c.step) {
		c.o.loop.mode = LOOP_MODE_STEP;
		rc = c.frames ? frames_parse(&fl, c.frames, err, sizeof(err)) :
				frames_range(&fl, c.o.loop.from, c.o.loop.to);
		if (rc) {
			fprintf(stderr, "strand play: %s\n", c.frames ? err : strerror(-rc));
			code = STRAND_EXIT_USAGE;
			goto out;
		}
		c.o.loop.frames = &fl;
	}
	if (!c.no_journal) {
		if (!c.journal[0])
			default_journal(c.journal, sizeof(c.journal), src.s.name);
		c.o.journal_path = c.journal;
	}
	c.o.status_tty = !c.quiet && isatty(STDERR_FILENO) ? stderr : NULL;
	rc = play_prepare(&p, rig, &src.s, &c.o, err, sizeof(err));
	if (rc) {
		fprintf(stderr, "%s: %s\n", c.scene, err);
		code = p.failed_at == PLAY_STAGE_LOOP && strstr(err, "--") ?
			       STRAND_EXIT_USAGE : prepare_exit(p.failed_at);
		goto out;
	}
	memset(&sa, 0, sizeof(sa));
	sa.sa_handler = on_signal;
	sigemptyset(&sa.sa_mask);
	g_play = &p;
	g_sigints = 0;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	code = play_run(&p);
	signal(SIGINT, SIG_DFL);
	signal(SIGTERM, SIG_DFL);
	g_play = NULL;
	if (code != STRAND_EXIT_OK) {
		play_describe(&p, err, sizeof(err));
		fprintf(stderr, "strand play: %s\n", err);
	}
	if (c.lat_hist && write_hist(c.lat_hist, &p.L.lat))
		fprintf(stderr, "strand play: %s: %s\n", c.lat_hist, strerror(errno));
	/* the reason is on stderr already when the run did not finish */
	if (!c.quiet)
		play_summary(&p, stdout, code == STRAND_EXIT_OK);
out:
	play_free(&p);
	frames_free(&fl);
	rig_auto_free(&ra);
	source_scene_free(&src);
	if (built.block)
		scene_built_free(&built);
	if (ps.release)
		ps.release(&ps);
	return code;
}

int journal_main(int argc, char **argv)
{
	char msg[512];
	int rc;

	if (argc == 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
		puts("usage: strand journal FILE\n\n"
		     "Prints a frame journal written by strand play as CSV: a header row, then\n"
		     "one row per trigger fired: frame, timecode, tick, trigger, state (fired, or\n"
		     "armed for a frame caught by a kill between its record and its edge),\n"
		     "due_ns, mono_ns, late_us, wall (UTC), ferr and ferr_channel (the worst\n"
		     "following error during the frame), then every output's setpoint in the\n"
		     "scene file's units (degrees for angles).");
		return STRAND_EXIT_OK;
	}
	if (argc != 2) {
		fprintf(stderr, "usage: strand journal FILE\n");
		return STRAND_EXIT_USAGE;
	}
	rc = journal_csv(argv[1], stdout, msg, sizeof(msg));
	if (fflush(stdout) && !rc) {
		rc = -EIO;
		snprintf(msg, sizeof(msg), "standard output: %s", strerror(errno));
	}
	if (rc) {
		fprintf(stderr, "strand journal: %s\n", msg);
		return STRAND_EXIT_IO;
	}
	return STRAND_EXIT_OK;
}
