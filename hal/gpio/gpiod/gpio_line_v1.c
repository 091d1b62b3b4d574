/* SPDX-License-Identifier: MIT */
/*
 * gpio_line_v1.c - gpio_line.h over libgpiod 1.x (Debian 12 ships 1.6.3):
 * chips and lines are objects the chip owns, a request is a "bulk" of
 * lines with one set of flags, and each input line requested for events
 * has a file descriptor of its own.
 *
 * The build compiles this file or gpio_line_v2.c, never both.
 */
#include "hal/gpio/gpio_line.h"

#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/rt.h"

_Static_assert(GPIO_LINE_MAX <= GPIOD_LINE_BULK_MAX_LINES, "a request is one v1 bulk");

struct gpio_req {
	struct gpiod_chip *chip;
	struct gpiod_line_bulk bulk;
	enum gpio_req_kind kind;
	uint32_t n;
	uint32_t offset[GPIO_LINE_MAX];
	int fd[GPIO_LINE_MAX]; /* inputs: each line's event descriptor */
	char chip_name[32];
};

/* The chip of the request: the one named, or the one holding the first
 * named line. */
static int open_chip(struct gpio_req *r, const struct gpio_req_cfg *cfg, char *err, size_t size)
{
	const struct gpio_line_cfg *first = &cfg->lines[0];
	struct gpiod_line *l;

	if (cfg->chip) {
		r->chip = gpiod_chip_open_lookup(cfg->chip);
		if (!r->chip)
			return gpio_line_fail(err, size, -ENOENT, cfg->chip, NULL,
					      "no such GPIO chip (%s); gpiodetect lists them",
					      strerror(errno));
	} else {
		if (!first->name)
			return gpio_line_fail(err, size, -EINVAL, NULL, first,
					      "a line given by offset needs a chip");
		l = gpiod_line_find(first->name);
		if (!l)
			return gpio_line_fail(err, size, -ENOENT, NULL, first,
					      "no GPIO line of that name on any chip; gpioinfo "
					      "lists them");
		r->chip = gpiod_line_get_chip(l);
	}
	snprintf(r->chip_name, sizeof(r->chip_name), "%s", gpiod_chip_name(r->chip));
	return 0;
}

static int find_line(struct gpio_req *r, const struct gpio_req_cfg *cfg, uint32_t i,
		     struct gpiod_line **out, char *err, size_t size)
{
	const struct gpio_line_cfg *lc = &cfg->lines[i];
	struct gpiod_line *l;

	if (lc->name) {
		l = gpiod_chip_find_line(r->chip, lc->name);
		if (l) {
			*out = l;
			return 0;
		}
		l = cfg->chip ? NULL : gpiod_line_find(lc->name);
		if (l) {
			char other[32];

			snprintf(other, sizeof(other), "%s", gpiod_chip_name(gpiod_line_get_chip(l)));
			gpiod_line_close_chip(l);
			return gpio_line_fail(err, size, -EXDEV, r->chip_name, lc,
					      "is on %s, and one request takes the lines of one "
					      "chip: give the device one chip", other);
		}
		return gpio_line_fail(err, size, -ENOENT, r->chip_name, lc,
				      "no line of that name on the chip; gpioinfo %s lists them",
				      r->chip_name);
	}
	if (lc->offset >= gpiod_chip_num_lines(r->chip))
		return gpio_line_fail(err, size, -EINVAL, r->chip_name, lc,
				      "the chip has lines 0 to %u", gpiod_chip_num_lines(r->chip) - 1);
	l = gpiod_chip_get_line(r->chip, lc->offset);
	if (!l)
		return gpio_line_fail(err, size, -errno, r->chip_name, lc, "%s", strerror(errno));
	*out = l;
	return 0;
}

/* After a refused request: which line is held, and by whom. */
static int request_failed(struct gpio_req *r, const struct gpio_req_cfg *cfg, int e, char *err,
			  size_t size)
{
	uint32_t i;

	for (i = 0; e == EBUSY && i < r->n; i++) {
		struct gpiod_line *l = r->bulk.lines[i];

		if (gpiod_line_update(l) == 0 && gpiod_line_is_used(l))
			return gpio_line_busy(err, size, r->chip_name, &cfg->lines[i], r->offset[i],
					      gpiod_line_consumer(l));
	}
	return gpio_line_fail(err, size, -e, r->chip_name, NULL, "requesting %u line%s: %s", r->n,
			      r->n == 1 ? "" : "s", strerror(e));
}

int gpio_req_open(struct gpio_req **out, const struct gpio_req_cfg *cfg, char *err,
		  size_t errsize)
{
	int initial[GPIO_LINE_MAX] = { 0 };
	struct gpio_req *r;
	uint32_t i, k;
	int rc;

	*out = NULL;
	if (!cfg->nlines || cfg->nlines > GPIO_LINE_MAX)
		return gpio_line_fail(err, errsize, -EINVAL, cfg->chip, NULL,
				      "%u lines in one request (1 to %u)", cfg->nlines,
				      GPIO_LINE_MAX);
	r = calloc(1, sizeof(*r));
	if (!r)
		return gpio_line_fail(err, errsize, -ENOMEM, cfg->chip, NULL, "out of memory");
	r->kind = cfg->kind;
	gpiod_line_bulk_init(&r->bulk);
	rc = open_chip(r, cfg, err, errsize);
	if (rc)
		goto fail;
	for (i = 0; i < cfg->nlines; i++) {
		struct gpiod_line *l = NULL;

		rc = find_line(r, cfg, i, &l, err, errsize);
		if (rc)
			goto fail;
		r->offset[i] = gpiod_line_offset(l);
		for (k = 0; k < i; k++)
			if (r->offset[k] == r->offset[i]) {
				rc = gpio_line_fail(err, errsize, -EINVAL, r->chip_name,
						    &cfg->lines[i], "offset %u is listed twice",
						    r->offset[i]);
				goto fail;
			}
		gpiod_line_bulk_add(&r->bulk, l);
		initial[i] = cfg->initial && cfg->initial[i];
	}
	r->n = cfg->nlines;
	if (cfg->kind == GPIO_REQ_OUTPUT)
		rc = gpiod_line_request_bulk_output(&r->bulk, cfg->consumer, initial);
	else
		rc = gpiod_line_request_bulk_both_edges_events(&r->bulk, cfg->consumer);
	if (rc) {
		rc = request_failed(r, cfg, errno, err, errsize);
		goto fail;
	}
	for (i = 0; cfg->kind == GPIO_REQ_INPUT_EDGES && i < r->n; i++)
		r->fd[i] = gpiod_line_event_get_fd(r->bulk.lines[i]);
	*out = r;
	return 0;
fail:
	if (r->chip)
		gpiod_chip_close(r->chip);
	free(r);
	return rc;
}

void gpio_req_close(struct gpio_req *r)
{
	if (!r)
		return;
	gpiod_line_release_bulk(&r->bulk);
	gpiod_chip_close(r->chip);
	free(r);
}

const char *gpio_req_chip(const struct gpio_req *r)
{
	return r->chip_name;
}

uint32_t gpio_req_offset(const struct gpio_req *r, uint32_t line)
{
	return r->offset[line];
}

int STRAND_RT gpio_req_set(struct gpio_req *r, const bool *high)
{
	int v[GPIO_LINE_MAX];
	uint32_t i;

	for (i = 0; i < r->n; i++)
		v[i] = high[i];
	return gpiod_line_set_value_bulk(&r->bulk, v) ? -errno : 0;
}

int gpio_req_get(struct gpio_req *r, bool *high)
{
	int v[GPIO_LINE_MAX];
	uint32_t i;

	if (gpiod_line_get_value_bulk(&r->bulk, v))
		return -errno;
	for (i = 0; i < r->n; i++)
		high[i] = v[i] != 0;
	return 0;
}

uint32_t gpio_req_fds(const struct gpio_req *r, int *fds, uint32_t max)
{
	uint32_t i;

	if (r->kind != GPIO_REQ_INPUT_EDGES)
		return 0;
	for (i = 0; i < r->n && i < max; i++)
		fds[i] = r->fd[i];
	return i;
}

int gpio_req_read(struct gpio_req *r, uint32_t k, struct gpio_line_event *ev, uint32_t max)
{
	struct gpiod_line_event e[16];
	int i, n;

	if (k >= r->n || r->kind != GPIO_REQ_INPUT_EDGES)
		return -EINVAL;
	n = gpiod_line_event_read_fd_multiple(r->fd[k], e, max < 16 ? max : 16);
	if (n < 0)
		return -errno;
	for (i = 0; i < n; i++) {
		ev[i].line = k;
		ev[i].rising = e[i].event_type == GPIOD_LINE_EVENT_RISING_EDGE;
		ev[i].ts_ns = (int64_t)e[i].ts.tv_sec * 1000000000 + e[i].ts.tv_nsec;
	}
	return n;
}

const char *gpio_line_lib_version(void)
{
	return gpiod_version_string();
}
