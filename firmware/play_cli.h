/* SPDX-License-Identifier: MIT */
/*
 * play_cli.h - the `strand play` and `strand journal` subcommands: options,
 * signals, the messages at the edge and the exit codes (exitcode.h).
 *
 * The scene file reaches them through a loader callback, so that the
 * command does not depend on how scenes are read (the YAML loader, or the
 * scenes built in code that stand in for files until it exists).
 */
#ifndef STRAND_PLAY_CLI_H
#define STRAND_PLAY_CLI_H

#include <stddef.h>

#include "rig_desc.h"
#include "scene_desc.h"

/* A loaded scene. The loader owns everything; release() frees it. */
struct play_scene {
	const char *path;
	const struct scene_desc *desc;
	const struct rig_desc *rig; /* its devices:/outputs:/...; NULL or empty: none */
	void *ctx;
	void (*release)(struct play_scene *ps);
};

/* Load path: 0, or a negative errno with the message in err, already in
 * the form `file:line:column: message`. */
typedef int (*play_load_fn)(const char *path, struct play_scene *out, char *err, size_t size);

/* What `strand check` says of the scene: 0 clean, > 0 violations (printed
 * already), < 0 error. NULL: no check wired in. */
typedef int (*play_check_fn)(const struct play_scene *ps);

int play_main(int argc, char **argv, play_load_fn load, play_check_fn check);
int journal_main(int argc, char **argv);

#endif /* STRAND_PLAY_CLI_H */
