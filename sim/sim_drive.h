/* SPDX-License-Identifier: MIT */
/*
 * sim_drive.h - a simulated servo drive behind the HAL axis interface.
 *
 * Each channel is a second-order plant, the textbook model of a position
 * loop: with target r (counts), feed-forward velocity r' (counts/s), actual
 * position x and velocity v,
 *
 *     a = w^2 (r - x) + 2 z w (kff r' - v),    w = 2 pi bandwidth
 *
 * with |a| <= acc_max and |v| <= vel_max, integrated semi-implicitly in
 * sub-steps of at most 0.05 / w (stable and accurate to well under a count
 * for the bandwidths a servo reaches). At constant speed the following error
 * settles to 2 z (1 - kff) v / w: proportional to speed, which is why the
 * loop's bound on it scales with speed as LinuxCNC's does. A velocity-mode
 * channel (cyclic synchronous velocity) follows its velocity target with a
 * first-order lag 1/w instead.
 *
 * Time is the tick: the plant advances one tick period per input(), so a
 * simulated run is deterministic on the virtual and on the wall clock alike.
 *
 * Faults are injected at a tick: the drive trips (fault latched, channel
 * unpowered), the axis jams (stops dead, the following error grows), or its
 * bandwidth collapses (it lags more and more). The drive also watches what
 * it is told: the largest commanded speed and acceleration per channel, the
 * tick it was disabled at, and optionally every target it received.
 */
#ifndef SIM_DRIVE_H
#define SIM_DRIVE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "hal/axis.h"

/* A simulated twin's plant where the scene gives none: a stiff, critically
 * damped position loop with most of the velocity fed forward, and drive
 * limits half as much again as the output's own (so that the loop's limits,
 * not the drive's, are what a run meets). */
#define SIM_DRIVE_DEFAULT_BANDWIDTH_HZ 40.0
#define SIM_DRIVE_DEFAULT_DAMPING 1.0
#define SIM_DRIVE_DEFAULT_FEEDFORWARD 0.9
#define SIM_DRIVE_DEFAULT_LIMIT_FACTOR 1.5

struct sim_drive_channel {
	double bandwidth_hz; /* > 0 */
	double damping;      /* zeta, > 0 (1: critically damped) */
	double feedforward;  /* 0..1 */
	double vel_max;      /* counts/s; 0: unlimited */
	double acc_max;      /* counts/s^2; 0: unlimited */
	int64_t initial;     /* counts at power-on */
	bool velocity_mode;  /* follows hal_setpoint.vel, not .pos */
};

enum sim_drive_fault {
	SIM_DRIVE_TRIP,     /* "overcurrent": fault latched, channel unpowered */
	SIM_DRIVE_JAM,      /* the axis stops dead; no fault of its own */
	SIM_DRIVE_SLUGGISH, /* bandwidth / 100 from then on */
};

/* What the drive saw on one channel. */
struct sim_drive_watch {
	double x, v;          /* actual position and velocity, counts, counts/s */
	int64_t target;       /* last target received */
	double cmd_vel_max;   /* largest |finite-difference speed| of the targets, counts/s */
	double cmd_acc_max;   /* largest |second difference| of the targets, counts/s^2 */
	int64_t commits;      /* setpoints received */
	int64_t last_commit_tick;
	int64_t disabled_tick; /* the first tick whose setpoint it did not get
				* because it was disabled; -1 while enabled */
	bool powered;
};

struct sim_drive;

/*
 * [init] A drive with nch channels at tick_hz into *out. ch[] gives each
 * channel's model; name is kept (not copied). 0, or a negative errno
 * (-EINVAL a bad parameter, -ENOMEM) with a message in err naming the
 * device; err may be NULL when errsize is 0.
 */
int sim_drive_new(struct sim_drive **out, const char *name, uint32_t nch, uint32_t tick_hz,
		  const struct sim_drive_channel *ch, char *err, size_t errsize);

/* The HAL view of the drive. */
struct hal_axis *sim_drive_axis(struct sim_drive *d);
struct sim_drive *sim_drive_of(struct hal_axis *ax);

/* [init] Make the fault happen on channel ch at the start of tick at_tick
 * (one per channel; a later call replaces it). */
void sim_drive_inject(struct sim_drive *d, uint32_t ch, int64_t at_tick, enum sim_drive_fault f);

/* [init] Record every commit's targets (int64 counts, nch per tick) into buf
 * for up to ticks ticks from the first commit. */
void sim_drive_trace(struct sim_drive *d, int64_t *buf, int64_t ticks);
int64_t sim_drive_traced(const struct sim_drive *d); /* ticks recorded */
/* The tick of the trace's first record (once there is one). */
int64_t sim_drive_trace_first(const struct sim_drive *d);
/* [init] With sim_drive_trace: also where each channel stood when each
 * tick's targets came (counts, nch per tick), into buf as long as the
 * trace's. */
void sim_drive_trace_actual(struct sim_drive *d, double *buf);

/* What channel ch saw; any thread once the loop has ended. */
const struct sim_drive_watch *sim_drive_watch(const struct sim_drive *d, uint32_t ch);

#endif /* SIM_DRIVE_H */
