/* SPDX-License-Identifier: MIT */
/*
 * strand_play.c - `strand play` and `strand journal` until the strand
 * command's dispatcher and the YAML loader are on main: SCENE is a scene
 * built in code, synth:robot_arm[:FRAMES] or synth:random:SEED:NODES, on a
 * simulated rig. Once the loader lands, firmware/main.c dispatches to
 * play_main() with the YAML loader and this file goes away.
 *
 *   strand-play play synth:robot_arm --sim
 *   strand-play journal FILE
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exitcode.h"
#include "play_cli.h"
#include "synth.h"

static void release(struct play_scene *ps)
{
	synth_free(ps->ctx);
	free(ps->ctx);
}

static int load_synth(const char *path, struct play_scene *out, char *err, size_t size)
{
	struct synth *s = calloc(1, sizeof(*s));
	unsigned long long seed;
	unsigned n;
	double frames = 240;

	if (!s)
		return -ENOMEM;
	if (!strncmp(path, "synth:robot_arm", 15) &&
	    (path[15] == '\0' || sscanf(path + 15, ":%lf", &frames) == 1)) {
		synth_robot_arm(s, 1.0, frames);
		s->d.name = "robot-arm";
	} else if (sscanf(path, "synth:random:%llu:%u", &seed, &n) == 2 && n > 0) {
		synth_random(s, seed, n, frames);
		s->d.name = "random";
	} else {
		free(s);
		snprintf(err, size, "%s:0:0: not a scene this build can read: "
			 "synth:robot_arm[:FRAMES] or synth:random:SEED:NODES", path);
		return -EINVAL;
	}
	out->path = path;
	out->desc = &s->d;
	out->rig = NULL;
	out->ctx = s;
	out->release = release;
	return 0;
}

int main(int argc, char **argv)
{
	if (argc >= 2 && !strcmp(argv[1], "play"))
		return play_main(argc - 1, argv + 1, load_synth, NULL);
	if (argc >= 2 && !strcmp(argv[1], "journal"))
		return journal_main(argc - 1, argv + 1);
	fprintf(stderr, "usage: strand-play play SCENE [options] | journal FILE\n");
	return STRAND_EXIT_USAGE;
}
