/* SPDX-License-Identifier: MIT */
/*
 * test_thread.c - threads started with their scheduling set (hal/thread.h),
 * each looked at from inside through the kernel: its name, SCHED_OTHER
 * when asked even from a SCHED_FIFO creator (nothing inherited), SCHED_FIFO
 * at the priority asked, its CPUs (one, or all but one), every signal
 * blocked, and a refused SCHED_FIFO falling back to SCHED_OTHER with the
 * refusal noted (in a child without the privilege). SCHED_FIFO needs
 * CAP_SYS_NICE or an RLIMIT_RTPRIO: where it is refused, the cases that
 * need it say so and pass.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <sched.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "hal/thread.h"

/* What a thread found about itself. */
struct seen {
	int policy, priority;
	cpu_set_t cpus;
	bool sigint_blocked, sigterm_blocked;
	char name[32];
};

static void *look(void *arg)
{
	struct seen *s = arg;
	struct sched_param sp;
	sigset_t mask;

	prctl(PR_GET_NAME, s->name, 0, 0, 0);
	s->policy = sched_getscheduler(0) & ~SCHED_RESET_ON_FORK;
	sched_getparam(0, &sp);
	s->priority = sp.sched_priority;
	sched_getaffinity(0, sizeof(s->cpus), &s->cpus);
	pthread_sigmask(SIG_SETMASK, NULL, &mask);
	s->sigint_blocked = sigismember(&mask, SIGINT);
	s->sigterm_blocked = sigismember(&mask, SIGTERM);
	return NULL;
}

static void run(struct hal_thread *t, const char *name, const struct hal_sched *sc,
		struct seen *s)
{
	memset(s, 0, sizeof(*s));
	assert_int_equal(hal_thread_start(t, name, sc, 0, look, s), 0);
	assert_true(t->running);
	hal_thread_join(t);
	assert_false(t->running);
}

/* May this process run SCHED_FIFO at all? */
static bool fifo_allowed(void)
{
	struct hal_sched s = { .priority = 1 };
	struct hal_thread t;
	struct seen seen;

	run(&t, "probe", &s, &seen);
	if (t.sched_err)
		printf("SKIP part: SCHED_FIFO refused here (%s): no CAP_SYS_NICE, no "
		       "RLIMIT_RTPRIO; the SCHED_FIFO cases are not run\n", strerror(t.sched_err));
	return !t.sched_err;
}

/* Asked for nothing: SCHED_OTHER on every CPU, named, signals blocked. */
static void test_other(void **state)
{
	struct hal_sched s = { 0 };
	struct hal_thread t;
	struct seen seen;
	cpu_set_t mine;

	run(&t, "strand-test", &s, &seen);
	assert_string_equal(seen.name, "strand-test");
	assert_int_equal(seen.policy, SCHED_OTHER);
	assert_false(t.fifo);
	assert_int_equal(t.sched_err, 0);
	assert_true(seen.sigint_blocked);
	assert_true(seen.sigterm_blocked);
	sched_getaffinity(0, sizeof(mine), &mine);
	assert_true(CPU_EQUAL(&mine, &seen.cpus));
}

/* A name longer than the kernel keeps is cut, not refused. */
static void test_long_name(void **state)
{
	struct hal_sched s = { 0 };
	struct hal_thread t;
	struct seen seen;
	char name[HAL_THREAD_NAME_MAX + 1];

	hal_thread_name(name, "strand-mb-", "a-very-long-device-name");
	assert_string_equal(name, "strand-mb-a-ver");
	run(&t, name, &s, &seen);
	assert_string_equal(seen.name, "strand-mb-a-ver");
}

/* SCHED_FIFO at the priority asked; and SCHED_OTHER asked from a
 * SCHED_FIFO thread is SCHED_OTHER (a thread would inherit its creator's
 * policy by default). */
static void test_fifo_and_not_inherited(void **state)
{
	struct hal_sched fifo = { .priority = 42 }, other = { 0 };
	struct sched_param sp = { .sched_priority = 30 }, none = { 0 };
	struct hal_thread t;
	struct seen seen;

	if (!fifo_allowed())
		return;
	run(&t, "strand-fifo", &fifo, &seen);
	assert_true(t.fifo);
	assert_int_equal(seen.policy, SCHED_FIFO);
	assert_int_equal(seen.priority, 42);
	assert_int_equal(pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp), 0);
	run(&t, "strand-other", &other, &seen);
	assert_int_equal(pthread_setschedparam(pthread_self(), SCHED_OTHER, &none), 0);
	assert_int_equal(seen.policy, SCHED_OTHER);
	assert_false(t.fifo);
}

/* On one CPU, or on all but one (the loop's), when there are two. */
static void test_cpus(void **state)
{
	struct hal_thread t;
	struct seen seen;
	cpu_set_t mine;
	int first = -1, c;

	sched_getaffinity(0, sizeof(mine), &mine);
	for (c = 0; c < CPU_SETSIZE && first < 0; c++)
		if (CPU_ISSET(c, &mine))
			first = c;
	run(&t, "strand-only", &(struct hal_sched){ .cpus = HAL_CPUS_ONLY, .cpu = first }, &seen);
	assert_int_equal(CPU_COUNT(&seen.cpus), 1);
	assert_true(CPU_ISSET(first, &seen.cpus));
	run(&t, "strand-but", &(struct hal_sched){ .cpus = HAL_CPUS_BUT, .cpu = first }, &seen);
	if (CPU_COUNT(&mine) < 2) {
		printf("one CPU: 'all but CPU %d' is every CPU\n", first);
		assert_true(CPU_EQUAL(&mine, &seen.cpus));
		return;
	}
	assert_int_equal(CPU_COUNT(&seen.cpus), CPU_COUNT(&mine) - 1);
	assert_false(CPU_ISSET(first, &seen.cpus));
	/* a CPU the process may not use: started anywhere, the refusal noted */
	run(&t, "strand-bad", &(struct hal_sched){ .cpus = HAL_CPUS_ONLY, .cpu = CPU_SETSIZE - 1 },
	    &seen);
	assert_true(CPU_EQUAL(&mine, &seen.cpus));
}

/* Without the privilege (a child: no root, no RLIMIT_RTPRIO), SCHED_FIFO
 * is refused and the thread runs SCHED_OTHER, the refusal in sched_err. */
static void test_refused(void **state)
{
	pid_t pid = fork();
	int st;

	assert_true(pid >= 0);
	if (pid == 0) {
		struct rlimit none = { 0, 0 };
		struct hal_sched fifo = { .priority = 42 };
		struct hal_thread t;
		struct seen seen;

		setrlimit(RLIMIT_RTPRIO, &none);
		if (geteuid() == 0 && setuid(65534))
			_exit(2);
		memset(&seen, 0, sizeof(seen));
		if (hal_thread_start(&t, "strand-refused", &fifo, 0, look, &seen))
			_exit(3);
		hal_thread_join(&t);
		_exit(t.sched_err == EPERM && !t.fifo && seen.policy == SCHED_OTHER ? 0 : 4);
	}
	assert_int_equal(waitpid(pid, &st, 0), pid);
	assert_true(WIFEXITED(st));
	assert_int_equal(WEXITSTATUS(st), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_other),
		cmocka_unit_test(test_long_name),
		cmocka_unit_test(test_fifo_and_not_inherited),
		cmocka_unit_test(test_cpus),
		cmocka_unit_test(test_refused),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
