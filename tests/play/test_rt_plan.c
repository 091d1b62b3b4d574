/* SPDX-License-Identifier: MIT */
/*
 * test_rt_plan.c - the priority plan (play/rt.h), from what it asks for to
 * what the kernel runs. The plan for a few --priority and --cpu values;
 * then `strand play` on the wall clock with every kind of thread strand
 * starts (a Modbus drive served by strand-simdrive, an e-stop on a GPIO
 * chip: the fake one, tests/fake/), each thread looked at through the
 * kernel while the loop runs (/proc/self/task: its name, policy, priority
 * and CPUs):
 *
 *   --priority 0, strand started from a SCHED_FIFO thread: every thread
 *     SCHED_OTHER, the service thread included (nothing is inherited);
 *   --priority 50 --cpu C: strand-rt FIFO 50 on CPU C, the GPIO event
 *     thread FIFO 50 and the Modbus I/O thread FIFO 49 off it, the
 *     service thread SCHED_OTHER;
 *   without the privilege (a child without root or RLIMIT_RTPRIO): the
 *     plan is SCHED_OTHER throughout, the refusal noted.
 *
 * SCHED_FIFO needs CAP_SYS_NICE or an RLIMIT_RTPRIO (CI runs as root):
 * where it is refused, the cases that need it print SKIP and pass.
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <pthread.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "cliutil.h"
#include "mbpeer.h"
#include "play/rt.h"
#include "playutil.h"
#include "tests/fake/gpio_line_fake.h"

/* ---- the plan ---- */

static void plan(struct rt_plan *pl, int priority, int cpu)
{
	struct rt_opts o = { .priority = priority, .cpu = cpu };

	rt_plan_make(pl, &o);
}

static bool fifo_refused(const struct rt_plan *pl)
{
	if (pl->sched_err)
		printf("SKIP part: SCHED_FIFO refused here (%s): no CAP_SYS_NICE, no RLIMIT_RTPRIO; "
		       "the SCHED_FIFO cases are not run\n", strerror(pl->sched_err));
	return pl->sched_err != 0;
}

/* The one table: loop and input events at P, bus I/O at P - 1, the CPUs
 * the loop's alone; P 0, and P 1 for the I/O, SCHED_OTHER. */
static void test_plan(void **state)
{
	struct rt_plan pl;

	plan(&pl, 0, -1);
	assert_int_equal(pl.sched_err, 0);
	assert_int_equal(pl.loop.priority, 0);
	assert_int_equal(pl.events.priority, 0);
	assert_int_equal(pl.io.priority, 0);
	assert_int_equal(pl.loop.cpus, HAL_CPUS_ANY);
	assert_int_equal(pl.events.cpus, HAL_CPUS_ANY);
	plan(&pl, 0, 1);
	assert_int_equal(pl.loop.cpus, HAL_CPUS_ONLY);
	assert_int_equal(pl.loop.cpu, 1);
	assert_int_equal(pl.events.cpus, HAL_CPUS_BUT);
	assert_int_equal(pl.io.cpus, HAL_CPUS_BUT);
	assert_int_equal(pl.io.cpu, 1);
	plan(&pl, 80, -1);
	if (fifo_refused(&pl)) {
		assert_int_equal(pl.loop.priority, 0);
		assert_int_equal(pl.events.priority, 0);
		assert_int_equal(pl.io.priority, 0);
		return;
	}
	assert_int_equal(pl.loop.priority, 80);
	assert_int_equal(pl.events.priority, 80);
	assert_int_equal(pl.io.priority, 80 - RT_IO_BELOW);
	plan(&pl, 1, -1);
	assert_int_equal(pl.loop.priority, 1);
	assert_int_equal(pl.io.priority, 0); /* never at or above the loop */
}

/* Without the privilege: SCHED_FIFO refused once, the whole plan
 * SCHED_OTHER, so that no thread runs real-time while the loop does not. */
static void test_plan_refused(void **state)
{
	pid_t pid = fork();
	int st;

	assert_true(pid >= 0);
	if (pid == 0) {
		struct rlimit none = { 0, 0 };
		struct rt_plan pl;

		setrlimit(RLIMIT_RTPRIO, &none);
		if (geteuid() == 0 && setuid(65534))
			_exit(2);
		plan(&pl, 50, -1);
		_exit(pl.sched_err == EPERM && !pl.loop.priority && !pl.events.priority &&
		      !pl.io.priority ? 0 : 3);
	}
	assert_int_equal(waitpid(pid, &st, 0), pid);
	assert_true(WIFEXITED(st));
	assert_int_equal(WEXITSTATUS(st), 0);
}

/* ---- a run, looked at ---- */

struct thread_seen {
	pid_t tid;
	char name[32];
	int policy, priority;
	cpu_set_t cpus;
};

struct look {
	struct thread_seen t[32];
	int n;
};

/* Every thread of this process now. */
static void look_now(struct look *lk)
{
	struct dirent *de;
	DIR *d = opendir("/proc/self/task");

	assert_non_null(d);
	lk->n = 0;
	while ((de = readdir(d)) && lk->n < 32) {
		struct thread_seen *t = &lk->t[lk->n];
		struct sched_param sp = { 0 };
		char path[64];
		FILE *f;

		if (de->d_name[0] < '0' || de->d_name[0] > '9')
			continue;
		t->tid = atoi(de->d_name);
		snprintf(path, sizeof(path), "/proc/self/task/%d/comm", t->tid);
		f = fopen(path, "r");
		if (!f)
			continue; /* gone meanwhile */
		if (!fgets(t->name, sizeof(t->name), f))
			t->name[0] = 0;
		fclose(f);
		t->name[strcspn(t->name, "\n")] = 0;
		t->policy = sched_getscheduler(t->tid) & ~SCHED_RESET_ON_FORK;
		sched_getparam(t->tid, &sp);
		t->priority = sp.sched_priority;
		sched_getaffinity(t->tid, sizeof(t->cpus), &t->cpus);
		lk->n++;
	}
	closedir(d);
}

static const struct thread_seen *by_name(const struct look *lk, const char *name)
{
	int i;

	for (i = 0; i < lk->n; i++)
		if (!strcmp(lk->t[i].name, name))
			return &lk->t[i];
	return NULL;
}

static const struct thread_seen *by_tid(const struct look *lk, pid_t tid)
{
	int i;

	for (i = 0; i < lk->n; i++)
		if (lk->t[i].tid == tid)
			return &lk->t[i];
	return NULL;
}

/* The scene: mbpeer's Modbus drive, the simulated camera, and an e-stop
 * on device 'pins', a GPIO chip (the fake gpiochip7). */
static void scene(const char *path, const char *conn)
{
	FILE *f = fopen(path, "w");

	assert_non_null(f);
	fprintf(f,
		"scene: plan\n"
		"timing: {tick_hz: 250, frame_rate: 24, frames: [0, 72]}\n"
		"nodes:\n"
		"  - {name: a, pivot: [0, 0, 0], joint: {type: revolute, axis: y},\n"
		"     limits: {min: -170, max: 170, velocity: 90, acceleration: 360}}\n"
		"strands:\n"
		"  - {node: a, interpolation: hermite, ease: {in: 12, out: 12},\n"
		"     keys: [{frame: 0, angle: 0}, {frame: 36, angle: 40}, {frame: 72, angle: 0}]}\n"
		"devices:\n"
		"  - name: drives\n"
		"    driver: modbus\n"
		"    modbus:\n"
		"      %s\n"
		"      unit: 1\n"
		"      axes:\n"
		"        - {register: 0, type: int32, actual: {register: 100}}\n"
		"  - {name: io, driver: sim}\n"
		"  - {name: pins, driver: gpio, chip: gpiochip7}\n"
		"outputs:\n"
		"  - {channel: a.angle, device: drives, axis: 0, counts_per_unit: 1000}\n"
		"triggers:\n"
		"  - {name: camera, device: io, line: 0, pulse_ms: 4}\n"
		"inputs:\n"
		"  - {name: estop, device: pins, line: estop, role: estop}\n",
		conn);
	fclose(f);
}

struct runner {
	const char *args;
	int fifo_before;     /* the runner's own SCHED_FIFO priority before it plays, 0: none */
	pid_t tid;
	int fifo_set;        /* pthread_setschedparam's answer */
	_Atomic bool done;
	struct run r;
};

static void *runner(void *arg)
{
	struct runner *rn = arg;

	rn->tid = (pid_t)syscall(SYS_gettid);
	if (rn->fifo_before) {
		struct sched_param sp = { .sched_priority = rn->fifo_before };

		rn->fifo_set = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
	}
	strand(&rn->r, rn->args);
	atomic_store(&rn->done, true);
	return NULL;
}

/* `strand play` with args on a thread of its own (the service thread),
 * looked at once its loop runs; its run's exit code. */
static int play_looked_at(const char *extra, int fifo_before, struct look *lk, pid_t *service)
{
	struct timespec ms = { 0, 1000000 };
	struct mbp_peer peer;
	struct runner rn;
	char sc[256], journal[256], conn[128], args[1024], logarg[300], log[256];
	pthread_t th;
	int port = mbp_free_port(), i;

	assert_true(port > 0);
	pu_tmpname(sc, sizeof(sc), "plan");
	pu_tmpname(journal, sizeof(journal), "plan-journal");
	pu_tmpname(log, sizeof(log), "plan-log");
	snprintf(conn, sizeof(conn), "tcp: {host: 127.0.0.1, port: %d}", port);
	scene(sc, conn);
	snprintf(logarg, sizeof(logarg), "--log %s", log);
	if (mbp_start(&peer, sc, logarg))
		fail_msg("strand-simdrive did not start: '%s'", peer.line);
	fake_reset();
	fake_chip.line_name[2] = "estop";
	fake_chip.high[2] = true; /* the chain is closed: active low, not asserted */
	snprintf(args, sizeof(args), "play %s --duration 1 --no-mlock --journal %s %s", sc,
		 journal, extra);
	memset(&rn, 0, sizeof(rn));
	rn.args = args;
	rn.fifo_before = fifo_before;
	assert_int_equal(pthread_create(&th, NULL, runner, &rn), 0);
	lk->n = 0;
	for (i = 0; i < 5000 && !atomic_load(&rn.done); i++) {
		look_now(lk);
		if (by_name(lk, "strand-rt"))
			break;
		nanosleep(&ms, NULL);
	}
	pthread_join(th, NULL);
	printf("strand %s: exit %d\n%s%s", args, rn.r.rc, rn.r.err ? rn.r.err : "",
	       rn.r.out ? rn.r.out : "");
	for (i = 0; i < lk->n; i++)
		printf("  thread %d %-16s policy %d priority %d, %d CPUs\n", lk->t[i].tid,
		       lk->t[i].name, lk->t[i].policy, lk->t[i].priority,
		       CPU_COUNT(&lk->t[i].cpus));
	assert_int_equal(mbp_stop(&peer), 0);
	assert_non_null(by_name(lk, "strand-rt"));
	if (fifo_before)
		assert_int_equal(rn.fifo_set, 0);
	*service = rn.tid;
	unlink(sc);
	unlink(journal);
	unlink(log);
	run_free(&rn.r);
	return rn.r.rc;
}

static const char *const strand_threads[] = { "strand-rt", "strand-gpio-pin", "strand-mb-drive" };

/* --priority 0 from a SCHED_FIFO thread: nothing real-time anywhere. */
static void test_run_priority_0(void **state)
{
	struct rt_plan pl;
	struct look lk;
	pid_t service;
	size_t k;
	int fifo = 0;

	plan(&pl, 10, -1);
	if (!fifo_refused(&pl))
		fifo = 10; /* the runner plays from SCHED_FIFO 10 */
	assert_int_equal(play_looked_at("--priority 0", fifo, &lk, &service), 0);
	for (k = 0; k < sizeof(strand_threads) / sizeof(strand_threads[0]); k++) {
		const struct thread_seen *t = by_name(&lk, strand_threads[k]);

		if (!t)
			fail_msg("no thread %s", strand_threads[k]);
		assert_int_equal(t->policy, SCHED_OTHER);
	}
	assert_non_null(by_tid(&lk, service));
	assert_int_equal(by_tid(&lk, service)->policy, SCHED_OTHER);
}

/* --priority 50 --cpu C: the table of play/rt.h, as the kernel runs it. */
static void test_run_priority_50(void **state)
{
	const struct thread_seen *rt, *gpio, *mb, *svc;
	struct rt_plan pl;
	struct look lk;
	cpu_set_t mine;
	char extra[64];
	pid_t service;
	int cpu = -1, c;

	plan(&pl, 50, -1);
	if (fifo_refused(&pl))
		return;
	sched_getaffinity(0, sizeof(mine), &mine);
	for (c = CPU_SETSIZE - 1; c >= 0 && cpu < 0; c--)
		if (CPU_ISSET(c, &mine))
			cpu = c;
	snprintf(extra, sizeof(extra), "--priority 50 --cpu %d", cpu);
	assert_int_equal(play_looked_at(extra, 0, &lk, &service), 0);
	rt = by_name(&lk, "strand-rt");
	gpio = by_name(&lk, "strand-gpio-pin");
	mb = by_name(&lk, "strand-mb-drive");
	svc = by_tid(&lk, service);
	assert_non_null(gpio);
	assert_non_null(mb);
	assert_non_null(svc);
	assert_int_equal(rt->policy, SCHED_FIFO);
	assert_int_equal(rt->priority, 50);
	assert_int_equal(gpio->policy, SCHED_FIFO);
	assert_int_equal(gpio->priority, 50);
	assert_int_equal(mb->policy, SCHED_FIFO);
	assert_int_equal(mb->priority, 50 - RT_IO_BELOW);
	assert_int_equal(svc->policy, SCHED_OTHER);
	assert_int_equal(CPU_COUNT(&rt->cpus), 1);
	assert_true(CPU_ISSET(cpu, &rt->cpus));
	if (CPU_COUNT(&mine) > 1) {
		assert_false(CPU_ISSET(cpu, &gpio->cpus));
		assert_false(CPU_ISSET(cpu, &mb->cpus));
		assert_int_equal(CPU_COUNT(&gpio->cpus), CPU_COUNT(&mine) - 1);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_plan),
		cmocka_unit_test(test_plan_refused),
		cmocka_unit_test(test_run_priority_0),
		cmocka_unit_test(test_run_priority_50),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
