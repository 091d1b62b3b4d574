/* SPDX-License-Identifier: MIT */
/*
 * opt.h - numbers on a command line: a whole number or a decimal, whole
 * (no trailing text), in plain notation, within [min, max]. Every program's
 * options go through these (strand's subcommands, strand-simdrive), so an
 * option value is refused the same way wherever it is given. Each returns
 * false when s is not such a number; *out is then unspecified.
 */
#ifndef STRAND_OPT_H
#define STRAND_OPT_H

#include <stdbool.h>

bool opt_long(const char *s, long long min, long long max, long long *out);

/* Finite, and within [min, max] (NaN and infinities are not numbers here). */
bool opt_double(const char *s, double min, double max, double *out);

#endif /* STRAND_OPT_H */
