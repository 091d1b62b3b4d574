/* SPDX-License-Identifier: MIT */
/*
 * ltc_alsa.c - LTC from a sound card's capture (ltc.h, ltc_cap.h), through
 * libasound: mono (or the first channel of a card that captures only
 * stereo) 16-bit at the rate asked, read a period at a time.
 *
 * Each read is stamped with snd_pcm_htimestamp(): the time of the driver's
 * last position update and the samples available then, on
 * CLOCK_MONOTONIC (the software parameters ask for it). So the stamp pairs
 * a sample position (read so far plus available) with the instant the
 * driver saw it, which is what the decoder's DLL needs; its jitter (the
 * interrupt's latency) is the DLL's to filter.
 *
 * The buffer holds ALSA_PERIODS periods: a capture is read as soon as a
 * period is there, so a long buffer adds no delay, only room for the
 * thread to be late (an overrun loses samples and costs a resync). A read
 * that finds no samples in time fails with EIO in the kernel (its wait is
 * the buffer's time plus 10%, at least 100 ms): a card that stopped, or a
 * machine that stalled for that long (seen under emulation). Either is
 * taken as an overrun, and the stream started again; ALSA_STALLS of them in
 * a row without a sample between are the card's failure.
 */
#include "ltc.h"

#include <alsa/asoundlib.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "hal/rt.h"

/* Periods in the buffer: 320 ms at 10 ms periods. */
#define ALSA_PERIODS 32
/* Reads in a row that time out before the card counts as failed. */
#define ALSA_STALLS 5

struct ltc_alsa {
	struct ltc_cap base; /* first */
	snd_pcm_t *pcm;
	unsigned channels;
	int16_t *frames;     /* a period of interleaved frames */
	int64_t pos;         /* samples read so far */
	int stalls;          /* reads in a row that timed out */
};

static int alsa_read(struct ltc_cap *c, int16_t *buf, uint32_t n, struct ltc_stamp *st)
{
	struct ltc_alsa *a = (struct ltc_alsa *)c;
	snd_pcm_uframes_t avail;
	snd_htimestamp_t ts;
	snd_pcm_sframes_t got;
	uint32_t i;

	if (n > c->period)
		n = c->period;
	got = snd_pcm_readi(a->pcm, a->frames, n);
	if (got == -EIO && ++a->stalls >= ALSA_STALLS)
		return -EIO;
	if (got == -EPIPE || got == -ESTRPIPE || got == -EIO) {
		/* an overrun (or a stall): prepared again, the next read starts
		 * the stream; the caller resyncs */
		got = snd_pcm_prepare(a->pcm);
		return got < 0 ? (int)got : -EPIPE;
	}
	if (got < 0)
		return (int)got;
	if (got > 0)
		a->stalls = 0;
	for (i = 0; i < (uint32_t)got; i++)
		buf[i] = a->frames[i * a->channels];
	a->pos += got;
	if (snd_pcm_htimestamp(a->pcm, &avail, &ts) == 0 && (ts.tv_sec || ts.tv_nsec)) {
		st->t_ns = (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
		st->pos = a->pos + (int64_t)avail;
	} else { /* no timestamp from the driver: now, at the end of the read */
		st->t_ns = hal_mono_ns();
		st->pos = a->pos;
	}
	return (int)got;
}

static void alsa_close(struct ltc_cap *c)
{
	struct ltc_alsa *a = (struct ltc_alsa *)c;

	if (a->pcm)
		snd_pcm_close(a->pcm);
	free(a->frames);
	free(a);
}

static const struct ltc_cap_ops alsa_ops = {
	.read = alsa_read,
	.close = alsa_close,
};

#define ALSA_TRY(call, what)                                                              \
	do {                                                                              \
		rc = (call);                                                              \
		if (rc < 0) {                                                             \
			snprintf(err, errsize, "ALSA device '%s': %s: %s", device, what,   \
				 snd_strerror(rc));                                       \
			goto fail;                                                        \
		}                                                                         \
	} while (0)

int ltc_alsa_open(struct ltc_cap **out, const char *device, uint32_t rate, uint32_t period,
		  char *err, size_t errsize)
{
	snd_pcm_hw_params_t *hw;
	snd_pcm_sw_params_t *sw;
	snd_pcm_uframes_t per = period, buf = (snd_pcm_uframes_t)period * ALSA_PERIODS;
	struct ltc_alsa *a;
	unsigned r = rate, ch = 1;
	int rc, dir = 0;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	a = calloc(1, sizeof(*a));
	if (!a) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	a->base.ops = &alsa_ops;
	rc = snd_pcm_open(&a->pcm, device, SND_PCM_STREAM_CAPTURE, 0);
	if (rc < 0) {
		snprintf(err, errsize, "ALSA device '%s': cannot open for capture: %s "
			 "(`arecord -l` lists the cards)", device, snd_strerror(rc));
		a->pcm = NULL;
		goto fail;
	}
	snd_pcm_hw_params_alloca(&hw);
	ALSA_TRY(snd_pcm_hw_params_any(a->pcm, hw), "no configuration");
	ALSA_TRY(snd_pcm_hw_params_set_access(a->pcm, hw, SND_PCM_ACCESS_RW_INTERLEAVED),
		 "interleaved access refused");
	ALSA_TRY(snd_pcm_hw_params_set_format(a->pcm, hw, SND_PCM_FORMAT_S16),
		 "16-bit samples refused");
	/* mono where the card offers it, else its fewest channels (the first
	 * one is read) */
	if (snd_pcm_hw_params_set_channels(a->pcm, hw, 1) < 0)
		ALSA_TRY(snd_pcm_hw_params_set_channels_first(a->pcm, hw, &ch), "no channel count");
	ALSA_TRY(snd_pcm_hw_params_set_rate_near(a->pcm, hw, &r, &dir), "rate refused");
	ALSA_TRY(snd_pcm_hw_params_set_period_size_near(a->pcm, hw, &per, &dir),
		 "period size refused");
	ALSA_TRY(snd_pcm_hw_params_set_buffer_size_near(a->pcm, hw, &buf), "buffer size refused");
	ALSA_TRY(snd_pcm_hw_params(a->pcm, hw), "hardware parameters refused");
	snd_pcm_sw_params_alloca(&sw);
	ALSA_TRY(snd_pcm_sw_params_current(a->pcm, sw), "no software parameters");
	ALSA_TRY(snd_pcm_sw_params_set_tstamp_mode(a->pcm, sw, SND_PCM_TSTAMP_ENABLE),
		 "timestamps refused");
	ALSA_TRY(snd_pcm_sw_params_set_tstamp_type(a->pcm, sw, SND_PCM_TSTAMP_TYPE_MONOTONIC),
		 "monotonic timestamps refused");
	ALSA_TRY(snd_pcm_sw_params_set_avail_min(a->pcm, sw, per), "avail_min refused");
	ALSA_TRY(snd_pcm_sw_params_set_start_threshold(a->pcm, sw, 1), "start threshold refused");
	ALSA_TRY(snd_pcm_sw_params(a->pcm, sw), "software parameters refused");
	a->channels = ch;
	a->base.rate = r;
	a->base.period = (uint32_t)per;
	a->frames = calloc((size_t)per * ch, sizeof(int16_t));
	if (!a->frames) {
		rc = -ENOMEM;
		snprintf(err, errsize, "out of memory");
		goto fail;
	}
	/* prepared; the capture thread's first read starts it (the start
	 * threshold is one sample), so that nothing overruns before it reads */
	ALSA_TRY(snd_pcm_prepare(a->pcm), "cannot prepare");
	*out = &a->base;
	return 0;
fail:
	alsa_close(&a->base);
	return rc < 0 ? rc : -EIO;
}
