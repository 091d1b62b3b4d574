/* SPDX-License-Identifier: MIT */
/*
 * slot.h - a lock-free "newest wins" slot between one producer and one
 * consumer: a triple buffer. Where ring.h keeps every element in order, a
 * slot keeps only the latest: the producer never waits and never fails, and
 * the consumer, whenever it looks, gets the newest value published since it
 * last looked (or nothing new). A bus backend's I/O thread takes the loop's
 * setpoints this way: when the bus is slower than the tick, the drive gets
 * the newest setpoint, never a queue of stale ones.
 *
 * Three buffers of esize bytes, owned by the caller: the producer fills its
 * back buffer and publishes it by swapping it with the middle one (one
 * atomic exchange, release); the consumer takes by swapping its front
 * buffer with the middle one when the middle is marked fresh (acquire). No
 * buffer is ever written by one side while the other reads it.
 *
 * The producer's functions are [rt] on its side, the consumer's on its own.
 */
#ifndef HAL_SLOT_H
#define HAL_SLOT_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "rt.h" /* STRAND_RT */

#define HAL_SLOT_FRESH 4u

struct hal_slot {
	_Alignas(64) _Atomic uint32_t mid; /* middle buffer's index | HAL_SLOT_FRESH */
	_Alignas(64) uint32_t back;        /* producer's buffer */
	_Alignas(64) uint32_t front;       /* consumer's buffer */
	uint32_t esize;
	unsigned char *buf;
};

/* [init] storage holds 3 * esize bytes. 0, or -EINVAL. */
int hal_slot_init(struct hal_slot *s, void *storage, uint32_t esize);

/* [rt, producer] The buffer to fill before hal_slot_publish(). */
static inline void STRAND_RT *hal_slot_back(struct hal_slot *s)
{
	return s->buf + (size_t)s->back * s->esize;
}

/* [rt, producer] Publish the back buffer. true when the previous publication
 * had not been taken yet: it is replaced, never seen by the consumer. */
static inline bool STRAND_RT hal_slot_publish(struct hal_slot *s)
{
	uint32_t old = atomic_exchange_explicit(&s->mid, s->back | HAL_SLOT_FRESH,
						memory_order_acq_rel);

	s->back = old & 3;
	return old & HAL_SLOT_FRESH;
}

/* [rt, consumer] The newest publication not taken yet, or NULL. The
 * pointer stays valid until the next take. */
static inline const void STRAND_RT *hal_slot_take(struct hal_slot *s)
{
	uint32_t old;

	if (!(atomic_load_explicit(&s->mid, memory_order_acquire) & HAL_SLOT_FRESH))
		return NULL;
	old = atomic_exchange_explicit(&s->mid, s->front, memory_order_acq_rel);
	s->front = old & 3;
	return s->buf + (size_t)s->front * s->esize;
}

#endif /* HAL_SLOT_H */
