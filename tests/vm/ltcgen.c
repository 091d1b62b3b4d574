/* SPDX-License-Identifier: MIT */
/*
 * ltcgen.c - LTC audio for the VM's sound tests (tests/vm/t_ltc_*.sh):
 * libltc's encoder, raw signed 16-bit mono samples on stdout, for aplay to
 * play into one side of snd-aloop while strand chases the other.
 *
 *     ltcgen FPS START SECONDS [RATE [DBFS]] | aplay -t raw -f S16_LE -c 1 -r RATE ...
 *
 * FPS: 24, 25, 30 or 29.97 (libltc marks that one drop-frame); START: HH:MM:SS:FF; RATE: samples
 * a second (48000); DBFS: the level (-3). Every frame is exactly RATE / FPS
 * samples long on average (libltc spreads the fraction), so the source's
 * clock is the sound card's: the loopback's rate shift is its clock error.
 * Debian packages no ltcgen (ltc-tools): this is the few lines of it the
 * tests need.
 */
#include <ltc.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int usage(void)
{
	fprintf(stderr, "usage: ltcgen FPS HH:MM:SS:FF SECONDS [RATE [DBFS]]\n");
	return 2;
}

int main(int argc, char **argv)
{
	double fps, secs, rate = 48000, dbfs = -3;
	unsigned hh, mm, ss, ff;
	enum LTC_TV_STANDARD std;
	SMPTETimecode tc;
	LTCEncoder *enc;
	long frames, i;

	if (argc < 4 || argc > 6)
		return usage();
	fps = atof(argv[1]);
	secs = atof(argv[3]);
	if (argc > 4)
		rate = atof(argv[4]);
	if (argc > 5)
		dbfs = atof(argv[5]);
	if (sscanf(argv[2], "%u:%u:%u%*[:;.]%u", &hh, &mm, &ss, &ff) != 4 || fps < 23 ||
	    fps > 30 || secs <= 0 || rate < 8000 || rate > 192000 || dbfs >= 0)
		return usage();
	if (fabs(fps - 30000.0 / 1001) < 0.01)
		fps = 30000.0 / 1001;
	std = fps < 24.5 ? LTC_TV_FILM_24 : fps < 25.5 ? LTC_TV_625_50 : LTC_TV_525_60;
	enc = ltc_encoder_create(rate, fps, std, 0);
	if (!enc) {
		fprintf(stderr, "ltcgen: libltc's encoder refuses %g fps at %g Hz\n", fps, rate);
		return 1;
	}
	ltc_encoder_set_volume(enc, dbfs);
	memset(&tc, 0, sizeof(tc));
	strcpy(tc.timezone, "+0000");
	tc.months = 1;
	tc.days = 1;
	tc.hours = (unsigned char)hh;
	tc.mins = (unsigned char)mm;
	tc.secs = (unsigned char)ss;
	tc.frame = (unsigned char)ff;
	ltc_encoder_set_timecode(enc, &tc);
	frames = lround(secs * fps);
	for (i = 0; i < frames; i++) {
		ltcsnd_sample_t *buf;
		short out[4096];
		int n, j;

		ltc_encoder_encode_frame(enc);
		n = ltc_encoder_get_bufferptr(enc, &buf, 1);
		if (n < 0 || n > 4096) {
			fprintf(stderr, "ltcgen: a frame of %d samples\n", n);
			return 1;
		}
		/* libltc's unsigned 8 bits, centred on 128, to 16 bits */
		for (j = 0; j < n; j++)
			out[j] = (short)((buf[j] - 128) * 256);
		if (fwrite(out, sizeof(out[0]), (size_t)n, stdout) != (size_t)n)
			return 1; /* the player went away */
		ltc_encoder_inc_timecode(enc);
	}
	ltc_encoder_free(enc);
	return fflush(stdout) ? 1 : 0;
}
