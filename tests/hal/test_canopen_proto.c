/* SPDX-License-Identifier: MIT */
/*
 * test_canopen_proto.c - the CANopen protocol pieces on their own: the SDO
 * client against the simulated drive's server (expedited and segmented,
 * both ways; aborts by name; toggle errors; timeouts), the CiA 402 state
 * table, emergency classes, the interpolation period, bus load.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <errno.h>
#include <string.h>

#include "hal/canopen/co_402.h"
#include "hal/canopen/co_emcy.h"
#include "hal/canopen/co_load.h"
#include "hal/canopen/co_master.h"
#include "hal/canopen/co_sdo.h"
#include "hal/canopen/co_socketcan.h"
#include "sim/co_slave.h"

#include <linux/can.h>
#include <linux/can/error.h>

/* ---- an SDO client talking to one simulated drive ---- */

#define QMAX 64

struct pipe {
	struct co_slave *s;
	struct co_frame q[QMAX]; /* what the drive sent, not yet taken */
	unsigned nq;
	unsigned requests;       /* frames the client sent */
	struct co_frame last_req;
};

static int drive_send(void *ctx, const struct co_frame *f, uint32_t n)
{
	struct pipe *p = ctx;

	assert_true(p->nq + n <= QMAX);
	memcpy(&p->q[p->nq], f, n * sizeof(*f));
	p->nq += n;
	return 0;
}

static void pipe_init(struct pipe *p, const char *name)
{
	struct co_slave_cfg c = {
		.node = 5, .name = name, .send = drive_send, .ctx = p,
		.model = { .bandwidth_hz = 40, .damping = 1, .feedforward = 0.9 },
	};

	memset(p, 0, sizeof(*p));
	assert_int_equal(co_slave_new(&p->s, &c, NULL, 0), 0);
	co_slave_power_on(p->s, 0);
	p->nq = 0; /* its boot-up message */
}

/* Deliver the client's request and every answer, to the end. */
static void pump(struct pipe *p, struct co_sdo *c, struct co_frame req)
{
	for (;;) {
		struct co_frame out;
		bool more = false;
		unsigned i, n;

		p->requests++;
		p->last_req = req;
		co_slave_rx(p->s, &req, 0);
		n = p->nq;
		p->nq = 0;
		for (i = 0; i < n; i++)
			if (co_sdo_rx(c, &p->q[i], 0, &out)) {
				req = out;
				more = true;
			}
		if (!more)
			return;
	}
}

static void test_sdo_expedited(void **state)
{
	struct pipe p;
	struct co_sdo c;
	struct co_frame f;
	uint8_t v[4] = { 0xf4, 0x01 }, got[4];

	pipe_init(&p, "x");
	co_sdo_init(&c, 5, 1000);
	co_sdo_download(&c, 0x1017, 0, v, 2, 0, &f);
	assert_int_equal(f.id, 0x605);
	assert_int_equal(f.data[0], 0x2b); /* expedited, size indicated, 2 bytes */
	pump(&p, &c, f);
	assert_int_equal(c.state, CO_SDO_DONE);
	assert_int_equal(co_slave_watch(p.s)->heartbeat_ms, 500);
	co_sdo_upload(&c, 0x1017, 0, got, sizeof(got), 0, &f);
	pump(&p, &c, f);
	assert_int_equal(c.state, CO_SDO_DONE);
	assert_int_equal(c.pos, 2);
	assert_int_equal(co_get16(got), 500);
	assert_int_equal(p.requests, 2); /* one frame each way per transfer */
	co_slave_free(p.s);
}

static void test_sdo_segmented(void **state)
{
	static const char note[] = "a note longer than seven bytes, in nine segments, about 60";
	struct pipe p;
	struct co_sdo c;
	struct co_frame f;
	char got[80];

	pipe_init(&p, "strand-simdrive");
	co_sdo_init(&c, 5, 1000);
	/* 0x1008, a string: segmented even though short */
	co_sdo_upload(&c, 0x1008, 0, got, sizeof(got), 0, &f);
	pump(&p, &c, f);
	assert_int_equal(c.state, CO_SDO_DONE);
	assert_int_equal(c.pos, strlen("strand-simdrive"));
	assert_memory_equal(got, "strand-simdrive", c.pos);
	assert_int_equal(p.requests, 1 + 3); /* initiate, then 15 bytes in 3 segments */
	/* a download of 58 bytes: initiate and 9 segments, toggling */
	p.requests = 0;
	co_sdo_download(&c, 0x2001, 0, note, sizeof(note) - 1, 0, &f);
	assert_int_equal(f.data[0], 0x21); /* segmented, size indicated */
	assert_int_equal(co_get32(&f.data[4]), sizeof(note) - 1);
	pump(&p, &c, f);
	assert_int_equal(c.state, CO_SDO_DONE);
	assert_int_equal(p.requests, 1 + 9);
	assert_int_equal(p.last_req.data[0] & 0x01, 1);    /* the last segment says so */
	assert_int_equal(p.last_req.data[0] & 0x10, 0);    /* ninth segment: toggle 0 */
	assert_int_equal((p.last_req.data[0] >> 1) & 7, 5); /* 58 = 8 x 7 + 2: 5 empty */
	memset(got, 0, sizeof(got));
	co_sdo_upload(&c, 0x2001, 0, got, sizeof(got), 0, &f);
	pump(&p, &c, f);
	assert_int_equal(c.state, CO_SDO_DONE);
	assert_int_equal(c.pos, sizeof(note) - 1);
	assert_string_equal(got, note);
	/* more than the room given: the client aborts, out of memory */
	co_sdo_upload(&c, 0x2001, 0, got, 20, 0, &f);
	pump(&p, &c, f);
	assert_int_equal(c.state, CO_SDO_ABORTED);
	assert_int_equal(c.abort, CO_ABORT_NO_MEMORY);
	assert_true(c.abort_sent);
	assert_int_equal(p.last_req.data[0], 0x80);
	co_slave_free(p.s);
}

static void expect_abort(struct pipe *p, uint16_t index, uint8_t sub, bool read, uint32_t value,
			 uint8_t size, uint32_t abort, const char *name)
{
	struct co_sdo c;
	struct co_frame f;
	uint8_t buf[8];

	co_sdo_init(&c, 5, 1000);
	co_put(buf, value, 4);
	if (read)
		co_sdo_upload(&c, index, sub, buf, sizeof(buf), 0, &f);
	else
		co_sdo_download(&c, index, sub, buf, size, 0, &f);
	pump(p, &c, f);
	assert_int_equal(c.state, CO_SDO_ABORTED);
	assert_false(c.abort_sent); /* the drive's */
	if (c.abort != abort)
		fail_msg("0x%04x:%u: abort 0x%08x (%s), want 0x%08x", index, sub, c.abort,
			 co_abort_name(c.abort), abort);
	assert_string_equal(co_abort_name(c.abort), name);
}

static void sdo_write(struct pipe *p, uint16_t index, uint8_t sub, uint32_t value, uint8_t size)
{
	struct co_sdo c;
	struct co_frame f;
	uint8_t buf[4];

	co_sdo_init(&c, 5, 1000);
	co_put(buf, value, 4);
	co_sdo_download(&c, index, sub, buf, size, 0, &f);
	pump(p, &c, f);
	assert_int_equal(c.state, CO_SDO_DONE);
}

static void test_sdo_aborts(void **state)
{
	struct pipe p;

	pipe_init(&p, "x");
	expect_abort(&p, 0x6543, 0, true, 0, 0, CO_ABORT_NO_OBJECT,
		     "object does not exist in the object dictionary");
	expect_abort(&p, 0x60c2, 7, true, 0, 0, CO_ABORT_NO_SUB, "sub-index does not exist");
	expect_abort(&p, 0x6041, 0, false, 1, 2, CO_ABORT_READ_ONLY,
		     "attempt to write a read-only object");
	expect_abort(&p, 0x2000, 0, true, 0, 0, CO_ABORT_WRITE_ONLY,
		     "attempt to read a write-only object");
	expect_abort(&p, 0x1017, 0, false, 1, 4, CO_ABORT_TYPE_LEN_HIGH,
		     "data type does not match, length too high");
	expect_abort(&p, 0x6060, 0, false, 3, 1, CO_ABORT_VALUE, "invalid value for parameter");
	/* a mapping entry of an object that cannot be mapped */
	expect_abort(&p, 0x1600, 1, false, 0x60850020, 4, CO_ABORT_NO_MAP,
		     "object cannot be mapped to the PDO");
	/* a mapping changed while its PDO is on: switch RPDO1 on first */
	sdo_write(&p, 0x1400, 1, 0x205, 4);
	expect_abort(&p, 0x1600, 0, false, 0, 1, CO_ABORT_DATA_STATE,
		     "data cannot be transferred or stored because of the present device state");
	/* what a test makes the drive refuse */
	co_slave_refuse(p.s, 0x60c2, 1, CO_ABORT_VALUE_HIGH);
	expect_abort(&p, 0x60c2, 1, false, 1, 1, CO_ABORT_VALUE_HIGH,
		     "value of parameter written too high");
	assert_string_equal(co_abort_name(0x12345678), "unknown abort code");
	co_slave_free(p.s);
}

/* A segment with the wrong toggle bit: the drive aborts, and a client that
 * receives one aborts too. */
static void test_sdo_toggle(void **state)
{
	struct pipe p;
	struct co_sdo c;
	struct co_frame f, seg;
	char got[40];

	pipe_init(&p, "a name of twenty bytes");
	/* the server's side: a first upload segment request with toggle 1 */
	co_frame_init(&f, 0x605, 8);
	f.data[0] = 0x40;
	co_put16(&f.data[1], 0x1008);
	co_slave_rx(p.s, &f, 0);
	assert_int_equal(p.nq, 1);
	assert_int_equal(p.q[0].data[0], 0x41);
	p.nq = 0;
	co_frame_init(&f, 0x605, 8);
	f.data[0] = 0x70;
	co_slave_rx(p.s, &f, 0);
	assert_int_equal(p.nq, 1);
	assert_int_equal(p.q[0].data[0], 0x80);
	assert_int_equal(co_get32(&p.q[0].data[4]), CO_ABORT_TOGGLE);
	p.nq = 0;
	/* the client's side: a segment answering with the wrong toggle */
	co_sdo_init(&c, 5, 1000);
	co_sdo_upload(&c, 0x1008, 0, got, sizeof(got), 0, &f);
	co_slave_rx(p.s, &f, 0);
	assert_int_equal(p.nq, 1);
	assert_true(co_sdo_rx(&c, &p.q[0], 0, &f));  /* asks for segment 0 */
	co_frame_init(&seg, 0x585, 8);
	seg.data[0] = 0x10; /* toggle 1, 7 bytes, more to come */
	assert_true(co_sdo_rx(&c, &seg, 0, &f));
	assert_int_equal(c.state, CO_SDO_ABORTED);
	assert_int_equal(c.abort, CO_ABORT_TOGGLE);
	assert_int_equal(f.data[0], 0x80);
	co_slave_free(p.s);
}

/* No answer: the client gives up at its deadline with an abort frame; a
 * late answer is then ignored. */
static void test_sdo_timeout(void **state)
{
	struct pipe p;
	struct co_sdo c;
	struct co_frame f;
	uint8_t got[4];

	pipe_init(&p, "x");
	co_slave_sdo_deaf(p.s, true);
	co_sdo_init(&c, 5, 100);
	co_sdo_upload(&c, 0x6064, 0, got, 4, 1000, &f);
	co_slave_rx(p.s, &f, 1000);
	assert_int_equal(p.nq, 0);
	assert_false(co_sdo_poll(&c, 1099, &f));
	assert_int_equal(c.state, CO_SDO_BUSY);
	assert_true(co_sdo_poll(&c, 1100, &f));
	assert_int_equal(c.state, CO_SDO_ABORTED);
	assert_int_equal(c.abort, CO_ABORT_TIMEOUT);
	assert_int_equal(f.id, 0x605);
	assert_int_equal(co_get32(&f.data[4]), CO_ABORT_TIMEOUT);
	assert_string_equal(co_abort_name(c.abort), "SDO protocol timed out");
	co_slave_free(p.s);
}

/* ---- CiA 402 ---- */

enum cmd { SHUTDOWN, SWITCH_ON, ENABLE, DISABLE_VOLTAGE, QUICK_STOP, NCMD };

static const uint16_t cmd_cw[NCMD] = { 0x06, 0x07, 0x0f, 0x00, 0x02 };

/* CiA 402-2's transitions, written out once more by hand: next[state][cmd]. */
static void test_402_table(void **state)
{
	const enum co402_state NR = CO402_NOT_READY, SD = CO402_DISABLED, RS = CO402_READY,
			       SO = CO402_SWITCHED_ON, OE = CO402_ENABLED, QS = CO402_QUICK_STOP,
			       FR = CO402_FAULT_REACTION, FA = CO402_FAULT;
	const uint8_t next[8][NCMD] = {
		/*        shutdown  switch on  enable  disable volt.  quick stop */
		[NR] = { NR, NR, NR, NR, NR },
		[SD] = { RS, SD, SD, SD, SD },            /* 2 */
		[RS] = { RS, SO, SO, SD, SD },            /* 3, 7 */
		[SO] = { RS, SO, OE, SD, SD },            /* 6, 4, 10 */
		[OE] = { RS, SO, OE, SD, QS },            /* 8, 5, 9, 11 */
		[QS] = { QS, QS, QS, SD, QS },            /* 12 */
		[FR] = { FR, FR, FR, FR, FR },
		[FA] = { FA, FA, FA, FA, FA },
	};
	unsigned s, c;

	for (s = 0; s < 8; s++) {
		/* the statusword of a state decodes to it, with any other bits */
		assert_int_equal(co402_decode(co402_state_bits(s)), s);
		assert_int_equal(co402_decode(co402_state_bits(s) | 0xff90 |
					      (s == SD || s == FR || s == FA ? 0x20 : 0)), s);
		for (c = 0; c < NCMD; c++) {
			enum co402_state got = co402_next(s, cmd_cw[c], 0, false);

			if (got != next[s][c])
				fail_msg("%s + controlword 0x%02x: %s, want %s", co402_state_name(s),
					 cmd_cw[c], co402_state_name(got),
					 co402_state_name(next[s][c]));
		}
	}
	/* 15: fault reset on the rising edge of bit 7 only */
	assert_int_equal(co402_next(FA, 0x80, 0x00, false), SD);
	assert_int_equal(co402_next(FA, 0x80, 0x80, false), FA);
	/* 16: enable operation leaves quick stop with option codes 5..8 */
	assert_int_equal(co402_next(QS, 0x0f, 0, true), OE);
	/* bit 7 held high hides every other command */
	assert_int_equal(co402_next(SD, 0x86, 0x80, false), SD);
}

/* The master's command from any state reaches "operation enabled" on the
 * drive's table within four steps (fault: reset edge, then three). */
static void test_402_toward_enabled(void **state)
{
	unsigned s0;

	for (s0 = CO402_DISABLED; s0 <= CO402_FAULT; s0++) {
		enum co402_state s = s0;
		uint16_t cw = 0x80; /* a reset edge must first go low */
		int steps = 0;

		if (s == CO402_FAULT_REACTION)
			continue; /* the drive's own doing, it ends in fault */
		while (s != CO402_ENABLED && steps < 8) {
			uint16_t next = co402_toward_enabled(s, cw);

			s = co402_next(s, next, cw, false);
			cw = next;
			steps++;
		}
		assert_int_equal(s, CO402_ENABLED);
		assert_true(steps <= 5);
	}
}

/* Controlword cw written by SDO at time t: the drive's state after it. */
static enum co402_state cw_at(struct pipe *p, uint16_t cw, int64_t t)
{
	struct co_sdo c;
	struct co_frame f;
	uint8_t v[2];

	unsigned i;

	co_put16(v, cw);
	co_sdo_init(&c, 5, 1000);
	co_sdo_download(&c, 0x6040, 0, v, 2, t, &f);
	p->nq = 0;
	co_slave_rx(p->s, &f, t);
	for (i = 0; i < p->nq; i++)
		assert_false(co_sdo_rx(&c, &p->q[i], t, &f));
	assert_int_equal(c.state, CO_SDO_DONE);
	return co402_decode(co_slave_watch(p->s)->sw);
}

/* Every transition of CiA 402-2 on the simulated drive, each read back from
 * its statusword; the drive's own ones (12 at the end of a quick stop, 13
 * and 14 on a fault) with their effects: an emergency each way. */
static void test_402_drive(void **state)
{
	struct pipe p;
	const struct co_slave_watch *w;
	int64_t t = 0;

	pipe_init(&p, "x");
	w = co_slave_watch(p.s);
	assert_int_equal(w->log[0].from, CO402_NOT_READY); /* 1, at power-on */
	assert_int_equal(w->log[0].to, CO402_DISABLED);
	assert_int_equal(co402_decode(w->sw), CO402_DISABLED);
	assert_int_equal(w->sw & 0x0200, 0x0200); /* remote */
	assert_int_equal(cw_at(&p, 0x06, t), CO402_READY);        /* 2 */
	assert_int_equal(cw_at(&p, 0x00, t), CO402_DISABLED);     /* 7 */
	assert_int_equal(cw_at(&p, 0x06, t), CO402_READY);
	assert_int_equal(cw_at(&p, 0x07, t), CO402_SWITCHED_ON);  /* 3 */
	assert_int_equal(cw_at(&p, 0x06, t), CO402_READY);        /* 6 */
	assert_int_equal(cw_at(&p, 0x07, t), CO402_SWITCHED_ON);
	assert_int_equal(cw_at(&p, 0x02, t), CO402_DISABLED);     /* 10 */
	assert_int_equal(cw_at(&p, 0x06, t), CO402_READY);
	assert_int_equal(cw_at(&p, 0x07, t), CO402_SWITCHED_ON);
	assert_int_equal(cw_at(&p, 0x0f, t), CO402_ENABLED);      /* 4 */
	assert_int_equal(w->sw & 0x1010, 0x1010); /* voltage, follows the target */
	assert_int_equal(cw_at(&p, 0x07, t), CO402_SWITCHED_ON);  /* 5 */
	assert_int_equal(cw_at(&p, 0x0f, t), CO402_ENABLED);
	assert_int_equal(cw_at(&p, 0x06, t), CO402_READY);        /* 8 */
	cw_at(&p, 0x07, t);
	assert_int_equal(cw_at(&p, 0x0f, t), CO402_ENABLED);
	assert_int_equal(cw_at(&p, 0x00, t), CO402_DISABLED);     /* 9 */
	cw_at(&p, 0x06, t);
	cw_at(&p, 0x07, t);
	cw_at(&p, 0x0f, t);
	assert_int_equal(cw_at(&p, 0x02, t), CO402_QUICK_STOP);   /* 11 */
	assert_int_equal(w->sw & 0x0020, 0);                      /* quick stop bit low */
	assert_int_equal(cw_at(&p, 0x00, t), CO402_DISABLED);     /* 12 by command */
	cw_at(&p, 0x06, t);
	cw_at(&p, 0x07, t);
	cw_at(&p, 0x0f, t);
	assert_int_equal(cw_at(&p, 0x02, t), CO402_QUICK_STOP);
	/* 12 by itself: at rest the ramp ends after one period */
	co_slave_poll(p.s, t + 1000000);
	assert_int_equal(co402_decode(w->sw), CO402_DISABLED);
	assert_int_equal(w->log[w->ntransitions - 1].cw, 0);
	/* 16 with option code 5: quick stop active until enabled again */
	sdo_write(&p, 0x605a, 0, 5, 2);
	cw_at(&p, 0x06, t);
	cw_at(&p, 0x07, t);
	cw_at(&p, 0x0f, t);
	assert_int_equal(cw_at(&p, 0x02, t), CO402_QUICK_STOP);
	co_slave_poll(p.s, t + 5000000);
	assert_int_equal(co402_decode(w->sw), CO402_QUICK_STOP);
	assert_int_equal(cw_at(&p, 0x0f, t), CO402_ENABLED);      /* 16 */
	/* 13, 14: a fault, announced; 15: reset on the edge, announced */
	p.nq = 0;
	co_slave_fault(p.s, 0x3210, t);
	assert_int_equal(co402_decode(w->sw), CO402_FAULT);
	assert_int_equal(w->log[w->ntransitions - 2].to, CO402_FAULT_REACTION);
	assert_int_equal(p.nq, 1);
	assert_int_equal(p.q[0].id, 0x85);
	assert_int_equal(co_get16(p.q[0].data), 0x3210);
	assert_int_equal(p.q[0].data[2], 0x05); /* generic + voltage */
	assert_int_equal(w->error_code, 0x3210);
	p.nq = 0;
	assert_int_equal(cw_at(&p, 0x0f, t), CO402_FAULT);        /* ignored */
	p.nq = 0;
	assert_int_equal(cw_at(&p, 0x80, t), CO402_DISABLED);     /* 15 */
	assert_int_equal(p.nq, 2); /* the EMCY, then the SDO answer */
	assert_int_equal(p.q[0].id, 0x85);
	assert_int_equal(co_get16(p.q[0].data), 0x0000);
	assert_int_equal(w->error_code, 0);
	/* 0x2000 injects a fault by SDO, for tests on a real bus */
	sdo_write(&p, 0x2000, 0, 0x2310, 2);
	assert_int_equal(co402_decode(w->sw), CO402_FAULT);
	assert_int_equal(w->error_code, 0x2310);
	co_slave_free(p.s);
}

static void test_emcy(void **state)
{
	struct co_frame f;
	struct co_emcy e;

	assert_string_equal(co_emcy_class(0x2310), "current, device output side");
	assert_string_equal(co_emcy_class(0x8130),
			    "communication, heartbeat or life guard error");
	assert_string_equal(co_emcy_class(0x8140), "communication, recovered from bus-off");
	assert_string_equal(co_emcy_class(0x8199), "communication");
	assert_string_equal(co_emcy_class(0x5530), "device hardware");
	assert_string_equal(co_emcy_class(0xff12), "device specific");
	assert_string_equal(co_emcy_class(0x0000), "error reset or no error");
	assert_string_equal(co_emcy_class(0x1000), "generic error");
	assert_string_equal(co_emcy_class(0xe000), "unknown error class");
	assert_int_equal(co_emcy_register_bit(0x2310), 0x02);
	assert_int_equal(co_emcy_register_bit(0x4310), 0x08);
	assert_int_equal(co_emcy_register_bit(0x8130), 0x10);
	co_emcy_frame(&f, 9, 0x3210, 0x05);
	assert_int_equal(f.id, 0x89);
	assert_true(co_emcy_parse(&f, 0x80, &e));
	assert_int_equal(e.node, 9);
	assert_int_equal(e.code, 0x3210);
	assert_int_equal(e.reg, 0x05);
	f.id = 0x80; /* the SYNC */
	assert_false(co_emcy_parse(&f, 0x80, &e));
	f.id = 0x89;
	assert_false(co_emcy_parse(&f, 0x89, &e)); /* a SYNC moved onto it */
}

static void test_interp_period(void **state)
{
	static const struct {
		uint32_t hz;
		int rc;
		uint8_t value;
		int8_t exp;
	} t[] = {
		{ 1000, 0, 1, -3 }, { 500, 0, 2, -3 },	 { 250, 0, 4, -3 }, { 100, 0, 1, -2 },
		{ 400, 0, 25, -4 }, { 8000, 0, 125, -6 }, { 1, 0, 1, 0 },  { 4000, 0, 25, -5 },
		/* 244.14 us as 244 us: 0.06% short, within the 0.1% */
		{ 4096, 1, 244, -6 },
	};
	uint8_t v;
	int8_t e;
	unsigned i;

	for (i = 0; i < sizeof(t) / sizeof(t[0]); i++) {
		assert_int_equal(co_interp_period(t[i].hz, &v, &e), t[i].rc);
		assert_int_equal(v, t[i].value);
		assert_int_equal(e, t[i].exp);
	}
	/* 333.3 us: 333 does not fit a byte, 33 x 10^-5 s is 1% off */
	assert_int_equal(co_interp_period(3000, &v, &e), -EINVAL);
	/* 976.6 us: 98 x 10^-5 s is 0.35% off */
	assert_int_equal(co_interp_period(1024, &v, &e), -EINVAL);
	assert_int_equal(co_interp_period(0, &v, &e), -EINVAL);
}

static void test_load(void **state)
{
	struct co_load l;

	/* the worst cases CAN's literature gives: 8 bytes 135 bits, 0 bytes 55 */
	assert_int_equal(co_frame_bits_max(8), 135);
	assert_int_equal(co_frame_bits_max(0), 55);
	assert_int_equal(co_frame_bits_max(1), 65);
	assert_int_equal(co_frame_bits_max(6), 115);
	/* 3 drives at 1 kHz, 1 Mbit/s, heartbeat 50 ms: SYNC + 3 x (115 +
	 * 115 + 65) = 940 of 1000 bits: too much */
	co_load_tick(&l, 3, 1000000, 1000, 50);
	assert_int_equal(l.bits, 940);
	assert_int_equal(l.capacity, 1000);
	assert_false(co_load_fits(&l));
	/* the same at 500 Hz: 940 of 2000, 47% */
	co_load_tick(&l, 3, 1000000, 500, 50);
	assert_true(co_load_fits(&l));
	/* 8 drives at 250 Hz on 1 Mbit/s: 55 + 8 x 295 = 2415 of 4000 */
	co_load_tick(&l, 8, 1000000, 250, 50);
	assert_int_equal(l.bits, 2415);
	assert_true(co_load_fits(&l));
	/* at 500 kbit/s: 2415 of 2000 */
	co_load_tick(&l, 8, 500000, 250, 50);
	assert_false(co_load_fits(&l));
	/* right at the margin: 70% of capacity fits, one bit more does not */
	l.capacity = 1000;
	l.bits = 700;
	assert_true(co_load_fits(&l));
	l.bits = 701;
	assert_false(co_load_fits(&l));
}

/* The error frames a SocketCAN driver sends, and the state each means. */
static void test_error_frames(void **state)
{
	uint8_t d[8] = { 0 };
	uint32_t crtl = CAN_ERR_FLAG | CAN_ERR_CRTL;

	d[1] = CAN_ERR_CRTL_TX_WARNING;
	assert_int_equal(co_socketcan_error_state(CO_BUS_ACTIVE, crtl, d), CO_BUS_WARNING);
	d[1] = CAN_ERR_CRTL_RX_PASSIVE;
	assert_int_equal(co_socketcan_error_state(CO_BUS_WARNING, crtl, d), CO_BUS_PASSIVE);
	d[1] = CAN_ERR_CRTL_TX_PASSIVE | CAN_ERR_CRTL_RX_WARNING;
	assert_int_equal(co_socketcan_error_state(CO_BUS_ACTIVE, crtl, d), CO_BUS_PASSIVE);
	d[1] = CAN_ERR_CRTL_ACTIVE;
	assert_int_equal(co_socketcan_error_state(CO_BUS_PASSIVE, crtl, d), CO_BUS_ACTIVE);
	d[1] = CAN_ERR_CRTL_RX_OVERFLOW; /* a lost frame: no change of state */
	assert_int_equal(co_socketcan_error_state(CO_BUS_WARNING, crtl, d), CO_BUS_WARNING);
	d[1] = 0;
	assert_int_equal(co_socketcan_error_state(CO_BUS_PASSIVE, CAN_ERR_FLAG | CAN_ERR_BUSOFF, d),
			 CO_BUS_OFF);
	assert_int_equal(co_socketcan_error_state(CO_BUS_OFF, CAN_ERR_FLAG | CAN_ERR_RESTARTED, d),
			 CO_BUS_ACTIVE);
	/* a bus error alone (a bit error, an ACK missing) says nothing of the state */
	assert_int_equal(co_socketcan_error_state(CO_BUS_ACTIVE, CAN_ERR_FLAG | CAN_ERR_ACK, d),
			 CO_BUS_ACTIVE);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sdo_expedited),
		cmocka_unit_test(test_sdo_segmented),
		cmocka_unit_test(test_sdo_aborts),
		cmocka_unit_test(test_sdo_toggle),
		cmocka_unit_test(test_sdo_timeout),
		cmocka_unit_test(test_402_table),
		cmocka_unit_test(test_402_toward_enabled),
		cmocka_unit_test(test_402_drive),
		cmocka_unit_test(test_emcy),
		cmocka_unit_test(test_interp_period),
		cmocka_unit_test(test_load),
		cmocka_unit_test(test_error_frames),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
