/* SPDX-License-Identifier: MIT */
/*
 * coutil.h - what the CANopen tests share: a bus of simulated CiA 402
 * drives (sim/co_simbus.h) under the master's HAL backend (co_axis.h), on
 * a virtual clock, with a loop that ticks it as strand-rt would.
 */
#ifndef COUTIL_H
#define COUTIL_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/axis.h"
#include "hal/canopen/co_axis.h"
#include "hal/clock.h"
#include "sim/co_simbus.h"

#define CU_MAX 8

struct cu_rig {
	struct hal_clock clk;
	struct co_simbus *sb;
	struct hal_axis *ax;
	struct co_master *m;
	struct co_drive_cfg drv[CU_MAX];
	struct co_slave_cfg slave[CU_MAX];
	struct co_axis_cfg cfg;
	uint32_t n;
	int64_t t0; /* when tick 0 is due (set by cu_start) */
	int64_t k;  /* the next tick */
};

/* n drives, node-IDs 1..n, CSP, a 40 Hz plant each standing at 1000 * id
 * counts; a master at tick_hz with heartbeat 20 ms (lost after 50 ms).
 * Nothing is made yet: a test may change r->drv, r->slave, r->cfg first. */
void cu_init(struct cu_rig *r, uint32_t n, uint32_t tick_hz);
/* Make the bus with its drives (powered on) and the axis. */
void cu_make(struct cu_rig *r);
/* hal_axis_start; on success tick 0 is due one period later. */
int cu_start(struct cu_rig *r);
/* One tick as the loop runs it: wait for its time, input, set every drive
 * (targets[i] for drive i, or what it holds when targets is NULL), commit.
 * The first non-zero code of input and commit. */
int cu_tick(struct cu_rig *r, const int64_t *targets);
/* Ticks until a fault (its code) or n ticks (0), holding position. */
int cu_run(struct cu_rig *r, int64_t n);
void cu_free(struct cu_rig *r);

/* Frames in the log from `from` (-1 the master, else a node-ID) with this
 * identifier, from record `start` on. */
uint64_t cu_count(const struct cu_rig *r, int from, uint16_t id, uint64_t start);
/* Index of the first such record at or after start, or -1. */
int64_t cu_find(const struct cu_rig *r, int from, uint16_t id, uint64_t start);

#endif /* COUTIL_H */
