/* SPDX-License-Identifier: MIT */
/*
 * journal_rt.c - the loop's side of the journal (journal.h): the next
 * record, ARMED before its edge goes out, FIRED after. [rt]: loads and
 * stores into a mapping the service thread made, nothing else.
 */
#include "journal.h"

#include <errno.h>

#include "hal/rt.h"

static bool STRAND_RT full(const struct journal *j)
{
	return j->capacity != JOURNAL_UNBOUNDED && j->next >= j->capacity;
}

struct journal_rec STRAND_RT *journal_next(struct journal *j)
{
	int64_t i = j->next, c = i / j->per_chunk;
	const struct journal_slot *s = &j->slot[c % j->nslots];

	if (full(j))
		return NULL;
	/* The slot may still hold the chunk nslots before (not unmapped
	 * yet), or be between two: only its own number says it is c. The
	 * acquire pairs with the service's release after it set `first`
	 * and faulted the pages in; the slot is not reused while the loop
	 * is in c (journal_svc.c), so `first` stays c's. */
	if (atomic_load_explicit(&s->chunk, memory_order_acquire) != c)
		return NULL;
	return (struct journal_rec *)(s->first + (size_t)(i % j->per_chunk) * j->rec_bytes);
}

int STRAND_RT journal_refused(const struct journal *j)
{
	int err = journal_error(j);

	return err ? err : full(j) ? -ENOSPC : 0;
}

void STRAND_RT journal_arm(struct journal *j, struct journal_rec *r)
{
	atomic_store_explicit(&r->state, JOURNAL_ARMED, memory_order_release);
	j->next++;
	/* releases the record to the service: it unmaps nothing the loop
	 * may still write (journal_info.behind) */
	atomic_store_explicit(&j->written, j->next, memory_order_release);
}

void STRAND_RT journal_fire(struct journal_rec *r, int64_t mono_ns, int64_t wall_ns)
{
	r->mono_ns = mono_ns;
	r->wall_ns = wall_ns;
	atomic_store_explicit(&r->state, JOURNAL_FIRED, memory_order_release);
}
