/* SPDX-License-Identifier: MIT */
/* rt.c - real-time thread set-up (see rt.h). */
#define _GNU_SOURCE
#include "rt.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <sched.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <unistd.h>

#include "hal/rt.h"

/* Threads rt_plan_report lists, at most (strand starts a handful). */
#define RT_REPORT_THREADS 64

static void *probe_main(void *arg)
{
	return arg;
}

void rt_plan_make(struct rt_plan *pl, const struct rt_opts *o)
{
	struct sched_param none = { .sched_priority = 0 };
	enum hal_cpus off = o->cpu >= 0 ? HAL_CPUS_BUT : HAL_CPUS_ANY;
	int p = o->priority > 0 ? o->priority : 0;

	STRAND_ASSERT_NOT_RT();
	memset(pl, 0, sizeof(*pl));
	pl->service_policy = sched_getscheduler(0) & ~SCHED_RESET_ON_FORK;
	if (pl->service_policy != SCHED_OTHER)
		pthread_setschedparam(pthread_self(), SCHED_OTHER, &none);
	if (p) {
		struct hal_sched s = { .priority = p };
		struct hal_thread probe;
		int rc = hal_thread_start(&probe, "strand-probe", &s, 0, probe_main, NULL);

		pl->sched_err = rc ? -rc : probe.sched_err;
		hal_thread_join(&probe);
		if (pl->sched_err)
			p = 0;
	}
	pl->loop = (struct hal_sched){ .priority = p, .cpu = o->cpu,
				       .cpus = o->cpu >= 0 ? HAL_CPUS_ONLY : HAL_CPUS_ANY };
	pl->events = (struct hal_sched){ .priority = p, .cpus = off, .cpu = o->cpu };
	pl->io = (struct hal_sched){ .priority = p > RT_IO_BELOW ? p - RT_IO_BELOW : 0,
				     .cpus = off, .cpu = o->cpu };
}

/* "0", "0-3", "0,2-3" into buf. */
static void cpu_list(char *buf, size_t size, const cpu_set_t *set)
{
	size_t used = 0;
	int c, first;

	buf[0] = 0;
	for (c = 0; c < CPU_SETSIZE && used < size; c++) {
		if (!CPU_ISSET(c, set))
			continue;
		for (first = c; c + 1 < CPU_SETSIZE && CPU_ISSET(c + 1, set); c++)
			;
		used += (size_t)snprintf(buf + used, size - used, first == c ? "%s%d" : "%s%d-%d",
					 used ? "," : "", first, c);
	}
}

static int by_tid(const void *a, const void *b)
{
	pid_t x = *(const pid_t *)a, y = *(const pid_t *)b;

	return (x > y) - (x < y);
}

/* One thread as the kernel schedules it: ", NAME SCHED_FIFO 80 on CPU 1";
 * false, and nothing said, for one that ended since the list was read (a
 * loop that stopped at its first tick). */
static bool report_one(FILE *f, pid_t tid, bool first, const cpu_set_t *all)
{
	struct sched_param sp = { 0 };
	char path[64], name[32] = "?", cpus[128];
	int policy = sched_getscheduler(tid);
	cpu_set_t set;
	FILE *c;

	snprintf(path, sizeof(path), "/proc/self/task/%d/comm", (int)tid);
	c = fopen(path, "r");
	if (!c || policy < 0 || sched_getparam(tid, &sp)) {
		if (c)
			fclose(c);
		return false;
	}
	if (fgets(name, sizeof(name), c))
		name[strcspn(name, "\n")] = 0;
	fclose(c);
	policy &= ~SCHED_RESET_ON_FORK;
	fprintf(f, "%s%s%s %s", first ? "" : ", ", name, tid == getpid() ? " (service)" : "",
		policy == SCHED_FIFO ? "SCHED_FIFO" : policy == SCHED_RR ? "SCHED_RR" :
		policy == SCHED_OTHER ? "SCHED_OTHER" : "SCHED_BATCH/IDLE");
	if (policy == SCHED_FIFO || policy == SCHED_RR)
		fprintf(f, " %d", sp.sched_priority);
	if (!sched_getaffinity(tid, sizeof(set), &set) && !CPU_EQUAL(&set, all)) {
		cpu_list(cpus, sizeof(cpus), &set);
		fprintf(f, " on CPU%s %s", CPU_COUNT(&set) == 1 ? "" : "s", cpus);
	}
	return true;
}

void rt_plan_report(const struct rt_plan *pl, FILE *f)
{
	pid_t tid[RT_REPORT_THREADS];
	cpu_set_t all;
	struct dirent *de;
	size_t n = 0, i, shown;
	DIR *d;

	STRAND_ASSERT_NOT_RT();
	d = opendir("/proc/self/task");
	if (!d)
		return;
	while ((de = readdir(d)) && n < RT_REPORT_THREADS)
		if (de->d_name[0] >= '0' && de->d_name[0] <= '9')
			tid[n++] = (pid_t)atoi(de->d_name);
	closedir(d);
	qsort(tid, n, sizeof(tid[0]), by_tid);
	/* the service thread's CPUs are the process's */
	if (sched_getaffinity(getpid(), sizeof(all), &all))
		CPU_ZERO(&all);
	fprintf(f, "strand: threads: ");
	for (i = 0, shown = 0; i < n; i++)
		shown += report_one(f, tid[i], shown == 0, &all);
	if (pl->sched_err)
		fprintf(f, "; SCHED_FIFO refused (%s), so every thread runs SCHED_OTHER",
			strerror(pl->sched_err));
	if (pl->service_policy != SCHED_OTHER)
		fprintf(f, "; the service thread was started %s and now runs SCHED_OTHER",
			pl->service_policy == SCHED_FIFO ? "SCHED_FIFO" :
			pl->service_policy == SCHED_RR ? "SCHED_RR" : "SCHED_BATCH/IDLE");
	fprintf(f, "\n");
}

void rt_lock_memory(const struct rt_opts *o, struct rt_result *r)
{
	int32_t zero = 0;

	r->lock_err = 0;
	r->qos_err = 0;
	r->qos_fd = -1;
	if (o->lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE))
		r->lock_err = errno;
	if (!o->pm_qos)
		return;
	/* the request lasts as long as the file stays open */
	r->qos_fd = open("/dev/cpu_dma_latency", O_RDWR | O_CLOEXEC);
	if (r->qos_fd < 0) {
		r->qos_err = errno;
	} else if (write(r->qos_fd, &zero, sizeof(zero)) != (ssize_t)sizeof(zero)) {
		r->qos_err = errno ? errno : EIO;
		close(r->qos_fd);
		r->qos_fd = -1;
	}
}

void rt_release(struct rt_result *r)
{
	if (r->qos_fd >= 0)
		close(r->qos_fd);
	r->qos_fd = -1;
}

/* Touch RT_PREFAULT_BYTES of stack below this frame. noinline: the array
 * must really be on the stack, below the caller's frame. */
static __attribute__((noinline)) void prefault_stack(void)
{
	volatile unsigned char buf[RT_PREFAULT_BYTES];
	size_t i;

	for (i = 0; i < sizeof(buf); i += 4096)
		buf[i] = 0;
}

int rt_thread_start(struct hal_thread *t, const struct rt_opts *o, const struct rt_plan *pl,
		    struct rt_result *r, void *(*fn)(void *), void *arg)
{
	int rc;

	STRAND_ASSERT_NOT_RT();
	rc = hal_thread_start(t, o->name ? o->name : "strand-rt", &pl->loop, RT_STACK_BYTES, fn,
			      arg);
	/* (rt_thread_setup, on the new thread, writes slack_err only) */
	r->sched_err = pl->sched_err ? pl->sched_err : t->sched_err;
	r->cpu_err = t->cpu_err;
	r->fifo = t->fifo;
	return rc;
}

void rt_thread_setup(const struct rt_opts *o, struct rt_result *r)
{
	r->slack_err = 0;
	if ((sched_getscheduler(0) & ~SCHED_RESET_ON_FORK) != SCHED_FIFO &&
	    prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0))
		r->slack_err = errno;
	prefault_stack();
}

void rt_report(const struct rt_opts *o, const struct rt_result *r, FILE *f)
{
	if (r->lock_err)
		fprintf(f,
			"strand: warning: memory not locked (mlockall: %s); page faults may delay "
			"the loop. Raise the memlock limit (systemd LimitMEMLOCK=infinity, or "
			"'memlock unlimited' in /etc/security/limits.conf).\n",
			strerror(r->lock_err));
	if (r->sched_err)
		fprintf(f,
			"strand: warning: real-time priority %d refused (SCHED_FIFO: %s); running "
			"at normal priority with 1 ns timer slack. Grant it with systemd "
			"LimitRTPRIO=%d, 'rtprio %d' in /etc/security/limits.conf, or run as root.\n",
			o->priority, strerror(r->sched_err), o->priority, o->priority);
	if (r->qos_err)
		fprintf(f,
			"strand: warning: cannot keep the CPUs out of deep idle states "
			"(/dev/cpu_dma_latency: %s); wake-ups may come later. Run as root or give "
			"the service access to that device.\n", strerror(r->qos_err));
	if (r->cpu_err)
		fprintf(f, "strand: warning: cannot pin the loop to CPU %d (%s); running unpinned.\n",
			o->cpu, strerror(r->cpu_err));
	if (r->slack_err)
		fprintf(f, "strand: warning: cannot set the timer slack (%s).\n",
			strerror(r->slack_err));
}
