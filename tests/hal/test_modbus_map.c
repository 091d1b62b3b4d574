/* SPDX-License-Identifier: MIT */
/*
 * test_modbus_map.c - a Modbus register map (hal/modbus_map.h): values into
 * registers and back in every type and word order against hand-written
 * words, values cut into blocks of adjacent registers, time on an RTU line
 * against the hand count; and the scene's modbus: section refused
 * where it is wrong, at its place.
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "hal/modbus/modbus_dev.h"
#include "hal/modbus/modbus_map.h"
#include "load/load.h"
#include "testutil.h"

static void test_encode(void **state)
{
	static const struct {
		enum modbus_type t;
		enum modbus_words o;
		int64_t v;
		uint16_t w[2];
	} cases[] = {
		{ MODBUS_TYPE_INT16, MODBUS_WORDS_HIGH_FIRST, -1, { 0xffff } },
		{ MODBUS_TYPE_INT16, MODBUS_WORDS_HIGH_FIRST, -32768, { 0x8000 } },
		{ MODBUS_TYPE_UINT16, MODBUS_WORDS_LOW_FIRST, 65535, { 0xffff } },
		{ MODBUS_TYPE_INT32, MODBUS_WORDS_HIGH_FIRST, -2, { 0xffff, 0xfffe } },
		{ MODBUS_TYPE_INT32, MODBUS_WORDS_LOW_FIRST, -2, { 0xfffe, 0xffff } },
		{ MODBUS_TYPE_INT32, MODBUS_WORDS_HIGH_FIRST, 40000, { 0x0000, 0x9c40 } },
		{ MODBUS_TYPE_INT32, MODBUS_WORDS_LOW_FIRST, INT32_MIN, { 0x0000, 0x8000 } },
		{ MODBUS_TYPE_UINT32, MODBUS_WORDS_HIGH_FIRST, 0x12345678, { 0x1234, 0x5678 } },
		{ MODBUS_TYPE_UINT32, MODBUS_WORDS_LOW_FIRST, 0xfedcba98, { 0xba98, 0xfedc } },
	};
	size_t i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		struct modbus_reg r = { 7, cases[i].t, cases[i].o };
		uint16_t w[2] = { 0x5555, 0x5555 };
		uint32_t n = modbus_type_nregs(r.type);

		assert_true(modbus_reg_fits(&r, cases[i].v));
		modbus_reg_encode(&r, cases[i].v, w);
		assert_memory_equal(w, cases[i].w, n * sizeof(uint16_t));
		if (n == 1)
			assert_int_equal(w[1], 0x5555); /* nothing past its register */
		assert_int_equal(modbus_reg_decode(&r, w), cases[i].v);
	}
}

static void test_fits(void **state)
{
	static const struct {
		enum modbus_type t;
		int64_t lo, hi;
	} cases[] = {
		{ MODBUS_TYPE_INT16, -32768, 32767 },
		{ MODBUS_TYPE_UINT16, 0, 65535 },
		{ MODBUS_TYPE_INT32, INT32_MIN, INT32_MAX },
		{ MODBUS_TYPE_UINT32, 0, UINT32_MAX },
	};
	size_t i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		struct modbus_reg r = { 0, cases[i].t, MODBUS_WORDS_HIGH_FIRST };

		assert_true(modbus_reg_fits(&r, cases[i].lo));
		assert_true(modbus_reg_fits(&r, cases[i].hi));
		assert_false(modbus_reg_fits(&r, cases[i].lo - 1));
		assert_false(modbus_reg_fits(&r, cases[i].hi + 1));
	}
}

static void test_plan(void **state)
{
	/* any order; 0-3 and 10-13 adjacent, so two requests */
	static const struct modbus_reg regs[] = {
		{ 10, MODBUS_TYPE_INT32, MODBUS_WORDS_HIGH_FIRST },
		{ 0, MODBUS_TYPE_INT32, MODBUS_WORDS_HIGH_FIRST },
		{ 3, MODBUS_TYPE_UINT16, MODBUS_WORDS_HIGH_FIRST },
		{ 2, MODBUS_TYPE_INT16, MODBUS_WORDS_HIGH_FIRST },
		{ 12, MODBUS_TYPE_UINT32, MODBUS_WORDS_LOW_FIRST },
	};
	struct modbus_reg many[130], over[2] = {
		{ 0, MODBUS_TYPE_INT32, MODBUS_WORDS_HIGH_FIRST },
		{ 1, MODBUS_TYPE_INT16, MODBUS_WORDS_HIGH_FIRST },
	}, top = { 65535, MODBUS_TYPE_INT32, MODBUS_WORDS_HIGH_FIRST };
	struct modbus_plan p;
	uint32_t a = 9, b = 9, i;

	assert_int_equal(modbus_plan_make(&p, regs, 5, MODBUS_MAP_WRITE_MAX, &a, &b), 0);
	assert_int_equal(p.nblocks, 2);
	assert_int_equal(p.block[0].addr, 0);
	assert_int_equal(p.block[0].count, 4);
	assert_int_equal(p.block[1].addr, 10);
	assert_int_equal(p.block[1].count, 4);
	assert_int_equal(p.nregs, 8);
	/* the image is the blocks' registers one after the other */
	assert_int_equal(p.off[1], 0);
	assert_int_equal(p.off[3], 2);
	assert_int_equal(p.off[2], 3);
	assert_int_equal(p.off[0], 4);
	assert_int_equal(p.off[4], 6);
	modbus_plan_free(&p);

	assert_int_equal(modbus_plan_make(&p, over, 2, MODBUS_MAP_WRITE_MAX, &a, &b), -EEXIST);
	assert_int_equal(a, 0);
	assert_int_equal(b, 1);
	assert_int_equal(modbus_plan_make(&p, &top, 1, MODBUS_MAP_WRITE_MAX, &a, &b), -ERANGE);

	/* a request carries at most 123 registers */
	for (i = 0; i < 130; i++)
		many[i] = (struct modbus_reg){ (uint16_t)(200 + i), MODBUS_TYPE_INT16,
					       MODBUS_WORDS_HIGH_FIRST };
	assert_int_equal(modbus_plan_make(&p, many, 130, MODBUS_MAP_WRITE_MAX, &a, &b), 0);
	assert_int_equal(p.nblocks, 2);
	assert_int_equal(p.block[0].count, 123);
	assert_int_equal(p.block[1].addr, 323);
	assert_int_equal(p.block[1].count, 7);
	modbus_plan_free(&p);
}

static void test_wire_time(void **state)
{
	int64_t w, r;

	/* t3.5: fixed above 19200 baud, 3.5 characters below */
	assert_int_equal(modbus_rtu_gap_ns(115200, 11), 1750000);
	assert_int_equal(modbus_rtu_gap_ns(9600, 11), 4010417); /* 3.5 * 11 / 9600 s */
	assert_int_equal(modbus_rtu_char_bits(true, 1), 11);
	assert_int_equal(modbus_rtu_char_bits(false, 2), 11);
	assert_int_equal(modbus_rtu_char_bits(false, 1), 10);
	/* the count: writing 8 registers (25 + 8 bytes) and reading 8
	 * (8 + 21 bytes) is 62 bytes, 5.92 ms at 11 bits and 115200 baud, and
	 * four 1.75 ms silences: 12.92 ms, "roughly 12 ms" */
	assert_int_equal(modbus_rtu_write_req_bytes(8) + MODBUS_RTU_WRITE_RSP_BYTES +
			 MODBUS_RTU_READ_REQ_BYTES + modbus_rtu_read_rsp_bytes(8), 62);
	w = modbus_rtu_transaction_ns(modbus_rtu_write_req_bytes(8), MODBUS_RTU_WRITE_RSP_BYTES,
				      115200, 11, 0);
	r = modbus_rtu_transaction_ns(MODBUS_RTU_READ_REQ_BYTES, modbus_rtu_read_rsp_bytes(8),
				      115200, 11, 0);
	assert_int_equal(w + r, 5920139 + 4 * 1750000);
}

/* A scene with one Modbus drive; `modbus` is its section's body. */
static int parse(const char *modbus, const char *outputs, struct load_err *e)
{
	char yaml[2048];
	struct scene_file sf;
	int rc;

	snprintf(yaml, sizeof(yaml),
		 "timing: {tick_hz: 1000, frame_rate: 24, frames: [0, 10]}\n"
		 "nodes: [{name: a, joint: {type: revolute, axis: z},\n"
		 "         limits: {velocity: 90, acceleration: 360}}]\n"
		 "devices:\n"
		 "  - name: d\n"
		 "    driver: modbus\n"
		 "    modbus: %s\n"
		 "outputs: [%s]\n", modbus,
		 outputs ? outputs : "{channel: a.angle, device: d, counts_per_unit: 1}");
	memset(e, 0, sizeof(*e));
	rc = scene_file_parse(&sf, "t.yaml", yaml, strlen(yaml), e);
	scene_file_free(&sf);
	return rc;
}

static void test_section(void **state)
{
	static const struct {
		const char *modbus, *outputs, *expect;
		uint32_t line, col; /* where, when 0 not checked */
	} cases[] = {
		{ "{unit: 1, axes: [{register: 0}]}", NULL,
		  "modbus: a tcp: or an rtu: connection, one of them", 7, 13 },
		{ "{tcp: {host: h}, rtu: {port: /dev/x}, unit: 1, axes: [{register: 0}]}", NULL,
		  "modbus: a tcp: or an rtu: connection, one of them", 7, 13 },
		{ "{rtu: {port: /dev/x, baud: 12345}, unit: 1, axes: [{register: 0}]}", NULL,
		  "baud 12345: not a standard rate", 0, 0 },
		{ "{rtu: {port: /dev/x}, unit: 0, axes: [{register: 0}]}", NULL,
		  "'0' is out of range (1 to 247)", 0, 0 },
		{ "{tcp: {host: h}, unit: 1, axes: [{register: 0}, {register: 1}]}", NULL,
		  "device 'd': two of its registers overlap", 0, 0 },
		{ "{tcp: {host: h}, unit: 1, heartbeat: {register: 1, type: int16}, "
		  "axes: [{register: 0, type: int16}]}", NULL,
		  "a heartbeat counts ticks: uint16 or uint32", 0, 0 },
		{ "{tcp: {host: h}, unit: 1, enable: {coil: 0, on: 2}, axes: [{register: 0}]}", NULL,
		  "a coil is on or off", 0, 0 },
		{ "{tcp: {host: h}, unit: 1, status: {register: 9, fault_mask: 0x1g}, "
		  "axes: [{register: 0}]}", NULL, "expected a 16-bit mask", 0, 0 },
		{ "{tcp: {host: h}, unit: 1, axes: [{register: 0}]}",
		  "{channel: a.angle, device: d, axis: 1, counts_per_unit: 1}",
		  "axis 1 of Modbus device 'd': its register map (modbus: axes:) has 1 axis", 8, 11 },
		{ "{tcp: {host: h}, unit: 1, update_hz: 2000, axes: [{register: 0}]}", NULL,
		  "update_hz 2000 is above the tick rate 1000", 0, 0 },
		/* 1 ms per answer assumed: a write and a read do not fit a 1 kHz tick */
		{ "{tcp: {host: h}, unit: 1, read_every: 10, axes: [{register: 0, actual: "
		  "{register: 10}}]}", NULL,
		  "device 'd': an update with its reads takes 2 ms on the bus (answer_ms per "
		  "request), more than the 1 ms between updates at 1000 Hz; it reaches 500 Hz", 0, 0 },
	};
	struct load_err e;
	size_t i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		assert_int_not_equal(parse(cases[i].modbus, cases[i].outputs, &e), 0);
		printf("%u:%u: %s\n", e.line, e.col, e.msg);
		if (!strstr(e.msg, cases[i].expect))
			fail_msg("case %zu: '%s' not in '%s'", i, cases[i].expect, e.msg);
		if (cases[i].line && (e.line != cases[i].line || e.col != cases[i].col))
			fail_msg("case %zu: at %u:%u, want %u:%u", i, e.line, e.col, cases[i].line,
				 cases[i].col);
	}
	/* the same device right: accepted */
	assert_int_equal(parse("{tcp: {host: h}, unit: 1, axes: [{register: 0}]}", NULL, &e), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_encode),
		cmocka_unit_test(test_fits),
		cmocka_unit_test(test_plan),
		cmocka_unit_test(test_wire_time),
		cmocka_unit_test(test_section),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
