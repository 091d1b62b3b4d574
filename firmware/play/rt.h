/* SPDX-License-Identifier: MIT */
/*
 * rt.h - what makes a thread real-time on Linux, and what to say when the
 * system refuses it.
 *
 *   - SCHED_FIFO at --priority (1..99; 0 keeps SCHED_OTHER). Refused without
 *     CAP_SYS_NICE or an RLIMIT_RTPRIO (limits.conf, systemd LimitRTPRIO=).
 *     pthread_setschedparam returns a positive error number, not -1 (the
 *     mistake SOEM makes, which lets a refusal pass silently).
 *   - mlockall(MCL_CURRENT | MCL_FUTURE): no page of the process is paged
 *     out or faulted in lazily later. Refused over RLIMIT_MEMLOCK
 *     (LimitMEMLOCK=).
 *   - a prefaulted stack: the thread touches its stack once, so the loop's
 *     deepest call does not fault a fresh page in.
 *   - --cpu N: pinned to one CPU (pthread_setaffinity_np).
 *   - under SCHED_OTHER, a timer slack of 1 ns (PR_SET_TIMERSLACK): the
 *     default 50 us slack would delay every wake-up by up to that much.
 *   - a PM QoS request of 0 us on /dev/cpu_dma_latency, held open for the
 *     run: the CPUs stay out of idle states that take long to leave. On
 *     this project's virtual machine (cpuidle driver haltpoll) it halves
 *     the median wake-up latency (cyclictest: avg 48 -> 22 us); cyclictest
 *     makes the same request by default. It costs power while strand runs.
 *     Needs root (the device is 0600).
 *
 * Each refusal is noted and reported once by rt_report(); the run goes on
 * with what it got.
 */
#ifndef STRAND_RT_H
#define STRAND_RT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#define RT_STACK_BYTES (512u << 10)
#define RT_PREFAULT_BYTES (128u << 10)

struct rt_opts {
	int priority;      /* SCHED_FIFO priority, 0: SCHED_OTHER */
	int cpu;           /* -1: no pinning */
	bool lock_memory;
	bool pm_qos;       /* hold /dev/cpu_dma_latency at 0 */
	const char *name;  /* thread name, <= 15 characters */
};

struct rt_result {
	int lock_err;  /* errno of mlockall, 0 if locked or not asked */
	int qos_fd;    /* the open PM QoS request, or -1 */
	int qos_err;
	int sched_err; /* pthread_setschedparam's error number, 0 if granted */
	int cpu_err;
	int slack_err;
	bool fifo;     /* running SCHED_FIFO */
};

/* [init] Lock the process's memory and make the PM QoS request (main
 * thread, before the threads); rt_release() withdraws the request. */
void rt_lock_memory(const struct rt_opts *o, struct rt_result *r);
void rt_release(struct rt_result *r);

/* [init] Called first thing in the real-time thread itself. */
void rt_thread_setup(const struct rt_opts *o, struct rt_result *r);

/* [init] Say, once and clearly, what was refused and what to do. */
void rt_report(const struct rt_opts *o, const struct rt_result *r, FILE *f);

#endif /* STRAND_RT_H */
