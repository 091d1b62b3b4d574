/* SPDX-License-Identifier: MIT */
/* dfm_parse.c - one DFMoco line (see dfm_parse.h). */
#include "dfm_parse.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

/* Each command's name and how many arguments it takes: exactly min when
 * max == min; bf takes 2 + 4 per motor. */
static const struct {
	char name[3];
	uint32_t min, max;
} table[DFM_NKINDS] = {
	[DFM_HI] = { "hi", 0, 0 }, [DFM_MS] = { "ms", 0, 0 }, [DFM_MM] = { "mm", 2, 2 },
	[DFM_MP] = { "mp", 1, 1 }, [DFM_SM] = { "sm", 1, 1 }, [DFM_SA] = { "sa", 0, 0 },
	[DFM_PR] = { "pr", 2, 2 }, [DFM_ZM] = { "zm", 1, 1 }, [DFM_NP] = { "np", 2, 2 },
	[DFM_JM] = { "jm", 2, 2 }, [DFM_IM] = { "im", 2, 2 }, [DFM_BF] = { "bf", 6, DFM_ARGS_MAX },
	[DFM_GO] = { "go", 0, 0 },
};

const char *dfm_name(enum dfm_kind k)
{
	return k < DFM_NKINDS ? table[k].name : "?";
}

static bool is_space(char ch)
{
	return ch == ' ' || ch == '\t';
}

/* A number at s[0..n): an optional sign and digits, within int32_t. */
static bool number(const char *s, size_t n, int32_t *out)
{
	int64_t v = 0;
	size_t i = 0;
	bool neg = false;

	if (i < n && (s[i] == '-' || s[i] == '+'))
		neg = s[i++] == '-';
	if (i == n)
		return false;
	for (; i < n; i++) {
		if (s[i] < '0' || s[i] > '9')
			return false;
		v = v * 10 + (s[i] - '0');
		if (v > (int64_t)INT32_MAX + 1)
			return false;
	}
	if (neg)
		v = -v;
	if (v > INT32_MAX || v < INT32_MIN)
		return false;
	*out = (int32_t)v;
	return true;
}

int dfm_parse(const char *line, size_t len, struct dfm_cmd *c, char *msg, size_t size)
{
	size_t i = 0, w;
	uint32_t k;

	if (len > DFM_LINE_MAX) {
		snprintf(msg, size, "a line of %zu bytes: at most %d", len, DFM_LINE_MAX);
		return -E2BIG;
	}
	while (i < len && is_space(line[i]))
		i++;
	if (len - i < 2 || (len - i > 2 && !is_space(line[i + 2]))) {
		snprintf(msg, size, "not a command: '%.*s'", (int)(len < 32 ? len : 32), line);
		return -EINVAL;
	}
	for (k = 0; k < DFM_NKINDS && memcmp(line + i, table[k].name, 2); k++)
		;
	if (k == DFM_NKINDS) {
		snprintf(msg, size, "unknown command '%.2s'", line + i);
		return -EINVAL;
	}
	c->kind = (enum dfm_kind)k;
	c->nargs = 0;
	for (i += 2;;) {
		while (i < len && is_space(line[i]))
			i++;
		if (i == len)
			break;
		for (w = i; w < len && !is_space(line[w]); w++)
			;
		if (c->nargs == DFM_ARGS_MAX || c->nargs == table[k].max) {
			snprintf(msg, size, "%s: too many arguments (at most %u)", table[k].name,
				 table[k].max);
			return -EINVAL;
		}
		if (!number(line + i, w - i, &c->arg[c->nargs])) {
			snprintf(msg, size, "%s: argument %u, '%.*s', is not a number within 32 bits",
				 table[k].name, c->nargs + 1, (int)(w - i < 24 ? w - i : 24), line + i);
			return -EINVAL;
		}
		c->nargs++;
		i = w;
	}
	if (c->nargs < table[k].min) {
		snprintf(msg, size, "%s: %u argument%s, it takes %u%s", table[k].name, c->nargs,
			 c->nargs == 1 ? "" : "s", table[k].min, k == DFM_BF ? " or more" : "");
		return -EINVAL;
	}
	if (k == DFM_BF && (c->nargs - 2) % 4) {
		snprintf(msg, size, "bf: %u arguments: exposure, blur, then four per motor",
			 c->nargs);
		return -EINVAL;
	}
	return 0;
}

void dfm_lines_feed(struct dfm_lines *l, const char *in, size_t n,
		    void (*fn)(void *ctx, const char *line, size_t len, bool overlong),
		    void *ctx)
{
	size_t i;

	for (i = 0; i < n; i++) {
		char ch = in[i];

		if (ch == '\n') {
			size_t len = l->len;

			if (len && l->buf[len - 1] == '\r')
				len--;
			/* an empty line is no command: Dragonframe's own "\r\n"
			 * after "\r" lines, a stray newline */
			if (len || l->overlong)
				fn(ctx, l->buf, len, l->overlong);
			l->len = 0;
			l->overlong = false;
			continue;
		}
		if (l->len < DFM_LINE_MAX + 1)
			l->buf[l->len++] = ch;
		else
			l->overlong = true;
	}
}
