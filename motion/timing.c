/* SPDX-License-Identifier: MIT */
/* timing.c - exact frame/tick arithmetic (see timing.h). */
#include "timing.h"

static uint32_t gcd32(uint32_t a, uint32_t b)
{
	while (b) {
		uint32_t r = a % b;

		a = b;
		b = r;
	}
	return a;
}

int mot_timing_init(struct mot_timing *t, uint32_t num, uint32_t den, uint32_t tick_hz)
{
	uint32_t g;

	if (num == 0 || den == 0 || tick_hz == 0 || num > MOT_RATE_MAX || den > MOT_RATE_MAX ||
	    tick_hz > MOT_TICK_HZ_MAX)
		return MOT_E_INVAL;
	g = gcd32(num, den);
	num /= g;
	den /= g;
	/* num / den <= tick_hz, compared exactly */
	if ((uint64_t)num > (uint64_t)tick_hz * den)
		return MOT_E_INVAL;
	t->num = num;
	t->den = den;
	t->tick_hz = tick_hz;
	t->ticks_den = (uint64_t)tick_hz * den;
	return mot_udiv_inv_init(&t->per_turn, 60 * (uint64_t)num);
}

mot_q32 mot_timing_tick_frame(const struct mot_timing *t, int64_t tick)
{
	/* k * num * 2^32 / (tick_hz * den): |k| < 2^52, num <= 2^24, so the
	 * product is below 2^108 and the quotient below 2^63 whenever the frame
	 * itself fits Q32.32. */
	return mot_muldiv(tick, (int64_t)t->num << 32, (int64_t)t->ticks_den, NULL);
}

/* ceil(a * m / d) for d > 0, exact (a * m must fit 126 bits). */
static int64_t muldiv_ceil(int64_t a, int64_t m, int64_t d)
{
	mot_acc p = mot_acc_mul(a, m);
	uint64_t q, r;

	if (mot_acc_is_neg(p)) {
		/* ceil(-x/d) = -floor(x/d) */
		q = mot_acc_udiv(mot_acc_neg(p), (uint64_t)d, &r, NULL);
		return -(int64_t)q;
	}
	q = mot_acc_udiv(p, (uint64_t)d, &r, NULL);
	return (int64_t)q + (r != 0);
}

/* floor(a * m / d) for d > 0, exact. */
static int64_t muldiv_floor(int64_t a, int64_t m, int64_t d)
{
	mot_acc p = mot_acc_mul(a, m);
	uint64_t q, r;

	if (mot_acc_is_neg(p)) {
		q = mot_acc_udiv(mot_acc_neg(p), (uint64_t)d, &r, NULL);
		return -(int64_t)q - (r != 0);
	}
	return (int64_t)mot_acc_udiv(p, (uint64_t)d, &r, NULL);
}

int64_t mot_timing_trigger_tick(const struct mot_timing *t, int64_t frame)
{
	return muldiv_ceil(frame, (int64_t)t->ticks_den, t->num);
}

bool mot_timing_fires(const struct mot_timing *t, int64_t tick, int64_t *frame)
{
	/* Frame f fires at tick k iff (k - 1) < f * D / num <= k, i.e.
	 * f = floor(k * num / D) and that frame's trigger tick is k. */
	int64_t f = muldiv_floor(tick, t->num, (int64_t)t->ticks_den);

	if (mot_timing_trigger_tick(t, f) != tick)
		return false;
	if (frame)
		*frame = f;
	return true;
}

int64_t mot_timing_next_frame(const struct mot_timing *t, int64_t tick)
{
	/* smallest f with ceil(f * D / num) >= k, i.e. f * D / num > k - 1 */
	int64_t f = muldiv_floor(tick - 1, t->num, (int64_t)t->ticks_den) + 1;

	return f;
}

mot_q32 mot_timing_frame_seconds(const struct mot_timing *t, mot_q32 frame, uint32_t *sat)
{
	return mot_muldiv(frame, t->den, t->num, sat);
}
