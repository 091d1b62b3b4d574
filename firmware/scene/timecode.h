/* SPDX-License-Identifier: MIT */
/*
 * timecode.h - SMPTE timecode of a frame number (SMPTE ST 12-1).
 *
 * The nominal rate is the frame rate rounded to an integer (24000/1001 ->
 * 24, 30000/1001 -> 30). At 30000/1001 and 60000/1001 the timecode is
 * drop-frame: labels 00 and 01 (00-03 at 60) are skipped at the start of
 * every minute except each tenth, so that the timecode stays within 2 frames
 * of the wall clock; it is written with ';' before the frames. Any other
 * rate counts every label (non-drop, ':'). Hours wrap at 24.
 */
#ifndef STRAND_TIMECODE_H
#define STRAND_TIMECODE_H

#include <stdbool.h>
#include <stdint.h>

struct timecode {
	uint32_t nominal; /* labels per second */
	uint32_t drop;    /* labels dropped per minute (0, 2 or 4) */
};

/* The timecode rules of a frame rate num/den frames per second. */
void timecode_init(struct timecode *tc, uint32_t num, uint32_t den);

/* "HH:MM:SS:FF" (or ';' when drop-frame) of frame f >= 0 into buf (>= 12
 * bytes). Negative frames are written as "-" and the timecode of -f. */
void timecode_format(const struct timecode *tc, int64_t f, char *buf, unsigned size);

#endif /* STRAND_TIMECODE_H */
