/* SPDX-License-Identifier: MIT */
/*
 * journal_rt.c - the loop's side of the journal (journal.h): the next
 * record, ARMED before its edge goes out, FIRED after. [rt]: loads and
 * stores into a mapping the service thread made, nothing else.
 */
#include "journal.h"
#include "hal/rt.h"

struct journal_rec STRAND_RT *journal_next(struct journal *j)
{
	int64_t i = j->next;
	unsigned char *c;

	if (i >= j->capacity)
		return NULL;
	c = atomic_load_explicit(&j->chunk[i / j->per_chunk], memory_order_acquire);
	if (!c)
		return NULL;
	return (struct journal_rec *)(c + (size_t)(i % j->per_chunk) * j->rec_bytes);
}

void STRAND_RT journal_arm(struct journal *j, struct journal_rec *r)
{
	atomic_store_explicit(&r->state, JOURNAL_ARMED, memory_order_release);
	j->next++;
	atomic_store_explicit(&j->written, j->next, memory_order_release);
}

void STRAND_RT journal_fire(struct journal_rec *r, int64_t mono_ns, int64_t wall_ns)
{
	r->mono_ns = mono_ns;
	r->wall_ns = wall_ns;
	atomic_store_explicit(&r->state, JOURNAL_FIRED, memory_order_release);
}
