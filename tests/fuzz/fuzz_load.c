/* SPDX-License-Identifier: MIT */
/*
 * fuzz_load.c - libFuzzer target: any bytes through the scene loader, the
 * builder and a few evaluations. A valid scene must build and evaluate; an
 * invalid one must be one positioned message. Never a crash, a leak or a
 * sanitizer report (`make fuzz`, and a short pass in `make test`).
 */
#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "load/load.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void evaluate(const struct scene_file *sf, const struct scene_built *b)
{
	struct mot_eval ev;
	struct mot_pose pose;
	int i;

	if (scene_eval_new(&ev, &b->sc))
		return;
	if (scene_pose_new(&pose, &b->sc)) {
		scene_eval_free(&ev);
		return;
	}
	/* a handful of frames across the span and around it */
	for (i = -1; i <= 8; i++) {
		double f = sf->desc.frame_first + (sf->desc.frame_last - sf->desc.frame_first) * i / 8;

		mot_scene_eval(&b->sc, &ev, (mot_q32)(f * 4294967296.0), &pose);
	}
	scene_pose_free(&pose);
	scene_eval_free(&ev);
}

/*
 * The work a build of the scene's systems and aims takes: item-steps over
 * the span, and the aims' march. A valid scene of a billion item-steps
 * builds in minutes, which is a long computation, not a bug; past a
 * budget the fuzzer leaves such a scene unbuilt so that one input stays
 * within its time limit (-timeout=10, under the sanitizers).
 */
static bool too_long(const struct scene_desc *d)
{
	double secs = (d->frame_last - d->frame_first) * d->rate_den / (double)d->rate_num, work = 0;
	uint32_t i;

	for (i = 0; i < d->nsys; i++) {
		const struct sd_system *s = &d->sys[i];
		double hz = s->kind == SD_PARTICLES ? (double)s->particles->rate_num / s->particles->rate_den :
			    s->kind == SD_FLOCK ? (double)s->flock->rate_num / s->flock->rate_den : 0;

		work += sd_sys_items(s) * (hz * secs + 1) * (s->kind == SD_FLOCK ? 8 : 1);
	}
	for (i = 0; i < d->naims; i++)
		work += (d->frame_last - d->frame_first + 1) * 4.0 * d->aims[i].sub * (d->nsys + 1) *
			64;
	return work > 2e6;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct scene_file sf;
	struct scene_built b;
	struct load_err e;

	if (scene_file_parse(&sf, "fuzz.yaml", (const char *)data, size, &e)) {
		/* every scene error has a position and a message */
		if ((e.code == -EINVAL || e.code == -ERANGE || e.code == -EBADMSG) &&
		    (e.line == 0 || !e.msg[0]))
			abort();
		return 0;
	}
	if (too_long(&sf.desc)) {
		scene_file_free(&sf);
		return 0;
	}
	if (!scene_file_build(&sf, &b, &e)) {
		evaluate(&sf, &b);
		scene_built_free(&b);
	} else if (!e.msg[0]) {
		abort();
	}
	scene_file_free(&sf);
	return 0;
}
