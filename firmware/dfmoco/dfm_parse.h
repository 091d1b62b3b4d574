/* SPDX-License-Identifier: MIT */
/*
 * dfm_parse.h - one line of DFMoco, the ASCII protocol Dragonframe's Arc
 * workspace speaks to a motion controller it does not make itself
 * (Dragonframe's DFMoco Arduino sketch is its reference implementation).
 *
 * A line is a command of two lowercase letters and its whole-number
 * arguments, separated by spaces, ended by "\r\n" (a lone "\n" is taken
 * too). Dragonframe sends, with the arguments each takes:
 *
 *     hi                  hello: the controller says its version and motors
 *     ms                  which motors are moving
 *     mm M P              move motor M to position P
 *     mp M                where motor M is
 *     sm M                stop motor M
 *     sa                  stop all
 *     pr M R              motor M's top speed, R positions a second
 *     zm M                motor M's position is now 0 (nothing moves)
 *     np M P              motor M's position is now P (nothing moves)
 *     jm M P              jog motor M towards P (repeated while held)
 *     im M P              inch motor M a step towards P
 *     bf E B M P0 P1 P2 ...  go-motion: E ms of exposure, blur B in
 *                         thousandths, and for each motor M its positions
 *                         at the previous frame, this one and the next
 *     go                  run the go-motion bf prepared
 *
 * Motors count from 1; positions are whole steps (a strand output's
 * counts). dfm_parse checks only the line: the command, the number of
 * arguments, each a number within 32 bits (the sketch's int32_t). Whether
 * a motor exists is the session's to say (dfm_session.h).
 */
#ifndef STRAND_DFM_PARSE_H
#define STRAND_DFM_PARSE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* Arguments a line may carry: bf for 32 motors (LOOP_LIVE_OUT_MAX). */
#define DFM_ARGS_MAX (2 + 4 * 32)
/* The longest line taken, its end included: every argument at its widest. */
#define DFM_LINE_MAX (3 + DFM_ARGS_MAX * 12 + 2)

enum dfm_kind {
	DFM_HI, DFM_MS, DFM_MM, DFM_MP, DFM_SM, DFM_SA, DFM_PR, DFM_ZM, DFM_NP, DFM_JM,
	DFM_IM, DFM_BF, DFM_GO, DFM_NKINDS,
};

struct dfm_cmd {
	enum dfm_kind kind;
	uint32_t nargs;
	int32_t arg[DFM_ARGS_MAX];
};

/*
 * line[0..len) without its end ("\r\n" or "\n" already cut off) into *c:
 * 0, or -EINVAL with why in msg (an unknown command, too few or too many
 * arguments, a word that is not a number, a number beyond 32 bits,
 * -E2BIG for a line longer than DFM_LINE_MAX). Pure: no I/O, no state.
 */
int dfm_parse(const char *line, size_t len, struct dfm_cmd *c, char *msg, size_t size);

/* "hi", "ms", ... */
const char *dfm_name(enum dfm_kind k);

/* Line assembly: bytes in, whole lines out. */
struct dfm_lines {
	char buf[DFM_LINE_MAX + 1];
	size_t len;
	bool overlong; /* the present line outgrew buf: dropped to its end */
};

/* Feed n bytes; fn(ctx, line, len, overlong) for each line ended by "\n"
 * (a "\r" before it cut off; an empty line is none); an over-long line is
 * given once, at its end, with overlong set and what was kept of it. */
void dfm_lines_feed(struct dfm_lines *l, const char *in, size_t n,
		    void (*fn)(void *ctx, const char *line, size_t len, bool overlong),
		    void *ctx);

#endif /* STRAND_DFM_PARSE_H */
