/* SPDX-License-Identifier: MIT */
/*
 * promise.c - strand's promise, as a property: a scene that `strand
 * check` passes plays to its last frame; one it rejects is refused before
 * anything moves, for the same first reason.
 *
 * Random valid scenes (tests/scenegen.c: every joint, free-node, curve and
 * ease kind, rpm strands, cycles, attributes, a camera, spans from a second
 * to a day, 100 Hz to 10 kHz, 24, 25 and 30000/1001 fps, with limits and
 * without; now and then a --from/--to, --ping-pong or --loop run, or
 * go-motion over a few frames: --mode step --shutter ANGLE) go
 * through `strand check --sim` and `strand play --sim --clock virtual`
 * in-process, with the same run options:
 *
 *   check passes   play exits 0, and its journal has every frame of the run
 *                  exactly once, in the run's order, each on the tick of
 *                  FORMULAS section 5 (within a pass, frames are as many
 *                  ticks apart as their trigger ticks are); go-motion's
 *                  each with its exposure's ticks (plan/gomo.h), the
 *                  trigger at the first
 *   check rejects  play exits 1 and names the same first violation
 *   check says 8   (saturation) play exits 8 before anything moves
 *
 * Built -O2 without sanitizers (mk/promise.mk: thousands of scenes must
 * fit `make test`'s time; every module it runs is also under the sanitized
 * unit tests). STRAND_PROMISE_SCENES (default 2000), STRAND_PROMISE_TICKS
 * (the longest span, default 5000 ticks) and STRAND_PROMISE_SEED (the first
 * seed, default 1) set the run; `make soak` runs many more and longer. A
 * failure prints its seed and the scene. The scenes under
 * tests/scenes/promise/ are counterexamples it found, each a regression
 * test with the fix it needed in its header.
 */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/exitcode.h"
#include "cliutil.h"
#include "load/load.h"
#include "motion/timing.h"
#include "plan/gomo.h"
#include "playutil.h"
#include "scenegen.h"
#include "testutil.h"

struct tally {
	int64_t scenes, played, refused, saturated, frames, ticks;
	int64_t gomo_played, gomo_refused; /* of them, go-motion runs */
};

static int64_t env_or(const char *name, int64_t dflt)
{
	const char *v = getenv(name);

	return v && *v ? atoll(v) : dflt;
}

/* The run's frames in firing order, as strand play's options say. */
struct order {
	int64_t from, to, passes;
	bool ping_pong;
	mot_q32 shutter; /* go-motion (step mode), 0: none */
};

static void order_of(struct order *o, const char *run, int64_t first, int64_t last)
{
	const char *p;

	o->from = first;
	o->to = last;
	o->passes = 1;
	o->ping_pong = strstr(run, "--ping-pong") != NULL;
	o->shutter = 0;
	if ((p = strstr(run, "--shutter ")))
		assert_true(gomo_shutter_of_angle(atof(p + 10), &o->shutter));
	if ((p = strstr(run, "--from ")))
		o->from = atoll(p + 7);
	if ((p = strstr(run, "--to ")))
		o->to = atoll(p + 5);
	if ((p = strstr(run, "--passes ")))
		o->passes = atoll(p + 9);
}

/* Frame n (from 0) of the run, and whether it starts a pass. */
static int64_t nth_frame(const struct order *o, int64_t n, bool *starts)
{
	int64_t per = o->to - o->from + 1, p, i, back;

	if (!o->ping_pong) {
		*starts = n % per == 0;
		return o->from + n % per;
	}
	/* F..T, then T-1..F, F+1..T, ...: the first pass per frames, each
	 * later one per - 1 */
	if (n < per) {
		*starts = n == 0;
		return o->from + n;
	}
	n -= per;
	p = n / (per - 1);
	i = n % (per - 1);
	*starts = i == 0;
	back = p % 2 == 0;
	return back ? o->to - 1 - i : o->from + 1 + i;
}

static void fail_scene(uint64_t seed, const struct scenegen *g, const char *what, ...)
{
	char msg[2048];
	va_list ap;

	va_start(ap, what);
	vsnprintf(msg, sizeof(msg), what, ap);
	va_end(ap);
	printf("PROMISE counterexample: seed %llu, run '%s': %s\n--- scene ---\n%s--- end ---\n",
	       (unsigned long long)seed, g->run, msg, g->yaml);
	fail_msg("seed %llu: %s", (unsigned long long)seed, msg);
}

/* Play's journal against the run's frames and their ticks. */
static void check_journal(uint64_t seed, const struct scenegen *g, const char *journal,
			  struct tally *t)
{
	struct mot_timing tm;
	struct order o;
	struct pu_csv c;
	int64_t n, want_frames, prev_f = 0, prev_k = 0;
	int cf, ct, cs, co, cc;

	assert_int_equal(mot_timing_init(&tm, g->num, g->den, g->tick_hz), 0);
	order_of(&o, g->run, g->first, g->last);
	want_frames = o.ping_pong ? (o.to - o.from + 1) + (o.passes - 1) * (o.to - o.from) :
				    (o.to - o.from + 1) * o.passes;
	if (pu_csv_read(&c, journal))
		fail_scene(seed, g, "no journal");
	cf = pu_csv_col(&c, "frame");
	ct = pu_csv_col(&c, "tick");
	cs = pu_csv_col(&c, "state");
	co = o.shutter ? pu_csv_col(&c, "open_tick") : -1;
	cc = o.shutter ? pu_csv_col(&c, "close_tick") : -1;
	if ((int64_t)c.nrows - 1 != want_frames)
		fail_scene(seed, g, "%u frames in the journal, want %lld", c.nrows - 1,
			   (long long)want_frames);
	for (n = 0; n < want_frames; n++) {
		char **row = c.cell[n + 1];
		bool starts;
		int64_t f = nth_frame(&o, n, &starts), k = atoll(row[ct]);

		if (atoll(row[cf]) != f || strcmp(row[cs], "fired"))
			fail_scene(seed, g, "journal row %lld: frame %s %s, want frame %lld fired",
				   (long long)n + 1, row[cf], row[cs], (long long)f);
		if (o.shutter) {
			/* step mode: each frame on its own; its exposure the
			 * window's ticks, the trigger (offset 0) at the first */
			int64_t k0, k1, open = atoll(row[co]), close = atoll(row[cc]);

			assert_int_equal(gomo_window(&tm, f, o.shutter, &k0, &k1), 0);
			if (!*row[cc] || close - open != k1 - k0 || k != open)
				fail_scene(seed, g, "frame %lld: edge at %lld, exposure %s..%s, want "
					   "%lld ticks from the edge", (long long)f, (long long)k,
					   row[co], row[cc], (long long)(k1 - k0));
			starts = true;
		}
		if (!starts) {
			int64_t dk = mot_timing_trigger_tick(&tm, f) -
				     mot_timing_trigger_tick(&tm, prev_f);

			if (k - prev_k != (dk < 0 ? -dk : dk))
				fail_scene(seed, g, "frame %lld at tick %lld, %lld after frame %lld: "
					   "want %lld", (long long)f, (long long)k,
					   (long long)(k - prev_k), (long long)prev_f,
					   (long long)(dk < 0 ? -dk : dk));
		}
		prev_f = f;
		prev_k = k;
	}
	t->frames += want_frames;
	pu_csv_free(&c);
}

/* The first line of out that names a violation (before the summary). */
static void first_line(const char *out, char *buf, size_t size)
{
	const char *nl = strchr(out, '\n');
	size_t n = nl ? (size_t)(nl - out) : strlen(out);

	snprintf(buf, size, "%.*s", (int)(n < size ? n : size - 1), out);
}

static void one(uint64_t seed, struct scenegen *g, const char *path, struct tally *t)
{
	char args[1400], journal[256], line[1024], want[1200];
	struct run chk, ply;
	FILE *f = fopen(path, "w");

	assert_non_null(f);
	fputs(g->yaml, f);
	fclose(f);
	pu_tmpname(journal, sizeof(journal), "promise.journal");
	snprintf(args, sizeof(args), "check --sim %s%s", path, g->run);
	strand(&chk, args);
	snprintf(args, sizeof(args), "play --sim --clock virtual --quiet --no-mlock --journal %s %s%s",
		 journal, path, g->run);
	strand(&ply, args);
	t->scenes++;
	switch (chk.rc) {
	case STRAND_EXIT_OK:
		if (ply.rc != STRAND_EXIT_OK)
			fail_scene(seed, g, "check passes, play exits %d: %s", ply.rc, ply.err);
		check_journal(seed, g, journal, t);
		t->played++;
		t->gomo_played += strstr(g->run, "--shutter") != NULL;
		t->ticks += g->ticks;
		break;
	case STRAND_EXIT_VIOLATION:
		first_line(chk.out, line, sizeof(line));
		snprintf(want, sizeof(want), "the first: %s.\n", line);
		if (ply.rc != STRAND_EXIT_VIOLATION || !strstr(ply.err, want))
			fail_scene(seed, g, "check rejects (%s), play exits %d: %s", line, ply.rc,
				   ply.err);
		t->refused++;
		t->gomo_refused += strstr(g->run, "--shutter") != NULL;
		break;
	case STRAND_EXIT_INTERNAL:
		if (ply.rc != STRAND_EXIT_INTERNAL || !strstr(chk.err, "saturated"))
			fail_scene(seed, g, "check exits 8 (%s), play %d: %s", chk.err, ply.rc,
				   ply.err);
		t->saturated++;
		break;
	default:
		fail_scene(seed, g, "check exits %d: %s%s", chk.rc, chk.out, chk.err);
	}
	run_free(&chk);
	run_free(&ply);
	unlink(journal);
}

/* A regression scene as the generator would have made it: its text, its
 * timing and span, and the run its "# run: OPTIONS" line asks for. */
static void from_file(struct scenegen *g, const char *path)
{
	struct scene_file sf;
	struct load_err e;
	FILE *f = fopen(path, "r");
	const char *run;
	long n;

	assert_non_null(f);
	fseek(f, 0, SEEK_END);
	n = ftell(f);
	rewind(f);
	g->yaml = realloc(g->yaml, (size_t)n + 1);
	assert_non_null(g->yaml);
	assert_int_equal(fread(g->yaml, 1, (size_t)n, f), (size_t)n);
	g->yaml[n] = '\0';
	fclose(f);
	if (scene_file_load(&sf, path, &e))
		fail_msg("%s: %s", path, e.msg);
	g->tick_hz = sf.desc.tick_hz;
	g->num = sf.desc.rate_num;
	g->den = sf.desc.rate_den;
	g->first = (int64_t)sf.desc.frame_first;
	g->last = (int64_t)sf.desc.frame_last;
	g->ticks = (int64_t)((double)(g->last - g->first) * g->tick_hz * g->den / g->num) + 1;
	scene_file_free(&sf);
	run = strstr(g->yaml, "\n# run: ");
	g->run[0] = '\0';
	if (run)
		snprintf(g->run, sizeof(g->run), " %.*s", (int)strcspn(run + 8, "\n"), run + 8);
}

/* The counterexamples found so far, as regression tests: each must play
 * to its end, every frame on its tick (their headers say what was wrong). */
static void test_regressions(void **state)
{
	DIR *d = opendir("tests/scenes/promise");
	struct scenegen g = { 0 };
	struct tally t = { 0 };
	struct dirent *e;
	char path[512], tmp[256];

	assert_non_null(d);
	pu_tmpname(tmp, sizeof(tmp), "regression.yaml");
	while ((e = readdir(d))) {
		int64_t played = t.played;

		if (!strstr(e->d_name, ".yaml"))
			continue;
		snprintf(path, sizeof(path), "tests/scenes/promise/%s", e->d_name);
		from_file(&g, path);
		one(0, &g, tmp, &t);
		if (t.played != played + 1)
			fail_msg("%s: refused: it must play to its end", path);
	}
	closedir(d);
	unlink(tmp);
	scenegen_free(&g);
	printf("promise: %lld regression scenes play to their end (%lld frames)\n",
	       (long long)t.played, (long long)t.frames);
}

static void test_random_scenes(void **state)
{
	int64_t n = env_or("STRAND_PROMISE_SCENES", 2000), seed0 = env_or("STRAND_PROMISE_SEED", 1);
	struct scenegen g = { .max_ticks = env_or("STRAND_PROMISE_TICKS", 5000) };
	struct tally t = { 0 };
	struct timespec a, b;
	char path[256];
	int64_t i;

	pu_tmpname(path, sizeof(path), "promise.yaml");
	clock_gettime(CLOCK_MONOTONIC, &a);
	for (i = 0; i < n; i++) {
		scenegen_make(&g, (uint64_t)(seed0 + i));
		one((uint64_t)(seed0 + i), &g, path, &t);
	}
	clock_gettime(CLOCK_MONOTONIC, &b);
	unlink(path);
	scenegen_free(&g);
	printf("promise: %lld scenes (seeds %lld..%lld): %lld played to the end (%lld frames, "
	       "%lld ticks), %lld refused for check's first reason, %lld saturated\n",
	       (long long)t.scenes, (long long)seed0, (long long)(seed0 + n - 1),
	       (long long)t.played, (long long)t.frames, (long long)t.ticks,
	       (long long)t.refused, (long long)t.saturated);
	printf("promise: go-motion runs among them: %lld played, %lld refused\n",
	       (long long)t.gomo_played, (long long)t.gomo_refused);
	printf("BENCH promise_scenes %lld\nBENCH promise_played %lld\nBENCH promise_refused %lld\n"
	       "BENCH promise_frames %lld\nBENCH promise_ticks %lld\nBENCH promise_wall_s %.1f\n",
	       (long long)t.scenes, (long long)t.played, (long long)t.refused,
	       (long long)t.frames, (long long)t.ticks,
	       (double)(b.tv_sec - a.tv_sec) + (b.tv_nsec - a.tv_nsec) / 1e9);
	/* both sides of the promise must have been exercised */
	assert_true(t.played > n / 10);
	assert_true(t.refused > n / 20);
	assert_true(t.gomo_played > n / 100);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_regressions),
		cmocka_unit_test(test_random_scenes),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
