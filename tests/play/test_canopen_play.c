/* SPDX-License-Identifier: MIT */
/*
 * test_canopen_play.c - strand play on a CANopen bus of simulated drives
 * (interface "sim": the master, the protocol and the drives in-process), on
 * the virtual clock: every target each drive took equals what the same run
 * sends the in-process twin, with the same following errors; a drive lost
 * (heartbeat), an emergency, an e-stop (quick stop on the bus), a start-up
 * refused by a drive, a start-up given up when a stop is asked for (a
 * signal) while it waits; and the loop thread allocates nothing throughout.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/exitcode.h"
#include "hal/canopen/co_axis.h"
#include "playutil.h"
#include "rig/drv_canopen.h"
#include "sim/co_simbus.h"
#include "sim/sim_drive.h"
#include "sim/sim_gpio.h"
#include "testutil.h"

#define MS 1000000LL
#define TICKS 11000 /* the arm's 240 frames at 24 fps, with pre- and post-roll */

/* The test arm with a on node 3 and b on node 7 of a simulated CANopen bus
 * (can), or on the in-process twin (!can). */
static void prepare(struct play *p, struct pu_rig *r, struct pu_source *ps, struct play_opts *o,
		    bool can, unsigned inputs)
{
	char err[256];

	pu_arm_source(ps, 24, 1, 1000, 0, 240);
	pu_rig_init(r, ps, 1, inputs);
	pu_opts(o, ps);
	if (can) {
		static const struct rig_canopen_desc bus = {
			.interface = "sim", .bitrate = 1000000, .sync_id = 0x80, .heartbeat_ms = 20,
		};

		r->dev[0].driver = &rig_drv_canopen;
		r->dev[0].priv = &bus;
		r->out[0].axis = 3;
		r->out[1].axis = 7;
		o->rig.sim = false;
	}
	pu_alloc_hook_install();
	if (play_prepare(p, &r->d, &ps->s, o, err, sizeof(err)))
		fail_msg("play_prepare: %s", err);
}

static struct co_slave *drive(struct play *p, uint8_t node)
{
	return co_simbus_node(rig_canopen_simbus(&p->rig, "arm"), node);
}

/* play_run, with no allocation by the loop thread. */
static int run(struct play *p)
{
	uint64_t before = pu_loop_allocations();
	char why[512];
	int code = pu_play(p);

	play_describe(p, why, sizeof(why));
	printf("run ended %d: %s\n", code, why);
	assert_int_equal(pu_loop_allocations() - before, 0);
	return code;
}

/* When loop tick k will be due: the loop starts on the whole millisecond
 * after the start-up left the virtual clock. */
static int64_t due(struct play *p, int64_t k)
{
	return (hal_clock_now(&p->clk) + MS - 1) / MS * MS + k * MS;
}

static void test_targets(void **state)
{
	static int32_t can_a[TICKS], can_b[TICKS];
	static int64_t twin[2 * TICKS];
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play pc, pt;
	uint32_t n, i;
	double fe_can, fe_twin;

	prepare(&pc, &r, &ps, &o, true, 0);
	co_slave_trace(drive(&pc, 3), can_a, TICKS);
	co_slave_trace(drive(&pc, 7), can_b, TICKS);
	assert_int_equal(run(&pc), STRAND_EXIT_OK);
	n = co_slave_traced(drive(&pc, 3));
	assert_int_equal(co_slave_traced(drive(&pc, 7)), n);
	assert_int_equal(n, loop_result(pc.L)->ticks_run);
	fe_can = loop_result(pc.L)->ferr_worst;
	/* the drives were switched off and left pre-operational */
	assert_int_equal(co_slave_watch(drive(&pc, 3))->state, CO402_READY);
	assert_int_equal(co_slave_watch(drive(&pc, 7))->nmt, CO_NMT_PREOPERATIONAL);
	play_free(&pc);

	prepare(&pt, &r, &ps, &o, false, 0);
	sim_drive_trace(sim_drive_of(pt.rig.axes[0]), twin, TICKS);
	assert_int_equal(run(&pt), STRAND_EXIT_OK);
	assert_int_equal(sim_drive_traced(sim_drive_of(pt.rig.axes[0])), n);
	for (i = 0; i < n; i++) {
		if (can_a[i] != twin[2 * i] || can_b[i] != twin[2 * i + 1])
			fail_msg("tick %u: the bus carried %d, %d; the twin got %lld, %lld", i,
				 can_a[i], can_b[i], (long long)twin[2 * i],
				 (long long)twin[2 * i + 1]);
	}
	/* the same plant behind the bus, fed back one SYNC later: the same
	 * following errors */
	fe_twin = loop_result(pt.L)->ferr_worst;
	printf("worst following error: bus %.9g, twin %.9g\n", fe_can, fe_twin);
	assert_true(fe_can == fe_twin);
	assert_true(fe_can > 0);
	play_free(&pt);
}

static const char *what(const struct play *p)
{
	const char *w = loop_result(p->L)->rep.what;

	return w ? w : "";
}

/* Node 7 loses power at tick 3000: heartbeat lost within 2.5 heartbeats
 * (50 ms), the run stops (exit 7) naming node 7, and node 3 on the same bus
 * brakes on its quick stop ramp and switches off. */
static void test_heartbeat_lost(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	const struct co_slave_watch *w;
	uint32_t k;
	const struct loop_report *rep;

	prepare(&p, &r, &ps, &o, true, 0);
	co_slave_inject(drive(&p, 7), due(&p, 3000), 0);
	assert_int_equal(run(&p), STRAND_EXIT_FAULT);
	rep = &loop_result(p.L)->rep;
	assert_int_equal(rep->cause, LOOP_CAUSE_DEVICE);
	assert_string_equal(rep->device, "arm");
	assert_int_equal(rep->channel, 7);
	assert_int_equal(rep->out, 1);
	assert_string_equal(what(&p), "heartbeat lost");
	assert_true(rep->tick >= 3030 && rep->tick <= 3051);
	w = co_slave_watch(drive(&p, 3));
	for (k = 0; k < w->ntransitions; k++)
		if (w->log[k].from == CO402_ENABLED)
			break;
	assert_true(k < w->ntransitions);
	assert_int_equal(w->log[k].to, CO402_QUICK_STOP);
	assert_int_equal(w->log[k].cw, 0x02);
	assert_int_equal(w->state, CO402_DISABLED);
	assert_int_equal(w->nmt, CO_NMT_PREOPERATIONAL);
	play_free(&p);
}

/* An over-current on node 3 at tick 2000: reported with its class and code. */
static void test_emcy(void **state)
{
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	char why[512];
	const struct loop_report *rep;

	prepare(&p, &r, &ps, &o, true, 0);
	co_slave_inject(drive(&p, 3), due(&p, 2000), 0x2310);
	assert_int_equal(run(&p), STRAND_EXIT_FAULT);
	rep = &loop_result(p.L)->rep;
	assert_int_equal(rep->tick, 2000);
	assert_int_equal(rep->channel, 3);
	assert_int_equal(rep->detail, 0x2310);
	play_describe(&p, why, sizeof(why));
	assert_non_null(strstr(why, "device fault: device 'arm' channel 3 (a.angle): emergency "
				    "0x2310 (current, device output side) (Input/output error) "
				    "at tick 2000"));
	assert_int_equal(co_slave_watch(drive(&p, 7))->state, CO402_DISABLED);
	play_free(&p);
}

/* The e-stop at tick 3000: that tick's targets never reach a drive, both
 * get the quick stop with the SYNC of that tick. */
static void test_estop(void **state)
{
	static int32_t trace[TICKS];
	struct pu_source ps;
	struct pu_rig r;
	struct play_opts o;
	struct play p;
	const struct co_slave_watch *w;

	prepare(&p, &r, &ps, &o, true, PU_ESTOP);
	co_slave_trace(drive(&p, 3), trace, TICKS);
	assert_int_equal(sim_gpio_schedule(rig_sim_gpio(&p.rig, "io"), 0, due(&p, 3000), true), 0);
	assert_int_equal(run(&p), STRAND_EXIT_ESTOP);
	assert_int_equal(loop_result(p.L)->rep.tick, 3000);
	assert_int_equal(co_slave_traced(drive(&p, 3)), 3000);
	w = co_slave_watch(drive(&p, 7));
	assert_int_equal(w->state, CO402_DISABLED);
	assert_int_equal(w->log[w->ntransitions - 2].to, CO402_QUICK_STOP);
	play_free(&p);
}

/* A drive refuses part of its configuration: the start fails naming the
 * node, the object and the abort, and no drive is left enabled. */
static void test_start_refused(void **state)
{
	static const struct rig_canopen_desc bus = { .interface = "sim", .bitrate = 1000000 };
	struct pu_source ps;
	struct pu_rig r;
	struct rig rig;
	struct hal_clock clk;
	struct rig_opts ro = { 0 };
	char err[512];

	pu_arm_source(&ps, 24, 1, 1000, 0, 240);
	pu_rig_init(&r, &ps, 1, 0);
	r.dev[0].driver = &rig_drv_canopen;
	r.dev[0].priv = &bus;
	r.out[0].axis = 3;
	r.out[1].axis = 7;
	hal_clock_init(&clk, true);
	assert_int_equal(rig_build(&rig, &r.d, &ps.s, &clk, &ro, err, sizeof(err)), 0);
	co_slave_refuse(co_simbus_node(rig_canopen_simbus(&rig, "arm"), 7), 0x6060, 0, CO_ABORT_VALUE);
	assert_int_equal(rig_start(&rig, err, sizeof(err)), -EIO);
	assert_string_equal(err, "device 'arm': start: node 7: SDO write of 0x6060:00 aborted: "
				 "invalid value for parameter (0x06090030) (Input/output error)");
	assert_true(co_slave_watch(co_simbus_node(rig_canopen_simbus(&rig, "arm"), 3))->state < CO402_SWITCHED_ON);
	assert_int_equal(co_slave_watch(co_simbus_node(rig_canopen_simbus(&rig, "arm"), 3))->nmt,
			 CO_NMT_PREOPERATIONAL);
	rig_free(&rig);
}

/* The virtual clock, with a signal's cancel request at a moment of
 * virtual time: the start's waits advance the clock, so the request comes
 * while the start waits, at the same point on every run. */
static const struct hal_clock_ops *virt_ops;
static struct hal_cancel sig_cancel;
static int64_t sig_at;

static int64_t sig_now(struct hal_clock *c)
{
	return virt_ops->now(c);
}

static void sig_sleep_until(struct hal_clock *c, int64_t t)
{
	virt_ops->sleep_until(c, t);
	if (sig_at >= 0 && virt_ops->now(c) >= sig_at)
		hal_cancel_request(&sig_cancel);
}

static int64_t sig_wall(struct hal_clock *c)
{
	return virt_ops->wall(c);
}

static const struct hal_clock_ops sig_ops = {
	.now = sig_now, .sleep_until = sig_sleep_until, .wall = sig_wall,
};

/*
 * Node 7 is powered off: the start waits the boot-up timeout (2 s) for it,
 * while node 3 boots, is configured and enabled. A stop asked for at 500 ms
 * (what SIGTERM's handler does) ends the start within HAL_CANCEL_POLL_NS:
 * rig_start fails with -ECANCELED, node 3 has been shut down (no longer
 * enabled, pre-operational) through the ordinary stop, node 7 was never
 * enabled. Without the request the same start fails after the 2 s.
 */
static void test_start_cancelled(void **state)
{
	static const struct rig_canopen_desc bus = { .interface = "sim", .bitrate = 1000000 };
	struct pu_source ps;
	struct pu_rig r;
	struct rig rig;
	struct hal_clock clk;
	struct rig_opts ro = { .cancel = &sig_cancel };
	const struct co_slave_watch *w;
	char err[512];
	uint32_t k;
	int round;

	for (round = 0; round < 2; round++) {
		bool enabled = false;

		pu_arm_source(&ps, 24, 1, 1000, 0, 240);
		pu_rig_init(&r, &ps, 1, 0);
		r.dev[0].driver = &rig_drv_canopen;
		r.dev[0].priv = &bus;
		r.out[0].axis = 3;
		r.out[1].axis = 7;
		hal_clock_init(&clk, true);
		virt_ops = clk.ops;
		clk.ops = &sig_ops;
		hal_cancel_init(&sig_cancel);
		sig_at = round == 0 ? 500 * MS : -1;
		assert_int_equal(rig_build(&rig, &r.d, &ps.s, &clk, &ro, err, sizeof(err)), 0);
		co_slave_power_off(co_simbus_node(rig_canopen_simbus(&rig, "arm"), 7));
		if (round == 1) {
			/* the control: the start would have waited its 2 s */
			assert_int_equal(rig_start(&rig, err, sizeof(err)), -ETIMEDOUT);
			printf("without the request: %s at %.3f s\n", err, hal_clock_now(&clk) / 1e9);
			assert_true(hal_clock_now(&clk) >= 2000 * MS);
			rig_free(&rig);
			continue;
		}
		assert_int_equal(rig_start(&rig, err, sizeof(err)), -ECANCELED);
		printf("given up: %s at %.3f s\n", err, hal_clock_now(&clk) / 1e9);
		assert_string_equal(err, "device 'arm': start given up");
		/* seen within a poll of the request; the stop took a few SYNCs */
		assert_true(hal_clock_now(&clk) >= 500 * MS);
		assert_true(hal_clock_now(&clk) < 500 * MS + HAL_CANCEL_POLL_NS + 100 * MS);
		w = co_slave_watch(co_simbus_node(rig_canopen_simbus(&rig, "arm"), 3));
		for (k = 0; k < w->ntransitions && k < CO_SLAVE_LOG; k++)
			enabled |= w->log[k].to == CO402_ENABLED;
		assert_true(enabled); /* it got that far */
		assert_true(w->state < CO402_SWITCHED_ON);
		assert_int_equal(w->nmt, CO_NMT_PREOPERATIONAL);
		/* node 7 went no further than its power-on's switch on disabled */
		w = co_slave_watch(co_simbus_node(rig_canopen_simbus(&rig, "arm"), 7));
		for (k = 0; k < w->ntransitions && k < CO_SLAVE_LOG; k++)
			assert_true(w->log[k].to < CO402_READY);
		assert_int_equal(w->state, CO402_DISABLED);
		rig_free(&rig);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_targets),
		cmocka_unit_test(test_heartbeat_lost),
		cmocka_unit_test(test_emcy),
		cmocka_unit_test(test_estop),
		cmocka_unit_test(test_start_refused),
		cmocka_unit_test(test_start_cancelled),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
