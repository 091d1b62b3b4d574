/* SPDX-License-Identifier: MIT */
/*
 * yedit.h - a scene file's keys edited in place: the text is changed only
 * where a key is, so its comments, order and layout stay as they were
 * written. libyaml's positions of the nodes (byte offsets) say where:
 *
 *   set     a key's value at a frame: the value's scalar is rewritten in
 *           place; a new key goes between its neighbours in frame order, in
 *           the style of the keys around it (a line "- {frame: F, angle: V}"
 *           at their indentation, or an item of a flow sequence); a strand
 *           the node does not have yet is added at the end of strands:
 *   delete  the key's item (its lines, or its item and comma)
 *   move    the key's frame rewritten, when it stays between its neighbours
 *
 * Each takes the text and returns a new one (malloc'd) or a negative errno
 * with a message; the caller checks what it made by loading it.
 */
#ifndef STRAND_YEDIT_H
#define STRAND_YEDIT_H

#include <stddef.h>

/* field: "angle" or "position". */
int yedit_key_set(const char *text, size_t len, const char *node, const char *field,
		  double frame, double value, char **out, size_t *outlen, char *err,
		  size_t errsize);
/* The same with the value as YAML text ("[1, 1.5, 3]" for a camera's eye);
 * node "camera": the camera's keys. A field's value in place is a scalar or
 * a flow sequence. */
int yedit_key_set_text(const char *text, size_t len, const char *node, const char *field,
		       double frame, const char *value, char **out, size_t *outlen, char *err,
		       size_t errsize);
int yedit_key_delete(const char *text, size_t len, const char *node, double frame, char **out,
		     size_t *outlen, char *err, size_t errsize);
int yedit_key_move(const char *text, size_t len, const char *node, double from, double to,
		   char **out, size_t *outlen, char *err, size_t errsize);

#endif /* STRAND_YEDIT_H */
