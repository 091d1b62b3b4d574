/* SPDX-License-Identifier: MIT */
/*
 * test_modbus.c - strand against strand-simdrive, a real Modbus server in a
 * process of its own: over loopback TCP and over a pseudo-terminal pair for
 * RTU, on the virtual clock (lockstep: every update, the same run every
 * time) and on the wall clock (the bus takes the newest setpoint).
 *
 * How ticks are matched: the scene's heartbeat register carries the loop's
 * tick in the same function-16 write as the targets, and strand-simdrive
 * logs every write with it. The journal gives the loop tick of frame 0;
 * `strand export --at frames` its scene tick; their difference maps a loop
 * tick of the play segment to the scene tick `strand export --at ticks`
 * evaluates. Every write received there must be that row's value in counts
 * (counts_per_unit and offset), rounded: export prints ten significant
 * digits, so the received count is within 0.5 of the exported value times
 * the scale, plus export's own rounding (1e-6 counts here).
 *
 * Then every injected fault: the run's exit code and the message that names
 * the device, the unit and the register; a connection dropped at rest made
 * again; a signal while the drive is being enabled at start; mbpoll,
 * Debian's independent Modbus client, reading the drive's registers after
 * a run.
 */
#define _GNU_SOURCE
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cli/exitcode.h"
#include "cliutil.h"
#include "mbpeer.h"
#include "playutil.h"
#include "testutil.h"

struct setup {
	char scene[256], log[256], journal[256], conn[320], pty[256];
	int port;
	struct mbp_peer peer;
};

static void tcp_setup(struct setup *s, const char *what)
{
	memset(s, 0, sizeof(*s));
	pu_tmpname(s->scene, sizeof(s->scene), what);
	pu_tmpname(s->log, sizeof(s->log), "mb-log");
	pu_tmpname(s->journal, sizeof(s->journal), "mb-journal");
	s->port = mbp_free_port();
	assert_true(s->port > 0);
	snprintf(s->conn, sizeof(s->conn), "tcp: {host: 127.0.0.1, port: %d}", s->port);
}

static void rtu_setup(struct setup *s, const char *what)
{
	memset(s, 0, sizeof(*s));
	pu_tmpname(s->scene, sizeof(s->scene), what);
	pu_tmpname(s->log, sizeof(s->log), "mb-log");
	pu_tmpname(s->journal, sizeof(s->journal), "mb-journal");
	pu_tmpname(s->pty, sizeof(s->pty), "mb-pty");
	snprintf(s->conn, sizeof(s->conn),
		 "rtu: {port: %s, baud: 115200, parity: none, stop_bits: 1}", s->pty);
}

static void start_peer(struct setup *s, const char *faults)
{
	char args[512];

	snprintf(args, sizeof(args), "--log %s %s", s->log, faults ? faults : "");
	if (mbp_start(&s->peer, s->scene, args))
		fail_msg("strand-simdrive did not start: '%s'", s->peer.line);
	printf("%s", s->peer.line);
}

static void finish(struct setup *s)
{
	if (s->peer.pid > 0)
		assert_int_equal(mbp_stop(&s->peer), 0);
	unlink(s->scene);
	unlink(s->log);
	unlink(s->journal);
}

/* A CSV of export: the column values of each row. */
struct table {
	int64_t n;
	int64_t *tick;
	double *a, *b;
};

static void export_table(struct table *t, const char *scene, const char *at)
{
	char args[512], *line, *save = NULL;
	int ca = -1, cb = -1, col;
	bool header = true;
	struct run r;

	snprintf(args, sizeof(args), "export %s --at %s --format csv", scene, at);
	strand(&r, args);
	assert_int_equal(r.rc, 0);
	memset(t, 0, sizeof(*t));
	t->tick = calloc(r.out_len / 8 + 1, sizeof(int64_t));
	t->a = calloc(r.out_len / 8 + 1, sizeof(double));
	t->b = calloc(r.out_len / 8 + 1, sizeof(double));
	for (line = strtok_r(r.out, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
		char *f, *s2 = NULL;

		col = 0;
		for (f = strtok_r(line, ",", &s2); f; f = strtok_r(NULL, ",", &s2), col++) {
			if (header) {
				if (!strcmp(f, "a.angle"))
					ca = col;
				if (!strcmp(f, "b.angle"))
					cb = col;
				continue;
			}
			if (col == 0)
				t->tick[t->n] = atoll(f);
			else if (col == ca)
				t->a[t->n] = strtod(f, NULL);
			else if (col == cb)
				t->b[t->n] = strtod(f, NULL);
		}
		if (!header && col > cb)
			t->n++;
		header = false;
	}
	assert_true(ca >= 0 && cb >= 0);
	run_free(&r);
}

static void table_free(struct table *t)
{
	free(t->tick);
	free(t->a);
	free(t->b);
}

/* The loop tick of frame 0 minus its scene tick. */
static int64_t tick_offset(const struct setup *s)
{
	struct table frames;
	struct pu_csv c;
	int64_t off;

	assert_int_equal(pu_csv_read(&c, s->journal), 0);
	assert_true(c.nrows > 1);
	assert_int_equal(atoll(c.cell[1][pu_csv_col(&c, "frame")]), 0);
	export_table(&frames, s->scene, "frames");
	off = atoll(c.cell[1][pu_csv_col(&c, "tick")]) - frames.tick[0];
	table_free(&frames);
	pu_csv_free(&c);
	return off;
}

/*
 * Every write the server logged against export: the ticks are the update
 * ticks (multiples of every), in order; a write of the play segment equals
 * the exported value there. Returns how many were compared; *missing gets
 * the update ticks of the play segment that no write carried.
 */
static int64_t compare(struct setup *s, int64_t every, int64_t *missing)
{
	struct table t;
	struct mbp_write *w;
	int64_t n, i, off = tick_offset(s), compared = 0, prev = -2, sk;
	int on, off_e;

	/* the server logs a request after it answered it: stopped, it has
	 * logged every one */
	assert_int_equal(mbp_stop(&s->peer), 0);
	export_table(&t, s->scene, "ticks");
	n = mbp_log_read(s->log, &w, &on, &off_e);
	assert_true(n > 1);
	assert_int_equal(on, 1);   /* enabled at start */
	assert_int_equal(off_e, 1); /* and cleared at stop */
	assert_int_equal(w[0].tick, -1); /* start: hold where it stands */
	/* the play segment's update ticks */
	for (*missing = 0, sk = 0; sk < t.n; sk++)
		*missing += (sk + off) % every == 0;
	for (i = 1; i < n; i++) {
		double ea, eb;

		sk = w[i].tick - off;
		assert_true(w[i].tick > prev);
		assert_int_equal(w[i].tick % every, 0);
		prev = w[i].tick;
		if (sk < 0 || sk >= t.n)
			continue;
		assert_int_equal(t.tick[sk], sk);
		ea = t.a[sk] * MBP_A_CPU;
		eb = t.b[sk] * MBP_B_CPU + MBP_B_OFFSET;
		if (fabs((double)w[i].v[0] - ea) > 0.5 + 1e-6 ||
		    fabs((double)w[i].v[1] - eb) > 0.5 + 1e-6)
			fail_msg("loop tick %lld (scene tick %lld): the drive received %lld %lld, "
				 "export gives %.6f %.6f counts", (long long)w[i].tick, (long long)sk,
				 (long long)w[i].v[0], (long long)w[i].v[1], ea, eb);
		compared++;
	}
	*missing -= compared;
	free(w);
	table_free(&t);
	return compared;
}

static void play(struct run *r, const struct setup *s, const char *opts)
{
	char args[768];
	uint64_t before = pu_loop_allocations();

	snprintf(args, sizeof(args), "play %s --journal %s %s", s->scene, s->journal, opts);
	strand(r, args);
	printf("%s%s", r->out, r->err);
	/* the Modbus backend allocates nothing in the loop either */
	assert_int_equal(pu_loop_allocations() - before, 0);
}

/* Virtual clock: the loop waits for each update's answer, so the drive gets
 * every tick's setpoint, and each is export's. */
/* The runs below are not about timeouts: 500 ms to answer (not the 20 ms
 * default) keeps a loaded test machine's scheduling from failing them. */
static void test_tcp_lockstep(void **state)
{
	struct setup s;
	struct run r;
	int64_t gaps;

	tcp_setup(&s, "mb-tcp");
	mbp_scene(s.scene, 1000, s.conn, "response_timeout_ms: 500\n"
		  "read_every: 10\nanswer_ms: 0.2\n",
		  ", ferror: 1, min_ferror: 0.2");
	start_peer(&s, NULL);
	play(&r, &s, "--clock virtual");
	assert_int_equal(r.rc, STRAND_EXIT_OK);
	assert_non_null(strstr(r.out, "0 replaced by a newer one"));
	run_free(&r);
	/* the scene's 3001 ticks, each one written */
	assert_int_equal(compare(&s, 1, &gaps), 3001);
	assert_int_equal(gaps, 0);
	finish(&s);
}

/* Wall clock, 250 updates a second: whatever the bus took is the tick's
 * setpoint; at most a few replaced by newer ones when the machine stalls. */
static void test_tcp_wall(void **state)
{
	struct setup s;
	struct run r;
	int64_t gaps, n;

	tcp_setup(&s, "mb-wall");
	mbp_scene(s.scene, 1000, s.conn, "response_timeout_ms: 500\n"
		  "update_hz: 250\nread_every: 20\nanswer_ms: 0.2\n", NULL);
	start_peer(&s, NULL);
	play(&r, &s, "--clock real");
	assert_int_equal(r.rc, STRAND_EXIT_OK);
	assert_non_null(strstr(r.out, "updates every 4 ticks"));
	run_free(&r);
	n = compare(&s, 4, &gaps);
	printf("%lld writes compared, %lld update ticks not written\n", (long long)n,
	       (long long)gaps);
	/* 3001 scene ticks, every fourth an update */
	assert_true(n + gaps >= 750 && n + gaps <= 751);
	assert_true(gaps <= 75);
	finish(&s);
}

/* RTU on a pseudo-terminal at 115200 baud (as the scene says; a pty does
 * not pace bytes), 50 updates a second. */
static void test_rtu_lockstep(void **state)
{
	struct setup s;
	struct run r;
	int64_t gaps;

	rtu_setup(&s, "mb-rtu");
	mbp_scene(s.scene, 1000, s.conn, "response_timeout_ms: 500\n"
		  "update_hz: 50\nread_every: 20\n", NULL);
	start_peer(&s, NULL);
	play(&r, &s, "--clock virtual");
	assert_int_equal(r.rc, STRAND_EXIT_OK);
	run_free(&r);
	assert_true(compare(&s, 20, &gaps) >= 150);
	assert_int_equal(gaps, 0);
	finish(&s);
}

/* The same run twice gives the same writes, tick for tick. */
static void test_lockstep_repeats(void **state)
{
	struct mbp_write *w[2];
	int64_t n[2];
	struct setup s;
	struct run r;
	int k;

	tcp_setup(&s, "mb-twice");
	mbp_scene(s.scene, 1000, s.conn, "response_timeout_ms: 500\n"
		  "update_hz: 500\nread_every: 10\nanswer_ms: 0.2\n", NULL);
	for (k = 0; k < 2; k++) {
		start_peer(&s, NULL);
		play(&r, &s, "--clock virtual");
		assert_int_equal(r.rc, STRAND_EXIT_OK);
		run_free(&r);
		assert_int_equal(mbp_stop(&s.peer), 0);
		n[k] = mbp_log_read(s.log, &w[k], NULL, NULL);
	}
	assert_true(n[0] > 1000);
	assert_int_equal(n[0], n[1]);
	assert_memory_equal(w[0], w[1], (size_t)n[0] * sizeof(*w[0]));
	free(w[0]);
	free(w[1]);
	finish(&s);
}

struct fault_case {
	const char *peer;   /* strand-simdrive's fault options */
	const char *scene;  /* extra modbus: settings */
	int rc;
	const char *msg;    /* what the stop says, after "device fault: device 'drives': " */
};

static void run_fault(const struct fault_case *fc, bool rtu)
{
	char want[512], extra[256];
	struct setup s;
	struct run r;

	if (rtu)
		rtu_setup(&s, "mb-fault");
	else
		tcp_setup(&s, "mb-fault");
	/* RTU at 115200 baud reaches some 50 updates a second (test_check) */
	snprintf(extra, sizeof(extra), "update_hz: %d\nread_every: 20\nanswer_ms: 0.2\n%s",
		 rtu ? 50 : 250, fc->scene ? fc->scene : "");
	mbp_scene(s.scene, 1000, s.conn, extra, NULL);
	start_peer(&s, fc->peer);
	play(&r, &s, "--clock virtual");
	assert_int_equal(r.rc, fc->rc);
	if (rtu)
		snprintf(want, sizeof(want), "device fault: device 'drives': rtu %s unit 1: %s",
			 s.pty, fc->msg);
	else
		snprintf(want, sizeof(want),
			 "device fault: device 'drives': tcp 127.0.0.1:%d unit 1: %s", s.port,
			 fc->msg);
	if (!strstr(r.err, want))
		fail_msg("want '%s'\nin '%s'", want, r.err);
	run_free(&r);
	/* the server saw its setpoints up to the fault, and none after it */
	if (strstr(fc->peer, "die"))
		assert_int_equal(mbp_wait(&s.peer, 5000), 0);
	finish(&s);
}

/* The faults that are not timeouts wait 200 ms for an answer, not the
 * default 20: on a loaded machine a busy answer came after 20 ms and the
 * run stopped on the timeout instead of the exception it was testing. */
#define SLOW_OK "response_timeout_ms: 200\n"

static const struct fault_case faults[] = {
	{ "--silent-after 200", NULL, STRAND_EXIT_FAULT,
	  "write of holding registers 0-5: no answer within 20 ms, 3 times in a row "
	  "(Connection timed out)" },
	/* late beyond three timeouts: three requests in a row unanswered */
	{ "--late-after 200 --late-ms 200", NULL, STRAND_EXIT_FAULT,
	  "write of holding registers 0-5: no answer within 20 ms, 3 times in a row "
	  "(Connection timed out)" },
	{ "--exception-after 200 --exception 4", SLOW_OK, STRAND_EXIT_FAULT,
	  "write of holding registers 0-5: exception 4 (Slave device or server failure), "
	  "3 times in a row (Protocol error)" },
	{ "--exception-after 200 --exception 2", "max_faults: 1\n" SLOW_OK, STRAND_EXIT_FAULT,
	  "write of holding registers 0-5: exception 2 (Illegal data address), 1 time in a "
	  "row (Protocol error)" },
	{ "--die-after 200", NULL, STRAND_EXIT_FAULT,
	  "not connected (the connection was lost) while the axes move, 3 times in a row "
	  "(Transport endpoint is not connected)" },
	{ "--trip-after 200", SLOW_OK, STRAND_EXIT_FAULT,
	  "the drive reports a fault: status register 50 reads 0x0008 (fault bits 0x0008) "
	  "(Input/output error)" },
};

static void test_faults_tcp(void **state)
{
	size_t i;

	for (i = 0; i < sizeof(faults) / sizeof(faults[0]); i++) {
		printf("-- %s\n", faults[i].peer);
		run_fault(&faults[i], false);
	}
}

static void test_faults_rtu(void **state)
{
	static const struct fault_case rtu[] = {
		{ "--silent-after 20", NULL, STRAND_EXIT_FAULT,
		  "write of holding registers 0-5: no answer within 20 ms, 3 times in a row "
		  "(Connection timed out)" },
		{ "--exception-after 20 --exception 6", SLOW_OK, STRAND_EXIT_FAULT,
		  "write of holding registers 0-5: exception 6 (Slave device or server is busy), "
		  "3 times in a row (Protocol error)" },
	};
	size_t i;

	for (i = 0; i < sizeof(rtu) / sizeof(rtu[0]); i++) {
		printf("-- rtu %s\n", rtu[i].peer);
		run_fault(&rtu[i], true);
	}
}

/* A drive that is not there: refused at start, with where it was looked for. */
static void test_no_drive(void **state)
{
	struct setup s;
	struct run r;
	char want[256];

	tcp_setup(&s, "mb-none");
	mbp_scene(s.scene, 1000, s.conn, "answer_ms: 0.2\n", NULL);
	play(&r, &s, "--clock virtual");
	assert_int_equal(r.rc, STRAND_EXIT_FAULT);
	snprintf(want, sizeof(want), "device 'drives': start: tcp 127.0.0.1:%d unit 1: cannot "
		 "connect: Connection refused", s.port);
	if (!strstr(r.err, want))
		fail_msg("want '%s' in '%s'", want, r.err);
	run_free(&r);
	finish(&s);
}

/* The connection dropped while the rig stands still (step mode, one frame
 * shot again and again): made again, the run goes on to its end. */
static void test_reconnect_at_rest(void **state)
{
	struct setup s;
	struct run r;
	int on, off;
	struct mbp_write *w;

	tcp_setup(&s, "mb-drop");
	mbp_scene(s.scene, 1000, s.conn, "response_timeout_ms: 500\n"
		  "update_hz: 100\nanswer_ms: 0.2\n", NULL);
	start_peer(&s, "--drop-after 30");
	play(&r, &s, "--clock real --mode step --frames 0x5 --settle 100 --exposure 100");
	assert_int_equal(r.rc, STRAND_EXIT_OK);
	assert_non_null(strstr(r.out, "1 connections lost, 1 made again, 0 updates unsent"));
	run_free(&r);
	assert_int_equal(mbp_stop(&s.peer), 0);
	assert_true(mbp_log_read(s.log, &w, &on, &off) > 40);
	free(w);
	assert_int_equal(on, 2); /* at start, and again after the drop */
	assert_int_equal(off, 1);
	finish(&s);
}

/* A signal sender: once the server has logged the start's setpoint write
 * (so strand's handlers are in place and its start is setting the enable
 * coil, which the drive answers late), `count` signals `sig` to the
 * process, 20 ms apart. It blocks them itself, so that they go to the
 * thread that runs strand. */
struct sender {
	const char *log;
	int sig, count;
};

static void *send_at_start(void *arg)
{
	const struct sender *s = arg;
	struct timespec ms = { 0, 1000000 }, gap = { 0, 20000000 }, settle = { 0, 250000000 };
	struct mbp_write *w = NULL;
	sigset_t set;
	int i;

	sigemptyset(&set);
	sigaddset(&set, SIGINT);
	sigaddset(&set, SIGTERM);
	pthread_sigmask(SIG_BLOCK, &set, NULL);
	for (i = 0; i < 10000; i++) {
		int64_t n = mbp_log_read(s->log, &w, NULL, NULL);

		free(w);
		if (n >= 1)
			break;
		nanosleep(&ms, NULL);
	}
	/* The write is logged once answered; strand sends the coil's request
	 * after that, and a loaded machine can hold it back for more than a
	 * millisecond (a CI run signalled first: the coil never set). A
	 * quarter second in, the request is out and its answer, 800 ms late,
	 * is not: the signal comes while the start waits. */
	nanosleep(&settle, NULL);
	for (i = 0; i < s->count; i++) {
		kill(getpid(), s->sig);
		nanosleep(&gap, NULL);
	}
	return NULL;
}

static volatile sig_atomic_t stray;

static void on_stray(int sig)
{
	stray++;
}

/*
 * SIGTERM, and then two SIGINTs, while strand's start waits for the drive
 * to answer the enable coil (800 ms late, as from its second request on):
 * the start is given up, the coil set is cleared again, nothing more is
 * written, exit 5 with the start-up's message; and the handlers the
 * process had before are its handlers again afterwards (no signal reached
 * them: strand's caught every one).
 */
static void test_signal_at_start(void **state)
{
	static const struct {
		int sig, count;
		const char *name;
	} cases[] = { { SIGTERM, 1, "SIGTERM" }, { SIGINT, 2, "SIGINT" } };
	struct sigaction mine = { .sa_handler = on_stray }, was_int, was_term, now;
	size_t k;

	sigemptyset(&mine.sa_mask);
	sigaction(SIGINT, &mine, &was_int);
	sigaction(SIGTERM, &mine, &was_term);
	for (k = 0; k < sizeof(cases) / sizeof(cases[0]); k++) {
		struct sender snd = { .sig = cases[k].sig, .count = cases[k].count };
		struct mbp_write *w;
		struct setup s;
		struct run r;
		pthread_t th;
		char want[256];
		int on, off;

		tcp_setup(&s, "mb-signal");
		mbp_scene(s.scene, 1000, s.conn, "response_timeout_ms: 3000\nanswer_ms: 0.2\n", NULL);
		start_peer(&s, "--late-after 1 --late-ms 800");
		snd.log = s.log;
		assert_int_equal(pthread_create(&th, NULL, send_at_start, &snd), 0);
		play(&r, &s, "--clock virtual");
		pthread_join(th, NULL);
		snprintf(want, sizeof(want), "strand play: stopped by a signal (%s) during start-up "
			 "(device 'drives': start given up); the devices that had started were "
			 "stopped, their drives disabled\n", cases[k].name);
		assert_int_equal(r.rc, STRAND_EXIT_STOPPED);
		if (!strstr(r.err, want))
			fail_msg("want '%s' in '%s'", want, r.err);
		run_free(&r);
		assert_int_equal(mbp_stop(&s.peer), 0);
		/* the start's write only; the coil set, then cleared */
		assert_int_equal(mbp_log_read(s.log, &w, &on, &off), 1);
		free(w);
		assert_int_equal(on, 1);
		assert_int_equal(off, 1);
		assert_int_equal(stray, 0);
		sigaction(SIGTERM, NULL, &now);
		assert_true(now.sa_handler == on_stray);
		sigaction(SIGINT, NULL, &now);
		assert_true(now.sa_handler == on_stray);
		finish(&s);
	}
	sigaction(SIGINT, &was_int, NULL);
	sigaction(SIGTERM, &was_term, NULL);
}

/* mbpoll, an independent client, reads what the drive holds after a run
 * that stops at frame 36 (a at 40 deg): the last setpoints in each word
 * order, the actual position, the heartbeat, the status and the enable
 * coil cleared at stop. */
static void test_mbpoll(void **state)
{
	static const char *const reads[] = {
		"-t 4:int -B -r 0", /* a.angle, high word first */
		"-t 4:int -r 2",    /* b.angle, low word first (mbpoll's default) */
		"-t 4:int -B -r 100", /* a's actual position */
		"-t 4:int -B -r 4", /* the heartbeat */
		"-t 4 -r 50",       /* status */
		"-t 0 -r 0",        /* the enable coil */
	};
	long long got[6];
	struct setup s;
	struct run r;
	struct mbp_write *w;
	int64_t n;
	char cmd[512], out[1024];
	size_t i, len;
	FILE *p;

	tcp_setup(&s, "mb-poll");
	mbp_scene(s.scene, 1000, s.conn, "response_timeout_ms: 500\n"
		  "update_hz: 500\nread_every: 10\nanswer_ms: 0.2\n", NULL);
	start_peer(&s, NULL);
	play(&r, &s, "--clock virtual --to 36");
	assert_int_equal(r.rc, STRAND_EXIT_OK);
	run_free(&r);
	n = mbp_log_read(s.log, &w, NULL, NULL);
	assert_true(n > 1);
	for (i = 0; i < 6; i++) {
		char tag[16];
		const char *at;

		snprintf(cmd, sizeof(cmd), "mbpoll -m tcp -p %d -a 1 -0 -1 %s -c 1 127.0.0.1",
			 s.port, reads[i]);
		p = popen(cmd, "r");
		assert_non_null(p);
		len = fread(out, 1, sizeof(out) - 1, p);
		out[len] = 0;
		assert_int_equal(pclose(p), 0);
		/* mbpoll prints "[REGISTER]: <tab>VALUE" */
		snprintf(tag, sizeof(tag), "[%d]:", atoi(strstr(reads[i], "-r ") + 3));
		at = strstr(out, tag);
		if (!at || sscanf(at + strlen(tag), "%lld", &got[i]) != 1)
			fail_msg("%s: %s", cmd, out);
		printf("%s -> %lld\n", reads[i], got[i]);
	}
	assert_true(w[n - 1].v[0] > 30000); /* a near 40 deg: both words matter */
	assert_int_equal(got[0], w[n - 1].v[0]);
	assert_int_equal(got[1], w[n - 1].v[1]);
	assert_true(llabs(got[2] - got[0]) < 200); /* at rest: within 0.2 deg */
	assert_int_equal(got[3], w[n - 1].tick);
	assert_int_equal(got[4], 0);
	assert_int_equal(got[5], 0);
	free(w);
	finish(&s);
}

/* strand check: the rate each bus reaches; a rate it cannot reach refused. */
static void test_check(void **state)
{
	struct setup s;
	struct run r;
	char args[300];

	rtu_setup(&s, "mb-check");
	mbp_scene(s.scene, 1000, s.conn, "response_timeout_ms: 500\n"
		  "update_hz: 50\nread_every: 20\n", NULL);
	snprintf(args, sizeof(args), "check %s", s.scene);
	strand(&r, args);
	printf("%s%s", r.out, r.err);
	assert_int_equal(r.rc, 0);
	/* write 0-5: 21 + 8 bytes; reads 100-103 (8 + 13) and 50 (8 + 7); 10
	 * bits a character at 115200 baud, two 1.75 ms silences and a 1 ms
	 * answer per request: 7.017 ms, then 6.323 and 5.802 ms */
	assert_non_null(strstr(r.out, "an update takes 7.02 ms, 19.1 ms with its reads (RTU "
				      "frames at 115200 baud 8N1, 1 ms answers assumed); reachable "
				      "52.24 updates/s, the scene asks 50/s (every 20 ticks)"));
	run_free(&r);
	mbp_scene(s.scene, 1000, s.conn, "response_timeout_ms: 500\n"
		  "update_hz: 100\nread_every: 20\n", NULL);
	strand(&r, args);
	assert_int_equal(r.rc, STRAND_EXIT_SCENE);
	assert_non_null(strstr(r.err, "device 'drives': an update with its reads takes 19.1 ms on "
				      "the bus (RTU frames at the baud rate), more than the 10 ms "
				      "between updates at 100 Hz; it reaches 52.24 Hz"));
	run_free(&r);
	finish(&s);
}

/* strand-simdrive's numbers are ranged where they enter, as strand's: a
 * usage error (exit 3) naming the option. */
static void test_simdrive_ranges(void **state)
{
	static const struct {
		const char *args, *err;
	} cases[] = {
		{ "--late-ms 0", "strand-simdrive: --late-ms 0: out of range\n" },
		{ "--late-ms 1e300", "strand-simdrive: --late-ms 1e300: out of range\n" },
		{ "--exception 256", "strand-simdrive: --exception 256: out of range\n" },
		{ "--die-after 0", "strand-simdrive: a fault's count 0: out of range\n" },
		{ "--can vcan0 --node 0", "strand-simdrive: --node 0: out of range\n" },
		{ "--can vcan0 --node 1 --bandwidth 1e300",
		  "strand-simdrive: --bandwidth 1e300: out of range\n" },
		{ "--can vcan0 --node 1 --initial 3e9",
		  "strand-simdrive: --initial 3e9: out of range\n" },
	};
	const char *bin = getenv("STRAND_SIMDRIVE") ? getenv("STRAND_SIMDRIVE") :
						      "build/strand-simdrive";
	char cmd[512], out[512];
	size_t i, n;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		FILE *f;
		int st;

		snprintf(cmd, sizeof(cmd), "%s %s %s 2>&1", bin, cases[i].args,
			 strncmp(cases[i].args, "--can", 5) ? "examples/robot_arm.yaml" : "");
		f = popen(cmd, "r");
		assert_non_null(f);
		n = fread(out, 1, sizeof(out) - 1, f);
		out[n] = '\0';
		st = pclose(f);
		if (!WIFEXITED(st) || WEXITSTATUS(st) != STRAND_EXIT_USAGE ||
		    strcmp(out, cases[i].err))
			fail_msg("%s: status %d, '%s'; want exit 3, '%s'", cmd, st, out,
				 cases[i].err);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_simdrive_ranges),
		cmocka_unit_test(test_tcp_lockstep),
		cmocka_unit_test(test_tcp_wall),
		cmocka_unit_test(test_rtu_lockstep),
		cmocka_unit_test(test_lockstep_repeats),
		cmocka_unit_test(test_faults_tcp),
		cmocka_unit_test(test_faults_rtu),
		cmocka_unit_test(test_no_drive),
		cmocka_unit_test(test_reconnect_at_rest),
		cmocka_unit_test(test_signal_at_start),
		cmocka_unit_test(test_mbpoll),
		cmocka_unit_test(test_check),
	};

	/* a peer that hangs must not hang the suite */
	alarm(300);
	signal(SIGPIPE, SIG_IGN);
	pu_alloc_hook_install();
	return cmocka_run_group_tests(tests, NULL, NULL);
}
