/* SPDX-License-Identifier: MIT */
/*
 * sim_ltc.c - the simulated LTC capture device (sim_ltc.h).
 *
 * Two clocks meet here, as on a set: the source's, which sends frame after
 * frame of LTC audio (libltc's encoder, at fs (1 + src_ppm) samples a
 * second of true time), and the card's, which takes a sample every
 * 1 / (fs (1 + cap_ppm)) s. Each captured sample is the source's signal at
 * that instant, interpolated between the source's samples (the encoder's
 * edges have a 40 us rise time, so a straight line between samples 21 us
 * apart is close). True time is the run's clock from the moment the device
 * was opened.
 */
#define _GNU_SOURCE
#include "sim_ltc.h"

#include <errno.h>
#include <ltc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Source samples kept: several frames at any rate LTC has. */
#define SIM_LTC_BUF 16384

struct sim_ltc {
	struct ltc_cap base; /* first */
	struct sim_ltc_cfg cfg;
	struct hal_clock *clk;
	int64_t t0;          /* the run's clock when capture began */
	LTCEncoder *enc;
	double fs_src, fs_cap; /* samples per second of true time */
	double gain;
	double *sb;          /* source samples sb_base .. sb_base + sb_len - 1 */
	int64_t sb_base, sb_len;
	int64_t pos;         /* samples captured */
	uint32_t next_ev;
	int dir;             /* 1 forwards, -1 backwards */
	double hold_until;
	uint64_t rng;
};

static uint64_t rng_next(struct sim_ltc *s)
{
	s->rng ^= s->rng >> 12;
	s->rng ^= s->rng << 25;
	s->rng ^= s->rng >> 27;
	return s->rng * 0x2545F4914F6CDD1DULL;
}

static enum LTC_TV_STANDARD standard(double fps)
{
	if (fps < 24.5)
		return LTC_TV_FILM_24;
	if (fps < 27.5)
		return LTC_TV_625_50;
	return LTC_TV_525_60;
}

static bool silent_at(const struct sim_ltc *s, double t)
{
	uint32_t i;

	if (t < s->cfg.begin_s)
		return true;
	for (i = 0; i < s->cfg.nevents; i++) {
		const struct sim_ltc_event *e = &s->cfg.events[i];

		if (e->ev == SIM_LTC_SILENCE && t >= e->at_s && t < e->until_s)
			return true;
	}
	return false;
}

/* The script's events due by a frame that starts at t (seconds). */
static void events_due(struct sim_ltc *s, double t)
{
	while (s->next_ev < s->cfg.nevents && s->cfg.events[s->next_ev].at_s <= t) {
		const struct sim_ltc_event *e = &s->cfg.events[s->next_ev++];
		SMPTETimecode tc;

		switch (e->ev) {
		case SIM_LTC_JUMP:
			ltc_encoder_get_timecode(s->enc, &tc);
			tc.hours = e->hh;
			tc.mins = e->mm;
			tc.secs = e->ss;
			tc.frame = e->ff;
			ltc_encoder_set_timecode(s->enc, &tc);
			break;
		case SIM_LTC_REVERSE:
			s->dir = -1;
			break;
		case SIM_LTC_FORWARD:
			s->dir = 1;
			break;
		case SIM_LTC_HOLD:
			s->hold_until = e->until_s;
			break;
		case SIM_LTC_SILENCE:
			break; /* by the sample (silent_at) */
		}
	}
}

/* One more frame of the source's samples; false when out of room. */
static bool encode_next(struct sim_ltc *s)
{
	int64_t u0 = s->sb_base + s->sb_len;
	double t = s->cfg.begin_s + u0 / s->fs_src;
	ltcsnd_sample_t *buf;
	SMPTETimecode tc;
	int n, i;

	events_due(s, t);
	ltc_encoder_get_timecode(s->enc, &tc);
	if (s->dir > 0)
		ltc_encoder_encode_frame(s->enc);
	else
		ltc_encoder_encode_reversed_frame(s->enc);
	n = ltc_encoder_get_bufferptr(s->enc, &buf, 1);
	if (n < 0 || s->sb_len + n > SIM_LTC_BUF)
		return false;
	for (i = 0; i < n; i++)
		s->sb[s->sb_len + i] = ((double)buf[i] - 128) * 256 * s->gain;
	s->sb_len += n;
	if (s->cfg.log_n) {
		size_t k = (*s->cfg.log_n)++;

		if (k < s->cfg.log_cap) {
			struct sim_ltc_frame *f = &s->cfg.log[k];

			f->t_ns = s->t0 + llround(t * 1e9);
			f->hh = tc.hours;
			f->mm = tc.mins;
			f->ss = tc.secs;
			f->ff = tc.frame;
			f->reverse = s->dir < 0;
			f->silent = silent_at(s, t);
		}
	}
	if (t < s->hold_until)
		return true; /* the source stands: the same label again */
	if (s->dir > 0)
		ltc_encoder_inc_timecode(s->enc);
	else
		ltc_encoder_dec_timecode(s->enc);
	return true;
}

/* The source's signal at source sample position u (fractional). */
static double sample_at(struct sim_ltc *s, double u)
{
	int64_t j = (int64_t)floor(u);
	double a = u - (double)j;

	/* the source runs on through a silence: every frame is encoded,
	 * heard or not, and what is behind j dropped to make room */
	while (j + 1 >= s->sb_base + s->sb_len) {
		if (s->sb_len + 4096 > SIM_LTC_BUF) {
			int64_t from = j - 16 < s->sb_base + s->sb_len ? j - 16 :
					s->sb_base + s->sb_len, drop = from - s->sb_base;

			if (drop > 0) {
				memmove(s->sb, s->sb + drop,
					(size_t)(s->sb_len - drop) * sizeof(*s->sb));
				s->sb_base += drop;
				s->sb_len -= drop;
			}
		}
		if (!encode_next(s))
			return 0;
	}
	if (j < s->sb_base)
		return 0;
	return s->sb[j - s->sb_base] * (1 - a) + s->sb[j + 1 - s->sb_base] * a;
}

static int sim_read(struct ltc_cap *c, int16_t *out, uint32_t n, struct ltc_stamp *st)
{
	struct sim_ltc *s = (struct sim_ltc *)c;
	double t_end;
	uint32_t j;

	if (n > c->period)
		n = c->period;
	for (j = 0; j < n; j++) {
		double t = (double)(s->pos + j) / s->fs_cap, v;

		if (t >= s->cfg.end_s)
			break;
		v = silent_at(s, t) ? 0 : sample_at(s, (t - s->cfg.begin_s) * s->fs_src);
		out[j] = (int16_t)lrint(v > 32767 ? 32767 : v < -32768 ? -32768 : v);
	}
	if (j == 0)
		return 0;
	s->pos += j;
	t_end = (double)s->pos / s->fs_cap;
	st->pos = s->pos;
	st->t_ns = s->t0 + llround(t_end * 1e9) +
		   (s->cfg.jitter_ns > 0 ? (int64_t)(rng_next(s) % (uint64_t)s->cfg.jitter_ns) : 0);
	if (!s->clk->is_virtual) {
		struct timespec ts = { .tv_sec = st->t_ns / 1000000000,
				       .tv_nsec = st->t_ns % 1000000000 };

		while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) == EINTR)
			;
	}
	return (int)j;
}

static void sim_close(struct ltc_cap *c)
{
	struct sim_ltc *s = (struct sim_ltc *)c;

	if (s->enc)
		ltc_encoder_free(s->enc);
	free(s->sb);
	free(s);
}

static const struct ltc_cap_ops sim_ops = {
	.read = sim_read,
	.close = sim_close,
};

int sim_ltc_open(struct ltc_cap **out, const struct sim_ltc_cfg *cfg, struct hal_clock *clk,
		 char *err, size_t errsize)
{
	double fps = (double)cfg->fps_num / cfg->fps_den;
	struct sim_ltc *s;
	SMPTETimecode tc;

	*out = NULL;
	if (!cfg->rate || !cfg->period || !cfg->fps_num || !cfg->fps_den || fps > 30 ||
	    cfg->jitter_ns < 0 || cfg->jitter_ns >= (int64_t)cfg->period * 1000000000 / cfg->rate) {
		snprintf(err, errsize, "simulated LTC: rates, period or jitter out of range");
		return -EINVAL;
	}
	s = calloc(1, sizeof(*s));
	if (!s) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	s->base.ops = &sim_ops;
	s->base.rate = cfg->rate;
	s->base.period = cfg->period;
	s->cfg = *cfg;
	if (s->cfg.end_s <= 0)
		s->cfg.end_s = 1e12;
	s->clk = clk;
	s->t0 = hal_clock_now(clk);
	s->fs_src = cfg->rate * (1 + cfg->src_ppm * 1e-6);
	s->fs_cap = cfg->rate * (1 + cfg->cap_ppm * 1e-6);
	s->gain = pow(10, ((cfg->volume_db ? cfg->volume_db : -3) + 1) / 20);
	s->dir = 1;
	s->hold_until = -1;
	s->rng = cfg->seed ? cfg->seed : 0x9E3779B97F4A7C15ULL;
	s->sb = malloc(SIM_LTC_BUF * sizeof(*s->sb));
	s->enc = ltc_encoder_create(cfg->rate, fps, standard(fps), 0);
	if (!s->sb || !s->enc) {
		sim_close(&s->base);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	ltc_encoder_set_volume(s->enc, -1);
	memset(&tc, 0, sizeof(tc));
	strcpy(tc.timezone, "+0000");
	tc.years = 0;
	tc.months = 1;
	tc.days = 1;
	tc.hours = cfg->hh;
	tc.mins = cfg->mm;
	tc.secs = cfg->ss;
	tc.frame = cfg->ff;
	ltc_encoder_set_timecode(s->enc, &tc);
	*out = &s->base;
	return 0;
}
