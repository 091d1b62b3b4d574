/* SPDX-License-Identifier: MIT */
/* ls_msg.c - the lockstep's datagrams (see ls_msg.h). */
#include "ls_msg.h"

#include <errno.h>
#include <string.h>

#define HDR 20 /* magic 4, version 1, type 1, from 2, seq 4, sent_ns 8 */

static const char *const kind_names[LS_STOP_KINDS] = {
	[LS_STOP_REFUSED] = "refused", [LS_STOP_ESTOP] = "e-stop",
	[LS_STOP_FAULT] = "fault",     [LS_STOP_ASKED] = "stop",
	[LS_STOP_LOST] = "lost",       [LS_STOP_FINISHED] = "finished",
};

const char *ls_stop_kind_name(unsigned kind)
{
	return kind < LS_STOP_KINDS ? kind_names[kind] : "?";
}

/* ---- little-endian fields ---- */

struct wr {
	uint8_t *p;
	size_t n, size;
	int full; /* the buffer was too small: the message is nothing */
};

static void put(struct wr *w, uint64_t v, unsigned bytes)
{
	unsigned i;

	if (w->n + bytes > w->size) {
		w->full = 1;
		return;
	}
	for (i = 0; i < bytes; i++)
		w->p[w->n++] = (uint8_t)(v >> (8 * i));
}

static void put_bytes(struct wr *w, const void *b, size_t n)
{
	if (w->n + n > w->size) {
		w->full = 1;
		return;
	}
	memcpy(w->p + w->n, b, n);
	w->n += n;
}

/* A text: its length (1 byte, < LS_TEXT), then its bytes. */
static void put_text(struct wr *w, const char *s)
{
	size_t n = strnlen(s, LS_TEXT - 1);

	put(w, n, 1);
	put_bytes(w, s, n);
}

struct rd {
	const uint8_t *p;
	size_t n, len;
	int bad;
};

static uint64_t get(struct rd *r, unsigned bytes)
{
	uint64_t v = 0;
	unsigned i;

	if (r->n + bytes > r->len) {
		r->bad = 1;
		return 0;
	}
	for (i = 0; i < bytes; i++)
		v |= (uint64_t)r->p[r->n++] << (8 * i);
	return v;
}

static void get_text(struct rd *r, char *s)
{
	size_t n = (size_t)get(r, 1);

	if (r->bad || n >= LS_TEXT || r->n + n > r->len || memchr(r->p + r->n, 0, n)) {
		r->bad = 1;
		s[0] = '\0';
		return;
	}
	memcpy(s, r->p + r->n, n);
	s[n] = '\0';
	r->n += n;
}

size_t ls_msg_encode(const struct ls_msg *m, uint8_t *buf, size_t size)
{
	struct wr w = { .p = buf, .n = 0, .size = size, .full = 0 };

	put(&w, LS_MAGIC, 4);
	put(&w, LS_VERSION, 1);
	put(&w, m->type, 1);
	put(&w, m->from, 2);
	put(&w, m->seq, 4);
	put(&w, (uint64_t)m->sent_ns, 8);
	switch (m->type) {
	case LS_HELLO:
		put_bytes(&w, m->u.hello.digest, LS_DIGEST);
		put(&w, (uint64_t)m->u.hello.need_ticks, 8);
		put(&w, m->u.hello.ptp_ok, 1);
		put_text(&w, m->u.hello.why);
		break;
	case LS_PING:
		break;
	case LS_PONG:
		put(&w, (uint64_t)m->u.pong.t1, 8);
		put(&w, (uint64_t)m->u.pong.t2, 8);
		break;
	case LS_START:
	case LS_ACK:
		put(&w, (uint64_t)m->u.start.play_ns, 8);
		break;
	case LS_BEAT:
		put(&w, (uint64_t)m->u.beat.tick, 8);
		put(&w, m->u.beat.state, 1);
		break;
	case LS_STOP:
		put(&w, m->u.stop.kind, 1);
		put(&w, m->u.stop.level, 1);
		put(&w, m->u.stop.origin, 2);
		put_text(&w, m->u.stop.text);
		break;
	default:
		return 0;
	}
	return w.full ? 0 : w.n;
}

int ls_msg_decode(struct ls_msg *m, const uint8_t *buf, size_t len, uint32_t nboards)
{
	struct rd r = { .p = buf, .n = 0, .len = len, .bad = 0 };

	memset(m, 0, sizeof(*m));
	if (get(&r, 4) != LS_MAGIC || get(&r, 1) != LS_VERSION)
		return -EBADMSG;
	m->type = (uint8_t)get(&r, 1);
	m->from = (uint16_t)get(&r, 2);
	m->seq = (uint32_t)get(&r, 4);
	m->sent_ns = (int64_t)get(&r, 8);
	if (r.bad || m->from >= nboards)
		return -EBADMSG;
	switch (m->type) {
	case LS_HELLO:
		if (r.n + LS_DIGEST > len)
			return -EBADMSG;
		memcpy(m->u.hello.digest, buf + r.n, LS_DIGEST);
		r.n += LS_DIGEST;
		m->u.hello.need_ticks = (int64_t)get(&r, 8);
		m->u.hello.ptp_ok = (uint8_t)get(&r, 1);
		get_text(&r, m->u.hello.why);
		if (m->u.hello.need_ticks < 0 || m->u.hello.ptp_ok > 1)
			return -EBADMSG;
		break;
	case LS_PING:
		break;
	case LS_PONG:
		m->u.pong.t1 = (int64_t)get(&r, 8);
		m->u.pong.t2 = (int64_t)get(&r, 8);
		break;
	case LS_START:
	case LS_ACK:
		m->u.start.play_ns = (int64_t)get(&r, 8);
		break;
	case LS_BEAT:
		m->u.beat.tick = (int64_t)get(&r, 8);
		m->u.beat.state = (uint8_t)get(&r, 1);
		break;
	case LS_STOP:
		m->u.stop.kind = (uint8_t)get(&r, 1);
		m->u.stop.level = (uint8_t)get(&r, 1);
		m->u.stop.origin = (uint16_t)get(&r, 2);
		get_text(&r, m->u.stop.text);
		if (m->u.stop.kind >= LS_STOP_KINDS || m->u.stop.level < 1 || m->u.stop.level > 2 ||
		    m->u.stop.origin >= nboards)
			return -EBADMSG;
		break;
	default:
		return -EBADMSG;
	}
	/* exactly the type's length: no more, no less */
	return r.bad || r.n != len ? -EBADMSG : 0;
}
