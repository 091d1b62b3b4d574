/* SPDX-License-Identifier: MIT */
/*
 * dfm_session.h - strand as a DFMoco motion controller: Dragonframe's lines
 * (dfm_parse.h) turned into a live session's commands (live/live.h), and
 * the replies Dragonframe waits for. The session never touches the loop:
 * every motion goes through live.h, so it obeys the outputs' limits and the
 * machine states as a console's does, and a move the limits forbid is
 * refused, never clamped.
 *
 * Motors are the scene's outputs in the order they are written, numbered
 * from 1; a position is its output's device counts, less the zero that zm
 * and np set (they move nothing: Dragonframe's numbering shifts, the
 * limits stay where the rig's are). Replies (the sketch's words, each line
 * ended by "\r\n"):
 *
 *     hi             hi 1 N 1.3.1 (protocol 1, N motors)
 *     ms             ms followed by one 0 or 1 per motor (1: moving)
 *     mm M P         mm M P, then mp M X lines while it moves; mp M P
 *                    when it is there already
 *     mp M           mp M X
 *     sm M           sm M, mp M X
 *     sa             sa
 *     pr M R         pr M R' (R' the speed it will jog at: R, at most the
 *                    output's velocity limit)
 *     zm M, np M P   zm M / np M P (the protocol document's), then mp M 0 /
 *                    mp M P (the sketch's)
 *     jm M P, im M P jm M / im M
 *     bf E B ...     bf D: D ms from go to the exposure, or bf -1 when the
 *                    limits forbid the motion (the sketch's "speed cannot
 *                    be reached")
 *     go             go
 *
 * A line that is not the protocol's, names a motor that does not exist or
 * carries a number out of range gets the sketch's error reply, "parse
 * error", and changes nothing. A command the rig refuses (a position
 * beyond a limit, the rig not at rest, e-stopped) gets a line saying why,
 * "error: ...", the sketch's form, and then the protocol's reply that keeps
 * Dragonframe's picture true (where the motor is, bf -1, parse error). An
 * e-stop or a fault is said as it happens ("error: e-stop: ..."), with every
 * motor's position; a new hi resets it once the e-stop input is released.
 *
 * Not thread-safe: one thread feeds input and takes output.
 */
#ifndef STRAND_DFM_SESSION_H
#define STRAND_DFM_SESSION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "dfm_parse.h"
#include "live/live.h"

/* Replies waiting for the port, at most: a client that reads none of them
 * loses the oldest (dfm_session_output). */
#define DFM_OUT_MAX 65536
/* While motors move, their positions are said this often. */
#define DFM_REPORT_NS 100000000

struct dfm_session {
	struct live *lv;
	FILE *log;              /* what was refused and why, or NULL */
	uint32_t n;             /* motors */
	struct live_out_info info[LOOP_LIVE_OUT_MAX];
	int64_t zero[LOOP_LIVE_OUT_MAX];   /* device counts at DFMoco's 0 */
	int64_t want[LOOP_LIVE_OUT_MAX];   /* device counts to move to ... */
	bool has_want[LOOP_LIVE_OUT_MAX];  /* ... when at rest */
	bool involved[LOOP_LIVE_OUT_MAX];  /* in the motion under way */
	bool was_moving[LOOP_LIVE_OUT_MAX];
	double jog[LOOP_LIVE_OUT_MAX];     /* jm's speed, a fraction of vmax (pr) */
	uint64_t jog_seq;
	int64_t shots;          /* go-motion frames run: the next bf's is shots + 1 */
	bool gomo_ready;        /* a bf accepted, its go awaited */
	bool gomo_still;        /* ... with blur 0: nothing moves */
	bool move_sent;         /* a move for the wants was sent */
	uint64_t busy_seq;      /* the last command that moves: until a sample at
				 * rest has seen it, its motors are moving */
	int64_t gather_ns;      /* the last mm: its neighbours join its move */
	enum live_state last_state;
	int64_t report_ns;
	struct live_snap snap;
	struct dfm_lines lines;
	char out[DFM_OUT_MAX];
	size_t out_len;
	uint64_t dropped;       /* output bytes no one read */
};

/* [init] A session on lv (open, its drives enabled or not). 0. */
int dfm_session_init(struct dfm_session *s, struct live *lv, FILE *log);

/* Bytes from the port. */
void dfm_session_input(struct dfm_session *s, const char *in, size_t n);

/* One line, its end cut off. */
void dfm_session_line(struct dfm_session *s, const char *line, size_t len, bool overlong);

/* The session's round, every few milliseconds: the live session's service,
 * a move waiting for the rig to rest, the positions of moving motors, an
 * e-stop or fault said. now: CLOCK_MONOTONIC ns. */
void dfm_session_tick(struct dfm_session *s, int64_t now_ns);

/* Output waiting for the port, and how much of it went. */
const char *dfm_session_output(const struct dfm_session *s, size_t *len);
void dfm_session_consumed(struct dfm_session *s, size_t n);

#endif /* STRAND_DFM_SESSION_H */
