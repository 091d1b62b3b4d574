/* SPDX-License-Identifier: MIT */
/* journal_read.c - a journal file as CSV, for `strand journal` (journal.h). */
#include "journal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "scene/timecode.h"

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
