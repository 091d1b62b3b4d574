/* SPDX-License-Identifier: MIT */
/*
 * gpio_line_v2.c - gpio_line.h over libgpiod 2.x: a chip is opened by path
 * only, a request is built from settings and config objects that are freed
 * as soon as it is made, and a request has one file descriptor for the
 * edge events of all its lines.
 *
 * The build compiles this file or gpio_line_v1.c, never both. Debian 12 has
 * only libgpiod 1.6, so this file is not compiled by this project's own
 * build and tests; it is written against libgpiod 2's include/gpiod.h and
 * checked with -fsyntax-only against that header (README, "GPIO").
 */
#include "hal/gpio/gpio_line.h"

#include <dirent.h>
#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/rt.h"

#define EVENTS_MAX 16

struct gpio_req {
	struct gpiod_chip *chip;
	struct gpiod_line_request *req;
	struct gpiod_edge_event_buffer *events; /* inputs: read into, never reallocated */
	enum gpio_req_kind kind;
	uint32_t n;
	unsigned int offset[GPIO_LINE_MAX];
	char chip_name[32];
};

/* Open /dev/<name> when it is a GPIO chip. */
static struct gpiod_chip *open_dev(const char *name)
{
	char path[300];

	snprintf(path, sizeof(path), "/dev/%s", name);
	return gpiod_is_gpiochip_device(path) ? gpiod_chip_open(path) : NULL;
}

/*
 * v2 opens chips by path only. Accept what v1's gpiod_chip_open_lookup()
 * accepted: a path, a name (gpiochip0), a number (0) or a label; or, with
 * no spec, the chip that has a line named `line`.
 */
static struct gpiod_chip *lookup_chip(const char *spec, const char *line)
{
	struct gpiod_chip *c = NULL;
	struct dirent *de;
	char name[280];
	DIR *dir;

	if (spec && strchr(spec, '/'))
		return gpiod_chip_open(spec);
	if (spec && spec[0] >= '0' && spec[0] <= '9' && strspn(spec, "0123456789") == strlen(spec)) {
		snprintf(name, sizeof(name), "gpiochip%s", spec);
		return open_dev(name);
	}
	if (spec && (c = open_dev(spec)))
		return c;
	dir = opendir("/dev");
	if (!dir)
		return NULL;
	while ((de = readdir(dir))) {
		struct gpiod_chip_info *info;
		bool match;

		if (strncmp(de->d_name, "gpiochip", 8))
			continue;
		c = open_dev(de->d_name);
		if (!c)
			continue;
		if (spec) {
			info = gpiod_chip_get_info(c);
			match = info && !strcmp(gpiod_chip_info_get_label(info), spec);
			if (info)
				gpiod_chip_info_free(info);
		} else {
			match = gpiod_chip_get_line_offset_from_name(c, line) >= 0;
		}
		if (match)
			break;
		gpiod_chip_close(c);
		c = NULL;
	}
	closedir(dir);
	if (!c)
		errno = ENOENT;
	return c;
}

static int open_chip(struct gpio_req *r, const struct gpio_req_cfg *cfg, char *err, size_t size)
{
	const struct gpio_line_cfg *first = &cfg->lines[0];
	struct gpiod_chip_info *info;

	if (!cfg->chip && !first->name)
		return gpio_line_fail(err, size, -EINVAL, NULL, first,
				      "a line given by offset needs a chip");
	r->chip = lookup_chip(cfg->chip, first->name);
	if (!r->chip && cfg->chip)
		return gpio_line_fail(err, size, -ENOENT, cfg->chip, NULL,
				      "no such GPIO chip (%s); gpiodetect lists them",
				      strerror(errno));
	if (!r->chip)
		return gpio_line_fail(err, size, -ENOENT, NULL, first,
				      "no GPIO line of that name on any chip; gpioinfo lists them");
	info = gpiod_chip_get_info(r->chip);
	snprintf(r->chip_name, sizeof(r->chip_name), "%s",
		 info ? gpiod_chip_info_get_name(info) : gpiod_chip_get_path(r->chip));
	if (info)
		gpiod_chip_info_free(info);
	return 0;
}

static int find_line(struct gpio_req *r, const struct gpio_req_cfg *cfg, uint32_t i, char *err,
		     size_t size)
{
	const struct gpio_line_cfg *lc = &cfg->lines[i];
	struct gpiod_chip_info *info;
	struct gpiod_chip *other;
	size_t nlines;
	int off;

	if (lc->name) {
		off = gpiod_chip_get_line_offset_from_name(r->chip, lc->name);
		if (off >= 0) {
			r->offset[i] = (unsigned int)off;
			return 0;
		}
		other = cfg->chip ? NULL : lookup_chip(NULL, lc->name);
		if (other) {
			char where[32];

			info = gpiod_chip_get_info(other);
			snprintf(where, sizeof(where), "%s",
				 info ? gpiod_chip_info_get_name(info) : "another chip");
			if (info)
				gpiod_chip_info_free(info);
			gpiod_chip_close(other);
			return gpio_line_fail(err, size, -EXDEV, r->chip_name, lc,
					      "is on %s, and one request takes the lines of one "
					      "chip: give the device one chip", where);
		}
		return gpio_line_fail(err, size, -ENOENT, r->chip_name, lc,
				      "no line of that name on the chip; gpioinfo %s lists them",
				      r->chip_name);
	}
	info = gpiod_chip_get_info(r->chip);
	if (!info)
		return gpio_line_fail(err, size, -errno, r->chip_name, lc, "%s", strerror(errno));
	nlines = gpiod_chip_info_get_num_lines(info);
	gpiod_chip_info_free(info);
	if (lc->offset >= nlines)
		return gpio_line_fail(err, size, -EINVAL, r->chip_name, lc,
				      "the chip has lines 0 to %zu", nlines - 1);
	r->offset[i] = lc->offset;
	return 0;
}

static int request_failed(struct gpio_req *r, const struct gpio_req_cfg *cfg, int e, char *err,
			  size_t size)
{
	uint32_t i;
	int rc;

	for (i = 0; e == EBUSY && i < r->n; i++) {
		struct gpiod_line_info *li = gpiod_chip_get_line_info(r->chip, r->offset[i]);

		if (li && gpiod_line_info_is_used(li)) {
			rc = gpio_line_busy(err, size, r->chip_name, &cfg->lines[i], r->offset[i],
					    gpiod_line_info_get_consumer(li));
			gpiod_line_info_free(li);
			return rc;
		}
		if (li)
			gpiod_line_info_free(li);
	}
	return gpio_line_fail(err, size, -e, r->chip_name, NULL, "requesting %u line%s: %s", r->n,
			      r->n == 1 ? "" : "s", strerror(e));
}

/* Settings and config live only for the request, as libgpiod intends. */
static struct gpiod_line_request *request(struct gpio_req *r, const struct gpio_req_cfg *cfg)
{
	enum gpiod_line_value initial[GPIO_LINE_MAX];
	uint32_t i;
	struct gpiod_line_settings *ls = gpiod_line_settings_new();
	struct gpiod_line_config *lc = gpiod_line_config_new();
	struct gpiod_request_config *rc = gpiod_request_config_new();
	struct gpiod_line_request *req = NULL;
	int ok = ls && lc && rc;

	if (ok && r->kind == GPIO_REQ_OUTPUT) {
		ok = !gpiod_line_settings_set_direction(ls, GPIOD_LINE_DIRECTION_OUTPUT) &&
		     !gpiod_line_settings_set_output_value(ls, GPIOD_LINE_VALUE_INACTIVE);
	} else if (ok) {
		ok = !gpiod_line_settings_set_direction(ls, GPIOD_LINE_DIRECTION_INPUT) &&
		     !gpiod_line_settings_set_edge_detection(ls, GPIOD_LINE_EDGE_BOTH) &&
		     !gpiod_line_settings_set_event_clock(ls, GPIOD_LINE_CLOCK_MONOTONIC);
	}
	if (ok)
		ok = !gpiod_line_config_add_line_settings(lc, r->offset, r->n, ls);
	for (i = 0; i < r->n; i++)
		initial[i] = cfg->initial && cfg->initial[i] ? GPIOD_LINE_VALUE_ACTIVE :
							       GPIOD_LINE_VALUE_INACTIVE;
	if (ok && r->kind == GPIO_REQ_OUTPUT)
		ok = !gpiod_line_config_set_output_values(lc, initial, r->n);
	if (ok) {
		gpiod_request_config_set_consumer(rc, cfg->consumer);
		req = gpiod_chip_request_lines(r->chip, rc, lc);
	} else if (!errno) {
		errno = ENOMEM;
	}
	/* the free functions are not documented to take NULL */
	if (rc)
		gpiod_request_config_free(rc);
	if (lc)
		gpiod_line_config_free(lc);
	if (ls)
		gpiod_line_settings_free(ls);
	return req;
}

int gpio_req_open(struct gpio_req **out, const struct gpio_req_cfg *cfg, char *err,
		  size_t errsize)
{
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
	rc = open_chip(r, cfg, err, errsize);
	if (rc)
		goto fail;
	for (i = 0; i < cfg->nlines; i++) {
		rc = find_line(r, cfg, i, err, errsize);
		if (rc)
			goto fail;
		for (k = 0; k < i; k++)
			if (r->offset[k] == r->offset[i]) {
				rc = gpio_line_fail(err, errsize, -EINVAL, r->chip_name,
						    &cfg->lines[i], "offset %u is listed twice",
						    r->offset[i]);
				goto fail;
			}
	}
	r->n = cfg->nlines;
	if (r->kind == GPIO_REQ_INPUT_EDGES) {
		r->events = gpiod_edge_event_buffer_new(EVENTS_MAX);
		if (!r->events) {
			rc = gpio_line_fail(err, errsize, -ENOMEM, r->chip_name, NULL,
					    "out of memory");
			goto fail;
		}
	}
	errno = 0;
	r->req = request(r, cfg);
	if (!r->req) {
		rc = request_failed(r, cfg, errno ? errno : EIO, err, errsize);
		goto fail;
	}
	*out = r;
	return 0;
fail:
	gpiod_edge_event_buffer_free(r->events);
	if (r->chip)
		gpiod_chip_close(r->chip);
	free(r);
	return rc;
}

void gpio_req_close(struct gpio_req *r)
{
	if (!r)
		return;
	gpiod_line_request_release(r->req);
	gpiod_edge_event_buffer_free(r->events);
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
	enum gpiod_line_value v[GPIO_LINE_MAX];
	uint32_t i;

	for (i = 0; i < r->n; i++)
		v[i] = high[i] ? GPIOD_LINE_VALUE_ACTIVE : GPIOD_LINE_VALUE_INACTIVE;
	return gpiod_line_request_set_values(r->req, v) ? -errno : 0;
}

int gpio_req_get(struct gpio_req *r, bool *high)
{
	enum gpiod_line_value v[GPIO_LINE_MAX];
	uint32_t i;

	if (gpiod_line_request_get_values(r->req, v))
		return -errno;
	for (i = 0; i < r->n; i++)
		high[i] = v[i] == GPIOD_LINE_VALUE_ACTIVE;
	return 0;
}

uint32_t gpio_req_fds(const struct gpio_req *r, int *fds, uint32_t max)
{
	if (r->kind != GPIO_REQ_INPUT_EDGES || !max)
		return 0;
	fds[0] = gpiod_line_request_get_fd(r->req);
	return 1;
}

int gpio_req_read(struct gpio_req *r, uint32_t k, struct gpio_line_event *ev, uint32_t max)
{
	int i, n;
	uint32_t j;

	if (k != 0 || r->kind != GPIO_REQ_INPUT_EDGES)
		return -EINVAL;
	n = gpiod_line_request_read_edge_events(r->req, r->events, max < EVENTS_MAX ? max : EVENTS_MAX);
	if (n < 0)
		return -errno;
	for (i = 0; i < n; i++) {
		struct gpiod_edge_event *e = gpiod_edge_event_buffer_get_event(r->events, (unsigned long)i);
		unsigned int off = gpiod_edge_event_get_line_offset(e);

		for (j = 0; j < r->n && r->offset[j] != off; j++)
			;
		ev[i].line = j; /* == n: not ours, which the kernel never sends */
		ev[i].rising = gpiod_edge_event_get_event_type(e) == GPIOD_EDGE_EVENT_RISING_EDGE;
		ev[i].ts_ns = (int64_t)gpiod_edge_event_get_timestamp_ns(e);
	}
	return n;
}

const char *gpio_line_lib_version(void)
{
	return gpiod_api_version();
}
