/* SPDX-License-Identifier: MIT */
/* sim_camera.c - the simulated camera (see sim_camera.h). */
#include "sim_camera.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "hal/rt.h"

struct sim_camera {
	struct sim_camera_params p;
	struct sim_camera_log *mem; /* the exposures */
	struct sim_camera_log *log; /* the mapped file of trigger edges, or NULL */
	size_t log_bytes;
	uint64_t missed;
	int64_t busy_until_ns;
	struct sim_gpio *ready_gpio;
	uint32_t ready_line;
	void (*on_exposure)(void *ctx, const struct sim_exposure *e);
	void *ctx;
};

static void STRAND_RT append(struct sim_camera_log *log, const struct sim_exposure *x)
{
	uint64_t n = atomic_load_explicit(&log->count, memory_order_relaxed);

	if (n < log->capacity)
		log->e[n] = *x;
	/* the entry first, then the count: a reader after a kill sees only
	 * complete entries */
	atomic_store_explicit(&log->count, n + 1, memory_order_release);
}

static void STRAND_RT on_edge(void *ctx, const struct sim_gpio_edge *e)
{
	struct sim_camera *c = ctx;
	struct sim_exposure x = { .tick = e->tick, .ts_ns = e->ts_ns, .exposed = 1 };

	if (!e->asserted)
		return;
	if (e->ts_ns < c->busy_until_ns) {
		c->missed++;
		x.exposed = 0;
		if (c->log)
			append(c->log, &x);
		return;
	}
	c->busy_until_ns = e->ts_ns + c->p.exposure_ns + c->p.readout_ns;
	if (c->log)
		append(c->log, &x);
	append(c->mem, &x);
	if (c->ready_gpio) {
		sim_gpio_schedule(c->ready_gpio, c->ready_line, e->ts_ns, false);
		sim_gpio_schedule(c->ready_gpio, c->ready_line, c->busy_until_ns, true);
	}
	if (c->on_exposure)
		c->on_exposure(c->ctx, &x);
}

int sim_camera_new(struct sim_camera **out, const struct sim_camera_params *p, uint64_t cap,
		   const char *log_path, char *err, size_t errsize)
{
	struct sim_camera *c = calloc(1, sizeof(*c));
	size_t bytes = sizeof(struct sim_camera_log) + cap * sizeof(struct sim_exposure);
	int fd, rc = -ENOMEM;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	if (!c)
		goto fail;
	c->p = *p;
	c->busy_until_ns = INT64_MIN;
	c->mem = calloc(1, bytes);
	if (!c->mem)
		goto fail;
	c->mem->capacity = cap;
	if (log_path) {
		fd = open(log_path, O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
		if (fd < 0) {
			rc = -errno;
			goto fail;
		}
		if (ftruncate(fd, (off_t)bytes)) {
			rc = -errno;
			close(fd);
			goto fail;
		}
		c->log = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
		rc = -errno;
		close(fd);
		if (c->log == MAP_FAILED) {
			c->log = NULL;
			goto fail;
		}
		c->log_bytes = bytes;
		memcpy(c->log->magic, "STRANDC2", 8);
		c->log->capacity = cap;
	}
	*out = c;
	return 0;
fail:
	snprintf(err, errsize, "simulated camera: %s", strerror(-rc));
	if (c)
		free(c->mem);
	free(c);
	return rc;
}

void sim_camera_free(struct sim_camera *c)
{
	STRAND_ASSERT_NOT_RT();
	if (!c)
		return;
	if (c->log)
		munmap(c->log, c->log_bytes);
	free(c->mem);
	free(c);
}

void sim_camera_trigger(struct sim_camera *c, struct sim_gpio *g, uint32_t line)
{
	sim_gpio_listen(g, line, on_edge, c);
}

int sim_camera_ready(struct sim_camera *c, struct sim_gpio *g, uint32_t line)
{
	c->ready_gpio = g;
	c->ready_line = line;
	return sim_gpio_schedule(g, line, INT64_MIN, true);
}

void sim_camera_on_exposure(struct sim_camera *c,
			    void (*fn)(void *ctx, const struct sim_exposure *), void *ctx)
{
	c->on_exposure = fn;
	c->ctx = ctx;
}

uint64_t sim_camera_count(const struct sim_camera *c)
{
	return atomic_load_explicit(&c->mem->count, memory_order_acquire);
}

uint64_t sim_camera_missed(const struct sim_camera *c)
{
	return c->missed;
}

const struct sim_exposure *sim_camera_exposure(const struct sim_camera *c, uint64_t i)
{
	return &c->mem->e[i];
}

int sim_camera_log_read(const char *path, struct sim_exposure **e, uint64_t *n)
{
	struct sim_camera_log h;
	int fd = open(path, O_RDONLY | O_CLOEXEC);
	uint64_t k;
	ssize_t got;
	int err = 0;

	*e = NULL;
	*n = 0;
	if (fd < 0)
		return -errno;
	if (read(fd, &h, sizeof(h)) != (ssize_t)sizeof(h) || memcmp(h.magic, "STRANDC2", 8)) {
		close(fd);
		return -EBADMSG;
	}
	k = atomic_load(&h.count);
	if (k > h.capacity)
		k = h.capacity;
	*e = malloc((k ? k : 1) * sizeof(**e));
	if (!*e) {
		close(fd);
		return -ENOMEM;
	}
	got = pread(fd, *e, k * sizeof(**e), (off_t)sizeof(h));
	if (got != (ssize_t)(k * sizeof(**e)))
		err = -EIO;
	close(fd);
	if (err) {
		free(*e);
		*e = NULL;
		return err;
	}
	*n = k;
	return 0;
}
