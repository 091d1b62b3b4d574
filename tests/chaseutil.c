/* SPDX-License-Identifier: MIT */
/* chaseutil.c - strand play --chase on the virtual clock (see chaseutil.h). */
#include "chaseutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "playutil.h"
#include "scene/timecode.h"

#define LOG_CAP 8192

static struct sim_ltc_frame g_log[LOG_CAP];
static size_t g_nlog;


/* The source frame a label names, in the source's rules. */
static int64_t label_frame(const struct timecode *tc, const struct sim_ltc_frame *f)
{
	return timecode_frame(tc, f->hh, f->mm, f->ss, f->ff);
}

/* Play the arm (frames 0..last at num/den, 1 kHz) chasing spec. */
void chase_run(struct chase_outcome *oc, const char *spec, struct sim_ltc_cfg *sc,
		struct hal_din *din, uint32_t num, uint32_t den, int64_t last,
		const char *tc_offset, double freewheel_ms, const int64_t *truth_ns,
		size_t ntruth)
{
	static struct pu_source ps;
	static struct pu_rig r;
	struct play_opts o;
	struct play p;
	struct pu_csv csv;
	struct timecode tc;
	char path[256];
	int64_t off = 0, prev_due = -1, prev_t = -1;
	uint32_t i;
	int cf, cd, cs;

	double *keep = oc->phase_us;
	size_t cap = oc->phase_cap;

	memset(oc, 0, sizeof(*oc));
	oc->phase_us = keep;
	oc->phase_cap = cap;
	oc->first_frame = -1;
	g_nlog = 0;
	if (sc) {
		sc->log = g_log;
		sc->log_cap = LOG_CAP;
		sc->log_n = &g_nlog;
	}
	pu_arm_source(&ps, num, den, 1000, 0, last);
	pu_rig_init(&r, &ps, 1, 0);
	pu_opts(&o, &ps);
	pu_tmpname(path, sizeof(path), "chase");
	o.journal_path = path;
	o.chase.spec = spec;
	o.chase.sim = sc;
	o.chase.sim_din = din;
	o.chase.tc_offset = tc_offset;
	o.chase.freewheel_ms = freewheel_ms;
	oc->code = pu_run(&p, &r, &ps, &o);
	oc->st = p.chase.st;
	oc->recues = p.chase.recues;
	if (oc->st.lock_ns >= 0)
		oc->lock_frames = (double)(oc->st.lock_ns - oc->st.first_mark_ns) / p.chase.frame_ns;
	timecode_init(&tc, num / p.chase.cfg.mult, den);
	off = p.chase.cfg.offset;
	play_free(&p);
	assert_int_equal(pu_csv_read(&csv, path), 0);
	cf = pu_csv_col(&csv, "frame");
	cd = pu_csv_col(&csv, "due_ns");
	cs = pu_csv_col(&csv, "source_tc");
	for (i = 1; i < csv.nrows; i++) {
		int64_t f = atoll(csv.cell[i][cf]), due = atoll(csv.cell[i][cd]), t = -1;
		int64_t want = off + f; /* the source frame the scene's frame is */
		double quant;
		size_t j;

		oc->fired++;
		if (oc->first_frame < 0)
			oc->first_frame = f;
		oc->last_frame = f;
		if (truth_ns) { /* pulses: the pulse that is this frame */
			if (want >= 0 && (size_t)want < ntruth)
				t = truth_ns[want];
		} else {
			char lbl[24];

			/* the label nearest in time (reverse play repeats labels) */
			for (j = 0; j < g_nlog && j < LOG_CAP; j++)
				if (!g_log[j].reverse &&
				    label_frame(&tc, &g_log[j]) == want % timecode_day(&tc) &&
				    (t < 0 || llabs(g_log[j].t_ns - due) < llabs(t - due)))
					t = g_log[j].t_ns;
			/* the journal names the label the source sent then */
			timecode_format(&tc, want, lbl, sizeof(lbl));
			assert_string_equal(csv.cell[i][cs], lbl);
		}
		if (t < 0 || llabs(due - t) > 20000000) {
			/* between a reverse or a stop of the source and the mark
			 * that shows it (LTC is decoded a frame late), the
			 * schedule freewheels on frames the source never played */
			oc->unplayed++;
			continue;
		}
		/* the scene's trigger tick is on the frame's start or up to a
		 * tick after it (FORMULAS.md 5): that much is the scene's */
		quant = ceil((double)f * den * 1000 / num - 1e-9) - (double)f * den * 1000 / num;
		tu_worst_add(&oc->phase, ((double)(due - t) - quant * 1e6) / 1000.0, (double)f);
		if (oc->nphase < oc->phase_cap)
			oc->phase_us[oc->nphase++] = ((double)(due - t) - quant * 1e6) / 1000.0;
		oc->matched++;
		if (prev_due >= 0 && prev_t >= 0 && t > prev_t)
			tu_worst_add(&oc->stretch, (double)(due - prev_due) / (double)(t - prev_t) - 1,
				     (double)f);
		prev_due = due;
		prev_t = t;
	}
	pu_csv_free(&csv);
	remove(path);
}

struct sim_ltc_cfg chase_ltc25(double cap_ppm, double src_ppm)
{
	struct sim_ltc_cfg c;

	memset(&c, 0, sizeof(c));
	c.rate = 48000;
	c.period = 480;
	c.fps_num = 25;
	c.fps_den = 1;
	c.ss = 1; /* 00:00:01:00: the scene's frame 25 */
	c.begin_s = 0.1;
	c.end_s = 12;
	c.cap_ppm = cap_ppm;
	c.src_ppm = src_ppm;
	c.jitter_ns = 1000000;
	c.seed = 5;
	return c;
}

