/* SPDX-License-Identifier: MIT */
/*
 * gpio_line_fake.c - gpio_line.h without a kernel, for tests/test_gpio.c:
 * one chip of FAKE_LINES lines in memory. An input request's edge events
 * come through one pipe per line, written by the test (fake_edge), so the
 * backend's event thread polls real descriptors. Linked into test_gpio
 * only, ahead of libfw.a, so that the archive's real implementation is not
 * pulled in.
 */
#include "gpio_line_fake.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct fake_chip fake_chip = { .name = "gpiochip7" };

struct gpio_req {
	enum gpio_req_kind kind;
	uint32_t n;
	uint32_t offset[GPIO_LINE_MAX];
	int rd[GPIO_LINE_MAX], wr[GPIO_LINE_MAX]; /* inputs: a pipe per line */
};

static struct gpio_req *input_req; /* the last input request, for fake_edge */
/* A level changes with its event at once, as far as the backend's thread
 * can tell (the kernel's window between the two is not what is tested). */
static pthread_mutex_t fake_lock = PTHREAD_MUTEX_INITIALIZER;

void fake_reset(void)
{
	memset(&fake_chip, 0, sizeof(fake_chip));
	fake_chip.name = "gpiochip7";
	input_req = NULL;
}

static int lookup(const struct gpio_req_cfg *cfg, const struct gpio_line_cfg *l, uint32_t *off,
		  char *err, size_t size)
{
	uint32_t i;

	if (!l->name) {
		if (l->offset >= FAKE_LINES)
			return gpio_line_fail(err, size, -EINVAL, fake_chip.name, l,
					      "the chip has lines 0 to %d", FAKE_LINES - 1);
		*off = l->offset;
		return 0;
	}
	for (i = 0; i < FAKE_LINES; i++)
		if (fake_chip.line_name[i] && !strcmp(fake_chip.line_name[i], l->name)) {
			*off = i;
			return 0;
		}
	return gpio_line_fail(err, size, -ENOENT, fake_chip.name, l,
			      "no line of that name on the chip");
}

int gpio_req_open(struct gpio_req **out, const struct gpio_req_cfg *cfg, char *err,
		  size_t errsize)
{
	struct gpio_req *r;
	uint32_t i;
	int rc, p[2];

	*out = NULL;
	if (cfg->chip && strcmp(cfg->chip, fake_chip.name))
		return gpio_line_fail(err, errsize, -ENOENT, cfg->chip, NULL, "no such GPIO chip");
	r = calloc(1, sizeof(*r));
	if (!r)
		return -ENOMEM;
	r->kind = cfg->kind;
	r->n = cfg->nlines;
	for (i = 0; i < r->n; i++) {
		rc = lookup(cfg, &cfg->lines[i], &r->offset[i], err, errsize);
		if (rc)
			goto fail;
		if (fake_chip.holder[r->offset[i]]) {
			rc = gpio_line_busy(err, errsize, fake_chip.name, &cfg->lines[i],
					    r->offset[i], fake_chip.holder[r->offset[i]]);
			goto fail;
		}
	}
	for (i = 0; i < r->n; i++) {
		fake_chip.holder[r->offset[i]] = cfg->consumer;
		if (cfg->kind == GPIO_REQ_OUTPUT) {
			fake_chip.high[r->offset[i]] = cfg->initial && cfg->initial[i];
		} else {
			if (pipe(p))
				abort();
			r->rd[i] = p[0];
			r->wr[i] = p[1];
		}
	}
	if (cfg->kind == GPIO_REQ_INPUT_EDGES)
		input_req = r;
	*out = r;
	return 0;
fail:
	free(r);
	return rc;
}

void gpio_req_close(struct gpio_req *r)
{
	uint32_t i;

	if (!r)
		return;
	for (i = 0; i < r->n; i++) {
		fake_chip.holder[r->offset[i]] = NULL;
		if (r->kind == GPIO_REQ_INPUT_EDGES) {
			close(r->rd[i]);
			if (r->wr[i] >= 0)
				close(r->wr[i]);
		}
	}
	if (input_req == r)
		input_req = NULL;
	free(r);
}

const char *gpio_req_chip(const struct gpio_req *r)
{
	return fake_chip.name;
}

uint32_t gpio_req_offset(const struct gpio_req *r, uint32_t line)
{
	return r->offset[line];
}

int gpio_req_set(struct gpio_req *r, const bool *high)
{
	uint32_t i;

	if (fake_chip.set_error)
		return fake_chip.set_error;
	fake_chip.sets++;
	for (i = 0; i < r->n; i++)
		fake_chip.high[r->offset[i]] = high[i];
	return 0;
}

int gpio_req_get(struct gpio_req *r, bool *high)
{
	uint32_t i;

	pthread_mutex_lock(&fake_lock);
	for (i = 0; i < r->n; i++)
		high[i] = fake_chip.high[r->offset[i]];
	pthread_mutex_unlock(&fake_lock);
	return 0;
}

uint32_t gpio_req_fds(const struct gpio_req *r, int *fds, uint32_t max)
{
	uint32_t i;

	if (r->kind != GPIO_REQ_INPUT_EDGES)
		return 0;
	for (i = 0; i < r->n && i < max; i++)
		fds[i] = r->rd[i];
	return i;
}

int gpio_req_read(struct gpio_req *r, uint32_t k, struct gpio_line_event *ev, uint32_t max)
{
	ssize_t n = read(r->rd[k], ev, sizeof(*ev));

	if (n < 0)
		return -errno;
	if (n != sizeof(*ev))
		return -EIO;
	ev->line = k;
	return 1;
}

const char *gpio_line_lib_version(void)
{
	return "fake";
}

void fake_edge(uint32_t line, bool rising, int64_t ts_ns)
{
	struct gpio_line_event e = { .line = line, .rising = rising, .ts_ns = ts_ns };

	pthread_mutex_lock(&fake_lock);
	fake_chip.high[input_req->offset[line]] = rising;
	if (write(input_req->wr[line], &e, sizeof(e)) != sizeof(e))
		abort();
	pthread_mutex_unlock(&fake_lock);
}

void fake_level(uint32_t offset, bool high)
{
	pthread_mutex_lock(&fake_lock);
	fake_chip.high[offset] = high;
	pthread_mutex_unlock(&fake_lock);
}

void fake_unplug(uint32_t line)
{
	close(input_req->wr[line]);
	input_req->wr[line] = -1;
}
