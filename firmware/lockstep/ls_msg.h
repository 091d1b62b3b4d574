/* SPDX-License-Identifier: MIT */
/*
 * ls_msg.h - the lockstep's datagrams (lockstep.h): a small fixed message
 * set over UDP, one message a datagram, every field at a fixed place in
 * little-endian order.
 *
 *   header   magic "STRL", version, type, the sender's board index, a
 *            sequence number, and the sender's PTP clock (CLOCK_REALTIME)
 *            when it sent it
 *   HELLO    follower -> leader, until the start: the scene's digest, the
 *            ticks from its tick 0 to the first tick of play (its pre-roll
 *            and run-up), whether its PTP is locked and why not
 *   PING     leader -> follower; PONG back with the ping's clock and the
 *            follower's clock when it came: the two clocks compared, as NTP
 *            compares them (lockstep.h)
 *   START    leader -> followers: the instant, on the PTP clock, at which
 *            every board plays the scene's first tick; ACK back
 *   BEAT     every board to every other while they run
 *   STOP     any board to every other: why (refused, e-stop, fault, a
 *            stop asked for, a board lost, finished), how (at once or
 *            under control), which board it began on, and its words
 *
 * A datagram is someone else's bytes: ls_msg_decode takes only a datagram
 * of exactly its type's length, of this version, from a board of the
 * scene, with its text's length inside it and no NUL in the text; anything
 * else is -EBADMSG and dropped (and counted) by the caller. Fuzzed
 * (tests/fuzz/fuzz_board.c).
 */
#ifndef STRAND_LS_MSG_H
#define STRAND_LS_MSG_H

#include <stddef.h>
#include <stdint.h>

#define LS_MAGIC 0x4c525453u /* "STRL" */
#define LS_VERSION 1
#define LS_DIGEST 32
/* The longest text a message carries: a stop's reason, a refusal. */
#define LS_TEXT 240
/* The longest datagram. */
#define LS_MSG_MAX 320

enum ls_type {
	LS_HELLO = 1,
	LS_PING,
	LS_PONG,
	LS_START,
	LS_ACK,
	LS_BEAT,
	LS_STOP,
};

enum ls_stop_kind {
	LS_STOP_REFUSED,  /* before the start: a board cannot start */
	LS_STOP_ESTOP,    /* an e-stop: every board at once */
	LS_STOP_FAULT,    /* a device fault, a limit, a following error */
	LS_STOP_ASKED,    /* a signal, a stop input, --duration */
	LS_STOP_LOST,     /* a board's heartbeats stopped coming */
	LS_STOP_FINISHED, /* the scene's range played: not a stop at all */
	LS_STOP_KINDS,
};

struct ls_msg {
	uint8_t type;       /* enum ls_type */
	uint16_t from;      /* the sender's index in boards: */
	uint32_t seq;
	int64_t sent_ns;    /* the sender's PTP clock when it sent the message */
	union {
		struct {
			uint8_t digest[LS_DIGEST];
			int64_t need_ticks;
			uint8_t ptp_ok;
			char why[LS_TEXT]; /* PTP not locked: why */
		} hello;
		struct {
			int64_t t1, t2; /* the ping's sent_ns; the follower's clock on receipt */
		} pong;
		struct {
			int64_t play_ns; /* START, ACK: the instant play begins */
		} start;
		struct {
			int64_t tick;
			uint8_t state;
		} beat;
		struct {
			uint8_t kind;    /* enum ls_stop_kind */
			uint8_t level;   /* 1: under control, 2: at once */
			uint16_t origin; /* the board it began on */
			char text[LS_TEXT];
		} stop;
	} u;
};

/* The datagram for m in buf: its length, 0 if size is too small. */
size_t ls_msg_encode(const struct ls_msg *m, uint8_t *buf, size_t size);

/* buf (len bytes, someone else's) into m: 0, or -EBADMSG. nboards: the
 * scene's boards, which from and origin must name. */
int ls_msg_decode(struct ls_msg *m, const uint8_t *buf, size_t len, uint32_t nboards);

const char *ls_stop_kind_name(unsigned kind);

#endif /* STRAND_LS_MSG_H */
