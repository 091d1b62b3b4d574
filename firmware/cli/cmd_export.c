/* SPDX-License-Identifier: MIT */
/*
 * cmd_export.c - `strand export SCENE`: the scene evaluated offline, one row
 * per sample: tick, frame (the sample's exact frame time), every node's
 * world position, then every channel (channel.h), as CSV or JSON lines.
 *
 * A sample is taken at a tick, as the controller would: `--at frames`
 * samples the tick at which each frame's trigger fires (FORMULAS section 5),
 * so the frame column is that tick's exact frame time, at most one tick
 * after the frame itself; `--at ticks` samples every tick.
 */
#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "exitcode.h"
#include "plan/timeline.h"
#include "report/numfmt.h"
#include "scene/channel.h"
#include "scene/source_scene.h"

#define FRAME_LIMIT 1073741823LL
#define OUT_BUF (1u << 16)

struct opts {
	bool ticks, jsonl, has_from, has_to;
	long long from, to, every;
	const struct cli_cmd *cmd;
	FILE *err;
};

static int on_opt(void *ctx, int opt, const char *arg)
{
	struct opts *o = ctx;

	switch (opt) {
	case 'a':
		if (strcmp(arg, "frames") && strcmp(arg, "ticks"))
			return cli_usage(o->cmd, o->err, "--at takes frames or ticks, not '%s'", arg);
		o->ticks = !strcmp(arg, "ticks");
		return -1;
	case 'f':
		o->has_from = true;
		if (!opt_long(arg, -FRAME_LIMIT, FRAME_LIMIT, &o->from))
			return cli_usage(o->cmd, o->err, "--from takes a whole frame number, not '%s'", arg);
		return -1;
	case 't':
		o->has_to = true;
		if (!opt_long(arg, -FRAME_LIMIT, FRAME_LIMIT, &o->to))
			return cli_usage(o->cmd, o->err, "--to takes a whole frame number, not '%s'", arg);
		return -1;
	case 'e':
		if (!opt_long(arg, 1, FRAME_LIMIT, &o->every))
			return cli_usage(o->cmd, o->err, "--every takes a whole number from 1, not '%s'", arg);
		return -1;
	case 'F':
		if (strcmp(arg, "csv") && strcmp(arg, "jsonl"))
			return cli_usage(o->cmd, o->err, "--format takes csv or jsonl, not '%s'", arg);
		o->jsonl = !strcmp(arg, "jsonl");
		return -1;
	}
	return STRAND_EXIT_USAGE;
}

/* Rows are built in one buffer and written in large blocks. */
struct sink {
	FILE *out;
	char *buf;
	size_t used;
	bool failed;
};

static void sink_flush(struct sink *s)
{
	if (s->used && fwrite(s->buf, 1, s->used, s->out) != s->used)
		s->failed = true;
	s->used = 0;
}

static char *sink_room(struct sink *s, size_t n)
{
	if (OUT_BUF - s->used < n)
		sink_flush(s);
	return s->buf + s->used;
}

static void header(struct sink *s, const struct chan_list *ch, bool jsonl)
{
	uint32_t i;
	char *p;

	p = sink_room(s, 32);
	s->used += (size_t)sprintf(p, jsonl ? "[\"tick\",\"frame\"" : "tick,frame");
	for (i = 0; i < ch->n; i++) {
		p = sink_room(s, sizeof(ch->c[i].name) + 8);
		s->used += (size_t)sprintf(p, jsonl ? ",\"%s\"" : ",%s", ch->c[i].name);
	}
	p = sink_room(s, 4);
	s->used += (size_t)sprintf(p, jsonl ? "]\n" : "\n");
}

static void row(struct sink *s, const struct chan_list *ch, const mot_q32 *v, int64_t tick,
		mot_q32 frame, bool jsonl)
{
	uint32_t i;
	char *p = sink_room(s, 2 * NUMFMT_MAX + 4);

	if (jsonl)
		*p++ = '[', s->used++;
	s->used += numfmt_int(s->buf + s->used, tick);
	s->buf[s->used++] = ',';
	s->used += numfmt_double(s->buf + s->used, chan_q32(frame));
	for (i = 0; i < ch->n; i++) {
		p = sink_room(s, NUMFMT_MAX + 2);
		*p++ = ',';
		s->used += 1 + numfmt_double(p, chan_value_q32(&ch->c[i], v[i]));
	}
	p = sink_room(s, 3);
	if (jsonl)
		*p++ = ']', s->used++;
	*p = '\n';
	s->used++;
}

/*
 * Every channel, selected in the source in the list's order, over the
 * range [from, to] as a run of those frames plays it (plan/timeline.h):
 * ticks beyond the range's own, such as the last frame's when it falls
 * after the frame's instant, carry each position on at its speed.
 */
static int range_of(struct source_scene *ss, const struct opts *o, struct timeline *tl,
		    bool **extend, mot_q32 **mem, uint32_t *sat)
{
	uint32_t n = ss->all.n, i, *sel = calloc(n + 1, sizeof(*sel));
	int rc = -ENOMEM;

	*extend = calloc(n + 1, sizeof(**extend));
	*mem = calloc(TIMELINE_WORDS(n) + 1, sizeof(**mem));
	if (sel && *extend && *mem) {
		for (i = 0; i < n; i++) {
			struct src_channel sc;

			sel[i] = i;
			(*extend)[i] = src_lookup(&ss->s, ss->all.c[i].name, &sc) == (int)i &&
				       timeline_extends(sc.unit);
		}
		rc = src_select(&ss->s, sel, n);
	}
	free(sel);
	if (!rc)
		timeline_init(tl, &ss->s, n, *extend, o->from, o->to, *mem, sat);
	return rc;
}

static int export(FILE *out, FILE *err, const char *path, const struct scene_file *sf,
		  const struct mot_scene *sc, const struct opts *o)
{
	const struct mot_timing *t = &sc->timing;
	struct sink s = { out, NULL, 0, false };
	struct source_scene ss;
	struct timeline tl;
	bool *extend = NULL;
	mot_q32 *mem = NULL, *v = NULL;
	uint32_t sat = 0;
	int64_t k, k_last;
	long long f;
	int rc = STRAND_EXIT_OK;

	if (source_scene_init(&ss, &sf->desc, sc)) {
		fprintf(err, "strand export: out of memory\n");
		return STRAND_EXIT_INTERNAL;
	}
	s.buf = malloc(OUT_BUF);
	v = calloc(ss.all.n + 1, sizeof(*v));
	if (!s.buf || !v || range_of(&ss, o, &tl, &extend, &mem, &sat)) {
		fprintf(err, "strand export: out of memory\n");
		rc = STRAND_EXIT_INTERNAL;
		goto out;
	}
	header(&s, &ss.all, o->jsonl);
	if (o->ticks) {
		k_last = mot_timing_trigger_tick(t, o->to);
		for (k = mot_timing_trigger_tick(t, o->from); k <= k_last && !s.failed; k += o->every) {
			timeline_eval(&tl, k, v, &sat);
			row(&s, &ss.all, v, k, mot_timing_tick_frame(t, k), o->jsonl);
		}
	} else {
		for (f = o->from; f <= o->to && !s.failed; f += o->every) {
			k = mot_timing_trigger_tick(t, f);
			timeline_eval(&tl, k, v, &sat);
			row(&s, &ss.all, v, k, mot_timing_tick_frame(t, k), o->jsonl);
		}
	}
	sink_flush(&s);
	if (s.failed || fflush(out)) {
		fprintf(err, "strand export: cannot write the output\n");
		rc = STRAND_EXIT_IO;
	} else if (sat) {
		fprintf(err, "%s: the core's arithmetic saturated: values too large for its Q32.32 format\n",
			path);
		rc = STRAND_EXIT_INTERNAL;
	}
out:
	free(extend);
	free(mem);
	free(v);
	free(s.buf);
	source_scene_free(&ss);
	return rc;
}

static int run(const struct cli_cmd *cmd, int argc, char **argv, FILE *out, FILE *err)
{
	static const struct option opts[] = {
		{ "help", no_argument, NULL, 'h' },	   { "at", required_argument, NULL, 'a' },
		{ "from", required_argument, NULL, 'f' },  { "to", required_argument, NULL, 't' },
		{ "every", required_argument, NULL, 'e' }, { "format", required_argument, NULL, 'F' },
		{ 0 },
	};
	struct opts o = { .every = 1, .cmd = cmd, .err = err };
	struct scene_file sf;
	struct scene_built b;
	const char *path;
	int rc;

	rc = cli_scene_args(cmd, argc, argv, out, err, opts, on_opt, &o, &path, &sf, &b);
	if (rc >= 0)
		return rc;
	if (!o.has_from)
		o.from = (long long)sf.desc.frame_first;
	if (!o.has_to)
		o.to = (long long)sf.desc.frame_last;
	if (o.to < o.from)
		rc = cli_usage(cmd, err, "--to %lld is before --from %lld", o.to, o.from);
	else
		rc = export(out, err, path, &sf, &b.sc, &o);
	scene_built_free(&b);
	scene_file_free(&sf);
	return rc;
}

const struct cli_cmd cmd_export = {
	.name = "export",
	.summary = "evaluate a scene offline: one row per frame or tick",
	.help = "usage: strand export SCENE.yaml [--at frames|ticks] [--from F] [--to F]\n"
		"                                  [--every N] [--format csv|jsonl]\n\n"
		"Evaluate the scene exactly as the controller plays it and print a header\n"
		"row, then one row per sample: tick, frame, every node's .x .y .z (its\n"
		"pivot in world space), then every channel: <node>.angle (degrees) or\n"
		"<node>.position, <node>.rpm, camera.x|y|z|pan|tilt|roll, <cycle>.index,\n"
		"and each attribute. Numbers have at least 10 significant digits.\n\n"
		"  --at frames    one row per frame, sampled at the tick its trigger fires\n"
		"                 (the frame column is that tick's exact frame time)\n"
		"  --at ticks     one row per tick\n"
		"  --from F       first frame (default: timing.frames' first)\n"
		"  --to F         last frame (default: timing.frames' last)\n"
		"  --every N      every Nth frame or tick (default 1)\n"
		"  --format csv   comma-separated values (default)\n"
		"  --format jsonl one JSON array per line, the first holding the column names\n\n"
		"exit codes: 0 ok, 2 invalid scene, 3 usage, 4 I/O, 8 the core's arithmetic saturated\n",
	.run = run,
};
