/* SPDX-License-Identifier: MIT */
/*
 * frames.h - the frames step mode shoots, from the command line:
 *
 *     --frames 0..240          a range (either direction: 240..0)
 *     --frames 1,5,9,20..24    a list of frames and ranges
 *     --frames 12x5            frame 12 shot five times (a reshoot)
 *     --frames 0..10x2         each frame of a range twice
 *
 * Parsing allocates the item array once; iterating is [rt].
 */
#ifndef STRAND_FRAMES_H
#define STRAND_FRAMES_H

#include <stdbool.h>
#include <stdint.h>

struct frame_item {
	int64_t first, last; /* inclusive; last < first runs backwards */
	int64_t repeat;      /* shots of each frame, >= 1 */
};

struct frame_list {
	struct frame_item *items;
	uint32_t n;
};

struct frame_iter {
	uint32_t item;
	int64_t frame;
	int64_t shot;
	bool started;
};

/* Parse spec: 0, or -EINVAL with a message in err (what and where). */
int frames_parse(struct frame_list *fl, const char *spec, char *err, unsigned errsize);
/* One item first..last (the default: the scene's span). */
int frames_range(struct frame_list *fl, int64_t first, int64_t last);
void frames_free(struct frame_list *fl);

/* The lowest and the highest frame the list shoots (0 when empty). */
int64_t frames_min(const struct frame_list *fl);
int64_t frames_max(const struct frame_list *fl);

/* Shots in the whole list; INT64_MAX when there are more. */
int64_t frames_count(const struct frame_list *fl);

/* The next frame to shoot: true and *frame, or false at the end. [rt] */
bool frames_next(const struct frame_list *fl, struct frame_iter *it, int64_t *frame);

#endif /* STRAND_FRAMES_H */
