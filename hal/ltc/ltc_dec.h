/* SPDX-License-Identifier: MIT */
/*
 * ltc_dec.h - LTC audio to marks (extclk.h): libltc's decoder finds each
 * frame's label and the sample position its first bit began at; a
 * delay-locked loop (dll.h) over the capture's timestamps turns sample
 * positions into CLOCK_MONOTONIC.
 *
 * Why a DLL over the timestamps and not the timestamps themselves: a sound
 * card's position is reported when its interrupt is handled, so the time
 * that goes with a position jitters by up to a jiffy (2.4 to 2.9 ms
 * measured at HZ=250 in the test VM), while the samples come at the card's
 * own steady rate. The loop follows that rate (whatever the card's crystal
 * is off by) and the jitter is filtered down to microseconds; each frame's
 * start is then placed to the sample (libltc's off_start, within 0.3
 * samples rms of where it was written). A stamp is late, never early (the
 * interrupt comes after the samples), so the loop, which goes through the
 * stamps' middle, would place every frame late by the mean latency: the
 * frames are placed on the stamps' lower edge instead, the least residual
 * seen, allowed to rise by LTC_DEC_FLOOR_RISE_NS per period so that it
 * follows a latency that changes.
 *
 * Levels: libltc reduces its input to 8 bits, so a signal 40 dB down would
 * be a few steps of it and lost. The samples are scaled up first by the
 * period's peak (at most 36 dB): quiet LTC decodes, silence stays silence.
 *
 * [capture thread] throughout (libltc allocates its queue at creation only;
 * its decoding allocates nothing, but nothing of it runs on the loop).
 */
#ifndef HAL_LTC_DEC_H
#define HAL_LTC_DEC_H

#include <stddef.h>
#include <stdint.h>

#include "hal/dll.h"
#include "hal/extclk.h"
#include "ltc_cap.h"

/* The sample clock's loop bandwidth once its start-up fit has narrowed. */
#define LTC_DEC_BW_HZ 0.02
/* How fast the lower edge of the stamps may rise, per period. */
#define LTC_DEC_FLOOR_RISE_NS 1000.0
/* The most the samples are scaled up before libltc's 8 bits: 36 dB. */
#define LTC_DEC_GAIN_MAX 64.0

struct ltc_dec {
	struct LTCDecoder *d;
	struct hal_dll clk;     /* sample position -> CLOCK_MONOTONIC, the stamps' middle */
	double floor_ns;        /* the stamps' lower edge against the loop's line */
	uint32_t rate, period;
	int apv;                /* samples per frame, for libltc */
	unsigned char *u8;      /* a period as libltc takes it */
	int64_t pos;            /* samples given to libltc so far */
	double peak;            /* the signal's recent peak, 16-bit units */
	int64_t frames;         /* frames decoded */
	int64_t resyncs;        /* times the capture's position broke off */
};

/* [init] A decoder for rate samples a second in periods of `period`,
 * expecting about fps frames a second. 0 or a negative errno with err. */
int ltc_dec_init(struct ltc_dec *x, uint32_t rate, uint32_t period, double fps, char *err,
		 size_t errsize);
void ltc_dec_free(struct ltc_dec *x);

/* Decode n samples captured with stamp st: the frames that ended in them
 * as marks in m (up to max; the rest are dropped, which one period of
 * audio cannot give), avail_ns = st->t_ns. How many. */
uint32_t ltc_dec_period(struct ltc_dec *x, const int16_t *s, uint32_t n,
			const struct ltc_stamp *st, struct hal_mark *m, uint32_t max);

/* The capture's position broke off (an overrun lost samples): the sample
 * clock starts its fit again from the next stamp, keeping its rate, and
 * the frame under way is dropped. 0, or -ENOMEM (the decoder is gone). */
int ltc_dec_resync(struct ltc_dec *x);

#endif /* HAL_LTC_DEC_H */
