/* SPDX-License-Identifier: MIT */
/*
 * canopen_bench.c - the CPU time the CANopen master takes per tick, as the
 * loop calls it (hal_axis_input, a set per drive, hal_axis_commit), for 8
 * drives: what strand-rt spends on the bus beyond the system calls.
 *
 * The master is started against 8 simulated drives on the simulated bus;
 * then the bus under it is swapped for a replay: every input() finds the 8
 * TPDOs of a tick waiting (the drives' answers to the last SYNC, as the
 * real bus would have them), every commit()'s 9 frames go nowhere. So the
 * time measured is the master's and its HAL backend's alone, not the
 * simulated drives'. Prints BENCH lines.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hal/canopen/co_axis.h"
#include "sim/co_simbus.h"

#define NDRIVES 8
#define TICKS 2000000

/* A transport that is the simulated bus until `replay` is set, then hands
 * out the same tick of TPDOs at every recv and swallows what is sent. */
struct tap {
	struct co_bus bus; /* first */
	struct co_bus *sim;
	int replay;
	int pending;       /* TPDOs not yet taken this tick */
	struct co_frame tpdo[NDRIVES];
	uint64_t sent;
};

static int tap_send(struct co_bus *b, const struct co_frame *f, uint32_t n)
{
	struct tap *t = (struct tap *)b;

	if (!t->replay)
		return co_bus_send(t->sim, f, n);
	t->sent += n;
	t->pending = NDRIVES; /* the SYNC went out: the answers come */
	return 0;
}

static int tap_recv(struct co_bus *b, struct co_frame *f, uint32_t max)
{
	struct tap *t = (struct tap *)b;
	int n, i;

	if (!t->replay) {
		n = co_bus_recv(t->sim, f, max);
		for (i = 0; i < n; i++) /* keep each drive's latest TPDO */
			if ((f[i].id & 0x780) == 0x180 && (f[i].id & 0x7f) <= NDRIVES)
				t->tpdo[(f[i].id & 0x7f) - 1] = f[i];
		return n;
	}
	n = t->pending < (int)max ? t->pending : (int)max;
	memcpy(f, t->tpdo, (size_t)n * sizeof(*f));
	t->pending = 0;
	return n;
}

static enum co_bus_state tap_state(struct co_bus *b)
{
	return CO_BUS_ACTIVE;
}

static void tap_wait(struct co_bus *b, int64_t until)
{
	co_bus_wait(((struct tap *)b)->sim, until);
}

static void tap_close(struct co_bus *b)
{
	co_bus_close(((struct tap *)b)->sim);
}

static const struct co_bus_ops tap_ops = {
	.send = tap_send, .recv = tap_recv, .state = tap_state, .wait = tap_wait,
	.close = tap_close,
};

static double cpu_s(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
	return ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(void)
{
	struct co_drive_cfg drv[NDRIVES];
	struct co_axis_cfg ac = { .name = "bench" };
	struct hal_clock clk;
	struct co_simbus *sb;
	struct hal_axis *ax;
	struct tap tap = { .bus = { .ops = &tap_ops, .name = "tap" } };
	double t0, t1;
	int64_t k;
	uint32_t i;

	hal_clock_init(&clk, true);
	if (co_simbus_new(&sb, &clk, 1024, 0, NULL, 0)) {
		fprintf(stderr, "canopen_bench: out of memory\n");
		return 1;
	}
	for (i = 0; i < NDRIVES; i++) {
		struct co_slave_cfg sc = {
			.node = (uint8_t)(i + 1), .name = "bench",
			.model = { .bandwidth_hz = 40, .damping = 1, .feedforward = 0.9 },
		};

		co_simbus_add(NULL, sb, &sc, false, NULL, 0);
		drv[i] = (struct co_drive_cfg){ .node = (uint8_t)(i + 1), .mode = CO402_MODE_CSP,
						.quick_stop_dec = 100000 };
	}
	tap.sim = co_simbus_bus(sb);
	ac.master = (struct co_master_cfg){
		.tick_hz = 1000, .sync_id = 0x80, .heartbeat_ms = 50,
		.heartbeat_timeout_ms = 125, .boot_timeout_ms = 1000, .sdo_timeout_ms = 100,
		.enable_timeout_ms = 1000, .stop_timeout_ms = 1000,
	};
	ac.drives = drv;
	ac.ndrives = NDRIVES;
	ac.bus = &tap.bus;
	ac.clk = &clk;
	if (co_axis_new(&ax, &ac, NULL, 0) || hal_axis_start(ax)) {
		fprintf(stderr, "canopen_bench: the master did not start\n");
		return 1;
	}
	tap.replay = 1;
	tap.pending = NDRIVES;
	t0 = cpu_s();
	for (k = 0; k < TICKS; k++) {
		/* time stands still: no heartbeat falls due, as in a tick */
		if (hal_axis_input(ax, k))
			break;
		for (i = 0; i < NDRIVES; i++) {
			struct hal_setpoint sp = { .pos = k + i, .vel = 1000 };

			hal_axis_set(ax, i + 1, &sp);
		}
		if (hal_axis_commit(ax, k))
			break;
	}
	t1 = cpu_s();
	if (k < TICKS || tap.sent != (uint64_t)TICKS * (NDRIVES + 1)) {
		fprintf(stderr, "canopen_bench: stopped at tick %lld, %llu frames sent\n",
			(long long)k, (unsigned long long)tap.sent);
		return 1;
	}
	printf("canopen_bench: the master and its HAL backend, %d drives, %d ticks: input "
	       "(%d TPDOs), %d sets, commit (%d RPDOs and the SYNC), bus I/O excluded\n",
	       NDRIVES, TICKS, NDRIVES, NDRIVES, NDRIVES);
	printf("BENCH canopen_master_ns_per_tick_8_drives %.1f\n", (t1 - t0) * 1e9 / TICKS);
	hal_axis_close(ax);
	co_simbus_free(sb);
	return 0;
}
