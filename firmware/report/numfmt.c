/* SPDX-License-Identifier: MIT */
/* numfmt.c - fast number formatting for export (see numfmt.h). */
#include "numfmt.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define SIG 10 /* significant digits */

static const double pow10_tab[] = { 1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8,
				    1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15 };

static size_t utoa(char *buf, uint64_t v)
{
	char tmp[24];
	size_t n = 0, i;

	do {
		tmp[n++] = (char)('0' + v % 10);
		v /= 10;
	} while (v);
	for (i = 0; i < n; i++)
		buf[i] = tmp[n - 1 - i];
	return n;
}

size_t numfmt_int(char *buf, int64_t v)
{
	size_t o = 0;

	if (v < 0) {
		buf[o++] = '-';
		o += utoa(buf + o, (uint64_t)0 - (uint64_t)v);
	} else {
		o += utoa(buf, (uint64_t)v);
	}
	buf[o] = '\0';
	return o;
}

/*
 * Fixed notation for 1e-4 <= |v| < 1e10: scale by 10^dec so that the
 * integer part has SIG digits, round once, and place the point. 10^dec is
 * exact in double for dec <= 22 and |v| 10^dec < 2^53, so the only
 * rounding is llround's. Everything else goes to snprintf.
 */
size_t numfmt_double(char *buf, double v)
{
	double a = fabs(v), scaled;
	uint64_t m, ip, fp;
	int e, dec;
	size_t o = 0, n;
	char digits[24];

	if (v == 0) {
		buf[0] = '0';
		buf[1] = '\0';
		return 1;
	}
	if (!(a >= 1e-4 && a < 1e10))
		return (size_t)snprintf(buf, NUMFMT_MAX, "%.*g", SIG, v);
	e = (int)floor(log10(a));
	dec = SIG - 1 - e;
	if (dec < 0)
		dec = 0;
	if (dec > 15)
		return (size_t)snprintf(buf, NUMFMT_MAX, "%.*g", SIG, v);
	scaled = a * pow10_tab[dec];
	m = (uint64_t)llround(scaled);
	if (m < (uint64_t)pow10_tab[SIG - 1] && dec < 15) {
		/* log10 rounded up across a power of ten: one more digit */
		dec++;
		m = (uint64_t)llround(a * pow10_tab[dec]);
	}
	if (v < 0)
		buf[o++] = '-';
	ip = m / (uint64_t)pow10_tab[dec];
	fp = m % (uint64_t)pow10_tab[dec];
	o += utoa(buf + o, ip);
	if (fp) {
		/* the fraction with its leading zeros, trailing zeros dropped */
		uint64_t t = fp;
		size_t nd = 0;

		do
			nd++, t /= 10;
		while (t);
		n = (size_t)dec;
		memset(digits, '0', n);
		utoa(digits + n - nd, fp);
		while (n && digits[n - 1] == '0')
			n--;
		buf[o++] = '.';
		memcpy(buf + o, digits, n);
		o += n;
	}
	buf[o] = '\0';
	return o;
}
