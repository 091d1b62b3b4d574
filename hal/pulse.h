/* SPDX-License-Identifier: MIT */
/*
 * pulse.h - a frame pulse as an external clock (extclk.h): one input line
 * of a digital input device (din.h), whose rising edges, timestamped where
 * the device timestamps them (the kernel, for GPIO), are the marks. The
 * device's own thread reads the edges (the GPIO backend's event thread):
 * here only the loop's side, which turns edges into marks.
 *
 * A camera's or a sync generator's pulse names no frame: the marks carry
 * no label, and the chase counts them (chase.h).
 */
#ifndef HAL_PULSE_H
#define HAL_PULSE_H

#include <stddef.h>
#include <stdint.h>

#include "din.h"
#include "extclk.h"

/* [init] The pulse on line `line` of din, which this takes over (closed
 * with it); name as --chase gave it. 0 and *out, or -ENOMEM with err. */
int hal_pulse_open(struct hal_extclk **out, struct hal_din *din, uint32_t line, const char *name,
		   char *err, size_t errsize);

#endif /* HAL_PULSE_H */
