/* SPDX-License-Identifier: MIT */
/* rt.c - real-time thread set-up (see rt.h). */
#define _GNU_SOURCE
#include "rt.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdint.h>
#include <sched.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <unistd.h>

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

void rt_thread_setup(const struct rt_opts *o, struct rt_result *r)
{
	pthread_t self = pthread_self();

	r->sched_err = 0;
	r->cpu_err = 0;
	r->slack_err = 0;
	r->fifo = false;
	if (o->name)
		pthread_setname_np(self, o->name);
	if (o->cpu >= 0) {
		cpu_set_t set;

		CPU_ZERO(&set);
		CPU_SET(o->cpu, &set);
		r->cpu_err = pthread_setaffinity_np(self, sizeof(set), &set);
	}
	if (o->priority > 0) {
		struct sched_param sp = { .sched_priority = o->priority };

		/* a positive error number on failure, never -1 */
		r->sched_err = pthread_setschedparam(self, SCHED_FIFO, &sp);
		r->fifo = r->sched_err == 0;
	}
	if (!r->fifo && prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0))
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
