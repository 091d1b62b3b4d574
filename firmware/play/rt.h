/* SPDX-License-Identifier: MIT */
/*
 * rt.h - what makes a thread real-time on Linux, and what to say when the
 * system refuses it.
 *
 *   - SCHED_FIFO at --priority (1..99; 0 keeps SCHED_OTHER), set when the
 *     thread is created (hal/thread.h). Refused without CAP_SYS_NICE or an
 *     RLIMIT_RTPRIO (limits.conf, systemd LimitRTPRIO=). pthread_create and
 *     pthread_setschedparam return a positive error number, not -1 (the
 *     mistake SOEM makes, which lets a refusal pass silently).
 *   - mlockall(MCL_CURRENT | MCL_FUTURE): no page of the process is paged
 *     out or faulted in lazily later. Refused over RLIMIT_MEMLOCK
 *     (LimitMEMLOCK=).
 *   - a prefaulted stack: the thread touches its stack once, so the loop's
 *     deepest call does not fault a fresh page in.
 *   - --cpu N: pinned to one CPU (pthread_attr_setaffinity_np); the other
 *     threads kept off it (below).
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
 *
 * The priority plan. Every thread strand starts is scheduled from one
 * plan, made here from --priority P and --cpu N (rt_plan_make), and
 * started through hal/thread.h with its scheduling set explicitly:
 *
 *   strand-rt          the loop                 SCHED_FIFO P, on CPU N
 *   strand-gpio-DEV    GPIO input events        SCHED_FIFO P, off CPU N
 *   strand-mb-DEV      Modbus I/O               SCHED_FIFO P - RT_IO_BELOW, off CPU N
 *   strand-ltc         LTC capture (--chase)    SCHED_FIFO P - RT_IO_BELOW, off CPU N
 *   strand-board       the lockstep (--node)    SCHED_FIFO P - RT_IO_BELOW, off CPU N
 *   strand (main)      the service thread       SCHED_OTHER
 *
 * The input event threads run at the loop's own priority: they carry the
 * e-stop's edge, which must not wait behind anything the loop would not
 * wait behind. The bus I/O threads run just below the loop: above ordinary
 * work (at normal priority on a busy machine the Modbus thread was seen
 * waking late enough that a quarter of the updates at 1 kHz were replaced
 * by newer ones), never above the loop, which they would otherwise delay
 * by a bus transaction's worth of CPU. The LTC capture thread is one of
 * them: a period read late is a timestamp read late, which its DLL filters,
 * with a buffer of 320 ms before samples are lost, while decoding a period
 * at the loop's priority on a CPU they share would delay the loop's
 * wake-up by that long (seen in the one-CPU test VM). With P = 0, or P = 1 for the I/O
 * threads, a thread runs SCHED_OTHER: none is SCHED_FIFO when the loop is
 * not. Off CPU N: every CPU the process may use but the loop's, when
 * there is another. Whether SCHED_FIFO is granted at all is found out once,
 * when the plan is made (a thread started at P and joined): refused, the
 * whole plan is SCHED_OTHER, so that no helper runs real-time while the
 * loop does not (an RLIMIT_RTPRIO between P - 1 and P would allow that).
 * The thread that makes the plan becomes the service thread, SCHED_OTHER
 * (strand started under chrt would otherwise hand the policy on).
 */
#ifndef STRAND_RT_H
#define STRAND_RT_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "hal/thread.h"

/* The bus I/O threads' priority below the loop's (see above). */
#define RT_IO_BELOW 1

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
	int sched_err; /* SCHED_FIFO's error number (EPERM), 0 if granted */
	int cpu_err;
	int slack_err;
	bool fifo;     /* running SCHED_FIFO */
};

/* Every thread's scheduling, from the loop's (see above). */
struct rt_plan {
	struct hal_sched loop;   /* strand-rt */
	struct hal_sched events; /* input event threads (GPIO) */
	struct hal_sched io;     /* bus I/O threads (Modbus) */
	int sched_err;           /* SCHED_FIFO at P refused when the plan was made */
	int service_policy;      /* the making thread's policy before it became the service's */
};

/* [init] The plan for o, SCHED_FIFO tried once; the calling thread (the
 * service thread) is made SCHED_OTHER. */
void rt_plan_make(struct rt_plan *pl, const struct rt_opts *o);

/* [init] One line on f: every thread of the process as the kernel
 * schedules it, by name ("strand play: threads: strand-rt SCHED_FIFO 80
 * on CPU 1, strand-gpio-io SCHED_FIFO 80, ..."), and what was refused. */
void rt_plan_report(const struct rt_plan *pl, FILE *f);

/* [init] Lock the process's memory and make the PM QoS request (main
 * thread, before the threads); rt_release() withdraws the request. */
void rt_lock_memory(const struct rt_opts *o, struct rt_result *r);
void rt_release(struct rt_result *r);

/* [init] Start the loop's thread (o->name) as the plan says, with a stack
 * of RT_STACK_BYTES; what was refused into r. 0 or a negative errno. */
int rt_thread_start(struct hal_thread *t, const struct rt_opts *o, const struct rt_plan *pl,
		    struct rt_result *r, void *(*fn)(void *), void *arg);

/* [init] Called first thing in the real-time thread itself: the timer
 * slack when it runs SCHED_OTHER, the stack prefaulted. */
void rt_thread_setup(const struct rt_opts *o, struct rt_result *r);

/* [init] Say, once and clearly, what was refused and what to do. */
void rt_report(const struct rt_opts *o, const struct rt_result *r, FILE *f);

#endif /* STRAND_RT_H */
