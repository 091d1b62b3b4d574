/* SPDX-License-Identifier: MIT */
/*
 * journal.h - the record of every frame trigger fired, written so that it
 * survives the process being killed.
 *
 * The journal is a file mapped into memory (MAP_SHARED) that the loop writes
 * into directly: a store into the mapping is in the kernel's page cache the
 * moment it is made, so `kill -9` one instruction later loses nothing
 * (a power cut is another matter: the service thread asks for writeback
 * once a second). No ring, no writer thread in between, no system call in
 * the loop.
 *
 * Layout: a header (magic, rates, output names and units) padded to a page,
 * then fixed-size records, one per rising trigger edge, in firing order.
 * A record is written in two steps around the edge:
 *
 *     1. the whole record with state ARMED (frame, tick, every setpoint)
 *     2. the edge goes out (hal_dout_commit), the clock is read
 *     3. the edge's monotonic and wall times, then state FIRED (release)
 *
 * A record left ARMED by a kill between 1 and 3 is the one frame whose edge
 * may or may not have gone out; `strand journal` prints it with state
 * "armed". Every FIRED record is an edge that went out; every edge that
 * went out has a record. The worst following error of a frame is filled in
 * while the frame lasts (until the next edge).
 *
 * Space: the loop never maps, grows or allocates. The file is mapped in
 * chunks of about 1 MiB by the service thread (an ordinary thread), ahead
 * of the loop: it allocates the disk blocks first (posix_fallocate), so a
 * full disk is an error the service reports and not a SIGBUS in the loop,
 * maps the chunk (populated at once under mlockall, touched page by page
 * otherwise) and publishes its address; chunks the loop has left behind
 * are unmapped. Mapping in chunks keeps memory bounded however long a
 * --loop runs, and keeps mlockall(MCL_FUTURE) from populating a mapping the
 * size of a day's journal. A record whose chunk is not mapped yet is refused
 * (journal_next returns NULL) and the loop stops the run rather than fire a
 * frame it cannot record; on the virtual clock it waits for the service.
 *
 * The loop's side is journal_rt.c, the service thread's journal_svc.c, the
 * reader (`strand journal`) journal_read.c.
 */
#ifndef STRAND_JOURNAL_H
#define STRAND_JOURNAL_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#define JOURNAL_MAGIC "STRANDJ1"
#define JOURNAL_NAME_MAX 48
#define JOURNAL_OUT_MAX 4096 /* outputs a journal holds at most */

enum journal_state {
	JOURNAL_EMPTY = 0,
	JOURNAL_ARMED = 1,
	JOURNAL_FIRED = 2,
};

/* How a channel's core value is written in the CSV. */
enum journal_unit {
	JOURNAL_UNIT_TURNS = 0, /* core turns, written as degrees */
	JOURNAL_UNIT_PLAIN = 1, /* scene units, rpm, index, attribute value */
};

struct journal_out {
	char name[JOURNAL_NAME_MAX];
	uint32_t unit; /* enum journal_unit */
	uint32_t pad;
};

struct journal_hdr {
	char magic[8];
	uint32_t version;
	uint32_t hdr_bytes;
	uint32_t rec_bytes;
	uint32_t nout;
	uint32_t rate_num, rate_den;
	uint32_t tick_hz;
	uint32_t mode; /* 0 continuous, 1 step */
	int64_t start_wall_ns;
	int64_t capacity; /* records the file has room for */
	char scene[64];
	struct journal_out out[];
};

struct journal_rec {
	_Atomic uint32_t state; /* enum journal_state */
	uint32_t trigger;       /* index of the trigger line */
	int64_t frame;
	int64_t tick;     /* run tick of the edge */
	int64_t due_ns;   /* when that tick was due (monotonic) */
	int64_t mono_ns;  /* clock right after the edge went out */
	int64_t wall_ns;  /* the same instant on CLOCK_REALTIME */
	double ferr;      /* worst |following error| during the frame, core units */
	int32_t ferr_out; /* its output, -1 when no output has feedback */
	uint32_t pad;
	int64_t sp[];     /* nout setpoints, Q32.32 core units */
};

struct journal {
	int fd;
	uint32_t hdr_bytes;
	uint32_t rec_bytes;
	uint32_t per_chunk; /* records per chunk */
	long page;
	int64_t capacity;   /* records */
	uint32_t nchunks;
	_Atomic(unsigned char *) *chunk; /* nchunks: first record of each mapped chunk, or NULL */
	void **chunk_map;   /* service: what to munmap */
	size_t *chunk_len;
	uint32_t mapped_lo, mapped_hi; /* service: chunks [lo, hi) are mapped */
	int64_t next;            /* loop: records armed so far */
	_Atomic int64_t written; /* loop -> service: records armed */
	int64_t ahead;           /* records the service keeps mapped ahead */
	_Atomic int err;         /* service -> loop: first error (negative errno) */
	int64_t synced_at_ns;
};

struct journal_info {
	const char *scene;
	uint32_t rate_num, rate_den, tick_hz;
	uint32_t mode;
	int64_t start_wall_ns;
	uint32_t nout;
	const char *const *out_name;
	const uint32_t *out_unit;
	int64_t capacity; /* records */
	int64_t ahead;    /* records to keep mapped ahead of the loop (>= 1) */
};

/* [init] Create the file (truncating an old one), write the header and
 * prepare the first records. 0 or a negative errno. */
int journal_open(struct journal *j, const char *path, const struct journal_info *info);

/*
 * [rt] The loop's side, per edge: r = journal_next() (NULL: its chunk is not
 * mapped yet, or the journal is full); fill r's fields; journal_arm(j, r);
 * the edge goes out; journal_fire(r, mono, wall).
 */
struct journal_rec *journal_next(struct journal *j);
void journal_arm(struct journal *j, struct journal_rec *r);
void journal_fire(struct journal_rec *r, int64_t mono_ns, int64_t wall_ns);

/* [service thread] Map chunks ahead of the loop, unmap those behind it, ask
 * for writeback once a second. 0 or the first error (sticky). */
int journal_service(struct journal *j, int64_t now_ns);

/* [init] Flush, cut the file to the records written, unmap, close. */
int journal_close(struct journal *j);

/* [init] Print a journal file as CSV with a header row. 0 or a negative
 * errno; msg says what was wrong with the file. */
int journal_csv(const char *path, FILE *out, char *msg, unsigned msgsize);

#endif /* STRAND_JOURNAL_H */
