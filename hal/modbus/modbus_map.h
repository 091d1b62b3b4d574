/* SPDX-License-Identifier: MIT */
/*
 * modbus_map.h - a Modbus device's register map: where each value lives in
 * the holding registers, how it is encoded, which values go out together,
 * and how long that takes on the wire.
 *
 * A value is 16 or 32 bits, signed or not. A 32-bit value takes two
 * registers; Modbus says nothing about their order, drives differ: high
 * word first ("big-endian", mbpoll -B) or low word first. Each register is
 * big-endian on the wire either way (libmodbus handles that).
 *
 * The values written every update (the axes' targets, the heartbeat) are
 * sorted by address and cut into blocks of adjacent registers: one block is
 * one "write multiple registers" request (function 16), so a drive whose
 * axes sit next to each other gets one request per update. Reads (actual
 * positions, status) are cut the same way into "read holding registers"
 * requests (function 3).
 *
 * Everything here is pure computation: [rt] except the plan's making.
 */
#ifndef HAL_MODBUS_MAP_H
#define HAL_MODBUS_MAP_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/rt.h"

enum modbus_type {
	MODBUS_TYPE_INT16,
	MODBUS_TYPE_UINT16,
	MODBUS_TYPE_INT32,
	MODBUS_TYPE_UINT32,
};

enum modbus_words {
	MODBUS_WORDS_HIGH_FIRST, /* the register at addr holds bits 31..16 */
	MODBUS_WORDS_LOW_FIRST,  /* the register at addr holds bits 15..0 */
};

/* Where a value lives. */
struct modbus_reg {
	uint16_t addr;          /* holding register, 0-based (PDU address) */
	enum modbus_type type;
	enum modbus_words words;
};

/* Protocol limits per request (Modbus application protocol 1.1b3, 6.3 and
 * 6.12): registers one function 3 reads, one function 16 writes. */
#define MODBUS_MAP_READ_MAX 125
#define MODBUS_MAP_WRITE_MAX 123

static inline uint32_t STRAND_RT modbus_type_nregs(enum modbus_type t)
{
	return t == MODBUS_TYPE_INT32 || t == MODBUS_TYPE_UINT32 ? 2 : 1;
}

static inline int64_t STRAND_RT modbus_type_min(enum modbus_type t)
{
	return t == MODBUS_TYPE_INT16 ? INT16_MIN : t == MODBUS_TYPE_INT32 ? INT32_MIN : 0;
}

static inline int64_t STRAND_RT modbus_type_max(enum modbus_type t)
{
	return t == MODBUS_TYPE_INT16 ? INT16_MAX : t == MODBUS_TYPE_UINT16 ? UINT16_MAX :
	       t == MODBUS_TYPE_INT32 ? INT32_MAX : UINT32_MAX;
}

/* [rt] true when v fits the register's type. */
static inline bool STRAND_RT modbus_reg_fits(const struct modbus_reg *r, int64_t v)
{
	return v >= modbus_type_min(r->type) && v <= modbus_type_max(r->type);
}

/* [rt] v (which must fit) into out[0 .. nregs - 1], in the register order. */
static inline void STRAND_RT modbus_reg_encode(const struct modbus_reg *r, int64_t v, uint16_t *out)
{
	uint32_t u = (uint32_t)v; /* two's complement: the low 32 bits */

	if (modbus_type_nregs(r->type) == 1) {
		out[0] = (uint16_t)u;
	} else if (r->words == MODBUS_WORDS_HIGH_FIRST) {
		out[0] = (uint16_t)(u >> 16);
		out[1] = (uint16_t)u;
	} else {
		out[0] = (uint16_t)u;
		out[1] = (uint16_t)(u >> 16);
	}
}

/* [rt] The value registers in[0 .. nregs - 1] hold. */
static inline int64_t STRAND_RT modbus_reg_decode(const struct modbus_reg *r, const uint16_t *in)
{
	uint32_t u;

	switch (r->type) {
	case MODBUS_TYPE_INT16:
		return (int16_t)in[0];
	case MODBUS_TYPE_UINT16:
		return in[0];
	default:
		u = r->words == MODBUS_WORDS_HIGH_FIRST ? (uint32_t)in[0] << 16 | in[1] :
							  (uint32_t)in[1] << 16 | in[0];
		return r->type == MODBUS_TYPE_INT32 ? (int64_t)(int32_t)u : (int64_t)u;
	}
}

/* A run of adjacent registers: one request. */
struct modbus_block {
	uint16_t addr;  /* first register */
	uint16_t count; /* registers */
	uint32_t off;   /* its first register's place in the plan's image */
};

/*
 * Values laid out as blocks. The image is the registers of every block one
 * after the other; value i's registers are image[off[i] ...]. The caller
 * owns the arrays (sized by modbus_plan_make from n).
 */
struct modbus_plan {
	uint32_t n;                   /* values */
	const struct modbus_reg *reg; /* n, the caller's */
	uint32_t *off;                /* n */
	uint32_t nblocks;
	struct modbus_block *block;   /* at most n */
	uint32_t nregs;               /* the image's length */
};

/*
 * [init] Lay out n values (any order) in blocks of adjacent registers of at
 * most max registers each. 0; -EEXIST when two values overlap (*a and *b
 * their indices); -ERANGE when a value runs past register 65535; -ENOMEM.
 */
int modbus_plan_make(struct modbus_plan *p, const struct modbus_reg *reg, uint32_t n,
		     uint32_t max, uint32_t *a, uint32_t *b);
void modbus_plan_free(struct modbus_plan *p);

/* ---- time on the wire ---- */

/* Bytes of the requests and answers (RTU framing: address and CRC
 * included; TCP replaces both with the 7-byte MBAP header). */
static inline uint32_t modbus_rtu_write_req_bytes(uint32_t nregs)
{
	return 9 + 2 * nregs; /* unit fc addr(2) qty(2) bytecount data crc(2) */
}
#define MODBUS_RTU_WRITE_RSP_BYTES 8 /* unit fc addr(2) qty(2) crc(2) */
#define MODBUS_RTU_READ_REQ_BYTES 8  /* unit fc addr(2) qty(2) crc(2) */
static inline uint32_t modbus_rtu_read_rsp_bytes(uint32_t nregs)
{
	return 5 + 2 * nregs; /* unit fc bytecount data crc(2) */
}

/* The line's framing: bits per character (start, 8 data, parity, stop). */
static inline uint32_t modbus_rtu_char_bits(bool parity, uint32_t stop_bits)
{
	return 1 + 8 + (parity ? 1 : 0) + stop_bits;
}

/* The silence that ends a frame, t3.5 (Modbus over serial line 1.02,
 * 2.5.1.1): 3.5 characters, fixed at 1.75 ms above 19200 baud. */
int64_t modbus_rtu_gap_ns(uint32_t baud, uint32_t char_bits);

/*
 * One transaction on an RTU line: the request, the silence after it, the
 * drive's answer time, the answer and the silence after it.
 */
int64_t modbus_rtu_transaction_ns(uint32_t req_bytes, uint32_t rsp_bytes, uint32_t baud,
				  uint32_t char_bits, int64_t answer_ns);

#endif /* HAL_MODBUS_MAP_H */
