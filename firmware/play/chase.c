/* SPDX-License-Identifier: MIT */
/* chase.c - the tick clock disciplined by an external clock (see chase.h). */
#include "chase.h"

#include <math.h>

#include "hal/rt.h"

static const char *const event_names[] = {
	[CHASE_EV_NONE] = "",
	[CHASE_EV_JUMP] = "the timecode jumped",
	[CHASE_EV_STOPPED] = "the source stopped",
	[CHASE_EV_REVERSE] = "the source plays backwards",
	[CHASE_EV_RATE] = "the source's rate is beyond what the limits allow",
	[CHASE_EV_LOST] = "the source is lost",
	[CHASE_EV_FORMAT] = "the source's drop-frame labels do not match the scene's frame rate",
};

const char *chase_event_name(enum chase_event e)
{
	return e <= CHASE_EV_FORMAT ? event_names[e] : "?";
}

void chase_init(struct chase *c, const struct chase_cfg *cfg)
{
	double src_num = (double)cfg->num / cfg->mult;

	*c = (struct chase){ .cfg = *cfg };
	timecode_init(&c->tc, cfg->num / cfg->mult, cfg->den);
	c->day = timecode_day(&c->tc);
	c->frame_ns = 1e9 * cfg->den / src_num;
	c->tick_frames = src_num / cfg->den / cfg->tick_hz;
	hal_dll_init(&c->dll, c->frame_ns, 1, CHASE_BW_HZ);
	c->st.first_mark_ns = -1;
	c->st.lock_ns = -1;
	c->st.rate = 1;
}

void STRAND_RT chase_begin(struct chase *c, int64_t t0)
{
	c->k_last = 0;
	c->due_last = (double)t0;
	c->step_ns = 1e9 / c->cfg.tick_hz;
	c->last_seen_ns = t0;
}

double STRAND_RT chase_src_at(const struct chase *c, double t)
{
	return hal_dll_at(&c->dll, t);
}

double STRAND_RT chase_time_of(const struct chase *c, double x)
{
	return hal_dll_time(&c->dll, x);
}

double STRAND_RT chase_src_of_scene_tick(const struct chase *c, int64_t s)
{
	return (double)c->cfg.offset + (double)s * c->tick_frames;
}

static void STRAND_RT note(struct chase *c, enum chase_event e)
{
	if (c->event == CHASE_EV_NONE)
		c->event = e;
	c->st.events[e]++;
}

/* A mark's frame: its label's, or for a pulse the frame the fit expects
 * nearest to it (the first pulse is frame 0). */
static int64_t STRAND_RT mark_frame(struct chase *c, const struct hal_mark *m)
{
	double per = c->good ? c->dll.per : c->frame_ns;

	if (m->flags & HAL_MARK_LABEL)
		return timecode_frame(&c->tc, m->hh, m->mm, m->ss, m->ff);
	if (c->st.marks == 0)
		return 0;
	return c->last_n + llround(((double)m->t_ns - c->last_t) / per);
}

static void STRAND_RT unlock(struct chase *c, int64_t n, double t)
{
	c->good = 1;
	c->locked = false;
	/* the rate the fit has is still the source's: only the phase is new */
	hal_dll_restart(&c->dll, (double)n, t);
}

static void STRAND_RT take(struct chase *c, const struct hal_mark *m, int64_t now)
{
	double t = (double)m->t_ns, per = c->good ? c->dll.per : c->frame_ns;
	int64_t n = mark_frame(c, m), want;
	bool drop = (m->flags & HAL_MARK_DROP) != 0;

	c->st.marks++;
	if (c->st.first_mark_ns < 0)
		c->st.first_mark_ns = m->t_ns;
	c->st.level_dbfs = m->level_dbfs;
	if (n < 0 || ((m->flags & HAL_MARK_LABEL) && drop != (c->tc.drop != 0))) {
		/* a label these rules do not have: a wrong format, not a jump */
		note(c, CHASE_EV_FORMAT);
		c->good = 0;
		c->locked = false;
		return;
	}
	c->last_seen_ns = now;
	if (c->good == 0) {
		c->last_n = n;
		c->last_t = t;
		unlock(c, n, t);
		return;
	}
	/* the frame expected at this mark's time, after the last one */
	want = c->last_n + llround((t - c->last_t) / per);
	if (!(m->flags & HAL_MARK_LABEL) && fabs(t - c->last_t - (double)(n - c->last_n) * per) >
						    per / 4) {
		c->st.outliers++; /* a pulse between frames: a glitch, not a frame */
		return;
	}
	if (n != want || (m->flags & HAL_MARK_REVERSE) || n <= c->last_n) {
		if (c->locked || c->mapped)
			note(c, (m->flags & HAL_MARK_REVERSE) || n < c->last_n ? CHASE_EV_REVERSE :
				n == c->last_n ? CHASE_EV_STOPPED : CHASE_EV_JUMP);
		c->last_n = n;
		c->last_t = t;
		unlock(c, n, t);
		return;
	}
	hal_dll_update(&c->dll, (double)n, t);
	c->last_n = n;
	c->last_t = t;
	if (++c->good >= CHASE_LOCK_MARKS && !c->locked) {
		c->locked = true;
		c->st.locks++;
		if (c->st.lock_ns < 0)
			c->st.lock_ns = now;
	}
	c->st.rate = c->frame_ns / c->dll.per;
	if (c->locked && fabs(c->st.rate - 1) > CHASE_RATE_MAX) {
		note(c, CHASE_EV_RATE);
		c->good = 0;
		c->locked = false;
	}
}

void STRAND_RT chase_poll(struct chase *c, int64_t now)
{
	uint32_t i, n;

	do {
		n = hal_extclk_poll(c->cfg.src, now, c->buf, CHASE_MARKS_PER_TICK);
		for (i = 0; i < n; i++)
			take(c, &c->buf[i], now);
	} while (n == CHASE_MARKS_PER_TICK);
}

enum chase_event STRAND_RT chase_take_event(struct chase *c, int64_t now)
{
	enum chase_event e = c->event;
	int64_t quiet = now - c->last_seen_ns;

	if (c->mapped && quiet > c->st.freewheel_max_ns)
		c->st.freewheel_max_ns = quiet;
	if (e == CHASE_EV_NONE && c->mapped && quiet > c->cfg.freewheel_ns) {
		note(c, CHASE_EV_LOST);
		c->good = 0;
		c->locked = false;
		c->mapped = false; /* the stop runs on at the last step */
		e = CHASE_EV_LOST;
	}
	c->event = CHASE_EV_NONE;
	return e;
}

int64_t STRAND_RT chase_due(struct chase *c, int64_t k)
{
	double next, corr, lim;

	if (k <= c->k_last)
		return llround(c->due_last);
	/* one scene tick of the source's time: the fit's rate while mapped,
	 * else the last step (free, or freewheeling) */
	if (c->mapped && c->good)
		c->step_ns = c->tick_frames * c->dll.per;
	next = c->due_last + c->step_ns;
	if (c->mapped && c->good) {
		double target = chase_time_of(c, chase_src_of_scene_tick(c, c->scene_begin + k -
									 c->k_play));
		double e = target - next;

		if (fabs(e) > c->st.phase_max_ns && k >= c->k_play)
			c->st.phase_max_ns = fabs(e);
		lim = CHASE_SLEW * c->step_ns;
		corr = e * CHASE_GAIN;
		next += corr > lim ? lim : corr < -lim ? -lim : corr;
	}
	c->due_last = next;
	c->k_last = k;
	return llround(next);
}
