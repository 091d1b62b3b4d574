/* SPDX-License-Identifier: MIT */
/* model.c - the simulated drive as strand-simdrive's servers move it (see
 * simdrive.h). */
#include "simdrive.h"

#include <time.h>

/* The plant never catches up more than this at once (a stalled client). */
#define MODEL_MAX_STEPS 100000

static int64_t mono_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* The plant to tick t. */
static void advance(struct simdrive *sd, int64_t t)
{
	struct hal_axis *ax = sim_drive_axis(sd->drive);
	int64_t n = 0;

	if (t - sd->tick > MODEL_MAX_STEPS)
		sd->tick = t - MODEL_MAX_STEPS;
	while (sd->tick < t && n++ < MODEL_MAX_STEPS)
		hal_axis_input(ax, ++sd->tick);
}

void simdrive_enable(struct simdrive *sd, bool on)
{
	struct hal_axis *ax = sim_drive_axis(sd->drive);

	if (on && !sd->enabled)
		hal_axis_start(ax);
	else if (!on && sd->enabled)
		hal_axis_disable(ax);
	sd->enabled = on;
}

void simdrive_targets(struct simdrive *sd, const int64_t *val, int64_t tick)
{
	struct hal_axis *ax = sim_drive_axis(sd->drive);
	int64_t now = mono_ns(), dt;
	uint32_t i;

	if (tick < 0) {
		/* no heartbeat: the wall clock since the first setpoint */
		if (!sd->t0_ns)
			sd->t0_ns = now;
		tick = (now - sd->t0_ns) * sd->tick_hz / 1000000000;
	}
	advance(sd, tick);
	dt = tick - sd->prev_tick;
	for (i = 0; i < sd->nch; i++) {
		struct hal_setpoint sp = { 0, 0 };

		if (sd->velocity[i]) {
			sp.vel = val[i];
		} else {
			/* a drive given positions only differentiates them for its
			 * velocity feed-forward */
			sp.pos = val[i];
			sp.vel = dt > 0 && sd->writes ? (val[i] - sd->prev[i]) * sd->tick_hz / dt : 0;
			sd->prev[i] = val[i];
		}
		hal_axis_set(ax, i, &sp);
	}
	sd->prev_tick = tick;
	hal_axis_commit(ax, tick);
	sd->writes++;
}

int64_t simdrive_actual(struct simdrive *sd, uint32_t ch)
{
	int64_t c = 0;

	hal_axis_actual(sim_drive_axis(sd->drive), ch, &c);
	return c;
}

bool simdrive_faulted(struct simdrive *sd)
{
	struct hal_fault f;

	return hal_axis_fault(sim_drive_axis(sd->drive), &f) != 0;
}

void simdrive_trip(struct simdrive *sd)
{
	uint32_t i;

	for (i = 0; i < sd->nch; i++)
		sim_drive_inject(sd->drive, i, sd->tick + 1, SIM_DRIVE_TRIP);
	advance(sd, sd->tick + 1);
}
