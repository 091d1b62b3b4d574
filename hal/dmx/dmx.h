/* SPDX-License-Identifier: MIT */
/*
 * dmx.h - lights (and anything else on DMX512) behind the HAL axis
 * interface: universes of 512 slots sent over UDP as E1.31 (sACN, ANSI
 * E1.31-2016) or Art-Net (ArtDmx, Art-Net 4), at the DMX refresh rate.
 *
 * A device is a set of universes sent to one destination the scene names
 * (a unicast address, a multicast group, or `multicast`: each universe to
 * its own sACN group 239.255.hi.lo); never to a default of strand's
 * choosing. Its channels are slots: channel c is slot c % 512 of the
 * device's universe c / 512 (its index in the list), an 8-bit value, or the
 * first of two for a 16-bit one (coarse then fine, as fixtures take them).
 * The setpoint of a channel is its value in counts (0 to 255, 0 to 65535);
 * one that does not fit is never sent clipped or wrapped: the device
 * faults, naming the slot.
 *
 * The socket is the I/O thread's, strand-dmx-DEVICE, scheduled as cfg.sched
 * says, never the loop's (sendto on a full socket buffer, a route being
 * resolved, may block):
 *
 *   strand-rt                          DMX I/O thread
 *   set() stages counts
 *   commit() every `every` ticks
 *     writes the universes' images --slot(newest wins)--> one packet a
 *     and wakes the thread                              universe, in order
 *   input() <------------- atomics: frames sent, a send error --
 *   disable() --- atomic: terminate -------------------> sACN's stream
 *                                                        terminated, 3 times
 *
 * It also resends the last frame every second when nothing new comes (a
 * receiver forgets a silent sACN source after 2.5 s). On the virtual clock
 * (lockstep) input() waits for each frame to be sent, so a run sends the
 * same frames every time, one for each update tick.
 */
#ifndef HAL_DMX_H
#define HAL_DMX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hal/axis.h"
#include "hal/thread.h"

#define DMX_SLOTS 512
#define DMX_UNIVERSES_MAX 64
#define DMX_E131_PORT 5568
#define DMX_ARTNET_PORT 6454
#define DMX_E131_UNIVERSE_MAX 63999
#define DMX_ARTNET_UNIVERSE_MAX 32767
#define DMX_REFRESH_DEFAULT 44.0 /* 512 slots at DMX512's 250 kbit/s */
#define DMX_REFRESH_MAX 1000.0

enum dmx_protocol {
	DMX_E131,
	DMX_ARTNET,
};

/* A device's settings (the scene's `dmx:` section). */
struct dmx_desc {
	enum dmx_protocol protocol;
	const char *destination;   /* an address, or "multicast" (sACN: each universe's group) */
	uint16_t port;             /* 0: the protocol's */
	const char *interface;     /* the local address multicast leaves from; NULL: the route's */
	uint32_t ttl;              /* multicast hops (default 1: the local network) */
	double refresh_hz;
	uint32_t nuniverses;
	const uint16_t *universes; /* sACN universe, or Art-Net port-address */
	uint8_t priority;          /* sACN, 0 to 200 */
	const char *source_name;   /* sACN */
	bool has_tick_slot;        /* the loop's tick, 4 slots big-endian (a test's clock) */
	uint32_t tick_slot;        /* its first slot, as a channel: universe index * 512 + slot */
};

/* One channel: used by an output, and its width. */
struct dmx_chan {
	bool used;
	uint8_t bits; /* 8 or 16 */
};

struct dmx_cfg {
	const char *name;            /* the device's name (kept) */
	const struct dmx_desc *d;    /* kept */
	uint32_t tick_hz;
	uint32_t nch;                /* channels: nuniverses * 512 at most */
	const struct dmx_chan *chan; /* nch */
	const int64_t *initial;      /* nch: counts before the first commit */
	bool lockstep;
	struct hal_sched sched;      /* the I/O thread's */
};

/* Ticks between frames at the device's refresh rate: ceil(tick_hz / hz). */
uint32_t dmx_every(const struct dmx_desc *d, uint32_t tick_hz);

/* [init] The backend; start() opens the socket and sends the first frame.
 * 0, or a negative errno with a message naming the device. */
int hal_dmx_open(struct hal_axis **out, const struct dmx_cfg *c, char *err, size_t errsize);

/* [init] A line for the run's summary. */
void hal_dmx_report(struct hal_axis *ax, FILE *f);

/* ---- packets (dmx_pkt.c), pure ----------------------------------------------------- */

#define DMX_E131_HEADER 126
#define DMX_E131_MAX (DMX_E131_HEADER + DMX_SLOTS)
#define DMX_ARTNET_HEADER 18
#define DMX_ARTNET_MAX (DMX_ARTNET_HEADER + DMX_SLOTS)
#define DMX_E131_TERMINATED 0x40

/* An E1.31 data packet of n slots (1 to 512) into buf (DMX_E131_MAX
 * bytes): its length. */
size_t dmx_e131_packet(uint8_t *buf, const uint8_t cid[16], const char *source, uint8_t priority,
		       uint8_t seq, uint8_t options, uint16_t universe, const uint8_t *slots,
		       uint16_t n);

/* An ArtDmx packet of n slots (rounded up to even, 2 to 512): its length. */
size_t dmx_artnet_packet(uint8_t *buf, uint8_t seq, uint16_t port_address, const uint8_t *slots,
			 uint16_t n);

/* A stable component identifier for a sender: a version 4 style UUID made
 * from its name (the same name, the same CID, run after run, as a receiver
 * wants of one source). */
void dmx_cid(uint8_t cid[16], const char *name);

#endif /* HAL_DMX_H */
