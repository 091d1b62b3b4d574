/* SPDX-License-Identifier: MIT */
/*
 * journal_svc.c - the service thread's side of the journal (journal.h):
 * the file, its header, and the chunks mapped ahead of the loop and
 * unmapped behind it.
 */
#include "journal.h"
#include "hal/rt.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#define CHUNK_BYTES (1u << 20)

static size_t round_up(size_t x, size_t a)
{
	return (x + a - 1) / a * a;
}

static off_t chunk_start(const struct journal *j, uint32_t c)
{
	return (off_t)j->hdr_bytes + (off_t)c * j->per_chunk * j->rec_bytes;
}

static int64_t chunk_records(const struct journal *j, uint32_t c)
{
	int64_t left = j->capacity - (int64_t)c * j->per_chunk;

	return left < j->per_chunk ? left : j->per_chunk;
}

/* Allocate the blocks of chunk c, grow the file over it, map it. */
static int map_chunk(struct journal *j, uint32_t c)
{
	off_t start = chunk_start(j, c);
	off_t end = start + (off_t)chunk_records(j, c) * j->rec_bytes;
	off_t lo = start / j->page * j->page;
	size_t len = (size_t)(end - lo);
	unsigned char *m;
	int err;
	off_t pg;

	/* posix_fallocate extends the file too; blocks exist before any store */
	err = posix_fallocate(j->fd, start, end - start);
	if (err)
		return -err;
	m = mmap(NULL, len, PROT_READ | PROT_WRITE, MAP_SHARED, j->fd, lo);
	if (m == MAP_FAILED)
		return -errno;
	/* Fault in the pages that belong to this chunk alone, so the loop's
	 * first store does not fault (the chunk is not published yet, nobody
	 * else writes them). A page shared with the previous chunk was made
	 * present through that chunk's mapping. */
	for (pg = round_up((size_t)start, (size_t)j->page); pg < end; pg += j->page)
		*(volatile unsigned char *)(m + (pg - lo)) = 0;
	j->chunk_map[c] = m;
	j->chunk_len[c] = len;
	atomic_store_explicit(&j->chunk[c], m + (start - lo), memory_order_release);
	return 0;
}

static void unmap_chunk(struct journal *j, uint32_t c)
{
	atomic_store_explicit(&j->chunk[c], NULL, memory_order_release);
	munmap(j->chunk_map[c], j->chunk_len[c]);
	j->chunk_map[c] = NULL;
}

int journal_open(struct journal *j, const char *path, const struct journal_info *info)
{
	struct journal_hdr *h;
	size_t hdr_bytes;
	uint32_t i;
	int err;

	STRAND_ASSERT_NOT_RT();
	memset(j, 0, sizeof(*j));
	j->fd = -1;
	if (info->nout > JOURNAL_OUT_MAX || info->capacity < 1 || info->ahead < 1)
		return -EINVAL;
	j->page = sysconf(_SC_PAGESIZE);
	hdr_bytes = round_up(sizeof(*h) + info->nout * sizeof(h->out[0]), (size_t)j->page);
	j->hdr_bytes = (uint32_t)hdr_bytes;
	j->rec_bytes = (uint32_t)(sizeof(struct journal_rec) + info->nout * sizeof(int64_t));
	j->per_chunk = CHUNK_BYTES / j->rec_bytes;
	if (j->per_chunk < 1)
		j->per_chunk = 1;
	j->capacity = info->capacity;
	j->nchunks = (uint32_t)((info->capacity + j->per_chunk - 1) / j->per_chunk);
	j->ahead = info->ahead;
	j->chunk = calloc(j->nchunks, sizeof(*j->chunk));
	j->chunk_map = calloc(j->nchunks, sizeof(*j->chunk_map));
	j->chunk_len = calloc(j->nchunks, sizeof(*j->chunk_len));
	h = calloc(1, hdr_bytes);
	if (!j->chunk || !j->chunk_map || !j->chunk_len || !h) {
		err = -ENOMEM;
		goto fail;
	}
	memcpy(h->magic, JOURNAL_MAGIC, 8);
	h->version = 1;
	h->hdr_bytes = j->hdr_bytes;
	h->rec_bytes = j->rec_bytes;
	h->nout = info->nout;
	h->rate_num = info->rate_num;
	h->rate_den = info->rate_den;
	h->tick_hz = info->tick_hz;
	h->mode = info->mode;
	h->start_wall_ns = info->start_wall_ns;
	h->capacity = info->capacity;
	strncpy(h->scene, info->scene ? info->scene : "", sizeof(h->scene) - 1);
	for (i = 0; i < info->nout; i++) {
		strncpy(h->out[i].name, info->out_name[i], JOURNAL_NAME_MAX - 1);
		h->out[i].unit = info->out_unit[i];
	}
	j->fd = open(path, O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
	if (j->fd < 0) {
		err = -errno;
		goto fail;
	}
	if (pwrite(j->fd, h, hdr_bytes, 0) != (ssize_t)hdr_bytes) {
		err = errno ? -errno : -EIO;
		goto fail;
	}
	free(h);
	h = NULL;
	err = journal_service(j, 0);
	if (err)
		goto fail;
	return 0;
fail:
	free(h);
	journal_close(j);
	unlink(path);
	return err;
}

int journal_service(struct journal *j, int64_t now_ns)
{
	int64_t w = atomic_load_explicit(&j->written, memory_order_acquire);
	int64_t want = w + j->ahead;
	uint32_t hi, cur = (uint32_t)(w / j->per_chunk);
	int err;

	STRAND_ASSERT_NOT_RT();
	if (j->err)
		return j->err;
	if (want > j->capacity)
		want = j->capacity;
	hi = (uint32_t)((want + j->per_chunk - 1) / j->per_chunk);
	if (hi > j->nchunks)
		hi = j->nchunks;
	while (j->mapped_hi < hi) {
		err = map_chunk(j, j->mapped_hi);
		if (err) {
			j->err = err;
			return err;
		}
		j->mapped_hi++;
	}
	/* keep the loop's chunk and the one before it (the last frame's
	 * following error is still being written there) */
	while (j->mapped_lo + 1 < cur && j->mapped_lo < j->mapped_hi) {
		unmap_chunk(j, j->mapped_lo);
		j->mapped_lo++;
	}
	if (now_ns - j->synced_at_ns >= 1000000000) {
		j->synced_at_ns = now_ns;
		fdatasync(j->fd); /* for power loss; a kill needs nothing */
	}
	return 0;
}

int journal_close(struct journal *j)
{
	int err = 0;
	uint32_t c;

	STRAND_ASSERT_NOT_RT();
	if (j->chunk_map)
		for (c = 0; c < j->nchunks; c++)
			if (j->chunk_map[c])
				unmap_chunk(j, c);
	if (j->fd >= 0) {
		off_t len = (off_t)j->hdr_bytes + (off_t)j->next * j->rec_bytes;

		if (ftruncate(j->fd, len) || fsync(j->fd))
			err = -errno;
		if (close(j->fd) && !err)
			err = -errno;
	}
	free(j->chunk);
	free(j->chunk_map);
	free(j->chunk_len);
	j->chunk = NULL;
	j->chunk_map = NULL;
	j->chunk_len = NULL;
	j->fd = -1;
	return err ? err : j->err;
}
