/* SPDX-License-Identifier: MIT */
/*
 * steps.h - the time of a simulated system (particles, flocks): state
 * integrated at a fixed step from its start, checkpoints to reach any step
 * quickly, and the cache of the two states a tick lies between.
 *
 * A system steps at rate_num / rate_den steps a second from frame f0 (step
 * 0 is its initial state) to step nsteps, the last its span needs. The
 * position of a frame on that time line is
 *     pos(f) = (f - f0) * den * rate_num / (num * rate_den)     (Q32.32 steps)
 * for the scene's frame rate num / den, computed afresh from the frame with
 * one 128-bit division: a pure function of the frame, so random access
 * gives the bits playback gives. Before f0 a system holds step 0, after
 * nsteps it holds the last step.
 *
 * Reaching a step. A state is a blob of state_bytes (the system's struct
 * array); the build integrates the whole span once and keeps every
 * `every`-th state (the checkpoints, in the scene's block). An evaluation
 * keeps two states of its own, a (step n) and b (step n + 1), and moves
 * them forward one step at a time while time moves forward; a jump back, or
 * forward by more than `every` steps, restores the checkpoint at or before
 * the step and integrates from there: at most `every` steps, whatever the
 * jump. So playback costs one step per step, `play --from` and `export
 * --from` one seek, and playing backwards (ping-pong) up to `every` steps
 * each time it crosses a step.
 */
#ifndef MOT_STEPS_H
#define MOT_STEPS_H

#include "curve.h"
#include "fix.h"
#include "timing.h"

/* Most steps a system takes over its span (their count is Q32.32 steps). */
#define MOT_STEPS_MAX ((int64_t)1 << 30)
/* Fastest step rate. */
#define MOT_STEP_HZ_MAX 100000u

struct mot_steps {
	mot_q32 f0;                  /* frame of step 0 */
	int64_t pos_num, pos_den;    /* pos(f) = (f - f0) * pos_num / pos_den */
	int64_t nsteps;              /* the last step */
	uint32_t rate_num, rate_den; /* steps a second */
	struct mot_recip rate;       /* divides by rate_num (seconds from steps) */
	uint32_t every;              /* a checkpoint every this many steps */
	uint32_t state_bytes;
	unsigned char *ckpt;         /* states of steps 0, every, 2 every, ... */
};

/*
 * The time line from frame f0 to frame f1 (>= f0) at rate_num / rate_den
 * steps a second (each 1 to MOT_STEP_HZ_MAX, the rate at most
 * MOT_STEP_HZ_MAX), checkpoints every `every` (>= 1) steps of state_bytes
 * (> 0, a multiple of 8). MOT_E_INVAL, or MOT_E_RANGE when the span takes
 * more than MOT_STEPS_MAX steps. ckpt is set by the caller afterwards
 * (mot_steps_ckpt_count() states). Init only.
 */
int mot_steps_init(struct mot_steps *s, const struct mot_timing *t, mot_q32 f0, mot_q32 f1,
		   uint32_t rate_num, uint32_t rate_den, uint32_t every, uint32_t state_bytes);

static inline uint32_t mot_steps_ckpt_count(const struct mot_steps *s)
{
	return (uint32_t)(s->nsteps / s->every) + 1;
}

/* The step position of a frame, clamped to [0, nsteps]. Real-time safe. */
mot_q32 mot_steps_pos(const struct mot_steps *s, mot_q32 frame, uint32_t *sat);

/* The frame of a step position (Q32.32 steps). Real-time safe. */
mot_q32 mot_steps_frame(const struct mot_steps *s, mot_q32 pos, uint32_t *sat);

/* Seconds of a number of steps (Q32.32 steps to Q32.32 seconds), within
 * 1 LSB: x * rate_den / rate_num with a prepared reciprocal. Real-time
 * safe. */
static inline mot_q32 mot_steps_seconds(const struct mot_steps *s, mot_q32 steps, uint32_t *sat)
{
	return mot_recip_ratio(steps * (int64_t)s->rate_den, &s->rate, sat);
}

/* One step of a system: the state of step n + 1 from that of step n
 * (in and out never alias). */
typedef void (*mot_step_fn)(const void *sys, const struct mot_curve *curves,
			    const void *in, void *out, int64_t n, void *scratch, uint32_t *sat);

/* An evaluation's two states: a at step n, b at step n + 1 when b_ok. */
struct mot_steps_cache {
	void *a, *b;
	int64_t n;  /* step of a; -1: nothing yet */
	bool b_ok;
};

/* Make c->a step n and c->b step n + 1 (0 <= n < nsteps), stepping
 * forward or from a checkpoint as above. Real-time safe: bounded by
 * `every` + 1 steps. */
void mot_steps_seek(const struct mot_steps *s, struct mot_steps_cache *c, int64_t n,
		    mot_step_fn fn, const void *sys, const struct mot_curve *curves, void *scratch,
		    uint32_t *sat);

/* Integrate the whole span from the state in ckpt[0] (the caller's initial
 * state), filling every checkpoint; a and b are two states of scratch.
 * `watch` (may be NULL) sees every state once, in order. Init only. */
void mot_steps_run(const struct mot_steps *s, void *a, void *b, mot_step_fn fn,
		   const void *sys, const struct mot_curve *curves, void *scratch,
		   void (*watch)(const void *sys, const void *state, int64_t n, void *ctx),
		   void *ctx, uint32_t *sat);

/* Copy n bytes (the core's memcpy: states are blobs). */
static inline void mot_copy(void *dst, const void *src, size_t n)
{
	__builtin_memcpy(dst, src, n);
}

#endif /* MOT_STEPS_H */
