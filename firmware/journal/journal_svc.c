/* SPDX-License-Identifier: MIT */
/*
 * journal_svc.c - the service thread's side of the journal (journal.h):
 * the file, its header, and the ring of chunks mapped ahead of the loop and
 * unmapped behind it.
 *
 * Why nslots = (ahead + behind) / per_chunk + 2 slots are enough: the
 * service keeps mapped the chunks from lo, that of record w - behind (w the
 * records armed when it looked), up to hi, the first chunk wholly beyond
 * record w + ahead. With x = w - behind = L * per_chunk + r (0 <= r <
 * per_chunk) and n = ahead + behind, hi - lo = ceil((r + n) / per_chunk) <=
 * 1 + ceil((n - 1) / per_chunk) <= 2 + n / per_chunk. So the chunk that
 * goes into a slot is always nslots past the one it replaces, which was
 * unmapped first: the loop, which looks for chunk c in slot c % nslots,
 * finds c there or another number, never another chunk's memory under c's.
 * And a slot is reused only for a chunk the loop has not reached, after
 * the loop has left the chunk it held (journal_next).
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

static off_t chunk_start(const struct journal *j, int64_t c)
{
	return (off_t)j->hdr_bytes + (off_t)c * j->per_chunk * j->rec_bytes;
}

static int64_t chunk_records(const struct journal *j, int64_t c)
{
	int64_t left;

	if (j->capacity == JOURNAL_UNBOUNDED)
		return j->per_chunk;
	left = j->capacity - c * j->per_chunk;
	return left < j->per_chunk ? left : j->per_chunk;
}

static struct journal_slot *slot_of(struct journal *j, int64_t c)
{
	return &j->slot[c % j->nslots];
}

/* Allocate the blocks of chunk c, grow the file over it, map it into its
 * slot (free: its last chunk was unmapped), publish it. */
static int map_chunk(struct journal *j, int64_t c)
{
	struct journal_slot *s = slot_of(j, c);
	off_t start = chunk_start(j, c);
	off_t end = start + (off_t)chunk_records(j, c) * j->rec_bytes;
	off_t lo = start / j->page * j->page;
	size_t len = (size_t)(end - lo);
	unsigned char *m;
	int err;
	off_t pg;

	/* posix_fallocate extends the file too; blocks exist before any
	 * store, so a full disk is ENOSPC here, not a SIGBUS in the loop;
	 * a signal that interrupts it (tmpfs checks) is no reason to stop */
	do
		err = posix_fallocate(j->fd, start, end - start);
	while (err == EINTR);
	if (err)
		return -err;
	m = mmap(NULL, len, PROT_READ | PROT_WRITE, MAP_SHARED, j->fd, lo);
	if (m == MAP_FAILED)
		return -errno;
	/* Fault every page in, so that the loop's first store does not fault
	 * (under mlockall the mapping came populated). The first page may be
	 * shared with the previous chunk, whose last record the loop may be
	 * writing right now: it is touched at this chunk's first byte, which
	 * nobody writes before the chunk is published. */
	for (pg = start; pg < end; pg = (pg / j->page + 1) * j->page)
		*(volatile unsigned char *)(m + (pg - lo)) = 0;
	s->map = m;
	s->len = len;
	s->first = m + (start - lo);
	atomic_store_explicit(&s->chunk, c, memory_order_release);
	return 0;
}

static void unmap_chunk(struct journal *j, int64_t c)
{
	struct journal_slot *s = slot_of(j, c);

	/* withdrawn before it goes: a loop that looks now finds no chunk */
	atomic_store_explicit(&s->chunk, -1, memory_order_release);
	munmap(s->map, s->len);
	s->map = NULL;
	s->first = NULL;
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
	if (info->nout > JOURNAL_OUT_MAX || info->ahead < 1 || info->behind < 0 ||
	    (info->capacity < 1 && info->capacity != JOURNAL_UNBOUNDED))
		return -EINVAL;
	j->page = sysconf(_SC_PAGESIZE);
	hdr_bytes = round_up(sizeof(*h) + info->nout * sizeof(h->out[0]), (size_t)j->page);
	j->hdr_bytes = (uint32_t)hdr_bytes;
	j->rec_bytes = (uint32_t)journal_rec_bytes(info->nout, info->mode);
	j->mode = info->mode;
	j->per_chunk = CHUNK_BYTES / j->rec_bytes;
	if (j->per_chunk < 1)
		j->per_chunk = 1;
	j->capacity = info->capacity;
	j->ahead = info->ahead;
	j->behind = info->behind ? info->behind : 1;
	/* what is in flight, not the run: see the top of the file */
	j->nslots = (uint32_t)((j->ahead + j->behind) / j->per_chunk + 2);
	j->slot = calloc(j->nslots, sizeof(*j->slot));
	h = calloc(1, hdr_bytes);
	if (!j->slot || !h) {
		err = -ENOMEM;
		goto fail;
	}
	for (i = 0; i < j->nslots; i++)
		atomic_init(&j->slot[i].chunk, -1);
	memcpy(h->magic, JOURNAL_MAGIC, 8);
	h->version = JOURNAL_VERSION;
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
	h->byte_order = JOURNAL_BYTE_ORDER;
	h->layout = journal_layout();
	h->probe = JOURNAL_PROBE;
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
	int64_t want = w + j->ahead, lo, hi;
	int err;

	STRAND_ASSERT_NOT_RT();
	err = atomic_load_explicit(&j->err, memory_order_relaxed);
	if (err)
		return err;
	if (j->capacity != JOURNAL_UNBOUNDED && want > j->capacity)
		want = j->capacity;
	hi = (want + j->per_chunk - 1) / j->per_chunk;
	/* the chunk of the oldest record the loop may still write: one tick's
	 * edges get their FIRED times, the current frame its following error */
	lo = w > j->behind ? (w - j->behind) / j->per_chunk : 0;
	/* behind first: the chunks ahead go into the slots this frees */
	while (j->mapped_lo < lo && j->mapped_lo < j->mapped_hi)
		unmap_chunk(j, j->mapped_lo++);
	while (j->mapped_hi < hi && j->mapped_hi - j->mapped_lo < j->nslots) {
		err = map_chunk(j, j->mapped_hi);
		if (err) {
			/* the loop stops at the last record mapped (journal_refused) */
			atomic_store_explicit(&j->err, err, memory_order_release);
			return err;
		}
		j->mapped_hi++;
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

	STRAND_ASSERT_NOT_RT();
	if (j->slot)
		while (j->mapped_lo < j->mapped_hi)
			unmap_chunk(j, j->mapped_lo++);
	if (j->fd >= 0) {
		off_t len = (off_t)j->hdr_bytes + (off_t)j->next * j->rec_bytes;

		if (ftruncate(j->fd, len) || fsync(j->fd))
			err = -errno;
		if (close(j->fd) && !err)
			err = -errno;
	}
	free(j->slot);
	j->slot = NULL;
	j->fd = -1;
	return err ? err : atomic_load(&j->err);
}
