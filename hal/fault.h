/* SPDX-License-Identifier: MIT */
/*
 * fault.h - a latched fault of a HAL device, as every device class reports
 * it (axis.h, dout.h, din.h): a negative errno, the channel or line, and a
 * static cause. The message that names the device and the channel is built
 * at the edge (the CLI), never in the loop.
 */
#ifndef HAL_FAULT_H
#define HAL_FAULT_H

#include <stdint.h>

struct hal_fault {
	int code;          /* negative errno: -EIO drive fault, -ETIMEDOUT no answer, ... */
	int32_t channel;   /* -1: the device as a whole */
	const char *cause; /* static text: "overcurrent", "heartbeat lost", ... */
	uint32_t detail;   /* backend-specific number: register, EMCY code; 0 if none */
};

#endif /* HAL_FAULT_H */
