/* SPDX-License-Identifier: MIT */
/* journal.c - the crash-proof frame journal (see journal.h). */
#include "journal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "scene/timecode.h"

#define CHUNK_BYTES (1u << 20)
#define JOURNAL_OUT_MAX 4096

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

struct journal_rec *journal_next(struct journal *j)
{
	int64_t i = j->next;
	unsigned char *c;

	if (i >= j->capacity)
		return NULL;
	c = atomic_load_explicit(&j->chunk[i / j->per_chunk], memory_order_acquire);
	if (!c)
		return NULL;
	return (struct journal_rec *)(c + (size_t)(i % j->per_chunk) * j->rec_bytes);
}

void journal_arm(struct journal *j, struct journal_rec *r)
{
	atomic_store_explicit(&r->state, JOURNAL_ARMED, memory_order_release);
	j->next++;
	atomic_store_explicit(&j->written, j->next, memory_order_release);
}

void journal_fire(struct journal_rec *r, int64_t mono_ns, int64_t wall_ns)
{
	r->mono_ns = mono_ns;
	r->wall_ns = wall_ns;
	atomic_store_explicit(&r->state, JOURNAL_FIRED, memory_order_release);
}

int journal_service(struct journal *j, int64_t now_ns)
{
	int64_t w = atomic_load_explicit(&j->written, memory_order_acquire);
	int64_t want = w + j->ahead;
	uint32_t hi, cur = (uint32_t)(w / j->per_chunk);
	int err;

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

/* ---- reading ---- */

static void wall_iso(int64_t ns, char *buf, size_t size)
{
	time_t s = (time_t)(ns >= 0 ? ns / 1000000000 : (ns - 999999999) / 1000000000);
	long frac = (long)(ns - (int64_t)s * 1000000000);
	struct tm tm;
	size_t n;

	gmtime_r(&s, &tm);
	n = strftime(buf, size, "%Y-%m-%dT%H:%M:%S", &tm);
	snprintf(buf + n, size - n, ".%09ldZ", frac);
}

static double to_file_units(int64_t q, uint32_t unit)
{
	double v = (double)q / 4294967296.0;

	return unit == JOURNAL_UNIT_TURNS ? v * 360.0 : v;
}

int journal_csv(const char *path, FILE *out, char *msg, unsigned msgsize)
{
	struct journal_hdr hh, *h = NULL;
	struct journal_rec *r = NULL;
	struct timecode tc;
	struct stat st;
	int fd, err = 0;
	uint32_t i;
	off_t off;

	fd = open(path, O_RDONLY | O_CLOEXEC);
	if (fd < 0) {
		err = -errno;
		snprintf(msg, msgsize, "%s: %s", path, strerror(errno));
		return err;
	}
	if (fstat(fd, &st) || pread(fd, &hh, sizeof(hh), 0) != (ssize_t)sizeof(hh) ||
	    memcmp(hh.magic, JOURNAL_MAGIC, 8) || hh.version != 1 || hh.nout > JOURNAL_OUT_MAX ||
	    hh.hdr_bytes < sizeof(hh) + hh.nout * sizeof(hh.out[0]) ||
	    hh.rec_bytes != sizeof(*r) + hh.nout * sizeof(int64_t) || !hh.rate_num ||
	    !hh.rate_den) {
		snprintf(msg, msgsize, "%s: not a strand journal", path);
		close(fd);
		return -EBADMSG;
	}
	h = malloc(hh.hdr_bytes);
	r = malloc(hh.rec_bytes);
	if (!h || !r) {
		err = -ENOMEM;
		snprintf(msg, msgsize, "out of memory");
		goto out;
	}
	if (pread(fd, h, hh.hdr_bytes, 0) != (ssize_t)hh.hdr_bytes) {
		err = -EIO;
		snprintf(msg, msgsize, "%s: truncated header", path);
		goto out;
	}
	timecode_init(&tc, h->rate_num, h->rate_den);
	fprintf(out, "frame,timecode,tick,trigger,state,due_ns,mono_ns,late_us,wall,ferr,ferr_channel");
	for (i = 0; i < h->nout; i++)
		fprintf(out, ",%.*s", JOURNAL_NAME_MAX, h->out[i].name);
	fputc('\n', out);
	for (off = h->hdr_bytes; off + (off_t)h->rec_bytes <= st.st_size; off += h->rec_bytes) {
		char tcs[24], wall[48];
		uint32_t state;

		if (pread(fd, r, h->rec_bytes, off) != (ssize_t)h->rec_bytes) {
			err = -EIO;
			snprintf(msg, msgsize, "%s: read error", path);
			break;
		}
		state = atomic_load(&r->state);
		if (state == JOURNAL_EMPTY)
			break; /* the end of a journal whose writer was killed */
		timecode_format(&tc, r->frame, tcs, sizeof(tcs));
		if (state == JOURNAL_FIRED) {
			wall_iso(r->wall_ns, wall, sizeof(wall));
			fprintf(out, "%lld,%s,%lld,%u,fired,%lld,%lld,%.3f,%s,",
				(long long)r->frame, tcs, (long long)r->tick, r->trigger,
				(long long)r->due_ns, (long long)r->mono_ns,
				(double)(r->mono_ns - r->due_ns) / 1000.0, wall);
		} else {
			fprintf(out, "%lld,%s,%lld,%u,armed,%lld,,,,", (long long)r->frame, tcs,
				(long long)r->tick, r->trigger, (long long)r->due_ns);
		}
		if (r->ferr_out >= 0 && (uint32_t)r->ferr_out < h->nout)
			fprintf(out, "%.10g,%.*s",
				h->out[r->ferr_out].unit == JOURNAL_UNIT_TURNS ? r->ferr * 360.0 : r->ferr,
				JOURNAL_NAME_MAX, h->out[r->ferr_out].name);
		else
			fputc(',', out);
		for (i = 0; i < h->nout; i++)
			fprintf(out, ",%.10g", to_file_units(r->sp[i], h->out[i].unit));
		fputc('\n', out);
	}
	if (!err && ferror(out)) {
		err = -EIO;
		snprintf(msg, msgsize, "write error");
	}
out:
	free(h);
	free(r);
	close(fd);
	return err;
}
