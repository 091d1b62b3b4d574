/* SPDX-License-Identifier: MIT */
/* thread.c - threads started with their scheduling set (see thread.h). */
#define _GNU_SOURCE
#include "thread.h"

#include <errno.h>
#include <sched.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/prctl.h>

#include "rt.h"

/* The thread names itself before anything else, and its creator names it
 * too before hal_thread_start returns: named only by its creator, it could
 * run a while unnamed; only by itself, the creator could look before it
 * ran (rt_plan_report, right after the loop's thread starts). */
static void *named(void *arg)
{
	struct hal_thread *t = arg;

	prctl(PR_SET_NAME, t->name, 0, 0, 0);
	return t->fn(t->arg);
}

/* The CPUs s asks for into *set: false when that is every CPU the
 * process may use (no affinity to set). */
static bool cpus_of(const struct hal_sched *s, cpu_set_t *set)
{
	if (s->cpus == HAL_CPUS_ANY || s->cpu < 0 || s->cpu >= CPU_SETSIZE)
		return false;
	CPU_ZERO(set);
	if (s->cpus == HAL_CPUS_ONLY) {
		CPU_SET(s->cpu, set);
		return true;
	}
	/* the creating thread's mask is the process's, unless someone
	 * pinned it: taskset, a systemd CPUAffinity= */
	if (sched_getaffinity(0, sizeof(*set), set))
		return false;
	if (!CPU_ISSET(s->cpu, set) || CPU_COUNT(set) < 2)
		return false;
	CPU_CLR(s->cpu, set);
	return true;
}

/* One attempt: 0 or pthread_create's error number. */
static int create(struct hal_thread *t, bool fifo, int priority, const cpu_set_t *set,
		  size_t stack_bytes)
{
	struct sched_param sp = { .sched_priority = fifo ? priority : 0 };
	pthread_attr_t attr;
	int rc = pthread_attr_init(&attr);

	if (rc)
		return rc;
	if (stack_bytes)
		rc = pthread_attr_setstacksize(&attr, stack_bytes);
	if (!rc)
		rc = pthread_attr_setinheritsched(&attr, PTHREAD_EXPLICIT_SCHED);
	if (!rc)
		rc = pthread_attr_setschedpolicy(&attr, fifo ? SCHED_FIFO : SCHED_OTHER);
	if (!rc)
		rc = pthread_attr_setschedparam(&attr, &sp);
	if (!rc && set)
		rc = pthread_attr_setaffinity_np(&attr, sizeof(*set), set);
	if (!rc)
		rc = pthread_create(&t->id, &attr, named, t);
	pthread_attr_destroy(&attr);
	return rc;
}

int hal_thread_start(struct hal_thread *t, const char *name, const struct hal_sched *s,
		     size_t stack_bytes, void *(*fn)(void *), void *arg)
{
	bool fifo = s->priority > 0;
	sigset_t all, old;
	cpu_set_t set;
	bool pin;
	int rc;

	STRAND_ASSERT_NOT_RT();
	memset(t, 0, sizeof(*t));
	snprintf(t->name, sizeof(t->name), "%s", name);
	t->fn = fn;
	t->arg = arg;
	pin = cpus_of(s, &set);
	/* the new thread starts with the mask it is created under */
	sigfillset(&all);
	pthread_sigmask(SIG_SETMASK, &all, &old);
	rc = create(t, fifo, s->priority, pin ? &set : NULL, stack_bytes);
	if (rc == EPERM && fifo) {
		t->sched_err = rc;
		fifo = false;
		rc = create(t, fifo, 0, pin ? &set : NULL, stack_bytes);
	}
	if (rc == EINVAL && pin) {
		t->cpu_err = rc;
		pin = false;
		rc = create(t, fifo, s->priority, NULL, stack_bytes);
	}
	pthread_sigmask(SIG_SETMASK, &old, NULL);
	if (rc)
		return -rc;
	t->running = true;
	t->fifo = fifo;
	pthread_setname_np(t->id, t->name);
	return 0;
}

void hal_thread_join(struct hal_thread *t)
{
	STRAND_ASSERT_NOT_RT();
	if (!t->running)
		return;
	pthread_join(t->id, NULL);
	t->running = false;
}

void hal_thread_name(char *buf, const char *prefix, const char *device)
{
	snprintf(buf, HAL_THREAD_NAME_MAX + 1, "%s%s", prefix, device);
}
