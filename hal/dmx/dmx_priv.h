/* SPDX-License-Identifier: MIT */
/*
 * dmx_priv.h - what the loop's side of a DMX device (dmx_axis.c) and its
 * I/O thread (dmx_io.c) share. Fields under "rt" are the loop's, under
 * "io" the thread's; they meet in the slot, the semaphore and the atomics.
 */
#ifndef HAL_DMX_PRIV_H
#define HAL_DMX_PRIV_H

#include <netinet/in.h>
#include <semaphore.h>
#include <stdatomic.h>

#include "dmx.h"
#include "hal/rt.h"
#include "hal/slot.h"
#include "hal/thread.h"

/* One frame: the loop's tick and every universe's 512 slots. */
struct dmx_frame {
	int64_t tick;
	uint8_t img[][DMX_SLOTS];
};

#define DMX_TEXT 256
#define DMX_IDLE_NS 1000000000LL /* resend the last frame after this long */

struct dmx_drv {
	struct hal_axis ax;         /* first: the HAL view */
	struct dmx_cfg c;
	const struct dmx_desc *d;
	uint32_t every;
	uint32_t nu;                /* universes */
	struct dmx_chan *chan;      /* nch */
	char where[160];            /* "sACN to 239.255.0.1:5568" */

	/* rt */
	int64_t *staged;            /* nch */
	struct hal_fault fault;
	bool disabled;
	int64_t published;          /* the last frame's tick, -1: none */
	int64_t frames;             /* published */
	int64_t replaced;           /* ... replaced before the thread sent them */
	char **chan_text;           /* nch (used ones): the fault's text when out of range */

	struct hal_slot slot;
	void *slot_buf;
	uint32_t frame_size;
	sem_t wake;
	bool wake_ready;
	_Atomic bool quit, terminate;
	_Atomic int64_t sent_tick;  /* the newest frame's tick the thread sent */
	_Atomic int io_error;       /* a send's negative errno; io_text written first */
	char io_text[DMX_TEXT];
	struct hal_thread thread;

	/* io */
	int fd;
	struct sockaddr_in dest[DMX_UNIVERSES_MAX];
	uint8_t cid[16];
	uint8_t seq[DMX_UNIVERSES_MAX];
	struct dmx_frame *last;     /* the frame sent last (a copy) */
	bool have_last;
	uint8_t pkt[DMX_E131_MAX];
	int64_t sent, packets, errors, resends;
};

static inline struct dmx_drv *dmx_of(struct hal_axis *ax)
{
	return (struct dmx_drv *)ax;
}

/* The thread (dmx_io.c). */
void *dmx_io_main(void *arg);
/* Send one frame's universes now (the start's and the stop's; the thread's
 * on its own side). options: sACN's (DMX_E131_TERMINATED). 0 or -errno. */
int dmx_io_send(struct dmx_drv *m, const struct dmx_frame *f, uint8_t options);
/* The socket and the destinations; 0 or -errno with m->io_text. */
int dmx_io_open(struct dmx_drv *m);
void dmx_io_close(struct dmx_drv *m);

#endif /* HAL_DMX_PRIV_H */
