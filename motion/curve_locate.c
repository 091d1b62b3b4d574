/* SPDX-License-Identifier: MIT */
/*
 * curve_locate.c - the piece or key interval that holds a frame, from the
 * cursor's last answer (curve_priv.h: locate_seg, locate_key). Real-time
 * safe: O(1) when the cursor moved to the same or the next entry, O(log n)
 * otherwise.
 */
#include "curve_priv.h"

/* The start frame of key interval j (keys) or of piece j. */
static inline mot_q32 start_of(const struct mot_curve *c, bool keys, uint32_t j)
{
	return keys ? c->keys[j].frame : c->seg[j].f0;
}

/* The start of interval or piece j + 1 (j + 1 < n): a piece's own f1, so
 * that the cursor's test reads one segment entry, not two. */
static inline mot_q32 end_of(const struct mot_curve *c, bool keys, uint32_t j)
{
	return keys ? c->keys[j + 1].frame : c->seg[j].f1;
}

/*
 * The last index j in [0, n) whose start is at or before f, given a
 * non-decreasing array of starts with start(0) <= f: the key intervals (n =
 * nkeys - 1) or the pieces (n = nseg). The hint (the cursor's last answer)
 * is tried first, then its successor; otherwise a binary search. A stale or
 * foreign hint costs only the search. Empty pieces (equal starts) are never
 * the answer.
 */
uint32_t mot_cv_locate(const struct mot_curve *c, bool keys, uint32_t n, uint32_t hint,
		       mot_q32 f)
{
	uint32_t lo = 0, hi = n;

	if (hint < n && start_of(c, keys, hint) <= f) {
		if (hint + 1 == n || f < end_of(c, keys, hint))
			return hint;
		if (hint + 2 == n || f < end_of(c, keys, hint + 1))
			return hint + 1;
		lo = hint + 2;
	}
	while (hi - lo > 1) {
		uint32_t mid = lo + (hi - lo) / 2;

		if (start_of(c, keys, mid) <= f)
			lo = mid;
		else
			hi = mid;
	}
	return lo;
}
