/* SPDX-License-Identifier: MIT */
/*
 * playutil.h - what the play tests share: an analytic source (channels
 * given as functions of the frame, in file units, so the tests know every
 * value exactly) and a simulated rig around it, plus a runner that plays
 * it on the virtual clock and hands back the run for inspection.
 */
#ifndef PLAYUTIL_H
#define PLAYUTIL_H

#include <stdbool.h>
#include <stdint.h>

#include "play/play.h"
#include "rig/drv_sim.h"
#include "rig/rig_desc.h"
#include "scene/source.h"

#define PU_MAX_CH 8

/* value in file units (degrees, units, rpm) at a frame (double) */
typedef double (*pu_fn)(const void *ctx, double frame);

struct pu_channel {
	const char *name;
	enum src_unit unit;
	pu_fn fn;
	const void *ctx;
	struct sd_limits limits;
};

struct pu_source {
	struct play_source s; /* first */
	uint32_t nch;
	struct pu_channel ch[PU_MAX_CH];
	uint32_t nsel;
	uint32_t sel[PU_MAX_CH];
};

/* A source at num/den fps and tick_hz, frames first..last. */
void pu_source_init(struct pu_source *ps, const char *name, uint32_t num, uint32_t den,
		    uint32_t tick_hz, int64_t first, int64_t last);
void pu_source_add(struct pu_source *ps, const char *name, enum src_unit unit, pu_fn fn,
		   const void *ctx, double vel, double acc);
/* The exact value eval() gives for a selected channel at a Q32.32 frame. */
mot_q32 pu_value(const struct pu_source *ps, uint32_t ch, mot_q32 frame);

/* The smooth test motions: 0 at rest at both ends of [f0, f1] with a
 * raised-cosine move of amplitude amp between. */
struct pu_smooth {
	double f0, f1, amp, base;
};
double pu_smooth(const void *ctx, double frame);

/* A rig description: one simulated drive "arm" carrying every channel of
 * the source (axis i = channel i, counts_per_unit cpu[i]), one simulated
 * I/O device "io" with `ntrig` trigger lines and the inputs asked for. */
struct pu_rig {
	struct rig_desc d;
	struct rig_device_desc dev[3]; /* arm, io, and arm2 for tests to use */
	struct rig_output_desc out[PU_MAX_CH];
	struct rig_trigger_desc trig[2];
	struct rig_input_desc in[3];
};

enum {
	PU_ESTOP = 1,
	PU_READY = 2,
	PU_STOP = 4,
};

void pu_rig_init(struct pu_rig *r, const struct pu_source *ps, uint32_t ntrig, unsigned inputs);

/* Default play options: virtual clock, continuous over the source's span,
 * no journal, no telemetry. */
void pu_opts(struct play_opts *o, const struct pu_source *ps);

/* The arm of most tests: a.angle (90 deg over frames 10..200, limits 60
 * deg/s and 120 deg/s^2) and b.position (0.1 + 0.25 m over 0..150, limits
 * 0.5 m/s, 2 m/s^2). */
extern struct pu_smooth pu_m_a, pu_m_b;
void pu_arm_source(struct pu_source *ps, uint32_t num, uint32_t den, uint32_t hz,
		   int64_t first, int64_t last);

/* Prepare and run, failing the test on a preparation error, then check
 * what every run must satisfy: no allocation by the loop thread, every
 * command the drives saw within its output's speed and acceleration limits,
 * no trigger missed by a camera. Returns the exit code. */
int pu_run(struct play *p, struct pu_rig *r, struct pu_source *ps, struct play_opts *o);
/* The same for a run already prepared (play_prepare); the camera check only
 * when check_missed. */
/* play_run, its outcome as the strand program's exit code. */
int pu_play(struct play *p);
int pu_finish(struct play *p, bool check_missed);

/* A journal file as rows of CSV fields (journal_csv's output): rows[0] is
 * the header. Free with pu_csv_free. */
struct pu_csv {
	uint32_t nrows, ncols;
	char ***cell; /* cell[row][col] */
	char *text;
};
int pu_csv_read(struct pu_csv *c, const char *journal_path);
void pu_csv_free(struct pu_csv *c);
int pu_csv_col(const struct pu_csv *c, const char *name);

/* A temporary file name under $TMPDIR, unique per call. */
void pu_tmpname(char *buf, size_t size, const char *what);

/* Allocations made by the loop thread while it ran loop_run, counted by
 * ASan's malloc hook: every test asserts it stays 0. */
uint64_t pu_loop_allocations(void);
void pu_alloc_hook_install(void);

#endif /* PLAYUTIL_H */
