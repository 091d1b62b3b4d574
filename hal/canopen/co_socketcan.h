/* SPDX-License-Identifier: MIT */
/*
 * co_socketcan.h - the CANopen transport on Linux SocketCAN: one raw socket
 * per interface (classic CAN frames), receive filters for what its user
 * consumes, the controller's error frames (CAN_RAW_ERR_FILTER) turned into
 * its error state, send and receive without blocking (MSG_DONTWAIT,
 * sendmmsg/recvmmsg: a tick's frames in one system call each way).
 *
 * Error state, from the error frames the driver sends (vcan sends none):
 * warning and passive from the controller's counters (CAN_ERR_CRTL),
 * bus-off (CAN_ERR_BUSOFF), back to active on a restart (CAN_ERR_RESTARTED)
 * or when the driver says so (CAN_ERR_CRTL_ACTIVE).
 *
 * After a bus-off the kernel drops what was queued for the interface when
 * it goes down (the qdisc is reset as the carrier goes); nothing of it is
 * sent after a restart, and the master sends nothing more by itself.
 */
#ifndef CO_SOCKETCAN_H
#define CO_SOCKETCAN_H

#include <stddef.h>
#include <stdint.h>

#include "co_bus.h"

/* The most frames one send() or recv() call moves. */
#define CO_SOCKETCAN_BATCH 130

/* A receive filter: frames whose identifier matches id in the bits of mask
 * (0x7ff: exactly id). */
struct co_rx_filter {
	uint16_t id, mask;
};

/* [init] A raw CAN socket bound to ifname into *out, receiving the data
 * frames with 11-bit identifiers that one of the n filters passes (every
 * frame when flt is NULL), and error frames. 0, or a negative errno with a
 * message in err naming the interface and what to do. */
int co_socketcan_open(struct co_bus **out, const char *ifname, const struct co_rx_filter *flt,
		      uint32_t n, char *err, size_t size);

/* [init] Replace the receive filters: 0 or a negative errno. */
int co_socketcan_filter(struct co_bus *b, const struct co_rx_filter *flt, uint32_t n);

/* The controller's state after an error frame (can_id with CAN_ERR_FLAG,
 * its 8 data bytes) in state prev: linux/can/error.h's classes. */
enum co_bus_state co_socketcan_error_state(enum co_bus_state prev, uint32_t can_id,
					   const uint8_t *data);

/* The socket, for a program's own poll loop (strand-simdrive). */
int co_socketcan_fd(struct co_bus *b);

#endif /* CO_SOCKETCAN_H */
