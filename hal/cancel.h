/* SPDX-License-Identifier: MIT */
/*
 * cancel.h - a request to give up the start of the devices, made from a
 * signal handler (SIGINT, SIGTERM) and seen by the waits of the backends'
 * [init] start(): a CANopen bus's boot-ups, SDO configuration and enabling
 * (seconds), a Modbus unit's connection and first transactions.
 *
 * The program makes one request for a run and installs its handlers before
 * any device starts; each backend gets it with its configuration, as it
 * gets the clock (co_axis_cfg, modbus_cfg; the rig passes rig_opts.cancel
 * on). A backend whose start() waits looks at it at least every
 * HAL_CANCEL_POLL_NS (a signal also cuts short the system call it waits
 * in, where the call allows); once it is set, the start goes no further:
 * nothing more is enabled, what was enabled is disabled through the
 * backend's ordinary stop, and start() returns -ECANCELED. The rig checks it
 * between devices too (rig_start), so a run that is asked to stop while its
 * devices start leaves none of them enabled.
 *
 * NULL stands for a request that never comes (tests, strand-simdrive, the
 * benchmarks). Requesting is async-signal-safe: one lock-free atomic store.
 */
#ifndef HAL_CANCEL_H
#define HAL_CANCEL_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

_Static_assert(ATOMIC_BOOL_LOCK_FREE == 2, "a signal handler sets it: it must be lock-free");

struct hal_cancel {
	atomic_bool requested;
};

/* The longest a start waits without looking at the request. */
#define HAL_CANCEL_POLL_NS (50 * 1000000LL)

/* [any thread, signal handlers] Ask every start under way to give up. */
static inline void hal_cancel_request(struct hal_cancel *c)
{
	atomic_store(&c->requested, true);
}

/* [init] Whether it was asked (never for NULL). */
static inline bool hal_cancelled(const struct hal_cancel *c)
{
	return c && atomic_load(&c->requested);
}

/* [init] A run's request, not asked yet. */
static inline void hal_cancel_init(struct hal_cancel *c)
{
	atomic_init(&c->requested, false);
}

#endif /* HAL_CANCEL_H */
