/* SPDX-License-Identifier: MIT */
/*
 * modbus_priv.h - what the two sides of a Modbus device share: the loop's
 * side (modbus_axis.c, the HAL operations) and the I/O thread's
 * (modbus_io.c, every libmodbus call). Not a public interface.
 *
 * Ownership: fields under "rt" are touched only by the thread running the
 * loop (or by init code while no loop runs), fields under "io" only by the
 * I/O thread (or by init code while it does not run). They meet in the
 * slot, the two rings, the semaphore and the atomics.
 */
#ifndef HAL_MODBUS_PRIV_H
#define HAL_MODBUS_PRIV_H

#include <modbus.h>
#include <pthread.h>
#include <semaphore.h>
#include <stdatomic.h>

#include "hal/ring.h"
#include "hal/rt.h"
#include "hal/slot.h"
#include "hal/thread.h"
#include "modbus_dev.h"

/* One update: the loop's tick and every channel's target register value. */
struct mb_update {
	int64_t tick;
	int64_t val[]; /* nch */
};

enum mb_done_flag {
	MB_DONE_WRITTEN = 1, /* the drive has the update's setpoints */
	MB_DONE_HELD = 2,    /* at rest and not connected: the drive holds them */
	MB_DONE_READ = 4,    /* actual and status read */
	MB_DONE_FAULT = 8,   /* the device faults: code, detail, fault_text */
};

/* What the I/O thread reports for one update. */
struct mb_done {
	int64_t tick;
	uint32_t flags;
	int32_t code;      /* negative errno with MB_DONE_FAULT */
	uint32_t detail;   /* the register */
	uint32_t status;
	int64_t pair[];    /* nch pairs: actual, the target written when it was read */
};

enum mb_cmd {
	MB_CMD_DISABLE = 1,
};

#define MB_DONE_RING 64
#define MB_CMD_RING 4
#define MB_FAULT_TEXT 320

struct modbus_drv {
	struct hal_axis ax; /* first: the HAL view */
	struct modbus_cfg c;
	const struct modbus_desc *d;
	uint32_t every;            /* ticks per update */
	int64_t silence_ticks;
	bool *velocity;            /* nch */
	int64_t *initial;          /* nch */

	/* the write plan: nch targets, then the heartbeat */
	struct modbus_reg *wreg;
	struct modbus_plan wplan;
	/* the read plan: the actual registers of the channels that have one,
	 * then the status register; rfield[ch] is channel ch's index or -1 */
	struct modbus_reg *rreg;
	struct modbus_plan rplan;
	int32_t *rfield;
	int32_t rstatus;

	struct hal_slot slot;
	void *slot_buf;
	struct hal_ring done;
	void *done_buf;
	uint32_t done_size;
	struct hal_ring cmd;
	uint32_t cmd_buf[MB_CMD_RING];
	sem_t wake;
	bool wake_ready;
	struct hal_thread thread;
	_Atomic bool quit;
	_Atomic bool thread_done;

	/* rt */
	int64_t *staged;           /* nch: this update's target register values */
	int64_t *last_pos;         /* nch: the position last staged */
	int64_t *actual, *at_read; /* nch: as read, and the target then */
	bool have_actual;
	int64_t published, completed, ok_tick;
	bool disabled;
	struct hal_fault fault;
	char **range_text;         /* nch: a target beyond its register's range */
	char silence_text[MB_FAULT_TEXT];
	struct mb_done *popped;    /* one completion, done_size bytes */
	int64_t updates, replaced;

	/* io */
	modbus_t *mb;
	bool connected, io_disabled, have_written, fault_sent;
	uint16_t *wimg, *rimg;
	int64_t *written;          /* nch: the values the drive holds */
	int64_t last_read_tick;
	bool have_read;
	uint32_t in_a_row;
	int64_t last_try_ns;
	struct mb_done *pending;   /* the completion being built, done_size bytes */
	char msg[MB_FAULT_TEXT];        /* the last failure */
	char fault_text[MB_FAULT_TEXT]; /* the fault's: fixed once fault_sent */
	struct modbus_stats st;    /* the I/O thread's counts */
	char where[96];            /* "tcp 127.0.0.1:1502 unit 1", for messages */
};

static inline struct modbus_drv STRAND_RT *mb_of(struct hal_axis *ax)
{
	return (struct modbus_drv *)ax;
}

/* ---- modbus_io.c: libmodbus, on the I/O thread (or at init) ---- */

/* Connect (and set the unit and timeouts): 0, or a negative errno with
 * fault_text set. */
int mb_io_connect(struct modbus_drv *m);
void mb_io_close(struct modbus_drv *m);
/* Read every actual and status register into m->pending: 0, or a negative
 * errno with fault_text set (and m->pending's detail the register). */
int mb_io_read(struct modbus_drv *m, int64_t tick);
/* Write vals (nch) with the heartbeat tick: 0, or as mb_io_read. */
int mb_io_write(struct modbus_drv *m, const int64_t *vals, int64_t tick);
/* The enable coil or register on or off: 0, or as mb_io_read. */
int mb_io_enable(struct modbus_drv *m, bool on);
/* The I/O thread. */
void *mb_io_main(void *arg);

#endif /* HAL_MODBUS_PRIV_H */
