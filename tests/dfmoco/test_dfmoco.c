/* SPDX-License-Identifier: MIT */
/*
 * test_dfmoco.c - strand as a DFMoco motion controller (dfmoco/), driven
 * by a client written here from the protocol (the messages of
 * dfm_parse.h and the replies Dragonframe waits for), over a
 * pseudo-terminal as over a serial line, on a simulated rig in virtual
 * time at the wall's pace:
 *
 *   - Dragonframe's session: hello, top speeds, zeroing, each frame's
 *     positions for every motor and ms polled until they stop, go-motion
 *     (bf, ms until armed, go, ms until done), a jog held with repeated jm
 *     and released with sm, a stop of all;
 *   - what each move did on the simulated drives: where they stand (within
 *     their in-position tolerance of the target), the speeds and
 *     accelerations they were sent (within the outputs' limits), and the
 *     go-motion's exposure in the journal and on the drive: a straight line
 *     through the positions bf gave, centred on this frame's;
 *   - every error case: the protocol's error reply and nothing changed;
 *     a position beyond a limit refused, never clamped; bf -1 when the
 *     limits forbid the speed; the e-stop input stopping a move, said to
 *     the client, and its reset by a new hello once released;
 *   - TCP: one client at a time.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include <arpa/inet.h>

#include "dfmoco/dfm_run.h"
#include "live/live_priv.h"
#include "playutil.h"
#include "rig/drv_sim.h"
#include "sim/sim_drive.h"
#include "sim/sim_gpio.h"
#include "testutil.h"

/* pan: 10000 counts a degree, -90..90, 180 deg/s, 1800 deg/s^2; slide:
 * 1000000 counts a metre (1 um), -0.5..0.5 m, 0.5 m/s, 5 m/s^2; prop: a
 * speed. */
static const char scene[] =
	"scene: dfm\n"
	"timing: {tick_hz: 1000, frame_rate: 24, frames: [0, 48]}\n"
	"nodes:\n"
	"  - {name: pan, joint: {type: revolute, axis: y},\n"
	"     limits: {min: -90, max: 90, velocity: 180, acceleration: 1800}}\n"
	"  - {name: slide, joint: {type: prismatic, axis: x},\n"
	"     limits: {min: -0.5, max: 0.5, velocity: 0.5, acceleration: 5}}\n"
	"  - {name: prop, joint: {type: revolute, axis: z}}\n"
	"strands:\n"
	"  - {node: prop, interpolation: linear, keys: [{frame: 0, rpm: 0}, {frame: 48, rpm: 0}]}\n"
	"devices:\n"
	"  - {name: drives, driver: sim}\n"
	"  - {name: io, driver: sim}\n"
	"outputs:\n"
	"  - {channel: pan.angle, device: drives, axis: 0, counts_per_unit: 10000,\n"
	"     in_position: 0.02}\n"
	"  - {channel: slide.position, device: drives, axis: 1, counts_per_unit: 1000000,\n"
	"     in_position: 0.0002}\n"
	"  - {channel: prop.rpm, device: drives, axis: 2, counts_per_unit: 1,\n"
	"     limits: {velocity: 100, acceleration: 100}}\n"
	"triggers:\n"
	"  - {name: camera, device: io, line: 0, pulse_ms: 2}\n"
	"inputs:\n"
	"  - {name: estop, device: io, line: 1, role: estop, active_low: false}\n";

struct fixture {
	char dir[64], path[128], pty[128], journal[128];
	struct live *lv;
	struct dfm_session *s;
	struct dfm_port port;
	pthread_t thread;
	volatile sig_atomic_t stop;
	int rc;
	/* the client */
	int fd;
	char in[65536];
	size_t len;
	int64_t mp[4]; /* the last position each motor was said to be at */
};

static void *serve(void *arg)
{
	struct fixture *f = arg;

	f->rc = dfm_run(f->s, &f->port, &f->stop, stderr);
	return NULL;
}

static void start(struct fixture *f, bool tcp, unsigned port)
{
	struct live_opts o = { .sim = true, .virtual_clock = true, .pace_all = true,
			       .deadman_ms = 300, .journal_gomo = true };
	char err[512];
	FILE *fp;

	memset(f, 0, sizeof(*f));
	snprintf(f->dir, sizeof(f->dir), "/tmp/strand-dfm-XXXXXX");
	assert_non_null(mkdtemp(f->dir));
	snprintf(f->path, sizeof(f->path), "%s/dfm.yaml", f->dir);
	snprintf(f->pty, sizeof(f->pty), "%s/moco", f->dir);
	snprintf(f->journal, sizeof(f->journal), "%s/dfm.journal", f->dir);
	fp = fopen(f->path, "w");
	assert_non_null(fp);
	fputs(scene, fp);
	fclose(fp);
	o.journal_file = f->journal;
	o.rt.cpu = -1;
	o.rt.name = "strand-rt";
	if (live_open(&f->lv, f->path, &o, err, sizeof(err)))
		fail_msg("live_open: %s", err);
	assert_int_equal(live_enable(f->lv, err, sizeof(err)), 0);
	f->s = calloc(1, sizeof(*f->s));
	assert_non_null(f->s);
	dfm_session_init(f->s, f->lv, stderr);
	if (tcp)
		assert_int_equal(dfm_port_listen(&f->port, "127.0.0.1", port, NULL, err,
						 sizeof(err)), 0);
	else
		assert_int_equal(dfm_port_pty(&f->port, f->pty, err, sizeof(err)), 0);
	assert_int_equal(pthread_create(&f->thread, NULL, serve, f), 0);
	f->fd = -1;
	if (!tcp) {
		struct termios t;

		f->fd = open(f->pty, O_RDWR | O_NOCTTY);
		assert_true(f->fd >= 0);
		assert_int_equal(tcgetattr(f->fd, &t), 0);
		cfmakeraw(&t);
		assert_int_equal(tcsetattr(f->fd, TCSANOW, &t), 0);
	}
}

static void stop(struct fixture *f)
{
	char cmd[300];

	if (f->fd >= 0)
		close(f->fd);
	f->stop = 1;
	pthread_join(f->thread, NULL);
	assert_int_equal(f->rc, 0);
	dfm_port_close(&f->port);
	live_close(f->lv);
	free(f->s);
	snprintf(cmd, sizeof(cmd), "rm -rf %s", f->dir);
	assert_int_equal(system(cmd), 0);
}

/* ---- the client ---- */

static void send_line(struct fixture *f, const char *fmt, ...)
{
	char line[8192];
	va_list ap;
	int n;

	va_start(ap, fmt);
	n = vsnprintf(line, sizeof(line) - 2, fmt, ap);
	va_end(ap);
	line[n++] = '\r';
	line[n++] = '\n';
	assert_int_equal(write(f->fd, line, (size_t)n), n);
}

/* The next line from the controller within timeout_ms: false if none. */
static bool next_line(struct fixture *f, char *line, size_t size, int timeout_ms)
{
	struct pollfd pfd = { .fd = f->fd, .events = POLLIN };
	char *end;

	for (;;) {
		end = memmem(f->in, f->len, "\r\n", 2);
		if (end) {
			size_t n = (size_t)(end - f->in);

			snprintf(line, size, "%.*s", (int)n, f->in);
			if (getenv("DFM_DEBUG"))
				printf("< %s\n", line);
			memmove(f->in, end + 2, f->len - n - 2);
			f->len -= n + 2;
			if (!strncmp(line, "mp ", 3)) {
				int m;
				long long p;

				if (sscanf(line, "mp %d %lld", &m, &p) == 2 && m >= 1 && m <= 3)
					f->mp[m] = p;
			}
			return true;
		}
		if (poll(&pfd, 1, timeout_ms) <= 0)
			return false;
		ssize_t got = read(f->fd, f->in + f->len, sizeof(f->in) - f->len);

		if (got <= 0)
			return false;
		f->len += (size_t)got;
	}
}

/* Send cmd and read the replies wanted, in order; the positions said
 * meanwhile ("mp" lines other than those wanted) are taken in and passed
 * over, any other line is a failure. */
static void exchange(struct fixture *f, const char *cmd, ...)
{
	const char *want;
	char line[1024];
	va_list ap;

	send_line(f, "%s", cmd);
	va_start(ap, cmd);
	while ((want = va_arg(ap, const char *))) {
		for (;;) {
			if (!next_line(f, line, sizeof(line), 3000))
				fail_msg("%s: no '%s' within 3 s", cmd, want);
			if (!strncmp(want, line, strlen(want)))
				break;
			if (strncmp(line, "mp ", 3))
				fail_msg("%s: '%s', want '%s'", cmd, line, want);
		}
	}
	va_end(ap);
}

/* ms polled until every motor rests (as Dragonframe does before a shot):
 * how many polls that took. */
static int until_still(struct fixture *f)
{
	char line[256];
	int polls;

	for (polls = 1; polls < 500; polls++) {
		send_line(f, "ms");
		for (;;) {
			assert_true(next_line(f, line, sizeof(line), 3000));
			if (!strncmp(line, "ms ", 3))
				break;
			if (strncmp(line, "mp ", 3))
				fail_msg("ms: '%s'", line);
		}
		if (!strcmp(line, "ms 000"))
			return polls;
		nanosleep(&(struct timespec){ .tv_nsec = 20000000 }, NULL);
	}
	fail_msg("the motors never stopped");
	return 0;
}

/* Lines that come unasked within ms: nothing but positions. */
static void quiet(struct fixture *f, int ms)
{
	char line[1024];

	while (next_line(f, line, sizeof(line), ms))
		if (strncmp(line, "mp ", 3))
			fail_msg("unasked: '%s'", line);
}

/* ---- the rig ---- */

static const struct sim_drive_watch *watch(struct fixture *f, uint32_t ch)
{
	return sim_drive_watch(sim_drive_of(f->lv->rig.axes[0]), ch);
}

/* Every command the drive got within its output's limits (the drive's
 * finite differences, a tick apart, of whole counts: a count a tick of
 * rounding allowed, as playutil's runs do), and where it stands within its
 * in-position tolerance of target (counts). */
static void drive_at(struct fixture *f, uint32_t ch, int64_t target)
{
	const struct rig_out *o = &f->lv->rig.out[ch];
	const struct sim_drive_watch *w = watch(f, ch);
	double cpu = fabs(o->scale.per_unit_d);

	double hz = 1000;

	if (w->cmd_vel_max > o->vmax * cpu * (1 + 1e-6) + hz ||
	    w->cmd_acc_max > o->amax * cpu * (1 + 1e-6) + 2 * hz * hz)
		fail_msg("%s: sent %g counts/s, %g counts/s^2; limits %g, %g", o->channel,
			 w->cmd_vel_max, w->cmd_acc_max, o->vmax * cpu, o->amax * cpu);
	assert_int_equal(w->target, target);
	if (fabs(w->x - (double)target) > o->in_position * cpu + 0.5)
		fail_msg("%s: at %.2f counts, %lld wanted", o->channel, w->x, (long long)target);
}

/* Let the drives settle onto their targets (the session says "ms 000"
 * when the setpoints rest; the plant follows within a few of its time
 * constants). */
static void settle(void)
{
	nanosleep(&(struct timespec){ .tv_nsec = 150000000 }, NULL);
}

/* ---- the tests ---- */

/* Dragonframe's session, and the motion each move made. */
static void test_session(void **state)
{
	static const int64_t pan[] = { 0, 50000, 150000, 100000, -250000 };
	static const int64_t slide[] = { 0, 20000, 60000, 30000, -100000 };
	struct fixture f;
	struct pu_csv c;
	int64_t buf[20000 * 3];
	int polls, k;

	start(&f, false, 0);
	exchange(&f, "hi", "hi 1 3 1.3.1", NULL);
	/* Arc's motor settings: top speeds, clamped to the limits */
	exchange(&f, "pr 1 900000", "pr 1 900000", NULL);
	exchange(&f, "pr 2 10000000", "pr 2 500000", NULL);
	exchange(&f, "zm 1", "zm 1", "mp 1 0", NULL);
	exchange(&f, "np 2 0", "np 2 0", "mp 2 0", NULL);
	exchange(&f, "ms", "ms 000", NULL);
	/* each frame: every motor's position, then ms until they stop */
	for (k = 0; k < 5; k++) {
		char l1[64], l2[64], w1[64], w2[64];

		snprintf(l1, sizeof(l1), "mm 1 %lld", (long long)pan[k]);
		snprintf(l2, sizeof(l2), "mm 2 %lld", (long long)slide[k]);
		snprintf(w1, sizeof(w1), k ? "mm 1 %lld" : "mp 1 %lld", (long long)pan[k]);
		snprintf(w2, sizeof(w2), k ? "mm 2 %lld" : "mp 2 %lld", (long long)slide[k]);
		send_line(&f, "%s\r\n%s", l1, l2);
		exchange(&f, "ms", w1, w2, "ms ", NULL);
		polls = until_still(&f);
		/* where they are now (the positions said while they moved
		 * lag behind) */
		exchange(&f, "mp 1", "mp 1", NULL);
		exchange(&f, "mp 2", "mp 2", NULL);
		assert_int_equal(f.mp[1], pan[k]);
		assert_int_equal(f.mp[2], slide[k]);
		settle();
		drive_at(&f, 0, pan[k]);
		drive_at(&f, 1, slide[k]);
		printf("frame %d: pan %lld, slide %lld, %d polls of ms\n", k, (long long)pan[k],
		       (long long)slide[k], polls);
	}
	exchange(&f, "mp 1", "mp 1 -250000", NULL);

	/* go-motion: 200 ms of exposure with blur 500 through -30, -25 and
	 * -20 degrees on the pan; the slide still. The rig goes to the
	 * run-up's start, the motors rest (armed), go runs it: half a frame
	 * centred on -25 degrees, -26.25 to -23.75, in 200 ms. */
	sim_drive_trace(sim_drive_of(f.lv->rig.axes[0]), buf, 20000);
	exchange(&f, "bf 200 500 1 -300000 -250000 -200000 2 -100000 -100000 -100000", "bf ",
		 NULL);
	until_still(&f);
	exchange(&f, "go", "go", NULL);
	until_still(&f);
	settle();
	assert_int_equal(pu_csv_read(&c, f.journal), 0);
	assert_int_equal(c.nrows, 2);
	{
		int64_t open = atoll(c.cell[1][pu_csv_col(&c, "open_tick")]);
		int64_t close = atoll(c.cell[1][pu_csv_col(&c, "close_tick")]);
		int64_t first = sim_drive_trace_first(sim_drive_of(f.lv->rig.axes[0])), j;
		double a = atof(c.cell[1][pu_csv_col(&c, "pan.angle@open")]);
		double b = atof(c.cell[1][pu_csv_col(&c, "pan.angle@close")]);

		assert_int_equal(atoll(c.cell[1][pu_csv_col(&c, "frame")]), 1);
		/* a quarter of the way to each neighbour, in 200 ms: 200 ticks */
		printf("go-motion: pan %.10g to %.10g deg, ticks %lld to %lld\n", a, b,
		       (long long)open, (long long)close);
		assert_true(fabs(a - -26.25) < 1e-6 && fabs(b - -23.75) < 1e-6);
		assert_int_equal(close - open, 200);
		assert_true(fabs(atof(c.cell[1][pu_csv_col(&c, "slide.position@open")]) + 0.1) <
			    1e-9);
		/* on the drive: the straight line, count by count */
		for (j = 0; j <= close - open; j++) {
			int64_t want = -262500 + 125 * j;
			int64_t got = buf[(open + j - first) * 3];

			if (llabs(got - want) > 1)
				fail_msg("exposure tick %lld: pan sent %lld counts, the line %lld",
					 (long long)j, (long long)got, (long long)want);
		}
	}
	pu_csv_free(&c);
	drive_at(&f, 1, -100000);

	/* a jog held (jm repeated, as Dragonframe does while the key is
	 * down) and released (sm): 90 deg/s (pr 1 900000) for about 0.4 s */
	{
		int64_t from = f.mp[1];
		int i;

		exchange(&f, "mp 1", "mp 1", NULL);
		from = f.mp[1];
		for (i = 0; i < 4; i++) {
			exchange(&f, "jm 1 900000", "jm 1", NULL);
			nanosleep(&(struct timespec){ .tv_nsec = 100000000 }, NULL);
		}
		exchange(&f, "ms", "ms 100", NULL);
		exchange(&f, "sm 1", "sm 1", "mp 1", NULL);
		until_still(&f);
		exchange(&f, "mp 1", "mp 1", NULL);
		printf("jog: pan from %lld to %lld counts\n", (long long)from, (long long)f.mp[1]);
		assert_true(f.mp[1] - from > 250000 && f.mp[1] - from < 600000);
		settle();
		drive_at(&f, 0, f.mp[1] + f.s->zero[0]);
	}
	/* stop all in the middle of a move: it stops short, within limits */
	exchange(&f, "mm 1 -800000", "mm 1 -800000", NULL);
	nanosleep(&(struct timespec){ .tv_nsec = 100000000 }, NULL);
	exchange(&f, "sa", "sa", NULL);
	until_still(&f);
	exchange(&f, "mp 1", "mp 1", NULL);
	assert_true(f.mp[1] > -800000);
	settle();
	drive_at(&f, 0, f.mp[1] + f.s->zero[0]);
	quiet(&f, 100);
	stop(&f);
}

/* Every bad line: the protocol's error reply, and nothing changes. */
static void test_errors(void **state)
{
	static const char *const bad[] = {
		"xx", "HI", "hi 1", "ms 3", "mm", "mm 1", "mm 1 2 3", "mm 4 0", "mm 0 0", "mp 9",
		"mm 1 9999999999", "mm 1 -2147483649", "mm 1 abc", "mm 1 1.5", "mm1 1",
		"bf 100 500 1 2 3", "bf 100 500", "bf 100 1001 1 1 2 3", "bf 0 500 1 1 2 3",
		"bf 100 500 1 0 0 0 1 0 0 0", "bf 100 500 4 0 0 0", "pr 1 0", "pr 5 100",
		"zm 0", "np 4 1", "jm 7 1", "im 0 1", "sm 4",
	};
	char longline[5000], line[256];
	struct fixture f;
	size_t i;

	start(&f, false, 0);
	exchange(&f, "hi", "hi 1 3 1.3.1", NULL);
	exchange(&f, "mm 1 100000", "mm 1 100000", NULL);
	until_still(&f);
	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++)
		exchange(&f, bad[i], "parse error", NULL);
	memset(longline, 'm', sizeof(longline) - 1);
	longline[sizeof(longline) - 1] = 0;
	exchange(&f, longline, "parse error", NULL);
	/* go without a bf; a speed motor positioned */
	exchange(&f, "go", "error: go: no go-motion prepared", "parse error", NULL);
	exchange(&f, "mm 3 10", "error: motor 3 (prop.rpm) is a speed", "parse error", NULL);
	/* beyond a limit: refused, never clamped; where it is said */
	exchange(&f, "mm 1 900001", "error: motor 1 (pan.angle): position 900001 (90.0001 deg) is "
		 "beyond its limits, -900000 to 900000: refused", "mp 1 100000", NULL);
	/* inch: two counts towards the position given */
	exchange(&f, "im 2 100", "im 2", NULL);
	until_still(&f);
	exchange(&f, "mp 2", "mp 2 2", NULL);
	/* a go-motion faster than the limits: bf -1 (900 deg/s) */
	exchange(&f, "bf 100 1000 1 -900000 0 900000", "error: go-motion: ", "bf -1", NULL);
	exchange(&f, "go", "error: go: no go-motion prepared", "parse error", NULL);
	exchange(&f, "ms", "ms 000", NULL);
	/* nothing moved: the pan where the first move left it */
	settle();
	drive_at(&f, 0, 100000);
	drive_at(&f, 1, 2);
	assert_false(next_line(&f, line, sizeof(line), 200));
	stop(&f);
}

/* The e-stop input stops a move in its tick, the client is told, and
 * nothing moves again until it is released and the client says hi. */
static void test_estop(void **state)
{
	struct sim_gpio *io;
	struct fixture f;
	char line[512];
	bool told = false;
	int i;

	start(&f, false, 0);
	io = rig_sim_gpio(&f.lv->rig, "io"); /* the e-stop: its first input line */
	exchange(&f, "hi", "hi 1 3 1.3.1", NULL);
	exchange(&f, "mm 1 800000", "mm 1 800000", NULL);
	nanosleep(&(struct timespec){ .tv_nsec = 150000000 }, NULL);
	assert_true(sim_gpio_inject(io, 0, true));
	for (i = 0; i < 100 && !told; i++)
		if (next_line(&f, line, sizeof(line), 100))
			told = !strncmp(line, "error: e-stop: ", 15);
	assert_true(told);
	printf("%s\n", line);
	exchange(&f, "ms", "ms 000", NULL);
	assert_false(watch(&f, 0)->powered);
	assert_true(watch(&f, 0)->target < 800000);
	exchange(&f, "mm 1 0", "error: e-stopped", "mp 1", NULL);
	exchange(&f, "bf 100 500 1 0 0 0", "error: e-stopped", "bf -1", NULL);
	/* hi while it is held: refused; released: reset, the drives on */
	exchange(&f, "hi", "hi 1 3", "error: the e-stop input 'estop' is asserted", NULL);
	assert_true(sim_gpio_inject(io, 0, false));
	nanosleep(&(struct timespec){ .tv_nsec = 50000000 }, NULL);
	exchange(&f, "hi", "hi 1 3", NULL);
	exchange(&f, "mm 1 0", "mm 1 0", NULL);
	until_still(&f);
	settle();
	assert_true(watch(&f, 0)->powered);
	drive_at(&f, 0, 0);
	stop(&f);
}

/* A bf without its go gives way to the next bf, or to a move, as the
 * sketch's does; a still frame (blur 0) moves to its positions and go
 * moves nothing; only frames run are journaled. */
static void test_gomo_replaced(void **state)
{
	struct fixture f;
	struct pu_csv c;

	start(&f, false, 0);
	exchange(&f, "hi", "hi 1 3 1.3.1", NULL);
	exchange(&f, "bf 100 500 1 -20000 0 20000", "bf ", NULL);
	until_still(&f);
	exchange(&f, "bf 100 250 1 0 20000 40000", "bf ", NULL);
	until_still(&f);
	exchange(&f, "mm 1 50000", "mm 1 50000", NULL);
	until_still(&f);
	exchange(&f, "mp 1", "mp 1 50000", NULL);
	exchange(&f, "bf 100 0 1 40000 60000 80000", "bf 0", NULL);
	until_still(&f);
	exchange(&f, "go", "go", NULL);
	exchange(&f, "mp 1", "mp 1 60000", NULL);
	exchange(&f, "bf 100 250 1 50000 60000 70000", "bf ", NULL);
	until_still(&f);
	exchange(&f, "go", "go", NULL);
	until_still(&f);
	settle();
	assert_int_equal(pu_csv_read(&c, f.journal), 0);
	assert_int_equal(c.nrows, 2);
	/* the first frame run: the frames bf prepared and never ran have no number */
	assert_int_equal(atoll(c.cell[1][pu_csv_col(&c, "frame")]), 1);
	/* an eighth of a frame either side of 60000 */
	assert_true(fabs(atof(c.cell[1][pu_csv_col(&c, "pan.angle@open")]) - 5.875) < 1e-6);
	assert_true(fabs(atof(c.cell[1][pu_csv_col(&c, "pan.angle@close")]) - 6.125) < 1e-6);
	pu_csv_free(&c);
	stop(&f);
}

/* TCP: a client says hi; a second one is turned away while it stays. */
static void test_tcp(void **state)
{
	struct sockaddr_in a = { .sin_family = AF_INET, .sin_port = htons(47213) };
	struct fixture f;
	char line[128];
	int second;

	start(&f, true, 47213);
	inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
	f.fd = socket(AF_INET, SOCK_STREAM, 0);
	assert_int_equal(connect(f.fd, (struct sockaddr *)&a, sizeof(a)), 0);
	exchange(&f, "hi", "hi 1 3 1.3.1", NULL);
	second = socket(AF_INET, SOCK_STREAM, 0);
	assert_int_equal(connect(second, (struct sockaddr *)&a, sizeof(a)), 0);
	nanosleep(&(struct timespec){ .tv_nsec = 50000000 }, NULL);
	assert_int_equal(write(second, "hi\r\n", 4), 4);
	{
		struct pollfd pfd = { .fd = second, .events = POLLIN };
		char b[16];

		/* closed by the controller, never answered */
		assert_int_equal(poll(&pfd, 1, 2000), 1);
		assert_int_equal(read(second, b, sizeof(b)), 0);
	}
	close(second);
	exchange(&f, "ms", "ms 000", NULL);
	(void)line;
	stop(&f);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_session),
		cmocka_unit_test(test_errors),
		cmocka_unit_test(test_estop),
		cmocka_unit_test(test_gomo_replaced),
		cmocka_unit_test(test_tcp),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
