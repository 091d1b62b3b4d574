/* SPDX-License-Identifier: MIT */
/*
 * limits.h - the check that `strand check` prints and that `strand play`
 * makes before anything moves: the same channels, the same run, the same
 * walk (check/limit_check.h), so that play refuses exactly the scenes
 * check rejects, for the same first reason.
 */
#ifndef STRAND_CLI_LIMITS_H
#define STRAND_CLI_LIMITS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "check/limit_check.h"
#include "rig/rig_desc.h"
#include "scene/source_scene.h"

struct cli_limits {
	struct lim_channel *ch;     /* the channels checked */
	uint32_t n;
	struct lim_result res;
	struct lim_violation first; /* the first violation reported, when res.violations */
	FILE *out;                  /* every violation's line goes there, or NULL */
};

struct cli_cmd;

/* The run's options against each other: -1 when they agree, else the
 * usage error's exit code, said on err. */
int cli_limits_usage(const struct cli_cmd *cmd, FILE *err, const struct lim_run *r);

/* --shutter ANGLE (degrees, 0 < ANGLE <= 360) into *s, the fraction of a
 * frame go-motion exposes (plan/gomo.h): -1, or the usage error's exit
 * code, said on err. */
int cli_shutter_arg(const struct cli_cmd *cmd, FILE *err, const char *arg, mot_q32 *s);

/* The shutter against the scene's timing: every exposure must hold two
 * ticks. -1, or the usage error's exit code. */
int cli_shutter_usage(const struct cli_cmd *cmd, FILE *err, const struct mot_timing *t,
		      mot_q32 s);

/* [init] The run over ss (the rig: its outputs and triggers, NULL: none)
 * into c; run's lead and tail are set from the rig's triggers. 0, or a
 * negative errno (-ENOMEM; -ENOENT: an output's channel is not the
 * scene's). c->ch is the caller's to free with cli_limits_free. */
int cli_limits_run(struct cli_limits *c, struct source_scene *ss, const struct rig_desc *rig,
		   struct lim_run *run);
void cli_limits_free(struct cli_limits *c);

/* A violation as one line of strand check, without the newline:
 * "base.angle: velocity 120 deg/s beyond limit 90 deg/s, frames 48.024 to 72". */
void cli_limits_line(char *buf, size_t size, const struct cli_limits *c,
		     const struct lim_violation *v);

/* The number of channels with limits (strand check's summary). */
uint32_t cli_limits_count(const struct cli_limits *c);

#endif /* STRAND_CLI_LIMITS_H */
