/* SPDX-License-Identifier: MIT */
/*
 * rig_chase.h - the external clock `strand play --chase SPEC` names, made
 * behind hal/extclk.h:
 *
 *   ltc:DEVICE          LTC on an ALSA capture device (hw:1, hw:Loopback,1,0)
 *   ltc:sim[:K=V,...]   LTC from the simulated capture (sim/sim_ltc.h): ppm=
 *                       (the card's clock error), src_ppm=, jitter_us=,
 *                       start=HH:MM:SS:FF, volume=dBFS, begin=S, end=S
 *   gpio:CHIP:LINE      a frame pulse on a GPIO input: its rising edges,
 *                       timestamped by the kernel (the line by offset or name)
 */
#ifndef STRAND_RIG_CHASE_H
#define STRAND_RIG_CHASE_H

#include <stddef.h>
#include <stdint.h>

#include "hal/clock.h"
#include "hal/din.h"
#include "hal/extclk.h"
#include "hal/thread.h"

struct sim_ltc_cfg;

struct rig_chase_cfg {
	const char *spec;
	struct hal_clock *clk;
	uint32_t num, den;        /* the source's frame rate */
	struct hal_sched sched;   /* the reading thread's (the plan's input threads') */
	const char *gpio_sysfs;   /* NULL: /sys (tests) */
	/* tests: "ltc:sim" takes this script instead of the spec's keys,
	 * and "gpio:sim" this input device (line 0), taken over */
	const struct sim_ltc_cfg *sim;
	struct hal_din *sim_din;
};

/* [init] 0 and *out, or a negative errno with err naming the source. */
int rig_chase_open(struct hal_extclk **out, const struct rig_chase_cfg *cfg, char *err,
		   size_t errsize);

#endif /* STRAND_RIG_CHASE_H */
