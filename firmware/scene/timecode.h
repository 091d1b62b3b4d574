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

/* The frame number of the label hh:mm:ss:ff (the inverse of
 * timecode_format within a day), or -1 when it is no label of these rules:
 * a field out of range, or a label drop-frame skips (00:01:00;00). */
int64_t timecode_frame(const struct timecode *tc, uint32_t hh, uint32_t mm, uint32_t ss,
		       uint32_t ff);

/* Frames in a day of these rules (the labels a day counts). */
int64_t timecode_day(const struct timecode *tc);

/* "HH:MM:SS:FF" (or with ';' or '.' before the frames) into its frame
 * number: 0, or -EINVAL when it is not a label of these rules. */
int timecode_parse(const struct timecode *tc, const char *s, int64_t *frame);

#endif /* STRAND_TIMECODE_H */
