/* SPDX-License-Identifier: MIT */
/* ltc_dec.c - LTC audio to marks (see ltc_dec.h). */
#include "ltc_dec.h"

#include <errno.h>
#include <ltc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* libltc's queue of decoded frames: a period holds less than one. */
#define LTC_DEC_QUEUE 16

int ltc_dec_init(struct ltc_dec *x, uint32_t rate, uint32_t period, double fps, char *err,
		 size_t errsize)
{
	x->rate = rate;
	x->period = period;
	x->pos = 0;
	x->peak = 0;
	x->floor_ns = 0;
	x->frames = 0;
	x->resyncs = 0;
	x->apv = (int)lround(rate / fps);
	x->u8 = malloc(period);
	x->d = ltc_decoder_create(x->apv, LTC_DEC_QUEUE);
	if (!x->u8 || !x->d) {
		ltc_dec_free(x);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	hal_dll_init(&x->clk, 1e9 / rate, period, LTC_DEC_BW_HZ);
	return 0;
}

void ltc_dec_free(struct ltc_dec *x)
{
	if (x->d)
		ltc_decoder_free(x->d);
	free(x->u8);
	x->d = NULL;
	x->u8 = NULL;
}

int ltc_dec_resync(struct ltc_dec *x)
{
	x->clk.n = 0;
	x->resyncs++;
	/* libltc has no reset: what it holds of a frame begun before the
	 * samples were lost would be spliced onto what comes after them, and
	 * 80 bits from two frames can pass for a frame with a label of
	 * neither (seen in the VM: a "jump" the source never made) */
	ltc_decoder_free(x->d);
	x->d = ltc_decoder_create(x->apv, LTC_DEC_QUEUE);
	return x->d ? 0 : -ENOMEM;
}

/* The period into x->u8, scaled so that its peak nears libltc's full 8
 * bits; the signal's level, dBFS. */
static double to_u8(struct ltc_dec *x, const int16_t *s, uint32_t n)
{
	double peak = 0, gain;
	uint32_t i;

	for (i = 0; i < n; i++)
		if (fabs((double)s[i]) > peak)
			peak = fabs((double)s[i]);
	/* the gain follows a rising level at once and a falling one slowly,
	 * so that a frame is not scaled differently halfway through */
	x->peak = peak > x->peak ? peak : 0.8 * x->peak + 0.2 * peak;
	gain = x->peak > 0 ? 30000.0 / x->peak : 1;
	if (gain > LTC_DEC_GAIN_MAX)
		gain = LTC_DEC_GAIN_MAX;
	if (gain < 1)
		gain = 1;
	for (i = 0; i < n; i++) {
		double v = 128 + s[i] * gain / 256;

		x->u8[i] = (unsigned char)(v < 0 ? 0 : v > 255 ? 255 : lrint(v));
	}
	return peak > 0 ? 20 * log10(peak / 32768) : -200;
}

uint32_t ltc_dec_period(struct ltc_dec *x, const int16_t *s, uint32_t n,
			const struct ltc_stamp *st, struct hal_mark *m, uint32_t max)
{
	LTCFrameExt f;
	uint32_t k = 0;
	double level, res;

	if (n > x->period)
		n = x->period;
	hal_dll_update(&x->clk, (double)st->pos, (double)st->t_ns);
	res = (double)st->t_ns - hal_dll_time(&x->clk, (double)st->pos);
	if (x->clk.n <= 1 || res < x->floor_ns + LTC_DEC_FLOOR_RISE_NS)
		x->floor_ns = x->clk.n <= 1 ? res : fmin(res, x->floor_ns + LTC_DEC_FLOOR_RISE_NS);
	else
		x->floor_ns += LTC_DEC_FLOOR_RISE_NS;
	level = to_u8(x, s, n);
	ltc_decoder_write(x->d, x->u8, n, x->pos);
	x->pos += n;
	while (ltc_decoder_read(x->d, &f) > 0) {
		SMPTETimecode tc;
		struct hal_mark *mk;

		x->frames++;
		if (k == max)
			continue;
		mk = &m[k++];
		ltc_frame_to_time(&tc, &f.ltc, 0);
		mk->t_ns = llround(hal_dll_time(&x->clk, (double)f.off_start) + x->floor_ns);
		mk->avail_ns = st->t_ns > mk->t_ns ? st->t_ns : mk->t_ns;
		mk->hh = tc.hours;
		mk->mm = tc.mins;
		mk->ss = tc.secs;
		mk->ff = tc.frame;
		mk->flags = HAL_MARK_LABEL | (f.ltc.dfbit ? HAL_MARK_DROP : 0) |
			    (f.reverse ? HAL_MARK_REVERSE : 0);
		mk->level_dbfs = (float)level;
	}
	return k;
}
