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
 * of the loop: it allocates the disk blocks first (posix_fallocate, which
 * also grows the file), so a full disk is an error the service reports and
 * not a SIGBUS in the loop, maps the chunk (populated at once under
 * mlockall, touched page by page otherwise) and publishes it; chunks the
 * loop has left behind are unmapped. A record whose chunk is not mapped yet
 * is refused (journal_next returns NULL) and the loop stops the run rather
 * than fire a frame it cannot record; on the virtual clock it waits for the
 * service.
 *
 * What is in flight is bounded, whatever the length of the run: the chunks
 * mapped are those from the oldest record the loop may still write
 * (`behind` records below the newest: one tick's edges, whose FIRED times
 * follow, and the current frame, whose following error is still being
 * written) to `ahead` records beyond it. The chunk index is a ring of
 * nslots = (ahead + behind) / per_chunk + 2 slots, chunk c in slot
 * c % nslots: no more are ever mapped at once (journal_svc.c shows why).
 * So a run of two billion passes holds the same few slots and megabytes as
 * a run of one, and a run without an end (capacity JOURNAL_UNBOUNDED) goes
 * on until the disk is full, the file at the file system's largest size,
 * or the run stops.
 *
 * The file is the writer's native structs, with the byte order and the
 * record's layout in the header: a journal from a machine that stores them
 * otherwise is refused by name, never misread.
 *
 * The loop's side is journal_rt.c, the service thread's journal_svc.c, the
 * reader (`strand journal`) journal_read.c.
 */
#ifndef STRAND_JOURNAL_H
#define STRAND_JOURNAL_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hal/rt.h" /* STRAND_RT */

#define JOURNAL_MAGIC "STRANDJ1"
/* 3: a go-motion journal's records end with their exposure (struct
 * journal_gomo); 2: the same without go-motion; 1: no byte order or layout
 * in the header. All three are read. */
#define JOURNAL_VERSION 3
#define JOURNAL_NAME_MAX 48
#define JOURNAL_OUT_MAX 4096 /* outputs a journal holds at most */
/* journal_info.capacity of a run without an end; the header says -1 */
#define JOURNAL_UNBOUNDED (-1)

/* The header's byte order marker as the writer's CPU stores it: a reader
 * of the other byte order sees 0x04030201. */
#define JOURNAL_BYTE_ORDER 0x01020304u
/* A double every IEEE 754 binary64 machine stores alike, for the header. */
#define JOURNAL_PROBE (-1.5)

/* The header's mode: bits. */
#define JOURNAL_MODE_STEP 1  /* step mode (else continuous) */
#define JOURNAL_MODE_CHASE 2 /* --chase: records hold the source's frame */
#define JOURNAL_MODE_GOMO 4  /* go-motion: records hold their exposure's poses too */

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

/* Versions 2 and 3. Version 1 is the same up to scene[], then out[] at once. */
struct journal_hdr {
	char magic[8];
	uint32_t version;
	uint32_t hdr_bytes;
	uint32_t rec_bytes;
	uint32_t nout;
	uint32_t rate_num, rate_den;
	uint32_t tick_hz;
	uint32_t mode; /* JOURNAL_MODE_* */
	int64_t start_wall_ns;
	int64_t capacity; /* records the run planned; -1: a run without an end */
	char scene[64];
	uint32_t byte_order; /* JOURNAL_BYTE_ORDER */
	uint32_t layout;     /* journal_layout() of the writer */
	double probe;        /* JOURNAL_PROBE */
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
	uint32_t src_frame; /* --chase: the source's frame at the edge's due
			     * time, plus one (its label's number in the day); 0: none */
	int64_t sp[];     /* nout setpoints, Q32.32 core units */
};

/* What a record of a go-motion journal (JOURNAL_MODE_GOMO, plan/gomo.h)
 * holds after its nout setpoints: its exposure's first and last tick (run
 * ticks, written once the exposure has ended: -1 until then) and the
 * setpoints there, nout at open_tick, then nout at close_tick. */
struct journal_gomo {
	int64_t open_tick, close_tick;
	int64_t sp[];
};

static inline struct journal_gomo *journal_gomo_of(struct journal_rec *r, uint32_t nout)
{
	return (struct journal_gomo *)(r->sp + nout);
}

/* The bytes of a record with nout outputs in a journal of this mode. */
static inline size_t journal_rec_bytes(uint32_t nout, uint32_t mode)
{
	size_t b = sizeof(struct journal_rec) + nout * sizeof(int64_t);

	if (mode & JOURNAL_MODE_GOMO)
		b += sizeof(struct journal_gomo) + 2 * (size_t)nout * sizeof(int64_t);
	return b;
}

/* The record's layout as this build lays it out: the offsets of its
 * fields and the sizes it rests on, one byte each. A reader built with
 * another ABI (other alignments, another size of double) computes another
 * value and refuses the file. */
static inline uint32_t journal_layout(void)
{
	return (uint32_t)offsetof(struct journal_rec, frame) |
	       (uint32_t)offsetof(struct journal_rec, ferr) << 8 |
	       (uint32_t)offsetof(struct journal_rec, sp) << 16 |
	       (uint32_t)(sizeof(double) << 4 | sizeof(struct journal_out) / 8) << 24;
}

/* One slot of the ring of chunks. */
struct journal_slot {
	_Atomic int64_t chunk; /* the chunk mapped here (published), -1: none */
	unsigned char *first;  /* its first record, set before chunk is published */
	void *map;             /* service: what to munmap */
	size_t len;
};

struct journal {
	int fd;
	uint32_t hdr_bytes;
	uint32_t rec_bytes;
	uint32_t mode;      /* the header's: JOURNAL_MODE_* */
	uint32_t per_chunk; /* records per chunk */
	long page;
	int64_t capacity;   /* records at most; JOURNAL_UNBOUNDED: no end */
	int64_t ahead;      /* records the service keeps mapped ahead of the loop */
	int64_t behind;     /* ... and below the newest it armed */
	uint32_t nslots;
	struct journal_slot *slot; /* nslots: chunk c in slot c % nslots */
	int64_t mapped_lo, mapped_hi; /* service: chunks [lo, hi) are mapped */
	int64_t next;            /* loop: records armed so far */
	_Atomic int64_t written; /* loop -> service: records armed (release) */
	_Atomic int err;         /* service -> loop: first error, negative errno (release) */
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
	int64_t capacity; /* records (>= 1), or JOURNAL_UNBOUNDED */
	int64_t ahead;    /* records to keep mapped ahead of the loop (>= 1) */
	int64_t behind;   /* records below the newest the loop may still write:
			   * the edges of one tick (0: 1) */
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

/* [rt] Why journal_next() will never give the next record: the service's
 * error (a negative errno: -ENOSPC for a full disk), -ENOSPC when a bounded
 * journal is full; 0 while the record may still come (its chunk is being
 * mapped). */
int journal_refused(const struct journal *j);

/* [rt] The service's first error, 0 if none. */
static inline int STRAND_RT journal_error(const struct journal *j)
{
	return atomic_load_explicit(&j->err, memory_order_acquire);
}

/* [service thread] Map chunks ahead of the loop, unmap those behind it, ask
 * for writeback once a second. 0 or the first error (sticky). */
int journal_service(struct journal *j, int64_t now_ns);

/* [init] Flush, cut the file to the records written, unmap, close. */
int journal_close(struct journal *j);

/* [init] Print a journal file as CSV with a header row. 0 or a negative
 * errno; msg says what was wrong with the file. */
int journal_csv(const char *path, FILE *out, char *msg, unsigned msgsize);

#endif /* STRAND_JOURNAL_H */
