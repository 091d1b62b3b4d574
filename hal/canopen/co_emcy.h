/* SPDX-License-Identifier: MIT */
/*
 * co_emcy.h - emergency messages (CiA 301 7.2.7): a drive announces an
 * error on 0x80 + node-ID with an error code, its error register (0x1001)
 * and five bytes of its own. The code's high bits say its class (current,
 * voltage, temperature, communication, ...); error code 0x0000 says the
 * errors are gone (error reset).
 *
 * Everything here is [rt]: pure functions, static strings.
 */
#ifndef CO_EMCY_H
#define CO_EMCY_H

#include <stdbool.h>
#include <stdint.h>

#include "co_frame.h"

/* Error codes strand's simulated drive sends (CiA 301 table 21, CiA 402). */
enum {
	CO_EMCY_RESET = 0x0000,          /* error reset or no error */
	CO_EMCY_OVERCURRENT = 0x2310,    /* continuous over-current, output side */
	CO_EMCY_OVERVOLTAGE = 0x3210,    /* DC link over-voltage */
	CO_EMCY_TEMPERATURE = 0x4310,    /* drive temperature */
	CO_EMCY_HEARTBEAT = 0x8130,      /* life guard or heartbeat error */
	CO_EMCY_FOLLOWING = 0x8611,      /* following error (CiA 402) */
};

struct co_emcy {
	uint8_t node;
	uint16_t code;
	uint8_t reg;       /* error register, 0x1001 */
	uint8_t vendor[5]; /* manufacturer-specific */
};

/* An EMCY frame (0x81..0xFF, 8 bytes) into *e: false when f is not one.
 * The SYNC shares the EMCY function code: sync_id is never an EMCY. */
bool co_emcy_parse(const struct co_frame *f, uint16_t sync_id, struct co_emcy *e);

/* The frame a drive sends. */
void co_emcy_frame(struct co_frame *f, uint8_t node, uint16_t code, uint8_t reg);

/* The class of an error code as static text, most specific first:
 * "current, device output side", "communication, heartbeat or life guard
 * error", "device specific". */
const char *co_emcy_class(uint16_t code);

/* The error register bit that goes with an error code's class (1 generic,
 * 2 current, 4 voltage, 8 temperature, 16 communication, 32 profile). */
uint8_t co_emcy_register_bit(uint16_t code);

#endif /* CO_EMCY_H */
