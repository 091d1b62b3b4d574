/* SPDX-License-Identifier: MIT */
/*
 * test_journal.c - the journal file on its own (many chunks mapped ahead
 * and unmapped behind, an armed record left by a kill, a file that is not a
 * journal, one of another machine, one of version 1), its memory sized by
 * what is in flight and not by the run (a run of two billion passes, one
 * without an end that writes past 2^24 records), a full disk as an error
 * and not a crash, SMPTE timecode including drop-frame, and the SPSC ring
 * between two threads.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/exitcode.h"
#include "cliutil.h"

#include "hal/ring.h"
#include "journal/journal.h"
#include "playutil.h"
#include "scene/timecode.h"
#include "testutil.h"

static void test_timecode(void **state)
{
	static const struct {
		uint32_t num, den;
		int64_t frame;
		const char *tc;
	} cases[] = {
		{ 24, 1, 0, "00:00:00:00" },
		{ 24, 1, 23, "00:00:00:23" },
		{ 24, 1, 24 * 3600, "01:00:00:00" },
		{ 24, 1, 24 * 86400, "00:00:00:00" }, /* hours wrap at 24 */
		{ 25, 1, 25 * 61 + 3, "00:01:01:03" },
		{ 24000, 1001, 24, "00:00:01:00" },    /* 23.976: not drop-frame */
		{ 30000, 1001, 1799, "00:00:59;29" },
		{ 30000, 1001, 1800, "00:01:00;02" }, /* labels 00 and 01 dropped */
		{ 30000, 1001, 3597, "00:01:59;29" },
		{ 30000, 1001, 3598, "00:02:00;02" },
		{ 30000, 1001, 17982, "00:10:00;00" }, /* not at the tenth minute */
		{ 30000, 1001, 17981, "00:09:59;29" },
		{ 30000, 1001, 107892, "01:00:00;00" },
		{ 30000, 1001, 2589407, "23:59:59;29" },
		{ 30000, 1001, 2589408, "00:00:00;00" },
		{ 60000, 1001, 3600, "00:01:00;04" },  /* 59.94: four labels */
		{ 60000, 1001, 35964, "00:10:00;00" },
		{ 30, 1, -1, "-00:00:00:01" },
	};
	size_t i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		struct timecode tc;
		char buf[24];

		timecode_init(&tc, cases[i].num, cases[i].den);
		timecode_format(&tc, cases[i].frame, buf, sizeof(buf));
		if (strcmp(buf, cases[i].tc))
			fail_msg("%u/%u frame %lld: %s, want %s", cases[i].num, cases[i].den,
				 (long long)cases[i].frame, buf, cases[i].tc);
	}
}

/* 50 000 records through a journal whose chunks hold about 10 000: the
 * loop's side refuses a record only until the service has mapped its
 * chunk; everything written comes back in order; chunks behind the loop
 * are unmapped; a last record left armed reads as "armed". */
static void test_journal_chunks(void **state)
{
	static const char *const names[] = { "a.angle", "b.position", "c" };
	static const uint32_t units[] = { JOURNAL_UNIT_TURNS, JOURNAL_UNIT_PLAIN, JOURNAL_UNIT_PLAIN };
	struct journal_info ji = {
		.scene = "chunks", .rate_num = 24, .rate_den = 1, .tick_hz = 1000,
		.nout = 3, .out_name = names, .out_unit = units,
		.capacity = 50001, .ahead = 4096,
	};
	struct journal j;
	struct pu_csv c;
	char path[256];
	int64_t i, refused = 0, lo_seen = 0;
	int cf, cs, ca;

	pu_tmpname(path, sizeof(path), "chunks");
	assert_int_equal(journal_open(&j, path, &ji), 0);
	assert_true(j.per_chunk < 20000);
	/* a ring of what is in flight: 4096 ahead, 1 behind */
	assert_int_equal(j.nslots, (4096 + 1) / j.per_chunk + 2);
	for (i = 0; i <= 50000; i++) {
		struct journal_rec *r;

		while (!(r = journal_next(&j))) {
			refused++;
			assert_int_equal(journal_service(&j, i), 0);
		}
		r->frame = i;
		r->tick = 10 * i;
		r->ferr_out = -1;
		r->sp[0] = (int64_t)i << 24; /* i / 256 turns */
		r->sp[1] = -i;
		r->sp[2] = 0;
		journal_arm(&j, r);
		if (i < 50000)
			journal_fire(r, 1000 * i, 2000 * i); /* the last one stays armed */
		if (j.mapped_lo > lo_seen)
			lo_seen = j.mapped_lo;
		assert_true(j.mapped_hi - j.mapped_lo <= j.nslots);
	}
	assert_true(refused > 0);  /* the service had to map chunks ahead */
	assert_true(lo_seen >= 2); /* and unmapped those left behind */
	assert_int_equal(journal_close(&j), 0);
	assert_int_equal(pu_csv_read(&c, path), 0);
	assert_int_equal(c.nrows, 50002);
	cf = pu_csv_col(&c, "frame");
	cs = pu_csv_col(&c, "state");
	ca = pu_csv_col(&c, "a.angle");
	for (i = 0; i <= 50000; i++) {
		assert_int_equal(atoll(c.cell[i + 1][cf]), i);
		assert_string_equal(c.cell[i + 1][cs], i < 50000 ? "fired" : "armed");
	}
	assert_true(atof(c.cell[257][ca]) == 360.0); /* frame 256: one turn */
	pu_csv_free(&c);
	unlink(path);
}

/* n bytes of a file at offset at: 0, or -1. */
static int file_read(const char *path, void *buf, size_t n, off_t at)
{
	int fd = open(path, O_RDONLY);
	ssize_t got = fd >= 0 ? pread(fd, buf, n, at) : -1;

	if (fd >= 0)
		close(fd);
	return got == (ssize_t)n ? 0 : -1;
}

/* A small journal of n records of two outputs, closed, at path. */
static void write_small(const char *path, int64_t n)
{
	static const char *const names[] = { "a.angle", "b.position" };
	static const uint32_t units[] = { JOURNAL_UNIT_TURNS, JOURNAL_UNIT_PLAIN };
	struct journal_info ji = {
		.scene = "small", .rate_num = 30000, .rate_den = 1001, .tick_hz = 1000,
		.nout = 2, .out_name = names, .out_unit = units, .capacity = n, .ahead = 4096,
	};
	struct journal j;
	int64_t i;

	assert_int_equal(journal_open(&j, path, &ji), 0);
	for (i = 0; i < n; i++) {
		struct journal_rec *r = journal_next(&j);

		assert_non_null(r);
		r->frame = i;
		r->tick = 33 * i + 1;
		r->due_ns = 1000000 * r->tick;
		r->ferr = 1e-4 * i;
		r->ferr_out = (int32_t)(i % 2);
		r->sp[0] = (int64_t)i << 26;
		r->sp[1] = -3 * i;
		journal_arm(&j, r);
		journal_fire(r, r->due_ns + 1500, HAL_CLOCK_VIRTUAL_EPOCH_NS + r->due_ns);
	}
	assert_null(journal_next(&j)); /* full */
	assert_int_equal(journal_refused(&j), -ENOSPC);
	assert_int_equal(journal_close(&j), 0);
}

static char *csv_of(const char *path, int *rc, char *msg, size_t msgsize)
{
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);

	assert_non_null(f);
	*rc = journal_csv(path, f, msg, (unsigned)msgsize);
	fclose(f);
	return text;
}

static void patch(const char *path, off_t at, const void *bytes, size_t n)
{
	int fd = open(path, O_WRONLY);

	assert_true(fd >= 0);
	assert_int_equal(pwrite(fd, bytes, n, at), (ssize_t)n);
	close(fd);
}

/* A journal of version 1 (no byte order or layout in its header, the
 * output names right after the scene's) and one of version 2 read as the
 * same journal of version 3 does. */
static void test_journal_version1(void **state)
{
	struct journal_hdr h;
	char path[256], msg[256], out[2 * sizeof(struct journal_out)];
	char *v2, *v1;
	uint32_t one = 1;
	int rc;

	pu_tmpname(path, sizeof(path), "v1");
	write_small(path, 100);
	v2 = csv_of(path, &rc, msg, sizeof(msg));
	assert_int_equal(rc, 0);
	/* version 2 wrote the same bytes but for the version (version 3 added
	 * go-motion's records only) */
	{
		uint32_t two = 2;
		char *v;

		patch(path, offsetof(struct journal_hdr, version), &two, sizeof(two));
		v = csv_of(path, &rc, msg, sizeof(msg));
		assert_int_equal(rc, 0);
		assert_string_equal(v, v2);
		free(v);
	}
	/* the same file as version 1 wrote it */
	assert_int_equal(file_read(path, &h, sizeof(h), 0), 0);
	assert_int_equal(h.version, 2);
	assert_int_equal(h.byte_order, JOURNAL_BYTE_ORDER);
	assert_int_equal(h.capacity, 100);
	assert_int_equal(file_read(path, out, sizeof(out), offsetof(struct journal_hdr, out)), 0);
	patch(path, offsetof(struct journal_hdr, byte_order), out, sizeof(out));
	patch(path, offsetof(struct journal_hdr, version), &one, sizeof(one));
	v1 = csv_of(path, &rc, msg, sizeof(msg));
	assert_int_equal(rc, 0);
	assert_string_equal(v1, v2);
	assert_non_null(strstr(v1, "99,00:00:03;09,3268,0,fired,3268000000,3268001500,1.500,"));
	free(v1);
	free(v2);
	unlink(path);
}

/* A journal of another machine is refused, saying which way it differs:
 * the other byte order (every number reversed, the version first), records
 * laid out otherwise, doubles of another format, a later version. */
static void test_journal_foreign(void **state)
{
	static const struct {
		const char *what;
		size_t at;
		uint32_t value;
		const char *msg;
	} cases[] = {
		{ "other byte order", offsetof(struct journal_hdr, version), 0x02000000,
		  "a strand journal written on a machine of the other byte order (big-endian)" },
		{ "marker only", offsetof(struct journal_hdr, byte_order), 0x04030201,
		  "not a strand journal" },
		{ "layout", offsetof(struct journal_hdr, layout), 0x87403004,
		  "a strand journal whose records are laid out otherwise (layout 0x87403004, this "
		  "build's 0x87403008: another architecture's ABI)" },
		{ "version 4", offsetof(struct journal_hdr, version), 4,
		  "a strand journal of version 4; this strand reads versions 1 to 3" },
	};
	char path[256], msg[512];
	size_t i;
	int rc;

	assert_int_equal(journal_layout(), 0x87403008); /* x86_64, aarch64, armhf alike */
	pu_tmpname(path, sizeof(path), "foreign");
	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		uint32_t bo = 0x04030201;

		write_small(path, 3);
		patch(path, cases[i].at, &cases[i].value, sizeof(uint32_t));
		if (i == 0) /* the marker is reversed too */
			patch(path, offsetof(struct journal_hdr, byte_order), &bo, sizeof(bo));
		free(csv_of(path, &rc, msg, sizeof(msg)));
		printf("%s: %s\n", cases[i].what, msg);
		assert_int_equal(rc, -EBADMSG);
		if (!strstr(msg, cases[i].msg))
			fail_msg("%s: '%s', want '%s'", cases[i].what, msg, cases[i].msg);
	}
	{
		double probe = 1.5;

		write_small(path, 3);
		patch(path, offsetof(struct journal_hdr, probe), &probe, sizeof(probe));
		free(csv_of(path, &rc, msg, sizeof(msg)));
		assert_int_equal(rc, -EBADMSG);
		assert_non_null(strstr(msg, "whose doubles are not this machine's IEEE 754 format"));
	}
	unlink(path);
}

/*
 * The chunk index is sized by what is in flight, not by the run: the run of
 * `--loop --passes 2000000000` (2e9 passes of the arm's 241 frames: 4.8e11
 * records, which took a 955 MB index before) has the ring of a run of one
 * pass, and a run without an end one as small, with no capacity at all.
 * Prepared by play itself, as `strand play` does.
 */
static void test_journal_sized_by_flight(void **state)
{
	static const int64_t passes[] = { 1, 2000000000, 0 };
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	char path[256], err[256];
	struct stat st;
	size_t i;

	for (i = 0; i < sizeof(passes) / sizeof(passes[0]); i++) {
		pu_arm_source(&ps, 24, 1, 1000, 0, 240);
		pu_rig_init(&r, &ps, 1, 0);
		pu_opts(&o, &ps);
		pu_tmpname(path, sizeof(path), "flight");
		o.journal_path = path;
		o.loop.loop = true;
		o.loop.passes = passes[i];
		assert_int_equal(play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err)), 0);
		printf("passes %lld: capacity %lld records, %u slots of %u records\n",
		       (long long)passes[i], (long long)p.jr.capacity, p.jr.nslots, p.jr.per_chunk);
		assert_int_equal(p.jr.capacity, passes[i] ? 241 * passes[i] : JOURNAL_UNBOUNDED);
		assert_int_equal(p.jr.nslots, 2);
		/* and on disk no more than the chunks ahead: one */
		assert_int_equal(stat(path, &st), 0);
		assert_true(st.st_size <= p.jr.hdr_bytes + p.jr.per_chunk * p.jr.rec_bytes);
		play_free(&p);
		unlink(path);
	}
}

/*
 * A journal without an end outlives 2^24 records (the cap an unbounded run
 * had): 2^24 + 100000 records of no outputs, 64 bytes each, through a ring
 * of two slots that wraps over a thousand times. What the loop left behind
 * is punched out of the file as the test goes, to keep 1 GB off the disk;
 * the file keeps its length, and its last records read back.
 */
#define PAST_2_24 ((1LL << 24) + 100000)

static void test_journal_past_2_24(void **state)
{
	struct journal_info ji = {
		.scene = "long", .rate_num = 500, .rate_den = 1, .tick_hz = 1000,
		.capacity = JOURNAL_UNBOUNDED, .ahead = 4096,
	};
	struct journal j;
	struct journal_rec rec;
	struct journal_hdr h;
	char path[256];
	int64_t i, punched = 0, services = 0;
	off_t upto;
	struct stat st;

	pu_tmpname(path, sizeof(path), "long");
	assert_int_equal(journal_open(&j, path, &ji), 0);
	assert_int_equal(j.rec_bytes, 64);
	assert_int_equal(j.nslots, 2);
	for (i = 0; i < PAST_2_24; i++) {
		struct journal_rec *r;

		while (!(r = journal_next(&j))) {
			assert_int_equal(journal_refused(&j), 0);
			assert_int_equal(journal_service(&j, i), 0);
			assert_true(j.mapped_hi - j.mapped_lo <= j.nslots);
			services++;
			upto = (off_t)j.hdr_bytes + (off_t)j.mapped_lo * j.per_chunk * j.rec_bytes;
			upto = upto / j.page * j.page;
			if (upto > punched + (1 << 24)) {
				assert_int_equal(fallocate(j.fd, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE,
							   j.hdr_bytes, upto - j.hdr_bytes), 0);
				punched = upto;
			}
		}
		r->frame = i;
		r->tick = 2 * i;
		r->ferr_out = -1;
		journal_arm(&j, r);
		journal_fire(r, 2000000 * i, 0);
	}
	printf("%lld records, %lld chunks through %u slots, %lld service rounds\n",
	       (long long)PAST_2_24, (long long)j.mapped_hi, j.nslots, (long long)services);
	assert_true(j.mapped_hi > 1000);
	assert_int_equal(journal_close(&j), 0);
	assert_int_equal(stat(path, &st), 0);
	assert_int_equal(st.st_size, (off_t)j.hdr_bytes + PAST_2_24 * 64);
	assert_int_equal(file_read(path, &h, sizeof(h), 0), 0);
	assert_int_equal(h.capacity, -1);
	for (i = PAST_2_24 - 3; i < PAST_2_24; i++) {
		assert_int_equal(file_read(path, &rec, sizeof(rec), (off_t)j.hdr_bytes + i * 64), 0);
		assert_int_equal(rec.state, JOURNAL_FIRED);
		assert_int_equal(rec.frame, i);
		assert_int_equal(rec.mono_ns, 2000000 * i);
	}
	unlink(path);
}

/* The file may not grow (a full disk; here RLIMIT_FSIZE, which fails
 * fallocate the same way with EFBIG once SIGXFSZ is ignored): the service
 * reports it, the loop's side is refused at the end of the chunks mapped,
 * never given a record whose blocks do not exist; close keeps what was
 * written. */
static void test_journal_full_disk(void **state)
{
	static const char *const names[] = { "a.angle", "b.position", "c" };
	static const uint32_t units[] = { JOURNAL_UNIT_TURNS, JOURNAL_UNIT_PLAIN, JOURNAL_UNIT_PLAIN };
	struct journal_info ji = {
		.scene = "full", .rate_num = 24, .rate_den = 1, .tick_hz = 1000,
		.nout = 3, .out_name = names, .out_unit = units,
		.capacity = JOURNAL_UNBOUNDED, .ahead = 4096,
	};
	struct sigaction ign = { .sa_handler = SIG_IGN }, old_sa;
	struct rlimit old, lim;
	struct journal j;
	struct pu_csv c;
	char path[256];
	int64_t n = 0;

	pu_tmpname(path, sizeof(path), "full");
	assert_int_equal(getrlimit(RLIMIT_FSIZE, &old), 0);
	sigaction(SIGXFSZ, &ign, &old_sa);
	lim = old;
	lim.rlim_cur = 2500000; /* two chunks of 1 MiB and the header */
	assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
	assert_int_equal(journal_open(&j, path, &ji), 0);
	for (;;) {
		struct journal_rec *r = journal_next(&j);

		if (!r) {
			if (journal_refused(&j))
				break;
			journal_service(&j, n);
			continue;
		}
		r->frame = n++;
		r->ferr_out = -1;
		journal_arm(&j, r);
		journal_fire(r, n, n);
	}
	assert_int_equal(journal_refused(&j), -EFBIG);
	assert_int_equal(journal_error(&j), -EFBIG);
	assert_int_equal(n, 2 * (int64_t)j.per_chunk);
	assert_int_equal(journal_service(&j, 0), -EFBIG); /* sticky */
	assert_int_equal(journal_close(&j), -EFBIG);
	assert_int_equal(setrlimit(RLIMIT_FSIZE, &old), 0);
	sigaction(SIGXFSZ, &old_sa, NULL);
	assert_int_equal(pu_csv_read(&c, path), 0);
	assert_int_equal(c.nrows, n + 1);
	pu_csv_free(&c);
	unlink(path);
}

/* The same through `strand play`, which ignores SIGXFSZ while it runs (the
 * limit would kill it otherwise, with the drives enabled): exit 4 and the
 * journal's message; the test process's disposition is its own again
 * afterwards. */
static void test_cli_file_limit(void **state)
{
	static const char scene[] =
		"scene: limit\n"
		"timing: {tick_hz: 1000, frame_rate: 250, frames: [0, 20000]}\n"
		"nodes:\n"
		"  - {name: a, joint: {type: revolute, axis: y}, limits: {velocity: 90, acceleration: 360}}\n"
		"strands:\n"
		"  - {node: a, keys: [{frame: 0, angle: 0}, {frame: 20000, angle: 10}]}\n";
	struct rlimit old, lim;
	struct sigaction now;
	char path[256], jpath[256], args[768];
	struct run r;
	FILE *f;

	pu_tmpname(path, sizeof(path), "limit.yaml");
	pu_tmpname(jpath, sizeof(jpath), "limit.journal");
	f = fopen(path, "w");
	assert_non_null(f);
	fputs(scene, f);
	fclose(f);
	snprintf(args, sizeof(args), "play %s --sim --clock virtual --journal %s --quiet", path, jpath);
	assert_int_equal(getrlimit(RLIMIT_FSIZE, &old), 0);
	lim = old;
	lim.rlim_cur = 1200000; /* the header and one chunk of 14563 records */
	assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
	strand(&r, args);
	assert_int_equal(setrlimit(RLIMIT_FSIZE, &old), 0);
	printf("%s", r.err);
	assert_int_equal(r.rc, STRAND_EXIT_IO);
	assert_non_null(strstr(r.err, "journal cannot record the next frame (File too large)"));
	assert_non_null(strstr(r.err, "last frame 14562;"));
	run_free(&r);
	sigaction(SIGXFSZ, NULL, &now);
	assert_true(now.sa_handler == SIG_DFL);
	unlink(path);
	unlink(jpath);
}

/* The same in a run: the loop stops before the frame it cannot record
 * (exit 4), nothing crashes, the journal keeps every frame fired. */
static void test_play_full_disk(void **state)
{
	static const struct pu_smooth still = { 0, 1, 0, 0 };
	struct sigaction ign = { .sa_handler = SIG_IGN }, old_sa;
	struct rlimit old, lim;
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct pu_csv c;
	char path[256], why[512];
	const struct loop_result *res;

	/* 250 frames a second: 20001 frames, more than the file may hold */
	pu_source_init(&ps, "full", 250, 1, 1000, 0, 20000);
	pu_source_add(&ps, "a.angle", SRC_UNIT_TURNS, pu_smooth, &still, 60, 120);
	pu_rig_init(&r, &ps, 1, 0);
	pu_opts(&o, &ps);
	pu_tmpname(path, sizeof(path), "playfull");
	o.journal_path = path;
	assert_int_equal(getrlimit(RLIMIT_FSIZE, &old), 0);
	sigaction(SIGXFSZ, &ign, &old_sa);
	lim = old;
	lim.rlim_cur = 1200000; /* one chunk and the header */
	assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
	assert_int_equal(pu_run(&p, &r, &ps, &o), STRAND_EXIT_IO);
	assert_int_equal(setrlimit(RLIMIT_FSIZE, &old), 0);
	sigaction(SIGXFSZ, &old_sa, NULL);
	res = loop_result(p.L);
	play_describe(&p, why, sizeof(why));
	printf("%s\n", why);
	assert_int_equal(res->rep.cause, LOOP_CAUSE_JOURNAL);
	assert_int_equal(res->rep.code, -EFBIG);
	assert_int_equal(res->frames_fired, p.jr.per_chunk);
	assert_non_null(strstr(why, "journal cannot record the next frame (File too large)"));
	assert_int_equal(pu_csv_read(&c, path), 0);
	assert_int_equal(c.nrows, res->frames_fired + 1);
	pu_csv_free(&c);
	play_free(&p);
	unlink(path);
}

static void test_not_a_journal(void **state)
{
	char path[256], msg[256];
	FILE *f;

	pu_tmpname(path, sizeof(path), "notajournal");
	f = fopen(path, "w");
	assert_non_null(f);
	fputs("frame,timecode\n0,00:00:00:00\n", f);
	fclose(f);
	f = fopen("/dev/null", "w");
	assert_int_equal(journal_csv(path, f, msg, sizeof(msg)), -EBADMSG);
	assert_non_null(strstr(msg, "not a strand journal"));
	assert_int_equal(journal_csv("/nonexistent/j", f, msg, sizeof(msg)), -ENOENT);
	fclose(f);
	unlink(path);
}

#define RING_N 2000000

struct ring_test {
	struct hal_ring r;
	uint64_t buf[64];
	uint64_t bad;
};

static void *consumer(void *arg)
{
	struct ring_test *t = arg;
	uint64_t want = 0, v;

	while (want < RING_N) {
		if (!hal_ring_pop(&t->r, &v))
			continue;
		t->bad += v != want;
		want++;
	}
	return NULL;
}

/* Two threads, two million elements through a ring of 64: every one
 * arrives, in order, none twice. */
static void test_ring_spsc(void **state)
{
	struct ring_test t = { 0 };
	pthread_t th;
	uint64_t i, full = 0;

	assert_int_equal(hal_ring_init(&t.r, t.buf, 64, sizeof(uint64_t)), 0);
	assert_int_equal(hal_ring_init(&t.r, t.buf, 63, sizeof(uint64_t)), -EINVAL);
	assert_int_equal(hal_ring_init(&t.r, t.buf, 64, sizeof(uint64_t)), 0);
	assert_int_equal(pthread_create(&th, NULL, consumer, &t), 0);
	for (i = 0; i < RING_N; i++)
		while (!hal_ring_push(&t.r, &i))
			full++;
	pthread_join(th, NULL);
	assert_int_equal(t.bad, 0);
	assert_int_equal(hal_ring_count(&t.r), 0);
	printf("ring: %d elements, the producer found it full %llu times\n", RING_N,
	       (unsigned long long)full);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_timecode),
		cmocka_unit_test(test_journal_chunks),
		cmocka_unit_test(test_not_a_journal),
		cmocka_unit_test(test_journal_version1),
		cmocka_unit_test(test_journal_foreign),
		cmocka_unit_test(test_journal_sized_by_flight),
		cmocka_unit_test(test_journal_past_2_24),
		cmocka_unit_test(test_journal_full_disk),
		cmocka_unit_test(test_play_full_disk),
		cmocka_unit_test(test_cli_file_limit),
		cmocka_unit_test(test_ring_spsc),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
