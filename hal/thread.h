/* SPDX-License-Identifier: MIT */
/*
 * thread.h - every thread strand starts, started one way: its scheduling
 * (policy, priority, CPUs) set explicitly when it is created, never
 * inherited from the thread that creates it (which may itself run
 * SCHED_FIFO: a thread inherits its creator's policy by default); every
 * signal blocked from its first instruction (signals are the service
 * thread's business); a name for ps, top and /proc/PID/task/TID/comm.
 *
 * What each thread gets is not decided here: one plan, made from the
 * loop's --priority and --cpu (firmware/play/rt.h), hands each kind of
 * thread its struct hal_sched, and the backends that start threads (the
 * GPIO input event thread, the Modbus I/O thread) are given theirs.
 *
 * A SCHED_FIFO refused (EPERM: no CAP_SYS_NICE, an RLIMIT_RTPRIO below
 * the priority) starts the thread at SCHED_OTHER instead, and CPUs refused
 * (EINVAL: a CPU the process may not use) start it on any; each refusal
 * is noted in struct hal_thread for the caller to report. Both errors are
 * pthread's positive error numbers: pthread_create does not return -1.
 *
 * [init] throughout: from the service thread, before the loop starts or
 * after it ended.
 */
#ifndef HAL_THREAD_H
#define HAL_THREAD_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>

/* The longest name the kernel keeps (TASK_COMM_LEN less its NUL). */
#define HAL_THREAD_NAME_MAX 15

enum hal_cpus {
	HAL_CPUS_ANY,  /* wherever the process may run */
	HAL_CPUS_ONLY, /* on `cpu` alone */
	HAL_CPUS_BUT,  /* anywhere the process may run but `cpu`, if that
			* leaves a CPU; else anywhere */
};

/* How a thread is scheduled. All zero: SCHED_OTHER, any CPU. */
struct hal_sched {
	int priority;       /* SCHED_FIFO at 1..99; 0: SCHED_OTHER */
	enum hal_cpus cpus;
	int cpu;
};

struct hal_thread {
	pthread_t id;
	bool running;       /* started, not joined yet */
	bool fifo;          /* started SCHED_FIFO */
	int sched_err;      /* SCHED_FIFO refused: the error number (EPERM), else 0 */
	int cpu_err;        /* the CPUs refused: the error number, else 0 */
	char name[HAL_THREAD_NAME_MAX + 1];
	void *(*fn)(void *); /* what it runs, named first (thread.c) */
	void *arg;
};

/*
 * [init] Start fn(arg) on a thread scheduled as s says, named `name` (cut
 * at HAL_THREAD_NAME_MAX characters), with a stack of stack_bytes (0: the
 * default). 0, or a negative errno when no thread started. *t must stay
 * where it is until the thread is joined.
 */
int hal_thread_start(struct hal_thread *t, const char *name, const struct hal_sched *s,
		     size_t stack_bytes, void *(*fn)(void *), void *arg);

/* [init] Wait for a started thread to end (nothing when it did not start). */
void hal_thread_join(struct hal_thread *t);

/* "strand-mb-" and a device's name, cut to fit a thread's name. */
void hal_thread_name(char *buf, const char *prefix, const char *device);

#endif /* HAL_THREAD_H */
