/* SPDX-License-Identifier: MIT */
/* journal_read.c - a journal file as CSV, for `strand journal` (journal.h). */
#include "journal.h"

#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
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

/* Where version v's output names begin: version 1 had none of the byte
 * order and layout fields, its out[] began where they are now. */
static size_t out_offset(uint32_t v)
{
	return v == 1 ? offsetof(struct journal_hdr, byte_order) : offsetof(struct journal_hdr, out);
}

/* Whether the header hh of a file of `size` bytes is one this build reads:
 * 0, or -EBADMSG with msg saying why not. */
static int check_header(const char *path, const struct journal_hdr *hh, off_t size, char *msg,
			unsigned msgsize)
{
	uint32_t v = hh->version;

	if (size < (off_t)sizeof(*hh) || memcmp(hh->magic, JOURNAL_MAGIC, 8)) {
		snprintf(msg, msgsize, "%s: not a strand journal", path);
		return -EBADMSG;
	}
	/* the version is the first number: in the other byte order it reads
	 * reversed, in either version */
	if (v < 1 || v > JOURNAL_VERSION || (v >= 2 && hh->byte_order != JOURNAL_BYTE_ORDER)) {
		uint32_t bv = __builtin_bswap32(v);

		if (bv >= 1 && bv <= JOURNAL_VERSION)
			snprintf(msg, msgsize, "%s: a strand journal written on a machine of the other "
				 "byte order (%s-endian); read it with strand on such a machine", path,
				 __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ ? "big" : "little");
		else if (v > JOURNAL_VERSION && v < 0x10000)
			snprintf(msg, msgsize, "%s: a strand journal of version %u; this strand reads "
				 "versions 1 to %u", path, v, JOURNAL_VERSION);
		else
			snprintf(msg, msgsize, "%s: not a strand journal", path);
		return -EBADMSG;
	}
	if (v >= 2 && hh->layout != journal_layout()) {
		snprintf(msg, msgsize, "%s: a strand journal whose records are laid out otherwise "
			 "(layout 0x%08x, this build's 0x%08x: another architecture's ABI); read "
			 "it with strand on the machine that wrote it", path, hh->layout,
			 journal_layout());
		return -EBADMSG;
	}
	if (v >= 2 && hh->probe != JOURNAL_PROBE) {
		snprintf(msg, msgsize, "%s: a strand journal whose doubles are not this machine's "
			 "IEEE 754 format; read it with strand on the machine that wrote it", path);
		return -EBADMSG;
	}
	if (hh->nout > JOURNAL_OUT_MAX ||
	    hh->hdr_bytes < out_offset(v) + hh->nout * sizeof(hh->out[0]) ||
	    hh->rec_bytes != journal_rec_bytes(hh->nout, v >= 3 ? hh->mode : 0) ||
	    !hh->rate_num || !hh->rate_den) {
		snprintf(msg, msgsize, "%s: not a strand journal", path);
		return -EBADMSG;
	}
	return 0;
}

int journal_csv(const char *path, FILE *out, char *msg, unsigned msgsize)
{
	struct journal_hdr hh, *h = NULL;
	const struct journal_out *o;
	struct journal_rec *r = NULL;
	struct timecode tc, src_tc;
	bool gomo;
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
	memset(&hh, 0, sizeof(hh));
	if (fstat(fd, &st) || pread(fd, &hh, sizeof(hh), 0) < 0) {
		err = -errno;
		snprintf(msg, msgsize, "%s: %s", path, strerror(errno));
		close(fd);
		return err;
	}
	err = check_header(path, &hh, st.st_size, msg, msgsize);
	if (err) {
		close(fd);
		return err;
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
	o = (const struct journal_out *)((const char *)h + out_offset(h->version));
	gomo = h->version >= 3 && (h->mode & JOURNAL_MODE_GOMO);
	timecode_init(&tc, h->rate_num, h->rate_den);
	/* the source counts at most 30 labels a second (play.c) */
	timecode_init(&src_tc, (double)h->rate_num / h->rate_den > 30.5 ? h->rate_num / 2 :
			       h->rate_num, h->rate_den);
	fprintf(out, "frame,timecode,%stick,trigger,state,due_ns,mono_ns,late_us,wall,ferr,"
		"ferr_channel%s", h->mode & JOURNAL_MODE_CHASE ? "source_tc," : "",
		gomo ? ",open_tick,close_tick" : "");
	for (i = 0; i < h->nout; i++)
		fprintf(out, ",%.*s", JOURNAL_NAME_MAX, o[i].name);
	/* go-motion: the setpoints where the exposure opened and closed */
	for (i = 0; gomo && i < h->nout; i++)
		fprintf(out, ",%.*s@open", JOURNAL_NAME_MAX, o[i].name);
	for (i = 0; gomo && i < h->nout; i++)
		fprintf(out, ",%.*s@close", JOURNAL_NAME_MAX, o[i].name);
	fputc('\n', out);
	for (off = h->hdr_bytes; off + (off_t)h->rec_bytes <= st.st_size; off += h->rec_bytes) {
		char tcs[48], wall[48];
		struct journal_gomo *g;
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
		if (h->mode & JOURNAL_MODE_CHASE) { /* and the source's */
			size_t l = strlen(tcs);

			tcs[l++] = ',';
			if (r->src_frame)
				timecode_format(&src_tc, (int64_t)r->src_frame - 1, tcs + l,
						(unsigned)(sizeof(tcs) - l));
			else
				tcs[l] = '\0';
		}
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
				o[r->ferr_out].unit == JOURNAL_UNIT_TURNS ? r->ferr * 360.0 : r->ferr,
				JOURNAL_NAME_MAX, o[r->ferr_out].name);
		else
			fputc(',', out);
		g = gomo ? journal_gomo_of(r, h->nout) : NULL;
		if (g && g->close_tick >= 0)
			fprintf(out, ",%lld,%lld", (long long)g->open_tick, (long long)g->close_tick);
		else if (g)
			fputs(",,", out); /* the exposure had not ended */
		for (i = 0; i < h->nout; i++)
			fprintf(out, ",%.10g", to_file_units(r->sp[i], o[i].unit));
		for (i = 0; g && i < 2 * h->nout; i++) {
			if (g->close_tick >= 0)
				fprintf(out, ",%.10g", to_file_units(g->sp[i], o[i % h->nout].unit));
			else
				fputc(',', out);
		}
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
