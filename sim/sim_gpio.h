/* SPDX-License-Identifier: MIT */
/*
 * sim_gpio.h - a simulated GPIO chip behind the HAL digital output and input
 * interfaces.
 *
 * Output lines keep their physical level and timestamp every edge with the
 * loop's clock (the edge's tick and nanoseconds); a listener per line (the
 * simulated camera) sees each edge as it happens. Input lines change by
 * edges that are scheduled ahead at a time (tests: "the e-stop opens at
 * tick 5000"; the camera: "ready again after readout"), or injected now by
 * one other thread (a test on the wall clock) through a lock-free ring.
 *
 * Polarity is per line: active-low lines are asserted at physical 0, as an
 * e-stop chain wired normally closed or an opto-isolated trigger.
 */
#ifndef SIM_GPIO_H
#define SIM_GPIO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "hal/clock.h"
#include "hal/din.h"
#include "hal/dout.h"

/* An edge on an output line. */
struct sim_gpio_edge {
	uint32_t line;
	bool level;    /* physical level after the edge */
	bool asserted; /* logical */
	int64_t tick;  /* the tick that committed it */
	int64_t ts_ns; /* the clock when it was committed */
};

typedef void (*sim_gpio_listener)(void *ctx, const struct sim_gpio_edge *e);

struct sim_gpio;

/*
 * [init] A chip with nout output and nin input lines, timestamping with clk,
 * into *out. queue_cap bounds the input edges scheduled ahead at any one
 * time (the camera needs one per frame in flight). 0, or -ENOMEM with a
 * message in err naming the device.
 */
int sim_gpio_new(struct sim_gpio **out, const char *name, uint32_t nout, uint32_t nin,
		 struct hal_clock *clk, uint32_t queue_cap, char *err, size_t errsize);
void sim_gpio_free(struct sim_gpio *g);

/* The HAL views; closing either one is a no-op, sim_gpio_free releases. */
struct hal_dout *sim_gpio_dout(struct sim_gpio *g);
struct hal_din *sim_gpio_din(struct sim_gpio *g);

/* [init] Line polarity (default active high). */
void sim_gpio_out_polarity(struct sim_gpio *g, uint32_t line, bool active_low);
void sim_gpio_in_polarity(struct sim_gpio *g, uint32_t line, bool active_low);

/* [init] Keep every output edge in buf (up to cap; sim_gpio_edges counts
 * them all). */
void sim_gpio_record(struct sim_gpio *g, struct sim_gpio_edge *buf, uint64_t cap);
uint64_t sim_gpio_edges(const struct sim_gpio *g);

/* [init] Call fn for every edge of output line `line`. */
void sim_gpio_listen(struct sim_gpio *g, uint32_t line, sim_gpio_listener fn, void *ctx);

/* Physical level of an output line now. */
bool sim_gpio_out_level(const struct sim_gpio *g, uint32_t line);

/* [init, or the loop's own thread] Schedule an input edge at at_ns: the
 * logical level becomes `asserted`. 0, or -ENOSPC when the queue is full. */
int sim_gpio_schedule(struct sim_gpio *g, uint32_t line, int64_t at_ns, bool asserted);

/* [one other thread] The input's logical level becomes `asserted` now (the
 * next poll sees it, timestamped then). false when the ring is full. */
bool sim_gpio_inject(struct sim_gpio *g, uint32_t line, bool asserted);

#endif /* SIM_GPIO_H */
