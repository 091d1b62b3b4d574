/* SPDX-License-Identifier: MIT */
/*
 * test_play_kill.c - the journal survives SIGKILL. A child plays on the
 * wall clock with a simulated camera that logs every trigger edge into a mapped
 * file (which also survives); the parent kills it with SIGKILL at an
 * arbitrary moment, then checks that every trigger edge that reached the
 * camera (and so every exposure) is in the journal, in order, and that the
 * journal invents nothing: each fired record has its edge at the camera,
 * and at most the very last record is left "armed" (killed between writing
 * it and confirming its edge). On the wall clock a stall of the machine can
 * bunch two edges so that the camera misses one: still an edge it received,
 * still in the journal.
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "playutil.h"
#include "sim/sim_camera.h"
#include "testutil.h"

static void child(const char *journal, const char *camlog)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	char err[256];

	/* 250 frames a second on a 1 kHz tick, for longer than the test waits,
	 * a slow turn keyed in frames (the test arm would be too fast) */
	static struct pu_smooth slow = { 0, 1000000, 90, 0 };

	pu_source_init(&ps, "kill", 250, 1, 1000, 0, 1000000);
	pu_source_add(&ps, "a.angle", SRC_UNIT_TURNS, pu_smooth, &slow, 60, 120);
	pu_rig_init(&r, &ps, 1, 0);
	pu_opts(&o, &ps);
	o.virtual_clock = false;
	o.journal_path = journal;
	o.rig.camera_log = camlog;
	o.rig.camera_cap = 1 << 20;
	if (play_prepare(&p, &r.d, &ps.s, &o, err, sizeof(err))) {
		fprintf(stderr, "child: %s\n", err);
		_exit(3);
	}
	if (pu_play(&p)) {
		play_describe(&p, err, sizeof(err));
		fprintf(stderr, "child: %s\n", err);
	}
	_exit(4); /* not reached within the test's patience */
}

static uint64_t triggers(const char *camlog)
{
	struct sim_exposure *e;
	uint64_t n = 0;

	if (sim_camera_log_read(camlog, &e, &n))
		return 0;
	free(e);
	return n;
}

static void test_kill9(void **state)
{
	int iter;

	for (iter = 0; iter < 8; iter++) {
		char journal[256], camlog[256];
		struct sim_exposure *e;
		struct pu_csv c;
		uint64_t n, i, fired = 0, exposed = 0;
		int status, cf, ct, cs, cm;
		struct timespec nap = { 0, 1000000 };
		pid_t pid;
		int waited = 0;

		pu_tmpname(journal, sizeof(journal), "kill-journal");
		pu_tmpname(camlog, sizeof(camlog), "kill-camera");
		unlink(camlog);
		pid = fork();
		assert_true(pid >= 0);
		if (pid == 0)
			child(journal, camlog);
		/* let it fire some frames, then kill it at a moment that varies
		 * from one round to the next */
		while (triggers(camlog) < 40 + 30 * (uint64_t)iter && waited++ < 10000)
			nanosleep(&nap, NULL);
		nap.tv_nsec = 530000 * iter; /* across a 4 ms frame period */
		nanosleep(&nap, NULL);
		assert_int_equal(kill(pid, SIGKILL), 0);
		assert_int_equal(waitpid(pid, &status, 0), pid);
		if (!WIFSIGNALED(status))
			fail_msg("the child exited by itself, status %d", WEXITSTATUS(status));
		assert_int_equal(WTERMSIG(status), SIGKILL);

		assert_int_equal(sim_camera_log_read(camlog, &e, &n), 0);
		assert_true(n >= 40);
		assert_int_equal(pu_csv_read(&c, journal), 0);
		cf = pu_csv_col(&c, "frame");
		ct = pu_csv_col(&c, "tick");
		cs = pu_csv_col(&c, "state");
		cm = pu_csv_col(&c, "mono_ns");
		for (i = 1; i < c.nrows; i++) {
			bool last = i == c.nrows - 1;

			assert_int_equal(atoll(c.cell[i][cf]), (long long)(i - 1));
			if (!strcmp(c.cell[i][cs], "fired")) {
				/* nothing invented: its edge reached the camera, at
				 * the same tick; the journal reads the clock right
				 * after the edge went out, the camera saw it during:
				 * never before. (How long after depends on the
				 * scheduler: the child plays at normal priority on a
				 * shared machine, so a preemption can come between;
				 * a second is only a sanity bound.) */
				long long after;

				assert_true(i - 1 < n);
				assert_int_equal(atoll(c.cell[i][ct]), e[i - 1].tick);
				after = atoll(c.cell[i][cm]) - e[i - 1].ts_ns;
				if (after < 0 || after >= 1000000000)
					fail_msg("frame %u: journal time %lld ns after the edge", i - 1,
						 after);
				fired++;
			} else {
				/* only the last record can be caught between its
				 * two writes; its edge may or may not be out */
				assert_string_equal(c.cell[i][cs], "armed");
				assert_true(last);
				if (i - 1 < n)
					assert_int_equal(atoll(c.cell[i][ct]), e[i - 1].tick);
			}
		}
		/* every edge the camera received is in the journal */
		assert_true(c.nrows - 1 >= n);
		assert_true(fired == n || fired + 1 == n);
		for (i = 0; i < n; i++)
			exposed += e[i].exposed;
		printf("round %d: %llu trigger edges at the camera (%llu exposed), %llu fired "
		       "in the journal, %u rows\n", iter, (unsigned long long)n,
		       (unsigned long long)exposed, (unsigned long long)fired, c.nrows - 1);
		pu_csv_free(&c);
		free(e);
		unlink(journal);
		unlink(camlog);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_kill9),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
