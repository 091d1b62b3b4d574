/* SPDX-License-Identifier: MIT */
/*
 * numfmt.h - numbers as export prints them: the shortest decimal with 10
 * significant digits (like printf's %.10g), but a few times faster, because
 * a day of frames is millions of rows of dozens of numbers.
 */
#ifndef STRAND_NUMFMT_H
#define STRAND_NUMFMT_H

#include <stddef.h>
#include <stdint.h>

#define NUMFMT_MAX 32 /* bytes a number may take, with the NUL */

/* Write v into buf (NUMFMT_MAX bytes) with at least 10 significant digits;
 * returns its length. */
size_t numfmt_double(char *buf, double v);

/* Write a whole number; returns its length. */
size_t numfmt_int(char *buf, int64_t v);

#endif /* STRAND_NUMFMT_H */
