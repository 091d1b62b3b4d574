/* SPDX-License-Identifier: MIT */
/* sim_drive.c - the simulated servo drive (see sim_drive.h). */
#include "sim_drive.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/rt.h"

/* The most plant steps a tick: a bound on the simulated drive's work. */
#define SIM_DRIVE_NSUB_MAX 1e7

struct sim_chan {
	struct sim_drive_channel p;
	struct sim_drive_watch w;
	double omega;        /* 2 pi bandwidth */
	double r, rdot;      /* the target being followed */
	double prev_cmd_v;   /* last commanded speed (finite difference), counts/s */
	bool have_cmd;
	int64_t fault_tick;  /* -1: none pending */
	enum sim_drive_fault fault;
	bool jammed, tripped;
};

struct sim_drive {
	struct hal_axis ax; /* first: the HAL view */
	uint32_t tick_hz;
	double dt;          /* one tick, s */
	uint32_t nsub;      /* plant sub-steps per tick */
	int64_t tick;       /* last tick input() ran for */
	bool started;
	struct hal_fault fault; /* first fault; code 0 while healthy */
	int64_t *trace;
	double *trace_x; /* NULL: targets only */
	int64_t trace_ticks, traced, trace_first;
	struct sim_chan ch[];
};

static struct sim_drive STRAND_RT *drive_of(struct hal_axis *ax)
{
	return (struct sim_drive *)ax; /* ax is the first member */
}

/* [init] for the loop, but rt-safe, and called in the loop's thread by a
 * simulated CANopen drive that is commanded back to operation enabled
 * (co_slave.c: plant_on): tagged, and without STRAND_ASSERT_NOT_RT. */
static int STRAND_RT sd_start(struct hal_axis *ax)
{
	struct sim_drive *d = drive_of(ax);
	uint32_t i;

	for (i = 0; i < ax->nch; i++) {
		struct sim_chan *c = &d->ch[i];

		c->w.powered = true;
		c->w.disabled_tick = -1;
		/* a drive enabled (again) holds where it stands: its target is
		 * there, at rest, until the first setpoint; what it followed
		 * before a stop is gone with the power */
		c->w.v = 0;
		c->r = c->w.x;
		c->w.target = c->p.velocity_mode ? 0 : (int64_t)llround(c->w.x);
		c->rdot = 0;
		c->prev_cmd_v = 0;
	}
	d->started = true;
	/* a new run counts its ticks from 0 again: the next input() steps */
	d->tick = INT64_MIN;
	return 0;
}

static void STRAND_RT latch(struct sim_drive *d, int code, uint32_t ch, const char *cause)
{
	if (d->fault.code)
		return;
	d->fault.code = code;
	d->fault.channel = (int32_t)ch;
	d->fault.cause = cause;
	d->fault.detail = 0;
}

/* One tick of one channel's plant. */
static void STRAND_RT plant_step(struct sim_drive *d, struct sim_chan *c)
{
	double h = d->dt / d->nsub;
	uint32_t s;

	if (!c->w.powered || c->jammed) {
		c->w.v = 0; /* unpowered: the brake holds; jammed: it cannot move */
		return;
	}
	for (s = 0; s < d->nsub; s++) {
		double a;

		if (c->p.velocity_mode)
			a = c->omega * (c->rdot - c->w.v);
		else
			a = c->omega * c->omega * (c->r - c->w.x) +
			    2 * c->p.damping * c->omega * (c->p.feedforward * c->rdot - c->w.v);
		if (c->p.acc_max > 0)
			a = fmax(-c->p.acc_max, fmin(c->p.acc_max, a));
		c->w.v += a * h;
		if (c->p.vel_max > 0)
			c->w.v = fmax(-c->p.vel_max, fmin(c->p.vel_max, c->w.v));
		c->w.x += c->w.v * h;
	}
}

static int STRAND_RT sd_input(struct hal_axis *ax, int64_t tick)
{
	struct sim_drive *d = drive_of(ax);
	uint32_t i;

	for (i = 0; i < ax->nch; i++) {
		struct sim_chan *c = &d->ch[i];

		if (c->fault_tick >= 0 && tick >= c->fault_tick) {
			c->fault_tick = -1;
			switch (c->fault) {
			case SIM_DRIVE_TRIP:
				c->tripped = true;
				c->w.powered = false;
				latch(d, -EIO, i, "overcurrent");
				break;
			case SIM_DRIVE_JAM:
				c->jammed = true;
				break;
			case SIM_DRIVE_SLUGGISH:
				c->omega /= 100;
				break;
			}
		}
		if (tick > d->tick)
			plant_step(d, c);
	}
	if (tick > d->tick)
		d->tick = tick;
	return d->fault.code;
}

static bool STRAND_RT sd_actual(struct hal_axis *ax, uint32_t ch, int64_t *counts)
{
	*counts = (int64_t)llround(drive_of(ax)->ch[ch].w.x);
	return true;
}

static void STRAND_RT sd_set(struct hal_axis *ax, uint32_t ch, const struct hal_setpoint *sp)
{
	struct sim_drive *d = drive_of(ax);
	struct sim_chan *c = &d->ch[ch];
	double v, prev = c->p.velocity_mode ? (double)c->w.target : 0;

	/* what was commanded: speed and acceleration by finite differences,
	 * the way the loop's limit check and the drive's own tracker see them */
	if (c->p.velocity_mode) {
		v = (double)sp->vel;
		c->w.target = sp->vel;
		c->rdot = (double)sp->vel;
		c->w.cmd_vel_max = fmax(c->w.cmd_vel_max, fabs(v));
		c->w.cmd_acc_max = fmax(c->w.cmd_acc_max, fabs(v - prev) * d->tick_hz);
	} else {
		v = (double)(sp->pos - (c->have_cmd ? c->w.target : c->p.initial)) * d->tick_hz;
		c->w.cmd_vel_max = fmax(c->w.cmd_vel_max, fabs(v));
		c->w.cmd_acc_max = fmax(c->w.cmd_acc_max, fabs(v - c->prev_cmd_v) * d->tick_hz);
		c->prev_cmd_v = v;
		c->w.target = sp->pos;
		c->r = (double)sp->pos;
		c->rdot = (double)sp->vel;
	}
	c->have_cmd = true;
}

static int STRAND_RT sd_commit(struct hal_axis *ax, int64_t tick)
{
	struct sim_drive *d = drive_of(ax);
	uint32_t i;

	for (i = 0; i < ax->nch; i++) {
		d->ch[i].w.commits++;
		d->ch[i].w.last_commit_tick = tick;
	}
	if (d->trace) {
		if (d->traced == 0)
			d->trace_first = tick;
		if (d->traced < d->trace_ticks && tick - d->trace_first == d->traced) {
			for (i = 0; i < ax->nch; i++)
				d->trace[d->traced * ax->nch + i] = d->ch[i].w.target;
			for (i = 0; d->trace_x && i < ax->nch; i++)
				d->trace_x[d->traced * ax->nch + i] = d->ch[i].w.x;
			d->traced++;
		}
	}
	return d->fault.code;
}

static int STRAND_RT sd_fault(struct hal_axis *ax, struct hal_fault *f)
{
	struct sim_drive *d = drive_of(ax);

	if (d->fault.code)
		*f = d->fault;
	return d->fault.code;
}

static void STRAND_RT sd_disable(struct hal_axis *ax)
{
	struct sim_drive *d = drive_of(ax);
	uint32_t i;

	for (i = 0; i < ax->nch; i++) {
		struct sim_chan *c = &d->ch[i];

		if (c->w.disabled_tick < 0)
			c->w.disabled_tick = c->w.commits ? c->w.last_commit_tick + 1 : 0;
		c->w.powered = false;
		c->w.v = 0;
	}
}

static int sd_stop(struct hal_axis *ax)
{
	sd_disable(ax);
	return 0;
}

static void sd_close(struct hal_axis *ax)
{
	STRAND_ASSERT_NOT_RT();
	free(drive_of(ax));
}

static const struct hal_axis_ops sim_drive_ops = {
	.start = sd_start,
	.input = sd_input,
	.actual = sd_actual,
	.set = sd_set,
	.commit = sd_commit,
	.fault = sd_fault,
	.disable = sd_disable,
	.stop = sd_stop,
	.close = sd_close,
};

int sim_drive_new(struct sim_drive **out, const char *name, uint32_t nch, uint32_t tick_hz,
		  const struct sim_drive_channel *ch, char *err, size_t errsize)
{
	struct sim_drive *d;
	double wmax = 0, nsub;
	uint32_t i;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (!nch || !tick_hz) {
		snprintf(err, errsize, "device '%s': simulated drive: %u channels at %u Hz", name,
			 nch, tick_hz);
		return -EINVAL;
	}
	for (i = 0; i < nch; i++)
		if (!(ch[i].bandwidth_hz > 0) || !(ch[i].damping > 0) || ch[i].feedforward < 0 ||
		    ch[i].feedforward > 1 || ch[i].vel_max < 0 || ch[i].acc_max < 0) {
			snprintf(err, errsize, "device '%s': simulated drive: channel %u: bandwidth "
				 "and damping above zero, feedforward 0 to 1, limits not negative",
				 name, i);
			return -EINVAL;
		}
	d = calloc(1, sizeof(*d) + nch * sizeof(d->ch[0]));
	if (!d) {
		snprintf(err, errsize, "device '%s': simulated drive: %s", name, strerror(ENOMEM));
		return -ENOMEM;
	}
	d->ax.ops = &sim_drive_ops;
	d->ax.name = name;
	d->ax.nch = nch;
	d->tick_hz = tick_hz;
	d->dt = 1.0 / tick_hz;
	d->tick = INT64_MIN;
	for (i = 0; i < nch; i++) {
		struct sim_chan *c = &d->ch[i];

		c->p = ch[i];
		c->omega = 2 * M_PI * ch[i].bandwidth_hz;
		c->w.x = (double)ch[i].initial;
		c->w.target = ch[i].velocity_mode ? 0 : ch[i].initial;
		c->r = c->w.x;
		c->w.disabled_tick = -1;
		c->fault_tick = -1;
		wmax = fmax(wmax, c->omega);
	}
	nsub = ceil(wmax * d->dt / 0.05);
	/* a scene's bandwidth is at most 10 kHz (rig_desc.h): at 1 Hz ticks,
	 * 1.3 million steps; more is a description made in code gone wrong */
	if (!(nsub <= SIM_DRIVE_NSUB_MAX)) {
		snprintf(err, errsize, "device '%s': simulated drive: a bandwidth of %g Hz needs "
			 "%.3g plant steps a tick at %u Hz, more than %g", name, wmax / (2 * M_PI),
			 nsub, tick_hz, SIM_DRIVE_NSUB_MAX);
		free(d);
		return -ERANGE;
	}
	d->nsub = nsub < 1 ? 1 : (uint32_t)nsub;
	*out = d;
	return 0;
}

struct hal_axis STRAND_RT *sim_drive_axis(struct sim_drive *d)
{
	return &d->ax;
}

struct sim_drive *sim_drive_of(struct hal_axis *ax)
{
	return ax->ops == &sim_drive_ops ? drive_of(ax) : NULL;
}

void sim_drive_inject(struct sim_drive *d, uint32_t ch, int64_t at_tick, enum sim_drive_fault f)
{
	if (ch >= d->ax.nch)
		return;
	d->ch[ch].fault_tick = at_tick;
	d->ch[ch].fault = f;
}

void sim_drive_trace(struct sim_drive *d, int64_t *buf, int64_t ticks)
{
	d->trace = buf;
	d->trace_ticks = ticks;
	d->traced = 0;
}

void sim_drive_trace_actual(struct sim_drive *d, double *buf)
{
	d->trace_x = buf;
}

int64_t sim_drive_trace_first(const struct sim_drive *d)
{
	return d->trace_first;
}

int64_t sim_drive_traced(const struct sim_drive *d)
{
	return d->traced;
}

const struct sim_drive_watch STRAND_RT *sim_drive_watch(const struct sim_drive *d, uint32_t ch)
{
	return &d->ch[ch].w;
}
