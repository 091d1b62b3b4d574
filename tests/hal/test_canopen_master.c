/* SPDX-License-Identifier: MIT */
/*
 * test_canopen_master.c - the CANopen master through its HAL backend against
 * simulated CiA 402 drives on the simulated bus, in virtual time: the
 * start-up sequence frame by frame, the cyclic exchange, aborts and timeouts
 * at start, a drive in fault at start, heartbeat loss, an emergency, a drive
 * that reboots, TPDOs that stop, bus-off, error-passive, the quick stop, the
 * orderly stop, a target beyond 32 bits, answers that come after the next
 * SYNC.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "coutil.h"
#include "sim/sim_drive.h"

#define MS 1000000LL

static const struct co_simbus_rec *log_of(const struct cu_rig *r, uint64_t *n)
{
	return co_simbus_log(r->sb, n);
}

static struct co_slave *drive(struct cu_rig *r, uint8_t node)
{
	return co_simbus_node(r->sb, node);
}

static void start_ok(struct cu_rig *r)
{
	int rc;

	cu_make(r);
	rc = cu_start(r);
	if (rc) {
		struct hal_fault f;

		hal_axis_fault(r->ax, &f);
		fail_msg("start: %d: %s", rc, f.cause);
	}
	assert_int_equal(co_master_phase(r->m), CO_MASTER_RUNNING);
}

/* ---- the start-up sequence ---- */

struct req {
	uint8_t cs;      /* 0x40 upload, 0x20 download */
	uint16_t index;
	uint8_t sub;
	uint32_t value;  /* downloads */
};

/* The configuration the master must write to node id in mode mode. */
static unsigned expected(struct req *q, uint8_t id, uint8_t mode)
{
	const struct req list[] = {
		{ 0x40, 0x1000, 0, 0 },
		{ 0x40, 0x1008, 0, 0 },
		{ 0x20, 0x1017, 0, 20 },
		{ 0x20, 0x6060, 0, mode },
		{ 0x20, 0x60c2, 1, 1 },
		{ 0x20, 0x60c2, 2, 0xfd },
		{ 0x20, 0x605a, 0, 2 },
		{ 0x20, 0x6085, 0, 400000 },
		{ 0x20, 0x1400, 1, 0x80000200u + id },
		{ 0x20, 0x1600, 0, 0 },
		{ 0x20, 0x1600, 1, 0x60400010 },
		{ 0x20, 0x1600, 2, mode == 8 ? 0x607a0020 : 0x60ff0020 },
		{ 0x20, 0x1600, 0, 2 },
		{ 0x20, 0x1400, 2, 1 },
		{ 0x20, 0x1400, 1, 0x200u + id },
		{ 0x20, 0x1401, 1, 0x80000300u + id },
		{ 0x20, 0x1402, 1, 0x80000400u + id },
		{ 0x20, 0x1403, 1, 0x80000500u + id },
		{ 0x20, 0x1800, 1, 0xc0000180u + id },
		{ 0x20, 0x1a00, 0, 0 },
		{ 0x20, 0x1a00, 1, 0x60410010 },
		{ 0x20, 0x1a00, 2, 0x60640020 },
		{ 0x20, 0x1a00, 0, 2 },
		{ 0x20, 0x1800, 2, 1 },
		{ 0x20, 0x1800, 1, 0x40000180u + id },
		{ 0x20, 0x1801, 1, 0xc0000280u + id },
		{ 0x20, 0x1802, 1, 0xc0000380u + id },
		{ 0x20, 0x1803, 1, 0xc0000480u + id },
		{ 0x40, 0x6064, 0, 0 },
		{ 0x40, 0x6041, 0, 0 },
	};

	memcpy(q, list, sizeof(list));
	return sizeof(list) / sizeof(list[0]);
}

/* One node's part of the start-up, from the bus log: NMT reset
 * communication, boot-up, the SDO configuration in order, NMT start, then
 * RPDOs with shutdown, switch on, enable operation. */
static void check_startup(struct cu_rig *r, uint8_t id, uint8_t mode)
{
	struct req want[40];
	unsigned nwant = expected(want, id, mode), got = 0;
	uint64_t n, i;
	const struct co_simbus_rec *log = log_of(r, &n);
	int64_t reset = -1, boot = -1, start = -1, last_sdo = -1;
	uint16_t cws[8];
	unsigned ncw = 0;

	for (i = 0; i < n; i++) {
		const struct co_frame *f = &log[i].f;

		if (log[i].from == -1 && f->id == 0 && f->data[1] == id) {
			if (f->data[0] == CO_NMT_RESET_COMM && reset < 0)
				reset = (int64_t)i;
			if (f->data[0] == CO_NMT_START)
				start = (int64_t)i;
		} else if (log[i].from == id && f->id == 0x700 + id && f->data[0] == 0 &&
			   reset >= 0 && boot < 0) {
			boot = (int64_t)i;
		} else if (log[i].from == -1 && f->id == 0x600 + id &&
			   ((f->data[0] & 0xe0) == 0x20 || (f->data[0] & 0xe0) == 0x40)) {
			const struct req *w = &want[got];
			uint8_t cs = f->data[0] & 0xe0;

			assert_true(got < nwant);
			if (cs != w->cs || co_get16(&f->data[1]) != w->index || f->data[3] != w->sub ||
			    (cs == 0x20 && (f->data[0] & 2) && co_get32(&f->data[4]) != w->value))
				fail_msg("node %u request %u: %s 0x%04x:%02x = 0x%08x, want %s "
					 "0x%04x:%02x = 0x%08x", id, got, cs == 0x40 ? "read" : "write",
					 co_get16(&f->data[1]), f->data[3], co_get32(&f->data[4]),
					 w->cs == 0x40 ? "read" : "write", w->index, w->sub, w->value);
			got++;
			last_sdo = (int64_t)i;
		} else if (log[i].from == -1 && f->id == 0x200 + id && ncw < 8 &&
			   (!ncw || cws[ncw - 1] != co_get16(f->data))) {
			cws[ncw++] = co_get16(f->data);
		}
	}
	assert_int_equal(got, nwant);
	assert_true(reset >= 0 && boot > reset && last_sdo > boot && start > last_sdo);
	assert_int_equal(ncw, 3);
	assert_int_equal(cws[0], 0x06);
	assert_int_equal(cws[1], 0x07);
	assert_int_equal(cws[2], 0x0f);
	assert_true(cu_find(r, -1, 0x200 + id, 0) > start);
}

static void test_startup(void **state)
{
	struct cu_rig r;
	const struct co_slave_watch *w;
	int64_t c;
	uint8_t id;

	cu_init(&r, 3, 1000);
	r.drv[2].mode = CO402_MODE_CSV;
	start_ok(&r);
	for (id = 1; id <= 3; id++) {
		check_startup(&r, id, id == 3 ? CO402_MODE_CSV : CO402_MODE_CSP);
		w = co_slave_watch(drive(&r, id));
		assert_int_equal(w->nmt, CO_NMT_OPERATIONAL);
		assert_int_equal(w->state, CO402_ENABLED);
		assert_int_equal(w->mode, id == 3 ? 9 : 8);
		assert_int_equal(w->heartbeat_ms, 20);
		/* power on, then 2, 3, 4 */
		assert_int_equal(w->ntransitions, 4);
		assert_int_equal(w->log[1].to, CO402_READY);
		assert_int_equal(w->log[2].to, CO402_SWITCHED_ON);
		assert_int_equal(w->log[3].to, CO402_ENABLED);
		assert_int_equal(w->log[3].cw, 0x0f);
		assert_string_equal(r.m->node[id - 1].name, "simdrive");
		assert_int_equal(r.m->node[id - 1].device_type & 0xffff, 402);
		/* the TPDOs of the last SYNC are in: it stands where it stood */
		assert_true(hal_axis_actual(r.ax, id, &c));
		assert_int_equal(c, 1000 * id);
	}
	/* a channel that is not a node */
	assert_false(hal_axis_actual(r.ax, 9, &c));
	cu_free(&r);
}

/* ---- the cyclic exchange ---- */

static void test_cycle(void **state)
{
	struct cu_rig r;
	int32_t trace[3][400];
	int64_t tg[3], k0, c;
	uint64_t first, n, i;
	const struct co_simbus_rec *log;
	uint32_t d;
	int k;

	cu_init(&r, 3, 1000);
	r.drv[2].mode = CO402_MODE_CSV;
	start_ok(&r);
	for (d = 0; d < 3; d++)
		co_slave_trace(drive(&r, (uint8_t)(d + 1)), trace[d], 400);
	log_of(&r, &first);
	for (k = 0; k < 300; k++) {
		tg[0] = 1000 + 10 * k;       /* 10 counts a tick: 10000 counts/s */
		tg[1] = 2000 - 5 * k;
		tg[2] = 3000;                /* velocity, counts/s */
		assert_int_equal(cu_tick(&r, tg), 0);
	}
	/* every target took effect, at the SYNC of its tick */
	for (d = 0; d < 3; d++)
		assert_int_equal(co_slave_traced(drive(&r, (uint8_t)(d + 1))), 300);
	for (k = 0; k < 300; k++) {
		assert_int_equal(trace[0][k], 1000 + 10 * k);
		assert_int_equal(trace[1][k], 2000 - 5 * k);
		assert_int_equal(trace[2][k], 3000);
	}
	/* each tick on the bus: RPDO 1, 2, 3, then one SYNC, then the TPDOs */
	log = log_of(&r, &n);
	assert_int_equal(cu_count(&r, -1, 0x80, first), 300);
	for (i = first, k0 = 0; i < n; i++) {
		if (log[i].from != -1 || log[i].f.id != 0x80)
			continue;
		assert_int_equal(log[i - 3].f.id, 0x201);
		assert_int_equal(log[i - 2].f.id, 0x202);
		assert_int_equal(log[i - 1].f.id, 0x203);
		assert_int_equal(log[i - 3].f.len, 6);
		/* one period apart: the virtual loop is exact */
		if (k0)
			assert_int_equal(log[i].t - k0, MS);
		k0 = log[i].t;
	}
	assert_int_equal(cu_count(&r, 1, 0x181, first), 300);
	/* the plant behind the bus is the in-process drive's: a twin fed the
	 * same targets reports the same positions, TPDO by TPDO */
	{
		struct sim_drive_channel ch = r.slave[0].model;
		struct sim_drive *twin;
		struct hal_axis *tx;
		int64_t j = (int64_t)first, x;

		ch.initial = 1000;
		assert_int_equal(sim_drive_new(&twin, "twin", 1, 1000, &ch, NULL, 0), 0);
		tx = sim_drive_axis(twin);
		hal_axis_start(tx);
		for (k = 0; k < 300; k++) {
			struct hal_setpoint sp = { 1000 + 10 * k, k ? 10000 : 0 };

			hal_axis_set(tx, 0, &sp);
			hal_axis_commit(tx, k);
			hal_axis_input(tx, k + 1);
			hal_axis_actual(tx, 0, &x);
			j = cu_find(&r, 1, 0x181, (uint64_t)j + 1);
			assert_true(j > 0);
			assert_int_equal((int32_t)co_get32(&log[j].f.data[2]), x);
		}
		/* 10000 counts/s at 40 Hz and 0.9 feed-forward: 2 z (1 - kff)
		 * v / w = 8 counts behind the staircase on average, 3 at the
		 * end of a period */
		assert_true(1000 + 10 * 299 - x >= 2 && 1000 + 10 * 299 - x <= 3);
		hal_axis_close(tx);
	}
	assert_int_equal(hal_axis_input(r.ax, 300), 0);
	assert_true(hal_axis_actual(r.ax, 1, &c));
	/* the velocity drive runs at 3000 counts/s */
	assert_true(co_slave_watch(drive(&r, 3))->actual > 3000 + 3000 * 0.2);
	cu_free(&r);
}

/* ---- failures at start ---- */

static void start_fails(struct cu_rig *r, int code, enum co_fault_kind kind, uint8_t node,
			const char *msg)
{
	struct hal_fault hf;
	struct co_fault f;
	int rc = cu_start(r);

	assert_int_equal(rc, code);
	assert_int_equal(co_master_fault(r->m, &f), code);
	assert_int_equal(f.kind, kind);
	assert_int_equal(f.node, node);
	assert_int_equal(hal_axis_fault(r->ax, &hf), code);
	if (strcmp(hf.cause, msg))
		fail_msg("cause '%s'\n want '%s'", hf.cause, msg);
}

/* Every drive that got anywhere is left switched off and pre-operational. */
static void all_off(struct cu_rig *r)
{
	uint32_t i;

	for (i = 0; i < r->n; i++) {
		const struct co_slave_watch *w = co_slave_watch(co_simbus_slave(r->sb, i));

		assert_true(w->state != CO402_ENABLED && w->state != CO402_SWITCHED_ON);
		assert_int_equal(w->nmt, CO_NMT_PREOPERATIONAL);
	}
}

static void test_start_sdo_abort(void **state)
{
	struct cu_rig r;

	cu_init(&r, 3, 1000);
	cu_make(&r);
	co_slave_refuse(drive(&r, 2), 0x60c2, 1, CO_ABORT_VALUE_HIGH);
	start_fails(&r, -EIO, CO_FAULT_SDO, 2,
		    "node 2: SDO write of 0x60C2:01 aborted: value of parameter written too high "
		    "(0x06090031)");
	all_off(&r);
	cu_free(&r);
}

/* A drive without TPDO3 says so: fine, the master only switches it off. */
static void test_start_optional_pdo(void **state)
{
	struct cu_rig r;

	cu_init(&r, 2, 1000);
	cu_make(&r);
	co_slave_refuse(drive(&r, 1), 0x1802, 1, CO_ABORT_NO_OBJECT);
	co_slave_refuse(drive(&r, 2), 0x1008, 0, CO_ABORT_NO_OBJECT); /* no name */
	assert_int_equal(cu_start(&r), 0);
	assert_string_equal(r.m->node[1].name, "");
	cu_free(&r);
}

static void test_start_sdo_timeout(void **state)
{
	struct cu_rig r;
	int64_t t0;

	cu_init(&r, 2, 1000);
	cu_make(&r);
	co_slave_sdo_deaf(drive(&r, 1), true);
	t0 = hal_clock_now(&r.clk);
	start_fails(&r, -EIO, CO_FAULT_SDO, 1,
		    "node 1: SDO read of 0x1000:00 aborted: SDO protocol timed out (0x05040000)");
	/* one request timed out, then the stop */
	assert_true(hal_clock_now(&r.clk) - t0 >= 100 * MS);
	cu_free(&r);
}

static void test_start_no_bootup(void **state)
{
	struct cu_rig r;
	int64_t t0, dt;

	cu_init(&r, 3, 1000);
	assert_int_equal(co_simbus_new(&r.sb, &r.clk, 1024, 1 << 16, NULL, 0), 0);
	assert_int_equal(co_simbus_add(NULL, r.sb, &r.slave[0], false, NULL, 0), 0);
	assert_int_equal(co_simbus_add(NULL, r.sb, &r.slave[1], true, NULL, 0), 0); /* powered off */
	assert_int_equal(co_simbus_add(NULL, r.sb, &r.slave[2], false, NULL, 0), 0);
	r.cfg.bus = co_simbus_bus(r.sb);
	assert_int_equal(co_axis_new(&r.ax, &r.cfg, NULL, 0), 0);
	r.m = co_axis_master(r.ax);
	t0 = hal_clock_now(&r.clk);
	start_fails(&r, -ETIMEDOUT, CO_FAULT_BOOT, 2,
		    "node 2: no boot-up message within 500 ms of the NMT reset communication "
		    "(powered, wired, node-ID and bitrate right?)");
	dt = r.m->fault.kind ? hal_clock_now(&r.clk) - t0 : 0;
	assert_true(dt >= 500 * MS);
	cu_free(&r);
}

static void test_start_enable_timeout(void **state)
{
	struct cu_rig r;

	cu_init(&r, 2, 1000);
	cu_make(&r);
	co_slave_stuck(drive(&r, 2), true);
	start_fails(&r, -ETIMEDOUT, CO_FAULT_ENABLE, 2,
		    "node 2: did not reach operation enabled within 500 ms: statusword 0x0240 "
		    "(switch on disabled)");
	assert_int_equal(co_slave_watch(drive(&r, 1))->state, CO402_READY);
	cu_free(&r);
}

/* A drive in fault at start: the master resets it (a rising edge of bit 7)
 * and enables it; the drive says its errors are gone with EMCY 0x0000. */
static void test_start_fault_reset(void **state)
{
	struct cu_rig r;
	const struct co_slave_watch *w;
	int64_t i, reset;
	uint32_t k;

	cu_init(&r, 2, 1000);
	cu_make(&r);
	co_slave_fault(drive(&r, 1), 0x4310, hal_clock_now(&r.clk));
	assert_int_equal(cu_start(&r), 0);
	w = co_slave_watch(drive(&r, 1));
	for (k = 0; k < w->ntransitions && w->log[k].from != CO402_FAULT; k++)
		;
	assert_true(k < w->ntransitions);
	assert_int_equal(w->log[k].to, CO402_DISABLED);
	assert_int_equal(w->log[k].cw, 0x80);
	assert_int_equal(w->state, CO402_ENABLED);
	/* two EMCYs: the fault, then the reset */
	i = cu_find(&r, 1, 0x81, 0);
	assert_true(i >= 0);
	assert_int_equal(co_get16(co_simbus_log(r.sb, &(uint64_t){ 0 })[i].f.data), 0x4310);
	reset = cu_find(&r, 1, 0x81, (uint64_t)i + 1);
	assert_true(reset > i);
	assert_int_equal(co_get16(co_simbus_log(r.sb, &(uint64_t){ 0 })[reset].f.data), 0);
	/* the fault before the start does not stop the run */
	assert_int_equal(cu_run(&r, 50), 0);
	cu_free(&r);
}

/* ---- faults while running ---- */

/* Someone else writes to a drive's dictionary (its answer goes to the
 * master, which ignores it). */
static void poke(struct cu_rig *r, uint8_t node, uint16_t index, uint8_t sub, uint32_t v,
		 uint8_t size)
{
	struct co_frame f;
	struct co_sdo c;
	uint8_t buf[4];

	co_put32(buf, v);
	co_sdo_init(&c, node, MS);
	co_sdo_download(&c, index, sub, buf, size, 0, &f);
	co_slave_rx(drive(r, node), &f, hal_clock_now(&r->clk));
}

/* Run until a fault; returns the tick it was seen in. */
static int64_t run_to_fault(struct cu_rig *r, int64_t max, int code)
{
	int64_t k;

	for (k = 0; k < max; k++) {
		int rc = cu_tick(r, NULL);

		if (rc) {
			assert_int_equal(rc, code);
			return r->k - 1;
		}
	}
	fail_msg("no fault in %lld ticks", (long long)max);
	return -1;
}

static void expect_fault(struct cu_rig *r, int code, enum co_fault_kind kind, int32_t channel,
			 const char *cause, uint32_t detail)
{
	struct hal_fault hf;
	struct co_fault f;

	assert_int_equal(hal_axis_fault(r->ax, &hf), code);
	assert_int_equal(hf.channel, channel);
	assert_string_equal(hf.cause, cause);
	assert_int_equal(hf.detail, detail);
	co_master_fault(r->m, &f);
	assert_int_equal(f.kind, kind);
}

static void test_heartbeat_lost(void **state)
{
	struct cu_rig r;
	int64_t seen, c;
	char msg[200];

	cu_init(&r, 3, 1000);
	start_ok(&r);
	assert_int_equal(cu_run(&r, 100), 0);
	co_slave_power_off(drive(&r, 2));
	seen = run_to_fault(&r, 200, -ETIMEDOUT);
	/* the last heartbeat came within 20 ms before the cut: lost 50 ms
	 * after it, seen at the next tick */
	assert_true(seen >= 100 + 30 && seen <= 100 + 51);
	expect_fault(&r, -ETIMEDOUT, CO_FAULT_HEARTBEAT, 2, "heartbeat lost", 0);
	co_master_describe(r.m, &r.m->fault, msg, sizeof(msg));
	assert_string_equal(msg, "node 2: heartbeat lost: none for 50 ms");
	/* its feedback stopped at once: never a stale position */
	assert_false(hal_axis_actual(r.ax, 2, &c));
	assert_true(hal_axis_actual(r.ax, 1, &c));
	/* the others brake and switch off; the lost one is not waited for */
	hal_axis_disable(r.ax);
	assert_int_equal(hal_axis_stop(r.ax), 0);
	assert_int_equal(co_slave_watch(drive(&r, 1))->state, CO402_DISABLED);
	assert_int_equal(co_slave_watch(drive(&r, 3))->state, CO402_DISABLED);
	cu_free(&r);
}

static void test_emcy_running(void **state)
{
	struct cu_rig r;
	char msg[200];
	int64_t seen;

	cu_init(&r, 3, 1000);
	start_ok(&r);
	assert_int_equal(cu_run(&r, 50), 0);
	co_slave_fault(drive(&r, 3), 0x2310, hal_clock_now(&r.clk));
	seen = run_to_fault(&r, 10, -EIO);
	assert_int_equal(seen, 50);
	expect_fault(&r, -EIO, CO_FAULT_EMCY, 3, "emergency 0x2310 (current, device output side)",
		     0x2310);
	co_master_describe(r.m, &r.m->fault, msg, sizeof(msg));
	assert_string_equal(msg, "node 3: emergency 0x2310 (current, device output side), error "
				 "register 0x03, drive operation enabled");
	cu_free(&r);
}

/* The statusword says fault before the EMCY comes: still named by it, if it
 * comes in the same batch; and without one, the statusword is the cause. */
static void test_left_enabled(void **state)
{
	struct cu_rig r;
	char msg[200];

	cu_init(&r, 2, 1000);
	start_ok(&r);
	assert_int_equal(cu_run(&r, 20), 0);
	/* a drive switched off by someone else: disable voltage */
	poke(&r, 2, 0x6040, 0, 0, 2);
	run_to_fault(&r, 10, -EIO);
	expect_fault(&r, -EIO, CO_FAULT_STATE, 2, "left operation enabled", 0);
	co_master_describe(r.m, &r.m->fault, msg, sizeof(msg));
	assert_string_equal(msg, "node 2: left operation enabled: statusword 0x0240 (switch on "
				 "disabled)");
	cu_free(&r);
}

static void test_drive_reboots(void **state)
{
	struct cu_rig r;

	cu_init(&r, 2, 1000);
	start_ok(&r);
	assert_int_equal(cu_run(&r, 20), 0);
	co_slave_power_off(drive(&r, 1));
	co_slave_power_on(drive(&r, 1), hal_clock_now(&r.clk));
	run_to_fault(&r, 5, -ECONNRESET);
	expect_fault(&r, -ECONNRESET, CO_FAULT_NMT, 1, "drive rebooted", 0);
	cu_free(&r);
}

/* TPDOs stop while the heartbeat goes on (someone switched TPDO1 off). */
static void test_tpdo_stops(void **state)
{
	struct cu_rig r;
	int64_t seen;

	cu_init(&r, 2, 1000);
	start_ok(&r);
	assert_int_equal(cu_run(&r, 20), 0);
	poke(&r, 2, 0x1800, 1, 0xc0000182, 4);
	seen = run_to_fault(&r, 100, -ETIMEDOUT);
	assert_true(seen >= 20 + 50 && seen <= 20 + 52);
	expect_fault(&r, -ETIMEDOUT, CO_FAULT_TPDO, 2, "TPDOs stopped", 0);
	cu_free(&r);
}

/* The loop's first tick long after the start-up's last SYNC (a loaded
 * machine between the start and the loop's thread): no SYNC went out in
 * the pause, so no TPDO was owed, and the watchdog stays quiet; the
 * drives that then stop answering are still caught, 50 ms after the
 * first SYNC they left unanswered. */
static void test_tpdo_pause(void **state)
{
	struct cu_rig r;
	int64_t seen;

	cu_init(&r, 2, 1000);
	start_ok(&r);
	r.t0 += 300000000; /* tick 0 300 ms late: six heartbeat timeouts */
	assert_int_equal(cu_run(&r, 20), 0);
	r.t0 += 300000000;
	assert_int_equal(cu_run(&r, 20), 0);
	poke(&r, 2, 0x1800, 1, 0xc0000182, 4);
	seen = run_to_fault(&r, 100, -ETIMEDOUT);
	assert_true(seen >= 40 + 50 && seen <= 40 + 52);
	expect_fault(&r, -ETIMEDOUT, CO_FAULT_TPDO, 2, "TPDOs stopped", 0);
	cu_free(&r);
}

/* Bus-off: the fault names it, and nothing the master would send after it
 * ever reaches the bus, not even once the controller is back. */
static void test_bus_off(void **state)
{
	struct cu_rig r;
	uint64_t at, n;
	char msg[200];

	cu_init(&r, 3, 1000);
	start_ok(&r);
	assert_int_equal(cu_run(&r, 20), 0);
	co_simbus_set_state(r.sb, CO_BUS_OFF);
	log_of(&r, &at);
	run_to_fault(&r, 2, -ENETDOWN);
	expect_fault(&r, -ENETDOWN, CO_FAULT_BUS_OFF, -1, "bus-off", 0);
	co_master_describe(r.m, &r.m->fault, msg, sizeof(msg));
	assert_string_equal(msg, "bus-off: the controller left the bus after too many errors; "
				 "nothing queued is sent after it");
	hal_axis_disable(r.ax);
	cu_tick(&r, NULL);
	co_simbus_set_state(r.sb, CO_BUS_ACTIVE); /* restarted */
	cu_tick(&r, NULL);
	hal_axis_disable(r.ax);
	assert_int_equal(hal_axis_stop(r.ax), -EIO);
	log_of(&r, &n);
	assert_int_equal(cu_count(&r, -1, 0x80, at), 0);
	assert_int_equal(cu_count(&r, -1, 0x201, at), 0);
	assert_int_equal(cu_count(&r, -1, 0x000, at), 0);
	cu_free(&r);
}

/* Error-passive: the run stops, the bus still carries the quick stop. */
static void test_error_passive(void **state)
{
	struct cu_rig r;

	cu_init(&r, 2, 1000);
	start_ok(&r);
	assert_int_equal(cu_run(&r, 20), 0);
	co_simbus_set_state(r.sb, CO_BUS_PASSIVE);
	run_to_fault(&r, 2, -ECOMM);
	expect_fault(&r, -ECOMM, CO_FAULT_PASSIVE, -1, "bus error-passive", 0);
	hal_axis_disable(r.ax);
	assert_int_equal(hal_axis_stop(r.ax), 0);
	assert_int_equal(co_slave_watch(drive(&r, 1))->state, CO402_DISABLED);
	assert_int_equal(co_slave_watch(drive(&r, 1))->nmt, CO_NMT_PREOPERATIONAL);
	cu_free(&r);
}

/* disable() at speed: the drive brakes on its own quick stop ramp (0x6085,
 * 400000 counts/s^2), without SYNCs, then switches off (option code 2). */
static void test_quick_stop(void **state)
{
	struct cu_rig r;
	const struct co_slave_watch *w;
	int64_t tg[1], x0, k, stop_dist;
	uint64_t at;
	int32_t last;

	cu_init(&r, 1, 1000);
	start_ok(&r);
	/* up to 100 counts a tick (100000 counts/s) and on */
	for (k = 0; k < 600; k++) {
		int64_t v = k < 200 ? k / 2 : 100;

		tg[0] = r.m->node[0].target + v;
		assert_int_equal(cu_tick(&r, tg), 0);
	}
	x0 = co_slave_watch(drive(&r, 1))->actual;
	log_of(&r, &at);
	hal_axis_disable(r.ax);
	/* one RPDO with quick stop, one SYNC, then nothing cyclic */
	assert_int_equal(cu_count(&r, -1, 0x80, at), 1);
	w = co_slave_watch(drive(&r, 1));
	assert_int_equal(w->state, CO402_QUICK_STOP);
	assert_int_equal(w->log[w->ntransitions - 1].cw, 0x02);
	/* v^2 / 2a = 1e10 / 8e5 = 12500 counts; the plant lags the ramp */
	do {
		last = w->actual;
		hal_clock_sleep_until(&r.clk, hal_clock_now(&r.clk) + MS);
		co_simbus_run(r.sb, hal_clock_now(&r.clk));
	} while (w->state == CO402_QUICK_STOP);
	stop_dist = last - x0;
	assert_true(stop_dist > 12500 * 0.9 && stop_dist < 12500 * 1.1);
	assert_int_equal(w->state, CO402_DISABLED);
	assert_int_equal(w->log[w->ntransitions - 1].from, CO402_QUICK_STOP);
	assert_int_equal(hal_axis_stop(r.ax), 0);
	assert_int_equal(co_master_phase(r.m), CO_MASTER_STOPPED);
	assert_int_equal(w->nmt, CO_NMT_PREOPERATIONAL);
	cu_free(&r);
}

/* The end of a run at rest: shutdown, confirmed, then pre-operational. */
static void test_stop(void **state)
{
	struct cu_rig r;
	const struct co_slave_watch *w;

	cu_init(&r, 2, 1000);
	start_ok(&r);
	assert_int_equal(cu_run(&r, 30), 0);
	assert_int_equal(hal_axis_stop(r.ax), 0);
	w = co_slave_watch(drive(&r, 2));
	assert_int_equal(w->state, CO402_READY);
	assert_int_equal(w->log[w->ntransitions - 1].cw, 0x06);
	assert_int_equal(w->nmt, CO_NMT_PREOPERATIONAL);
	/* a second stop has nothing to do */
	assert_int_equal(hal_axis_stop(r.ax), 0);
	cu_free(&r);
}

static void test_target_range(void **state)
{
	struct cu_rig r;
	int64_t tg[2] = { 1000, 1LL << 40 };
	uint64_t at;
	struct co_fault f;

	cu_init(&r, 2, 1000);
	start_ok(&r);
	assert_int_equal(cu_run(&r, 5), 0);
	log_of(&r, &at);
	assert_int_equal(cu_tick(&r, tg), -ERANGE);
	assert_int_equal(cu_count(&r, -1, 0x80, at), 0); /* that tick sent nothing */
	co_master_fault(r.m, &f);
	assert_int_equal(f.kind, CO_FAULT_RANGE);
	assert_int_equal(f.node, 2);
	cu_free(&r);
}

/* A SYNC COB-ID other than 0x80 is configured into every drive. */
static void test_sync_id(void **state)
{
	struct cu_rig r;
	uint64_t at;

	cu_init(&r, 2, 500);
	r.cfg.master.sync_id = 0x7f;
	start_ok(&r);
	log_of(&r, &at);
	assert_int_equal(cu_run(&r, 10), 0);
	assert_int_equal(cu_count(&r, -1, 0x7f, at), 10);
	assert_int_equal(cu_count(&r, -1, 0x80, at), 0);
	assert_int_equal(cu_count(&r, 2, 0x182, at), 10);
	cu_free(&r);
}

/* ---- answers that come late ---- */

/* The last TPDO of node id in the log: its position actual. */
static int32_t last_actual(const struct cu_rig *r, uint8_t id)
{
	uint64_t n, i;
	const struct co_simbus_rec *log = co_simbus_log(r->sb, &n);

	for (i = n; i-- > 0;)
		if (log[i].from == id && log[i].f.id == 0x180 + id)
			return (int32_t)co_get32(&log[i].f.data[2]);
	fail_msg("no TPDO from node %u", id);
	return 0;
}

/* Ticks k0..k1-1 of a ramp of 10 counts a tick from 1000, node 1's. */
static void ramp(struct cu_rig *r, int k0, int k1)
{
	int64_t tg[1];
	int k;

	for (k = k0; k < k1; k++) {
		tg[0] = 1000 + 10 * k;
		assert_int_equal(cu_tick(r, tg), 0);
	}
}

/* A drive that answers a SYNC only after the next one went out (its
 * process starved of CPU while the loop caught up on late ticks): its
 * answer is not taken for the latest SYNC's, so the following error the
 * loop computes (latest target - actual) is the one the drive had. Before
 * this was fixed, each SYNC of delay added a tick of motion (here 10
 * counts) to it. */
static void test_late_tpdo(void **state)
{
	struct cu_rig r;
	int64_t c;
	int32_t a;

	cu_init(&r, 1, 1000);
	start_ok(&r);
	ramp(&r, 0, 50);
	/* on time: the answer to the SYNC of target 1490 */
	assert_int_equal(hal_axis_input(r.ax, 50), 0);
	assert_true(hal_axis_actual(r.ax, 1, &c));
	assert_int_equal(c, last_actual(&r, 1));
	assert_int_equal(r.m->node[0].tpdo_late, 0);

	/* ticks 50 and 51 go out; the drive sees neither until released */
	co_simbus_hold(r.sb, true);
	ramp(&r, 50, 52);
	assert_false(hal_axis_actual(r.ax, 1, &c)); /* none since the latest SYNC */
	/* the drive takes tick 50's RPDO and SYNC and answers that SYNC only */
	assert_int_equal(co_simbus_deliver(r.sb, 2), 2);
	assert_int_equal(hal_axis_input(r.ax, 52), 0);
	assert_true(hal_axis_actual(r.ax, 1, &c));
	a = last_actual(&r, 1);
	assert_true(1500 - a > 0); /* behind target 1500 of tick 50 */
	assert_int_equal(1510 - c, 1500 - a);
	assert_int_equal(r.m->node[0].tpdo_late, 1);

	/* released: the answer to tick 51's SYNC is certain again */
	co_simbus_hold(r.sb, false);
	assert_int_equal(hal_axis_input(r.ax, 52), 0);
	assert_true(hal_axis_actual(r.ax, 1, &c));
	assert_int_equal(c, last_actual(&r, 1));
	assert_int_equal(r.m->node[0].tpdo_lo, r.m->node[0].tpdo_sync);

	/* and on time from then on */
	ramp(&r, 52, 60);
	assert_int_equal(hal_axis_input(r.ax, 60), 0);
	assert_true(hal_axis_actual(r.ax, 1, &c));
	assert_int_equal(c, last_actual(&r, 1));
	assert_int_equal(r.m->node[0].tpdo_late, 1);
	assert_int_equal(co_simbus_overflows(r.sb), 0);
	cu_free(&r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_startup),
		cmocka_unit_test(test_cycle),
		cmocka_unit_test(test_start_sdo_abort),
		cmocka_unit_test(test_start_optional_pdo),
		cmocka_unit_test(test_start_sdo_timeout),
		cmocka_unit_test(test_start_no_bootup),
		cmocka_unit_test(test_start_enable_timeout),
		cmocka_unit_test(test_start_fault_reset),
		cmocka_unit_test(test_heartbeat_lost),
		cmocka_unit_test(test_emcy_running),
		cmocka_unit_test(test_left_enabled),
		cmocka_unit_test(test_drive_reboots),
		cmocka_unit_test(test_tpdo_stops),
		cmocka_unit_test(test_tpdo_pause),
		cmocka_unit_test(test_bus_off),
		cmocka_unit_test(test_error_passive),
		cmocka_unit_test(test_quick_stop),
		cmocka_unit_test(test_stop),
		cmocka_unit_test(test_target_range),
		cmocka_unit_test(test_sync_id),
		cmocka_unit_test(test_late_tpdo),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
