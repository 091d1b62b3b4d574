/* SPDX-License-Identifier: MIT */
/*
 * ring.h - a single-producer single-consumer lock-free ring of fixed-size
 * elements, the one way data crosses between the strand-rt thread and an
 * ordinary thread (journal and telemetry out, edge events and bus replies
 * in). As grbl's planner and stepper share their block buffer: static
 * storage sized before the run, no lock, no allocation.
 *
 * The caller owns the storage: capacity (a power of two) elements of esize
 * bytes. head counts pushes, tail counts pops, both free-running 32-bit
 * counters (their difference is the fill level, wrap-around included). The
 * producer publishes an element with a release store of head after copying
 * it in; the consumer reads head with acquire before copying out, and the
 * mirror image for tail. The two counters live on separate cache lines so
 * that the threads do not bounce one line between their cores.
 *
 * push and pop are [rt] on their own side, never blocking: a full ring
 * refuses the push, an empty one the pop.
 */
#ifndef HAL_RING_H
#define HAL_RING_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "rt.h" /* STRAND_RT */

struct hal_ring {
	_Alignas(64) _Atomic uint32_t head; /* producer's */
	_Alignas(64) _Atomic uint32_t tail; /* consumer's */
	_Alignas(64) uint32_t mask;         /* capacity - 1 */
	uint32_t esize;
	unsigned char *buf;
};

/* [init] capacity must be a power of two (>= 2): 0, or -EINVAL. */
int hal_ring_init(struct hal_ring *r, void *storage, uint32_t capacity, uint32_t esize);

/* [rt, producer] Copy one element in: false when the ring is full. */
static inline bool STRAND_RT hal_ring_push(struct hal_ring *r, const void *e)
{
	uint32_t h = atomic_load_explicit(&r->head, memory_order_relaxed);
	uint32_t t = atomic_load_explicit(&r->tail, memory_order_acquire);

	if (h - t > r->mask)
		return false;
	memcpy(r->buf + (size_t)(h & r->mask) * r->esize, e, r->esize);
	atomic_store_explicit(&r->head, h + 1, memory_order_release);
	return true;
}

/* [rt, consumer] Copy the oldest element out: false when empty. */
static inline bool STRAND_RT hal_ring_pop(struct hal_ring *r, void *e)
{
	uint32_t t = atomic_load_explicit(&r->tail, memory_order_relaxed);
	uint32_t h = atomic_load_explicit(&r->head, memory_order_acquire);

	if (h == t)
		return false;
	memcpy(e, r->buf + (size_t)(t & r->mask) * r->esize, r->esize);
	atomic_store_explicit(&r->tail, t + 1, memory_order_release);
	return true;
}

/* Elements waiting, as seen from either side (a snapshot). */
static inline uint32_t STRAND_RT hal_ring_count(struct hal_ring *r)
{
	return atomic_load_explicit(&r->head, memory_order_acquire) -
	       atomic_load_explicit(&r->tail, memory_order_acquire);
}

#endif /* HAL_RING_H */
