/* SPDX-License-Identifier: MIT */
/*
 * co_sdo.h - the SDO client of CiA 301 (7.2.4): reads and writes of one
 * node's object dictionary, expedited (up to 4 bytes in the initiating
 * frame) or segmented (7 bytes per segment, a toggle bit per segment), with
 * abort codes named.
 *
 * A pure state machine, one transfer at a time per client: start a transfer
 * (download = write to the drive, upload = read from it), then hand it every
 * frame the drive sends on 0x580 + node and call poll() for the timeout.
 * Whenever a function returns true, *out is a frame to send to 0x600 + node.
 * The caller owns the data buffers and keeps them until the transfer ends.
 *
 * The client is used while a drive is configured ([init]); its functions
 * allocate nothing and do no I/O, so they are [rt]-safe as well.
 */
#ifndef CO_SDO_H
#define CO_SDO_H

#include <stdbool.h>
#include <stdint.h>

#include "co_frame.h"

/* Abort codes (CiA 301, table 22) that strand meets or sends. */
enum co_abort {
	CO_ABORT_TOGGLE = 0x05030000,        /* toggle bit not alternated */
	CO_ABORT_TIMEOUT = 0x05040000,       /* SDO protocol timed out */
	CO_ABORT_COMMAND = 0x05040001,       /* command specifier not valid or unknown */
	CO_ABORT_NO_MEMORY = 0x05040005,     /* out of memory */
	CO_ABORT_ACCESS = 0x06010000,        /* unsupported access to an object */
	CO_ABORT_WRITE_ONLY = 0x06010001,    /* read of a write-only object */
	CO_ABORT_READ_ONLY = 0x06010002,     /* write of a read-only object */
	CO_ABORT_NO_OBJECT = 0x06020000,     /* object does not exist */
	CO_ABORT_NO_MAP = 0x06040041,        /* object cannot be mapped to a PDO */
	CO_ABORT_MAP_LEN = 0x06040042,       /* mapping would exceed the PDO length */
	CO_ABORT_PARAM = 0x06040043,         /* general parameter incompatibility */
	CO_ABORT_INTERNAL = 0x06040047,      /* general internal incompatibility */
	CO_ABORT_HARDWARE = 0x06060000,      /* access failed due to a hardware error */
	CO_ABORT_TYPE_LEN = 0x06070010,      /* data type or length does not match */
	CO_ABORT_TYPE_LEN_HIGH = 0x06070012, /* ... length too high */
	CO_ABORT_TYPE_LEN_LOW = 0x06070013,  /* ... length too low */
	CO_ABORT_NO_SUB = 0x06090011,        /* sub-index does not exist */
	CO_ABORT_VALUE = 0x06090030,         /* invalid value */
	CO_ABORT_VALUE_HIGH = 0x06090031,    /* value too high */
	CO_ABORT_VALUE_LOW = 0x06090032,     /* value too low */
	CO_ABORT_GENERAL = 0x08000000,       /* general error */
	CO_ABORT_DATA = 0x08000020,          /* data cannot be transferred or stored */
	CO_ABORT_DATA_LOCAL = 0x08000021,    /* ... because of local control */
	CO_ABORT_DATA_STATE = 0x08000022,    /* ... because of the device state */
};

/* The abort code's meaning in words (static text); "unknown abort code"
 * for a code CiA 301 does not define. */
const char *co_abort_name(uint32_t code);

enum co_sdo_state {
	CO_SDO_IDLE,    /* no transfer yet */
	CO_SDO_BUSY,    /* a request is out, an answer awaited */
	CO_SDO_DONE,    /* the last transfer succeeded */
	CO_SDO_ABORTED, /* the last transfer was aborted: see abort */
};

struct co_sdo {
	uint8_t node;
	uint8_t state;      /* enum co_sdo_state */
	uint8_t phase;      /* what the outstanding request was (co_sdo.c) */
	uint8_t toggle;     /* of the next segment, 0 or 0x10 */
	uint16_t index;
	uint8_t sub;
	bool abort_sent;    /* the abort was ours (timeout, protocol), not the drive's */
	uint32_t abort;     /* enum co_abort, once aborted */
	uint8_t *dst;       /* upload: where the data goes */
	const uint8_t *src; /* download: the data */
	uint32_t size;      /* download: bytes to write; upload: room in dst */
	uint32_t pos;       /* bytes moved so far */
	uint32_t announced; /* upload: the size the drive gave (0: none) */
	int64_t timeout_ns;
	int64_t deadline;   /* of the outstanding request */
};

/* A client for node (1..127) that gives up after timeout_ns per request. */
void co_sdo_init(struct co_sdo *s, uint8_t node, int64_t timeout_ns);

/* Write n bytes of data (kept by the caller until the end) to index:sub. */
void co_sdo_download(struct co_sdo *s, uint16_t index, uint8_t sub, const void *data,
		     uint32_t n, int64_t now, struct co_frame *out);

/* Read index:sub into dst, which has room for cap bytes; s->pos is the
 * size read once done. More data than cap aborts with CO_ABORT_NO_MEMORY. */
void co_sdo_upload(struct co_sdo *s, uint16_t index, uint8_t sub, void *dst, uint32_t cap,
		   int64_t now, struct co_frame *out);

/* A frame from the bus: ignored unless it is this node's SDO response to
 * the transfer under way. true: send *out. */
bool co_sdo_rx(struct co_sdo *s, const struct co_frame *in, int64_t now, struct co_frame *out);

/* The timeout: past the deadline the transfer is aborted with
 * CO_ABORT_TIMEOUT and true is returned with the abort frame in *out. */
bool co_sdo_poll(struct co_sdo *s, int64_t now, struct co_frame *out);

/* An abort frame from a client or a server. */
void co_sdo_abort_frame(struct co_frame *out, uint16_t id, uint16_t index, uint8_t sub,
			uint32_t code);

#endif /* CO_SDO_H */
