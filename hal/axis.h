/* SPDX-License-Identifier: MIT */
/*
 * axis.h - the HAL interface of a device that moves axes: a servo drive, a
 * multi-axis controller, a Modbus unit, a CANopen bus with its nodes.
 *
 * A device has nch channels (axes), numbered from 0. Each tick the loop calls,
 * in this order:
 *
 *     hal_axis_input()    gather feedback and status that arrived
 *     hal_axis_actual()   read a channel's actual position (if it has one)
 *     hal_axis_set()      stage a setpoint per channel
 *     hal_axis_commit()   send the staged setpoints as one transaction
 *
 * so a backend can batch a tick's setpoints (one Modbus write of adjacent
 * registers, the RPDOs of every node and then one SYNC). Setpoints and
 * feedback are device counts: the rig scales scene units with struct
 * hal_scale (scale.h) before they reach the device.
 *
 * Where each operation may be called from (as LinuxCNC's HAL marks them):
 *   [init]  before the loop starts or after it ended, from an ordinary
 *           thread: may block, allocate, talk on the bus and wait.
 *   [rt]    from the strand-rt thread while the loop runs: no allocation, no
 *           blocking system call, no lock shared with another thread, bounded
 *           time. A backend whose bus blocks (libmodbus) hands the work to an
 *           I/O thread of its own through a lock-free slot.
 * Both are enforced (hal/rt.h): every [rt] operation of a backend is
 * STRAND_RT, which `make check-rt` holds to these rules, and an [init] one
 * that may block starts with STRAND_ASSERT_NOT_RT().
 *
 * Every operation of a backend's table is implemented (there is no NULL to
 * test for in the loop); a device without feedback answers false from
 * actual().
 *
 * Errors are negative errno codes. A fault is latched by the backend and
 * described by struct hal_fault (fault.h) with a static cause string; the
 * message that names the device and the channel is built at the edge (the
 * CLI), never in the loop.
 */
#ifndef HAL_AXIS_H
#define HAL_AXIS_H

#include <stdbool.h>
#include <stdint.h>

#include "fault.h"
#include "rt.h" /* STRAND_RT */

/* One channel's setpoint for one tick, in device counts. pos is the target
 * position (cyclic synchronous position); vel the velocity in counts per
 * second: the velocity target of a velocity-mode channel (a spin joint in
 * cyclic synchronous velocity), a feed-forward term for a position channel. */
struct hal_setpoint {
	int64_t pos;
	int64_t vel;
};

struct hal_axis;

struct hal_axis_ops {
	/* [init] Bring the device up and enable its power stage; the channels
	 * hold their present position. 0 or a negative errno; -ECANCELED
	 * when the cancel request its configuration gave (cancel.h) came
	 * while it waited: then nothing of it is left enabled. */
	int (*start)(struct hal_axis *ax);
	/* [rt] Take in what arrived since the last tick (feedback, status).
	 * 0, or the negative errno of a fault latched now or before. */
	int (*input)(struct hal_axis *ax, int64_t tick);
	/* [rt] Actual position of channel ch in counts as of the last input():
	 * true and *counts set, or false when the channel has no feedback. */
	bool (*actual)(struct hal_axis *ax, uint32_t ch, int64_t *counts);
	/* [rt] Stage channel ch's setpoint for this tick. */
	void (*set)(struct hal_axis *ax, uint32_t ch, const struct hal_setpoint *sp);
	/* [rt] Send every staged setpoint of this tick. 0 or a negative errno. */
	int (*commit)(struct hal_axis *ax, int64_t tick);
	/* [rt] The first latched fault: 0 when healthy, else its code with *f
	 * filled. */
	int (*fault)(struct hal_axis *ax, struct hal_fault *f);
	/* [rt] Power stage off now (e-stop, fault). Never blocks: a bus backend
	 * queues the request and completes it from its own thread. Idempotent. */
	void (*disable)(struct hal_axis *ax);
	/* [init] Orderly end after the loop: disable if still enabled and wait
	 * until the device confirms. 0 or a negative errno. */
	int (*stop)(struct hal_axis *ax);
	/* [init] Release everything the backend holds, the struct included. */
	void (*close)(struct hal_axis *ax);
};

/* The part every backend's struct starts with. */
struct hal_axis {
	const struct hal_axis_ops *ops; /* first: the backend's table */
	const char *name;               /* the device's name in the scene */
	uint32_t nch;                   /* channels 0 .. nch - 1 */
};

static inline int hal_axis_start(struct hal_axis *ax)
{
	return ax->ops->start(ax);
}

static inline int STRAND_RT hal_axis_input(struct hal_axis *ax, int64_t tick)
{
	return ax->ops->input(ax, tick);
}

static inline bool STRAND_RT hal_axis_actual(struct hal_axis *ax, uint32_t ch, int64_t *counts)
{
	return ax->ops->actual(ax, ch, counts);
}

static inline void STRAND_RT hal_axis_set(struct hal_axis *ax, uint32_t ch,
					  const struct hal_setpoint *sp)
{
	ax->ops->set(ax, ch, sp);
}

static inline int STRAND_RT hal_axis_commit(struct hal_axis *ax, int64_t tick)
{
	return ax->ops->commit(ax, tick);
}

static inline int STRAND_RT hal_axis_fault(struct hal_axis *ax, struct hal_fault *f)
{
	return ax->ops->fault(ax, f);
}

static inline void STRAND_RT hal_axis_disable(struct hal_axis *ax)
{
	ax->ops->disable(ax);
}

static inline int hal_axis_stop(struct hal_axis *ax)
{
	return ax->ops->stop(ax);
}

static inline void hal_axis_close(struct hal_axis *ax)
{
	if (ax)
		ax->ops->close(ax);
}

#endif /* HAL_AXIS_H */
