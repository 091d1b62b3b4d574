/* SPDX-License-Identifier: MIT */
/*
 * co_slave.c - the simulated CiA 402 drive: NMT, PDOs, the state machine,
 * the plant, heartbeat and emergencies (see co_slave.h).
 */
#include "co_slave_priv.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/canopen/co_emcy.h"
#include "hal/rt.h"

#define NS_PER_S 1000000000LL

void STRAND_RT co_slave_send(struct co_slave *s, const struct co_frame *f)
{
	if (s->powered)
		s->cfg.send(s->cfg.ctx, f, 1);
}

static int32_t STRAND_RT clamp32(double v)
{
	if (v >= INT32_MAX)
		return INT32_MAX;
	if (v <= INT32_MIN)
		return INT32_MIN;
	return (int32_t)lround(v);
}

/* The watch is kept current after everything that comes in from outside,
 * so that a pointer to it stays a live view. */
static void STRAND_RT watch(struct co_slave *s)
{
	struct co_slave_watch *w = &s->w;

	w->state = s->state;
	w->mode = s->mode;
	w->heartbeat_ms = s->heartbeat_ms;
	w->error_code = s->error_code;
	w->actual = s->actual_pos;
	w->sw = s->sw;
}

/* ---- the plant ---- */

/* The tick rate of the interpolation period 0x60C2. */
static uint32_t STRAND_RT period_hz(const struct co_slave *s)
{
	double period = s->ip_value * pow(10, s->ip_exp);

	return period > 0 ? (uint32_t)lround(1 / period) : 0;
}

static struct hal_axis STRAND_RT *plant_axis(struct co_slave *s)
{
	return sim_drive_axis(s->plant);
}

/*
 * Make the plant (again) for a new period or mode. Both are set by SDO
 * (0x60C2, 0x6060), which the master writes while it configures the drives
 * at start, before the loop; a drive commanded back to operation enabled
 * in the loop finds its plant made. So this is [init] code reached from
 * the rt path below: the one reference mk/check-rt.list takes on trust
 * (a "ref" line), and sim_drive_new's STRAND_ASSERT_NOT_RT proves it in
 * the debug build. noinline: were it inlined into its caller, its calls
 * would be the rt section's.
 */
static __attribute__((noinline)) bool plant_make(struct co_slave *s, uint32_t hz, bool vel)
{
	struct sim_drive_channel ch = s->cfg.model;

	if (s->plant)
		hal_axis_close(plant_axis(s));
	ch.initial = s->actual_pos;
	ch.velocity_mode = vel;
	s->plant = NULL;
	if (!hz || sim_drive_new(&s->plant, s->cfg.name, 1, hz, &ch, NULL, 0))
		return false;
	s->plant_hz = hz;
	s->plant_vel = vel;
	s->plant_tick = 0;
	return true;
}

/* Power the plant; made (again) when the period or the mode changed. */
static bool STRAND_RT plant_on(struct co_slave *s)
{
	uint32_t hz = period_hz(s);
	bool vel = s->mode == CO402_MODE_CSV;

	if ((!s->plant || hz != s->plant_hz || vel != s->plant_vel) && !plant_make(s, hz, vel))
		return false;
	/* the table's start, not hal_axis_start(): that wrapper is [init]
	 * and untagged, the simulated drive's start is rt (sd_start) */
	plant_axis(s)->ops->start(plant_axis(s));
	s->prev_target = s->actual_pos;
	return true;
}

static void STRAND_RT plant_off(struct co_slave *s)
{
	if (s->plant)
		hal_axis_disable(plant_axis(s));
	s->actual_vel = 0;
}

/* One period of the plant towards (pos, vel). */
static void STRAND_RT plant_step(struct co_slave *s, int64_t pos, double vel)
{
	struct hal_axis *ax = plant_axis(s);
	struct hal_setpoint sp = { .pos = pos, .vel = (int64_t)llround(vel) };
	int64_t actual;

	hal_axis_set(ax, 0, &sp);
	hal_axis_commit(ax, s->plant_tick);
	s->plant_tick++;
	hal_axis_input(ax, s->plant_tick);
	hal_axis_actual(ax, 0, &actual);
	s->actual_pos = clamp32((double)actual);
	s->actual_vel = clamp32(sim_drive_watch(s->plant, 0)->v);
}

/* ---- the 402 state machine ---- */

static void STRAND_RT update_sw(struct co_slave *s)
{
	enum co402_state st = (enum co402_state)s->state;
	uint16_t sw = co402_state_bits(st) | CO402_SW_REMOTE;

	if (st >= CO402_READY && st <= CO402_QUICK_STOP)
		sw |= CO402_SW_VOLTAGE_ENABLED;
	if (st == CO402_ENABLED)
		sw |= CO402_SW_FOLLOWS_TARGET;
	s->sw = sw;
	s->w.sw = sw;
}

static void STRAND_RT emcy(struct co_slave *s, uint16_t code)
{
	struct co_frame f;

	co_emcy_frame(&f, s->cfg.node, code, s->error_register);
	co_slave_send(s, &f);
	s->w.emcys++;
}

static void STRAND_RT enter(struct co_slave *s, enum co402_state to, uint16_t cw, int64_t now)
{
	enum co402_state from = (enum co402_state)s->state;

	if (to == from)
		return;
	if (s->w.ntransitions < CO_SLAVE_LOG) {
		struct co_slave_transition *t = &s->w.log[s->w.ntransitions];

		t->from = (uint8_t)from;
		t->to = (uint8_t)to;
		t->cw = cw;
	}
	s->w.ntransitions++;
	s->state = (uint8_t)to;
	switch (to) {
	case CO402_ENABLED:
		if (from != CO402_QUICK_STOP && !plant_on(s)) {
			co_slave_fault(s, 0x6100, now); /* internal software */
			return;
		}
		break;
	case CO402_QUICK_STOP:
		s->qs_t0 = now;
		s->qs_next = now;
		s->qs_x0 = s->actual_pos;
		s->qs_v0 = s->plant ? sim_drive_watch(s->plant, 0)->v : 0;
		break;
	default:
		if (from == CO402_ENABLED || from == CO402_QUICK_STOP ||
		    to == CO402_FAULT_REACTION)
			plant_off(s);
		break;
	}
	if (from == CO402_FAULT && to == CO402_DISABLED) {
		/* fault reset: the errors are gone, and the bus is told */
		s->error_code = 0;
		s->error_register = 0;
		emcy(s, CO_EMCY_RESET);
	}
	update_sw(s);
}

void STRAND_RT co_slave_controlword(struct co_slave *s, int64_t now)
{
	uint16_t prev = s->w.cw;
	bool stays = s->qs_option >= 5 && s->qs_option <= 8;

	s->w.cw = s->cw;
	if (s->stuck)
		return;
	enter(s, co402_next((enum co402_state)s->state, s->cw, prev, stays), s->cw, now);
}

void STRAND_RT co_slave_fault(struct co_slave *s, uint16_t code, int64_t now)
{
	if (!s->powered)
		return;
	s->error_code = code;
	/* CiA 301: the generic bit is set whenever any error is */
	s->error_register |= 0x01 | co_emcy_register_bit(code);
	emcy(s, code);
	enter(s, CO402_FAULT_REACTION, 0, now);
	/* the reaction of a simulated drive: power stage off, done */
	enter(s, CO402_FAULT, 0, now);
	watch(s);
}

/* The quick stop ramp on the drive's own clock: brake at qs_dec from where
 * it was, one period at a time, then switch off (option codes 1-4). */
static void STRAND_RT quick_stop(struct co_slave *s, int64_t now)
{
	int64_t period = NS_PER_S / s->plant_hz;
	double v0 = s->qs_v0, dec = s->qs_dec, sgn = v0 < 0 ? -1 : 1;
	double stop_t = dec > 0 ? fabs(v0) / dec : 0;
	unsigned guard = 100000;

	while (now >= s->qs_next && guard--) {
		double t = (double)(s->qs_next + period - s->qs_t0) / NS_PER_S, v, x;
		bool done = t >= stop_t;

		if (done) {
			v = 0;
			x = s->qs_x0 + v0 * stop_t / 2;
		} else {
			v = v0 - sgn * dec * t;
			x = s->qs_x0 + v0 * t - sgn * dec * t * t / 2;
		}
		if (s->plant_vel)
			plant_step(s, 0, v);
		else
			plant_step(s, (int64_t)llround(x), v);
		s->qs_next += period;
		if (done) {
			if (s->qs_option >= 0 && s->qs_option <= 4)
				enter(s, CO402_DISABLED, 0, now);
			return;
		}
	}
}

/* ---- PDOs and SYNC ---- */

static unsigned STRAND_RT mapped_bytes(const struct co_pdo *p)
{
	unsigned i, n = 0;

	for (i = 0; i < p->count; i++)
		n += (p->map[i] & 0xff) / 8;
	return n;
}

static void STRAND_RT unpack(struct co_slave *s, const struct co_pdo *p, const uint8_t *data)
{
	unsigned i, off = 0;

	for (i = 0; i < p->count; i++) {
		unsigned n = (p->map[i] & 0xff) / 8;

		co_slave_map_set(s, p->map[i], co_get(data + off, n));
		off += n;
	}
}

static void STRAND_RT send_tpdo(struct co_slave *s, const struct co_pdo *p)
{
	struct co_frame f;
	unsigned i, off = 0;
	uint32_t v;

	co_frame_init(&f, (uint16_t)(p->cobid & 0x7ff), (uint8_t)mapped_bytes(p));
	for (i = 0; i < p->count; i++) {
		unsigned n = (p->map[i] & 0xff) / 8;

		if (co_slave_map_get(s, p->map[i], &v))
			co_put(f.data + off, v, n);
		off += n;
	}
	co_slave_send(s, &f);
	s->w.tpdos++;
}

static void STRAND_RT rpdo(struct co_slave *s, unsigned k, const struct co_frame *f, int64_t now)
{
	struct co_pdo *p = &s->rpdo[k];

	if (f->len < mapped_bytes(p)) {
		emcy(s, 0x8210); /* PDO not processed due to length error */
		return;
	}
	if (k == 0 && p->type <= 240) {
		/* synchronous: it takes effect at the next SYNC */
		memcpy(s->rpdo_data, f->data, f->len);
		s->rpdo_len = f->len;
		s->rpdo_pending = true;
		return;
	}
	unpack(s, p, f->data);
	s->w.rpdos++;
	co_slave_controlword(s, now);
}

static void STRAND_RT sync(struct co_slave *s, int64_t now)
{
	unsigned k;

	s->w.syncs++;
	if (s->rpdo_pending) {
		s->rpdo_pending = false;
		unpack(s, &s->rpdo[0], s->rpdo_data);
		s->w.rpdos++;
		co_slave_controlword(s, now);
	}
	if (s->state == CO402_ENABLED) {
		if (s->plant_vel) {
			plant_step(s, 0, s->target_vel);
			s->w.target = s->target_vel;
		} else {
			plant_step(s, s->target_pos,
				   ((double)s->target_pos - s->prev_target) * s->plant_hz);
			s->prev_target = s->target_pos;
			s->w.target = s->target_pos;
		}
		if (s->trace && s->traced < s->trace_cap)
			s->trace[s->traced++] = s->w.target;
	}
	update_sw(s);
	for (k = 0; k < 4; k++) {
		struct co_pdo *p = &s->tpdo[k];

		if ((p->cobid & CO_PDO_COBID_OFF) || p->type < 1 || p->type > 240)
			continue;
		if (++p->syncs >= p->type) {
			p->syncs = 0;
			send_tpdo(s, p);
		}
	}
}

/* ---- NMT ---- */

static void STRAND_RT boot_up(struct co_slave *s, int64_t now)
{
	struct co_frame f;

	s->w.nmt = CO_NMT_BOOTUP;
	co_frame_init(&f, (uint16_t)(CO_ID_HEARTBEAT + s->cfg.node), 1);
	f.data[0] = CO_NMT_BOOTUP;
	co_slave_send(s, &f);
	s->w.nmt = CO_NMT_PREOPERATIONAL;
	co_slave_heartbeat_changed(s, now);
}

static void STRAND_RT set_nmt(struct co_slave *s, enum co_nmt_state to, int64_t now)
{
	/* the connection to the master is gone: brake (0x6007 quick stop) */
	if (s->w.nmt == CO_NMT_OPERATIONAL && to != CO_NMT_OPERATIONAL &&
	    s->state == CO402_ENABLED)
		enter(s, CO402_QUICK_STOP, 0, now);
	if (to != CO_NMT_OPERATIONAL)
		s->rpdo_pending = false;
	s->w.nmt = (uint8_t)to;
}

static void STRAND_RT nmt(struct co_slave *s, uint8_t cmd, int64_t now)
{
	switch (cmd) {
	case CO_NMT_START:
		set_nmt(s, CO_NMT_OPERATIONAL, now);
		break;
	case CO_NMT_STOP:
		set_nmt(s, CO_NMT_STOPPED, now);
		break;
	case CO_NMT_PREOP:
		set_nmt(s, CO_NMT_PREOPERATIONAL, now);
		break;
	case CO_NMT_RESET_NODE:
		set_nmt(s, CO_NMT_PREOPERATIONAL, now);
		plant_off(s);
		co_slave_od_defaults(s, true);
		enter(s, CO402_NOT_READY, 0, now);
		enter(s, CO402_DISABLED, 0, now);
		boot_up(s, now);
		break;
	case CO_NMT_RESET_COMM:
		set_nmt(s, CO_NMT_PREOPERATIONAL, now);
		co_slave_od_defaults(s, false);
		boot_up(s, now);
		break;
	}
}

void STRAND_RT co_slave_heartbeat_changed(struct co_slave *s, int64_t now)
{
	s->next_hb = s->heartbeat_ms ? now + s->heartbeat_ms * 1000000LL : INT64_MAX;
}

/* ---- the interface ---- */

int co_slave_new(struct co_slave **out, const struct co_slave_cfg *cfg, char *err,
		 size_t errsize)
{
	const struct sim_drive_channel *m = &cfg->model;
	struct co_slave *s;
	int rc = -EINVAL;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (cfg->node < 1 || cfg->node > CO_NODE_MAX || !cfg->send || !(m->bandwidth_hz > 0) ||
	    !(m->damping > 0) || m->feedforward < 0 || m->feedforward > 1)
		goto fail;
	rc = -ENOMEM;
	s = calloc(1, sizeof(*s));
	if (!s)
		goto fail;
	s->cfg = *cfg;
	s->actual_pos = cfg->initial;
	co_slave_od_defaults(s, true);
	s->state = CO402_NOT_READY;
	s->next_hb = INT64_MAX;
	s->inject_at = INT64_MAX;
	update_sw(s);
	*out = s;
	return 0;
fail:
	snprintf(err, errsize, "device '%s': simulated drive %u: %s", cfg->name ? cfg->name : "",
		 cfg->node, strerror(-rc));
	return rc;
}

void co_slave_free(struct co_slave *s)
{
	STRAND_ASSERT_NOT_RT();
	if (!s)
		return;
	if (s->plant)
		hal_axis_close(plant_axis(s));
	free(s);
}

void co_slave_power_on(struct co_slave *s, int64_t now)
{
	STRAND_ASSERT_NOT_RT();
	s->powered = true;
	co_slave_od_defaults(s, true);
	s->error_code = 0;
	s->error_register = 0;
	s->state = CO402_NOT_READY;
	enter(s, CO402_DISABLED, 0, now); /* 1: self-test passed */
	boot_up(s, now);
	watch(s);
}

void STRAND_RT co_slave_power_off(struct co_slave *s)
{
	plant_off(s);
	s->powered = false;
	watch(s);
}

bool co_slave_powered(const struct co_slave *s)
{
	return s->powered;
}

static void STRAND_RT rx(struct co_slave *s, const struct co_frame *f, int64_t now)
{
	unsigned k;

	if (f->id == CO_ID_NMT) {
		if (f->len >= 2 && (f->data[1] == 0 || f->data[1] == s->cfg.node))
			nmt(s, f->data[0], now);
		return;
	}
	if (f->id == CO_ID_SDO_RX + s->cfg.node) {
		if (s->w.nmt != CO_NMT_STOPPED)
			co_slave_sdo(s, f, now);
		return;
	}
	if (s->w.nmt != CO_NMT_OPERATIONAL)
		return;
	if (f->id == (s->sync_id & 0x7ff)) {
		sync(s, now);
		return;
	}
	for (k = 0; k < 4; k++)
		if (!(s->rpdo[k].cobid & CO_PDO_COBID_OFF) && f->id == (s->rpdo[k].cobid & 0x7ff))
			rpdo(s, k, f, now);
}

void STRAND_RT co_slave_rx(struct co_slave *s, const struct co_frame *f, int64_t now)
{
	if (!s->powered)
		return;
	rx(s, f, now);
	watch(s);
}

int64_t STRAND_RT co_slave_poll(struct co_slave *s, int64_t now)
{
	int64_t next;

	if (!s->powered)
		return INT64_MAX;
	if (now >= s->inject_at) {
		s->inject_at = INT64_MAX;
		if (!s->inject_code) {
			co_slave_power_off(s);
			return INT64_MAX;
		}
		co_slave_fault(s, s->inject_code, now);
	}
	if (now >= s->next_hb) {
		struct co_frame f;
		int64_t period = s->heartbeat_ms * 1000000LL;

		co_frame_init(&f, (uint16_t)(CO_ID_HEARTBEAT + s->cfg.node), 1);
		f.data[0] = s->w.nmt;
		co_slave_send(s, &f);
		s->w.heartbeats++;
		s->next_hb = s->next_hb + period > now ? s->next_hb + period : now + period;
	}
	if (s->state == CO402_QUICK_STOP && s->plant)
		quick_stop(s, now);
	watch(s);
	next = s->next_hb < s->inject_at ? s->next_hb : s->inject_at;
	if (s->state == CO402_QUICK_STOP && s->plant && s->qs_next < next)
		next = s->qs_next;
	return next;
}

void co_slave_inject(struct co_slave *s, int64_t at_ns, uint16_t code)
{
	s->inject_at = at_ns;
	s->inject_code = code;
}

void co_slave_refuse(struct co_slave *s, uint16_t index, uint8_t sub, uint32_t abort)
{
	s->refuse_index = index;
	s->refuse_sub = sub;
	s->refuse_abort = abort;
}

void co_slave_sdo_deaf(struct co_slave *s, bool deaf)
{
	s->deaf = deaf;
}

void co_slave_stuck(struct co_slave *s, bool stuck)
{
	s->stuck = stuck;
}

void co_slave_trace(struct co_slave *s, int32_t *buf, uint32_t cap)
{
	s->trace = buf;
	s->trace_cap = cap;
	s->traced = 0;
}

uint32_t co_slave_traced(const struct co_slave *s)
{
	return s->traced;
}

const struct co_slave_watch *co_slave_watch(const struct co_slave *s)
{
	return &s->w;
}

uint8_t co_slave_node(const struct co_slave *s)
{
	return s->cfg.node;
}

uint16_t co_slave_sync_id(const struct co_slave *s)
{
	return (uint16_t)(s->sync_id & 0x7ff);
}
