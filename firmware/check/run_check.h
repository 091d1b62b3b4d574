/* SPDX-License-Identifier: MIT */
/*
 * run_check.h - the check that `strand check` prints and that `strand play`
 * and a live session (live/live.h: a move, a play) make before anything
 * moves: the same channels, the same run, the same walk (limit_check.h),
 * so that they refuse exactly the scenes check rejects, for the same first
 * reason.
 */
#ifndef STRAND_CHECK_RUN_CHECK_H
#define STRAND_CHECK_RUN_CHECK_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "limit_check.h"
#include "rig/rig_desc.h"
#include "scene/source_scene.h"

struct run_check {
	struct lim_channel *ch;     /* the channels checked */
	uint32_t n;
	struct lim_result res;
	struct lim_violation first; /* the first violation reported, when res.violations */
	FILE *out;                  /* every violation's line goes there, or NULL */
};

/* The run's options against each other (as strand play's and a live
 * play's options give them): 0, or -EINVAL with the reason in msg
 * ("--ping-pong needs at least two frames"). */
int run_check_options(const struct lim_run *r, char *msg, size_t size);

/* Go-motion's shutter (plan/gomo.h) against the scene's timing: every
 * exposure must hold two ticks. 0, or -EINVAL with the reason in msg. */
int run_check_shutter(const struct mot_timing *t, mot_q32 s, char *msg, size_t size);

/* [init] The run over ss (the rig: its outputs and triggers, NULL: none)
 * into c; run's lead and tail are set from the rig's triggers. 0, or a
 * negative errno (-ENOMEM; -ENOENT: an output's channel is not the
 * scene's). c->ch is the caller's to free with run_check_free. */
int run_check(struct run_check *c, struct source_scene *ss, const struct rig_desc *rig,
	      struct lim_run *run);
void run_check_free(struct run_check *c);

/* A violation as one line of strand check, without the newline:
 * "base.angle: velocity 120 deg/s beyond limit 90 deg/s, frames 48.024 to 72". */
void run_check_line(char *buf, size_t size, const struct run_check *c,
		    const struct lim_violation *v);

/* The number of channels with limits (strand check's summary). */
uint32_t run_check_count(const struct run_check *c);

#endif /* STRAND_CHECK_RUN_CHECK_H */
