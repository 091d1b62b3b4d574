/* SPDX-License-Identifier: MIT */
/* coutil.c - the CANopen tests' bus and loop (see coutil.h). */
#include "coutil.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <string.h>

void cu_init(struct cu_rig *r, uint32_t n, uint32_t tick_hz)
{
	uint32_t i;

	memset(r, 0, sizeof(*r));
	hal_clock_init(&r->clk, true);
	r->n = n;
	for (i = 0; i < n; i++) {
		r->drv[i].node = (uint8_t)(i + 1);
		r->drv[i].mode = CO402_MODE_CSP;
		r->drv[i].quick_stop_dec = 400000;
		r->slave[i].node = (uint8_t)(i + 1);
		r->slave[i].name = "simdrive";
		r->slave[i].model.bandwidth_hz = 40;
		r->slave[i].model.damping = 1;
		r->slave[i].model.feedforward = 0.9;
		r->slave[i].initial = 1000 * (int32_t)(i + 1);
	}
	r->cfg.name = "drives";
	r->cfg.drives = r->drv;
	r->cfg.ndrives = n;
	r->cfg.clk = &r->clk;
	r->cfg.master.tick_hz = tick_hz;
	r->cfg.master.sync_id = CO_ID_SYNC;
	r->cfg.master.heartbeat_ms = 20;
	r->cfg.master.heartbeat_timeout_ms = 50;
	r->cfg.master.boot_timeout_ms = 500;
	r->cfg.master.sdo_timeout_ms = 100;
	r->cfg.master.enable_timeout_ms = 500;
	r->cfg.master.stop_timeout_ms = 2000;
}

void cu_make(struct cu_rig *r)
{
	uint32_t i;

	assert_int_equal(co_simbus_new(&r->sb, &r->clk, 1024, 1 << 20, NULL, 0), 0);
	for (i = 0; i < r->n; i++)
		assert_int_equal(co_simbus_add(NULL, r->sb, &r->slave[i], false, NULL, 0), 0);
	r->cfg.bus = co_simbus_bus(r->sb);
	assert_int_equal(co_axis_new(&r->ax, &r->cfg, NULL, 0), 0);
	r->m = co_axis_master(r->ax);
	assert_non_null(r->m);
}

int cu_start(struct cu_rig *r)
{
	int rc = hal_axis_start(r->ax);

	r->t0 = hal_clock_now(&r->clk) + 1000000000LL / r->cfg.master.tick_hz;
	r->k = 0;
	return rc;
}

int cu_tick(struct cu_rig *r, const int64_t *targets)
{
	uint32_t hz = r->cfg.master.tick_hz, i;
	int64_t k = r->k++;
	int in, out;

	hal_clock_sleep_until(&r->clk, r->t0 + k / hz * 1000000000LL +
					      k % hz * 1000000000LL / hz);
	in = hal_axis_input(r->ax, k);
	for (i = 0; i < r->n; i++) {
		struct hal_setpoint sp = { 0 };
		const struct co_node *nd = &r->m->node[i];

		if (targets)
			sp.pos = sp.vel = targets[i];
		else
			sp.pos = nd->target, sp.vel = nd->target;
		hal_axis_set(r->ax, r->drv[i].node, &sp);
	}
	out = hal_axis_commit(r->ax, k);
	return in ? in : out;
}

int cu_run(struct cu_rig *r, int64_t n)
{
	int rc = 0;

	while (n-- > 0 && !(rc = cu_tick(r, NULL)))
		;
	return rc;
}

void cu_free(struct cu_rig *r)
{
	hal_axis_close(r->ax);
	co_simbus_free(r->sb);
	r->ax = NULL;
	r->sb = NULL;
}

uint64_t cu_count(const struct cu_rig *r, int from, uint16_t id, uint64_t start)
{
	uint64_t n, i, c = 0;
	const struct co_simbus_rec *log = co_simbus_log(r->sb, &n);

	for (i = start; i < n; i++)
		c += log[i].from == from && log[i].f.id == id;
	return c;
}

int64_t cu_find(const struct cu_rig *r, int from, uint16_t id, uint64_t start)
{
	uint64_t n, i;
	const struct co_simbus_rec *log = co_simbus_log(r->sb, &n);

	for (i = start; i < n; i++)
		if (log[i].from == from && log[i].f.id == id)
			return (int64_t)i;
	return -1;
}
