/* SPDX-License-Identifier: MIT */
/*
 * co_load.h - whether a CANopen bus carries one tick's traffic in one tick:
 * the worst-case bits of every frame of a tick (bit stuffing included)
 * against the bits the bitrate gives a tick, with a margin.
 *
 * A tick carries, per drive, one RPDO (controlword and target, 6 bytes) and
 * one TPDO (statusword and position actual, 6 bytes), plus one SYNC; and in
 * the worst tick every drive's heartbeat (1 byte) as well, since nothing
 * keeps the drives' heartbeats apart. The margin (CO_LOAD_MAX_PERCENT) is
 * for what cannot be planned: an error frame and the retransmission that
 * follows it, an EMCY, and the time a drive takes to answer the SYNC.
 *
 * Pure functions: [rt] and [init] alike.
 */
#ifndef CO_LOAD_H
#define CO_LOAD_H

#include <stdbool.h>
#include <stdint.h>

/* The share of a tick's bits that the worst case may take. */
#define CO_LOAD_MAX_PERCENT 70

/* Bytes of the PDOs the master maps (co_master.c). */
#define CO_RPDO_BYTES 6
#define CO_TPDO_BYTES 6

/*
 * Worst-case length in bits of a classic CAN data frame with an 11-bit
 * identifier and n data bytes (0..8), the 3-bit interframe space included.
 * Of its 47 + 8n bits, the 34 + 8n from the start of frame to the end of
 * the CRC are stuffed: after five equal bits the sender inserts a
 * complementary one, which in the worst case counts as the first of the
 * next five, so at most floor((34 + 8n - 1) / 4) stuff bits (Davis, Burns,
 * Bril and Lukkien, "Controller Area Network (CAN) schedulability analysis:
 * refuted, revisited and revised", Real-Time Systems 35, 2007, eq. 1).
 * 8 bytes: 135 bits; a SYNC (0 bytes): 55.
 */
uint32_t co_frame_bits_max(unsigned n);

struct co_load {
	uint32_t drives;
	uint32_t bits;     /* worst-case bits in one tick */
	uint32_t capacity; /* bits one tick holds: bitrate / tick rate */
};

/* One tick of ndrives drives at tick_hz on a bus of bitrate bit/s whose
 * drives send a heartbeat every heartbeat_ms. */
void co_load_tick(struct co_load *l, uint32_t ndrives, uint32_t bitrate, uint32_t tick_hz,
		  uint32_t heartbeat_ms);

/* The worst case within CO_LOAD_MAX_PERCENT of the capacity. */
bool co_load_fits(const struct co_load *l);

#endif /* CO_LOAD_H */
