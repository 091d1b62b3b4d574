/* SPDX-License-Identifier: MIT */
/* rig_chase.c - the external clock --chase names (see rig_chase.h). */
#include "rig_chase.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/gpio/gpio.h"
#include "hal/ltc/ltc.h"
#include "hal/pulse.h"
#include "sim/sim_ltc.h"

/* Capture: 48 kHz in periods of 10 ms. */
#define RIG_LTC_RATE 48000
#define RIG_LTC_PERIOD 480

/* "ltc:sim:ppm=100,jitter_us=1000,..." into c. */
static int sim_keys(const char *keys, struct sim_ltc_cfg *c, char *err, size_t errsize)
{
	char buf[256], *save = NULL, *kv;

	snprintf(buf, sizeof(buf), "%s", keys);
	for (kv = strtok_r(buf, ",", &save); kv; kv = strtok_r(NULL, ",", &save)) {
		char *v = strchr(kv, '='), *end;
		unsigned hh, mm, ss, ff;
		double d;

		if (!v)
			goto bad;
		*v++ = '\0';
		if (!strcmp(kv, "start")) {
			if (sscanf(v, "%u:%u:%u%*[:;.]%u", &hh, &mm, &ss, &ff) != 4 || hh > 23 ||
			    mm > 59 || ss > 59 || ff > 29)
				goto bad;
			c->hh = (uint8_t)hh;
			c->mm = (uint8_t)mm;
			c->ss = (uint8_t)ss;
			c->ff = (uint8_t)ff;
			continue;
		}
		d = strtod(v, &end);
		if (end == v || *end)
			goto bad;
		if (!strcmp(kv, "ppm") && d > -1e5 && d < 1e5)
			c->cap_ppm = d;
		else if (!strcmp(kv, "src_ppm") && d > -1e5 && d < 1e5)
			c->src_ppm = d;
		else if (!strcmp(kv, "jitter_us") && d >= 0 && d < 10000)
			c->jitter_ns = (int64_t)(d * 1000);
		else if (!strcmp(kv, "volume") && d < 0 && d > -100)
			c->volume_db = d;
		else if (!strcmp(kv, "begin") && d >= 0 && d < 1e6)
			c->begin_s = d;
		else if (!strcmp(kv, "end") && d > 0 && d < 1e9)
			c->end_s = d;
		else
			goto bad;
	}
	return 0;
bad:
	snprintf(err, errsize, "--chase ltc:sim:%s: keys are ppm=, src_ppm=, jitter_us= (below "
		 "10000), volume= (dBFS, below 0), begin=, end= (seconds), start=HH:MM:SS:FF", keys);
	return -EINVAL;
}

static int open_ltc(struct hal_extclk **out, const struct rig_chase_cfg *cfg, const char *dev,
		    char *err, size_t errsize)
{
	struct hal_ltc_cfg lc = { .name = cfg->spec, .clk = cfg->clk,
				  .fps = (double)cfg->num / cfg->den, .sched = cfg->sched };
	struct ltc_cap *cap;
	int rc;

	if (!strcmp(dev, "sim") || !strncmp(dev, "sim:", 4)) {
		struct sim_ltc_cfg sc;

		if (cfg->sim) {
			sc = *cfg->sim;
		} else {
			memset(&sc, 0, sizeof(sc));
			sc.rate = RIG_LTC_RATE;
			sc.period = RIG_LTC_PERIOD;
			sc.fps_num = cfg->num;
			sc.fps_den = cfg->den;
			sc.begin_s = 0.1;
			if (dev[3] == ':' && (rc = sim_keys(dev + 4, &sc, err, errsize)))
				return rc;
		}
		rc = sim_ltc_open(&cap, &sc, cfg->clk, err, errsize);
	} else {
		if (cfg->clk->is_virtual) {
			snprintf(err, errsize, "--chase %s: a sound card runs on the wall clock, "
				 "not with --clock virtual", cfg->spec);
			return -EINVAL;
		}
		rc = ltc_alsa_open(&cap, dev, RIG_LTC_RATE, RIG_LTC_PERIOD, err, errsize);
	}
	if (rc)
		return rc;
	lc.cap = cap;
	return hal_ltc_open(out, &lc, err, errsize);
}

static int open_gpio(struct hal_extclk **out, const struct rig_chase_cfg *cfg, const char *rest,
		     char *err, size_t errsize)
{
	char chip[128], *line, *end;
	struct hal_gpio_line gl = { 0 };
	struct hal_gpio_cfg gc;
	struct hal_din *din;
	unsigned long off;
	int rc;

	if (!strcmp(rest, "sim") && cfg->sim_din)
		return hal_pulse_open(out, cfg->sim_din, 0, cfg->spec, err, errsize);
	snprintf(chip, sizeof(chip), "%s", rest);
	line = strrchr(chip, ':');
	if (!line || line == chip || !line[1]) {
		snprintf(err, errsize, "--chase %s: gpio:CHIP:LINE (gpiochip0:17, or a line's "
			 "name: gpiochip0:CAM_SYNC)", cfg->spec);
		return -EINVAL;
	}
	*line++ = '\0';
	off = strtoul(line, &end, 10);
	if (*end || end == line)
		gl.name = line;
	else
		gl.offset = (uint32_t)off;
	memset(&gc, 0, sizeof(gc));
	gc.device = cfg->spec;
	gc.chip = chip;
	gc.nlines = 1;
	gc.lines = &gl;
	gc.sched = cfg->sched;
	gc.sysfs = cfg->gpio_sysfs;
	rc = hal_gpio_din_open(&din, &gc, err, errsize);
	if (rc)
		return rc;
	return hal_pulse_open(out, din, 0, cfg->spec, err, errsize);
}

int rig_chase_open(struct hal_extclk **out, const struct rig_chase_cfg *cfg, char *err,
		   size_t errsize)
{
	*out = NULL;
	if (!strncmp(cfg->spec, "ltc:", 4) && cfg->spec[4])
		return open_ltc(out, cfg, cfg->spec + 4, err, errsize);
	if (!strncmp(cfg->spec, "gpio:", 5) && cfg->spec[5])
		return open_gpio(out, cfg, cfg->spec + 5, err, errsize);
	snprintf(err, errsize, "--chase %s: ltc:DEVICE (an ALSA capture device), ltc:sim, or "
		 "gpio:CHIP:LINE", cfg->spec);
	return -EINVAL;
}
