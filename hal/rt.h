/* SPDX-License-Identifier: MIT */
/*
 * rt.h - the real-time boundary, enforced rather than only written down.
 *
 * The comments of the HAL say where each operation may be called from:
 * [init] before the loop starts or after it ended, [rt] from the strand-rt
 * thread while the loop runs (axis.h). Two things hold them to it, as the
 * kernel holds __init code to its place with modpost's section-mismatch
 * check and might_sleep():
 *
 *   STRAND_RT            on the definition of every [rt] function: it is
 *                        placed in the section .text.strand_rt, and
 *                        mk/check-rt.sh fails the build when anything in
 *                        that section references an allocator, stdio, a
 *                        lock, a call that sleeps, or a function of the
 *                        project that is neither STRAND_RT nor part of the
 *                        motion core (proven allocation- and libc-free by
 *                        `make check-freestanding`).
 *   STRAND_ASSERT_NOT_RT()  first in every [init] function that may block
 *                        or allocate: in a debug build (STRAND_DEBUG, the
 *                        sanitized build the tests run) it aborts with the
 *                        function's name when called on the loop's thread;
 *                        in a release it is nothing.
 *
 * Tagging. Put STRAND_RT where the kernel puts __init, after the return
 * type: `static int STRAND_RT ca_input(...)`, `static const char STRAND_RT
 * *emcy_text(...)`. Tag the function, not its prototype. A call through a
 * function pointer cannot be followed by the check, so every operation an
 * ops table marks [rt] is tagged in every backend; a static helper an [rt]
 * function calls is tagged too (the check does not follow untagged
 * functions, as modpost does not). A static inline function of a header
 * that [rt] code calls is tagged as well: inlined, its code is in its
 * caller's section and checked there; where the compiler keeps a copy
 * (-O1, a big body) the copy goes to .text.strand_rt and is checked in
 * its own right. Functions GCC makes from a tagged one (.constprop, .isra,
 * .part clones) stay in its section.
 *
 * The section name is chosen so that no function lands in it by accident:
 * with -ffunction-sections GCC names a function's section .text.NAME, so a
 * function called strand_rt would; mk/check-rt.sh refuses a symbol of that
 * name. GCC does not split a function with a section of its own into hot
 * and cold parts; if a future one did, the cold part (.text.unlikely) would
 * be an untagged function to the check, which fails rather than passes.
 */
#ifndef HAL_RT_H
#define HAL_RT_H

#include <stdbool.h>

#define STRAND_RT __attribute__((section(".text.strand_rt")))

/* True on the thread that runs the loop, between strand_rt_enter() and
 * strand_rt_leave(); what STRAND_ASSERT_NOT_RT() and the tests' allocation
 * counter (tests/playutil.c) key on. */
extern _Thread_local bool strand_rt_thread;

/* [rt thread] The loop's thread says so before its first tick, and after
 * its last one. */
static inline void strand_rt_enter(void)
{
	strand_rt_thread = true;
}

static inline void strand_rt_leave(void)
{
	strand_rt_thread = false;
}

/* [any thread] Is this the loop's thread, inside the loop? */
static inline bool STRAND_RT strand_rt_here(void)
{
	return strand_rt_thread;
}

/* Prints "strand: FUNC is [init] and was called from the real-time thread"
 * on stderr and aborts. */
void strand_rt_assert_failed(const char *func) __attribute__((noreturn, cold));

#ifdef STRAND_DEBUG
#define STRAND_ASSERT_NOT_RT()                                \
	do {                                                  \
		if (strand_rt_thread)                         \
			strand_rt_assert_failed(__func__);    \
	} while (0)
#else
#define STRAND_ASSERT_NOT_RT() ((void)0)
#endif

#endif /* HAL_RT_H */
