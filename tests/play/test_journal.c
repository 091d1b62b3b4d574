/* SPDX-License-Identifier: MIT */
/*
 * test_journal.c - the journal file on its own (many chunks mapped ahead
 * and unmapped behind, an armed record left by a kill, a file that is not a
 * journal), SMPTE timecode including drop-frame, and the SPSC ring between
 * two threads.
 */
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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
	int64_t i, refused = 0;
	uint32_t lo_seen = 0;
	int cf, cs, ca;

	pu_tmpname(path, sizeof(path), "chunks");
	assert_int_equal(journal_open(&j, path, &ji), 0);
	assert_true(j.per_chunk < 20000);
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
		cmocka_unit_test(test_ring_spsc),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
