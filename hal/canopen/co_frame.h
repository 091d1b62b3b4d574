/* SPDX-License-Identifier: MIT */
/*
 * co_frame.h - a classic CAN frame as the CANopen code sees it, the CiA 301
 * identifiers it uses, and little-endian packing (CANopen puts every
 * multi-byte value on the bus least significant byte first).
 *
 * The protocol code (master, SDO client, simulated drive) only builds and
 * parses these; a transport (SocketCAN, the simulated bus) moves them. 11-bit
 * identifiers only: CiA 301's predefined connection set is 11-bit, and so
 * are the drives strand talks to.
 *
 * Everything here is [rt]: pure functions of their arguments.
 */
#ifndef CO_FRAME_H
#define CO_FRAME_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "hal/rt.h"

struct co_frame {
	uint16_t id;      /* 11-bit identifier (COB-ID) */
	uint8_t len;      /* data length, 0..8 */
	uint8_t data[8];
};

/* CiA 301 predefined connection set: function code + node-ID. */
enum {
	CO_ID_NMT = 0x000,
	CO_ID_SYNC = 0x080,      /* default; 0x1005 moves it */
	CO_ID_EMCY = 0x080,      /* + node-ID */
	CO_ID_TPDO1 = 0x180,     /* + node-ID, drive to master */
	CO_ID_RPDO1 = 0x200,     /* + node-ID, master to drive */
	CO_ID_SDO_TX = 0x580,    /* + node-ID, server (drive) to client */
	CO_ID_SDO_RX = 0x600,    /* + node-ID, client to server (drive) */
	CO_ID_HEARTBEAT = 0x700, /* + node-ID: NMT error control, boot-up */
};

#define CO_NODE_MAX 127

/* PDO n (1..4): TPDOn at 0x180 + 0x100 (n - 1), RPDOn at 0x200 + 0x100 (n - 1). */
static inline uint16_t STRAND_RT co_tpdo_id(unsigned n, uint8_t node)
{
	return (uint16_t)(CO_ID_TPDO1 + 0x100 * (n - 1) + node);
}

static inline uint16_t STRAND_RT co_rpdo_id(unsigned n, uint8_t node)
{
	return (uint16_t)(CO_ID_RPDO1 + 0x100 * (n - 1) + node);
}

/* NMT commands (byte 0 of a frame to CO_ID_NMT; byte 1 is the node-ID, 0 all). */
enum co_nmt_cmd {
	CO_NMT_START = 0x01,
	CO_NMT_STOP = 0x02,
	CO_NMT_PREOP = 0x80,
	CO_NMT_RESET_NODE = 0x81,
	CO_NMT_RESET_COMM = 0x82,
};

/* NMT states as a heartbeat reports them. */
enum co_nmt_state {
	CO_NMT_BOOTUP = 0x00,
	CO_NMT_STOPPED = 0x04,
	CO_NMT_OPERATIONAL = 0x05,
	CO_NMT_PREOPERATIONAL = 0x7f,
};

/* PDO communication parameter, sub-index 1 (COB-ID): the PDO does not exist
 * (is off) while bit 31 is set; bit 30 set forbids remote requests. */
#define CO_PDO_COBID_OFF 0x80000000u
#define CO_PDO_COBID_NO_RTR 0x40000000u
/* Sub-index 2: transmission type 1 = synchronous, every SYNC. */
#define CO_PDO_SYNC_EVERY 1
/* A mapping entry: index << 16 | sub-index << 8 | length in bits. */
static inline uint32_t STRAND_RT co_map(uint16_t index, uint8_t sub, uint8_t bits)
{
	return (uint32_t)index << 16 | (uint32_t)sub << 8 | bits;
}

static inline uint16_t STRAND_RT co_get16(const uint8_t *p)
{
	return (uint16_t)(p[0] | p[1] << 8);
}

static inline uint32_t STRAND_RT co_get32(const uint8_t *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static inline void STRAND_RT co_put16(uint8_t *p, uint16_t v)
{
	p[0] = (uint8_t)v;
	p[1] = (uint8_t)(v >> 8);
}

static inline void STRAND_RT co_put32(uint8_t *p, uint32_t v)
{
	p[0] = (uint8_t)v;
	p[1] = (uint8_t)(v >> 8);
	p[2] = (uint8_t)(v >> 16);
	p[3] = (uint8_t)(v >> 24);
}

/* Little-endian value of n bytes (1..4). */
static inline uint32_t STRAND_RT co_get(const uint8_t *p, unsigned n)
{
	uint32_t v = 0;

	while (n--)
		v = v << 8 | p[n];
	return v;
}

static inline void STRAND_RT co_put(uint8_t *p, uint32_t v, unsigned n)
{
	unsigned i;

	for (i = 0; i < n; i++, v >>= 8)
		p[i] = (uint8_t)v;
}

static inline void STRAND_RT co_frame_init(struct co_frame *f, uint16_t id, uint8_t len)
{
	memset(f, 0, sizeof(*f));
	f->id = id;
	f->len = len;
}

/* The controller's state, as the transport reports it. */
enum co_bus_state {
	CO_BUS_ACTIVE,
	CO_BUS_WARNING, /* an error counter reached 96: noted, not a fault */
	CO_BUS_PASSIVE,
	CO_BUS_OFF,
};

/* Frames out, in order, without blocking: 0 when all n were taken, else a
 * negative errno (a master latches a fault and sends nothing after; a slave
 * loses them, as a real drive would). */
typedef int (*co_send_fn)(void *ctx, const struct co_frame *f, uint32_t n);

#endif /* CO_FRAME_H */
