/* SPDX-License-Identifier: MIT */
/*
 * lockstep.h - several boards playing one scene as one machine (README
 * "Several boards, one scene"). Each board runs `strand play SCENE --node
 * NAME`: its own loop on its own devices (the scene's boards: section says
 * which), all of them evaluating the same scene, so that their ticks line
 * up by construction once they agree on one instant. The clocks are
 * linuxptp's (ptp4l, phc2sys): this file adds no clock protocol, only a
 * start and a watch, over UDP (ls_msg.h).
 *
 * The start (ls_join, before the loop runs; blocking):
 *   every board asks its ptp4l whether it is locked (ls_ptp.h);
 *   each follower sends HELLO to the leader (the scene's digest, the ticks
 *     its pre-roll and run-up take, its PTP state) until the leader starts
 *     or refuses;
 *   the leader refuses, telling every board why, when a digest differs
 *     (two boards loaded different scenes), a board's PTP is not locked, a
 *     board did not come up within join_ms, or the clocks disagree: it
 *     compares its clock with each follower's by PING and PONG, as NTP does
 *     (offset = ((t2 - t1) + (t3 - t4)) / 2, the least delayed of eight
 *     exchanges), and refuses beyond max_offset_us;
 *   else it proposes the instant at which every board plays the scene's
 *     first tick: now on the PTP clock, plus the longest pre-roll, plus
 *     start_ms (START); every board turns it into CLOCK_MONOTONIC (the PTP
 *     clock is CLOCK_REALTIME: linuxptp sets it, from its own software
 *     timestamps or through phc2sys from a NIC's clock) and starts its tick
 *     0 its own pre-roll earlier; a board for which that is already past
 *     refuses, telling every board; each confirms (ACK).
 *
 * The watch (a thread, strand-board, while the loops run): every board
 * sends every other a heartbeat each heartbeat_ms and a STOP when its own
 * run stops, saying why in its own words; a board that hears a STOP stops
 * too (an e-stop at once, anything else under control) and passes the
 * STOP on; a board that hears nothing from another for lost_ms stops under
 * control, naming it. So no board goes on alone.
 *
 * [init] but for the hooks, which the board thread calls.
 */
#ifndef STRAND_LOCKSTEP_H
#define STRAND_LOCKSTEP_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "hal/cancel.h"
#include "hal/thread.h"
#include "ls_msg.h"

struct ls_board {
	const char *name;
	const char *address; /* an IP address or a host name */
	uint32_t port;
};

struct ls_cfg {
	uint32_t nboards, self, lead;
	const struct ls_board *boards; /* nboards; kept, not copied */
	uint8_t digest[LS_DIGEST];     /* the scene file's SHA-256 */
	uint32_t tick_hz;
	int64_t need_ticks;            /* this board's ticks from tick 0 to the first of play */
	double start_ms, heartbeat_ms, lost_ms, join_ms, max_offset_us, ptp_offset_ns;
	const char *ptp_socket;        /* ptp4l's uds_address */
	bool ptp_free_running;         /* ls_ptp.h */
	const struct hal_cancel *cancel; /* a signal gives the start up */
	struct hal_sched sched;        /* the board thread's */
	FILE *log;                     /* what the start does, a line at a time; NULL: quiet */
};

/* What the board thread asks of the run and does to it. */
struct ls_hooks {
	void *ctx;
	/* How the local run is ending: -1 while it plays on; -2 when it stops
	 * because another board said so (nothing to tell); else an enum
	 * ls_stop_kind, with *level (1 under control, 2 at once) and the
	 * words in text. */
	int (*local_end)(void *ctx, int *level, char *text, size_t size);
	/* Stop the local run because of another board. */
	void (*stop)(void *ctx, int level, int kind);
	/* The local loop has run its last tick. */
	bool (*ended)(void *ctx);
};

struct ls_stats {
	int64_t play_ns;        /* the instant play began, on the PTP clock */
	int64_t t0_ns;          /* this board's tick 0, CLOCK_MONOTONIC */
	double offset_us_max;   /* the leader: the largest clock offset measured */
	uint32_t offset_board;  /* ... of that board */
	double delay_us_max;    /* ... and the largest round trip behind the offsets */
	int64_t beats_sent, beats_got;
	int64_t dropped;        /* datagrams refused by ls_msg_decode or from a stranger */
	int64_t beat_gap_max_ns; /* the longest wait for another board's heartbeat */
};

struct lockstep;

/* The socket, bound to this board's address and port, and the others'
 * addresses. 0 or a negative errno with err. */
int ls_open(struct lockstep **out, const struct ls_cfg *cfg, char *err, size_t errsize);

/* The start (above): 0 and this board's tick 0 on CLOCK_MONOTONIC, or a
 * negative errno with err, every other board told: -EPERM a refusal,
 * -ETIMEDOUT a board not heard from, -ECANCELED a signal. */
int ls_join(struct lockstep *s, int64_t *t0_ns, char *err, size_t errsize);

/* The watch, on its thread, until ls_close. 0 or a negative errno. */
int ls_watch(struct lockstep *s, const struct ls_hooks *h);

/* Why another board stopped this run ("board 'b': e-stop: ..."), and how
 * (*level); NULL when none did. Once the run has ended. */
const char *ls_stop_reason(const struct lockstep *s, int *level);

void ls_stats(const struct lockstep *s, struct ls_stats *st);

/* Stop the watch (after telling the others how the run ended), close. */
void ls_close(struct lockstep *s);

#endif /* STRAND_LOCKSTEP_H */
