/* SPDX-License-Identifier: MIT */
/*
 * sleep_tick.c - the floor under the play loop's CPU time per tick: a
 * thread that does nothing but what every loop on the wall clock does, set
 * up as strand's loop is (memory locked, SCHED_FIFO at the given priority,
 * the PM QoS request of 0 us held) and sleeping to absolute 1 ms ticks with
 * clock_nanosleep, reading the clock once after each wake-up. Its CPU time
 * per tick is what the kernel charges a thread for sleeping and waking up
 * on this machine; strand's play_cpu_per_tick_wall minus this is strand's
 * own (mk/bench-play.sh prints both). Prints
 *
 *     BENCH sleep_cpu_per_tick_wall <ns> ns
 *
 * usage: sleep_tick TICKS PRIORITY (0: SCHED_OTHER)
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <sched.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

static int64_t now_ns(clockid_t c)
{
	struct timespec ts;

	clock_gettime(c, &ts);
	return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

int main(int argc, char **argv)
{
	struct sched_param sp = { 0 };
	int32_t zero = 0;
	int64_t n, k, t0, c0, c1, late = 0;
	int fd;

	if (argc != 3 || (n = atoll(argv[1])) <= 0 || (sp.sched_priority = atoi(argv[2])) < 0) {
		fprintf(stderr, "usage: sleep_tick TICKS PRIORITY\n");
		return 2;
	}
	if (mlockall(MCL_CURRENT | MCL_FUTURE))
		fprintf(stderr, "sleep_tick: mlockall: %s\n", strerror(errno));
	if (sp.sched_priority && sched_setscheduler(0, SCHED_FIFO, &sp))
		fprintf(stderr, "sleep_tick: SCHED_FIFO %d: %s\n", sp.sched_priority,
			strerror(errno));
	fd = open("/dev/cpu_dma_latency", O_RDWR | O_CLOEXEC);
	if (fd < 0 || write(fd, &zero, sizeof(zero)) != (ssize_t)sizeof(zero))
		fprintf(stderr, "sleep_tick: /dev/cpu_dma_latency: %s\n", strerror(errno));
	t0 = now_ns(CLOCK_MONOTONIC) + 1000000;
	c0 = now_ns(CLOCK_THREAD_CPUTIME_ID);
	for (k = 0; k < n; k++) {
		int64_t due = t0 + k * 1000000;
		struct timespec ts = { .tv_sec = due / 1000000000, .tv_nsec = due % 1000000000 };

		while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR)
			;
		late += now_ns(CLOCK_MONOTONIC) - due;
	}
	c1 = now_ns(CLOCK_THREAD_CPUTIME_ID);
	printf("BENCH sleep_cpu_per_tick_wall %lld ns\n", (long long)((c1 - c0) / n));
	printf("# sleep_tick: %lld ticks, average wake-up latency %.1f us\n", (long long)n,
	       late / 1e3 / (double)n);
	if (fd >= 0)
		close(fd);
	return 0;
}
