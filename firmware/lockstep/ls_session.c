/* SPDX-License-Identifier: MIT */
/* ls_session.c - the lockstep's start and watch (see lockstep.h). */
#define _GNU_SOURCE
#include "lockstep.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <netdb.h>
#include <poll.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "hal/clock.h"
#include "hal/rt.h"
#include "ls_ptp.h"
#include "scene/sha256.h"

/* A follower says HELLO this often until the start. */
#define LS_HELLO_MS 100
/* Clock comparisons per follower, and the time each may take. */
#define LS_PINGS 8
#define LS_PING_WAIT_MS 20
/* The leader resends START this often until every board confirmed. */
#define LS_START_MS 50
/* A board's tick 0 must be at least this far ahead when START comes. */
#define LS_START_MARGIN_NS 20000000
/* A STOP or a FINISHED is sent this many times, a heartbeat apart. */
#define LS_TELL 3
/* The watch looks at the local run at least this often. */
#define LS_WATCH_MS 2
/* The tests' boards share one clock; this environment variable moves one
 * board's view of the PTP clock, so that the refusals for clocks that
 * disagree and a start instant already past can be tested there. */
#define LS_SKEW_ENV "STRAND_LOCKSTEP_CLOCK_SKEW_NS"

struct peer {
	struct sockaddr_storage sa;
	socklen_t salen;
	bool hello, ptp_ok, acked;
	uint8_t digest[LS_DIGEST];
	int64_t need;
	char why[LS_TEXT];
	int pongs;
	double delay_ns, offset_ns; /* the least delayed comparison */
	int64_t last_seen;          /* CLOCK_MONOTONIC */
	bool finished, stopped;
};

struct lockstep {
	struct ls_cfg cfg;
	int fd;
	struct peer *peer;          /* nboards; peer[self] unused */
	uint32_t seq;
	int64_t skew_ns;
	int64_t play_ns, t0;
	struct ls_hooks hooks;
	struct hal_thread thread;
	_Atomic bool quit, done;
	char reason[LS_TEXT + 64];  /* why another board stopped this run */
	int reason_level;
	_Atomic bool has_reason;
	struct ls_stats st;
};

static const char *name_of(const struct lockstep *s, uint32_t i)
{
	return s->cfg.boards[i].name;
}

static uint32_t port_of(const struct lockstep *s, uint32_t i)
{
	return s->cfg.boards[i].port;
}

/* The PTP clock: CLOCK_REALTIME, as linuxptp sets it. */
static int64_t pt_now(const struct lockstep *s)
{
	struct timespec t;

	clock_gettime(CLOCK_REALTIME, &t);
	return (int64_t)t.tv_sec * 1000000000 + t.tv_nsec + s->skew_ns;
}

/* The PTP clock less CLOCK_MONOTONIC, read between two monotonic
 * readings, the closest pair of five. */
static int64_t pt_minus_mono(const struct lockstep *s)
{
	int64_t best = INT64_MAX, off = 0;
	int i;

	for (i = 0; i < 5; i++) {
		int64_t m1 = hal_mono_ns(), p = pt_now(s), m2 = hal_mono_ns();

		if (m2 - m1 < best) {
			best = m2 - m1;
			off = p - (m1 + (m2 - m1) / 2);
		}
	}
	return off;
}

static void say(const struct lockstep *s, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));
static void say(const struct lockstep *s, const char *fmt, ...)
{
	va_list ap;

	if (!s->cfg.log)
		return;
	va_start(ap, fmt);
	fprintf(s->cfg.log, "strand play: lockstep: board '%s': ", name_of(s, s->cfg.self));
	vfprintf(s->cfg.log, fmt, ap);
	fputc('\n', s->cfg.log);
	va_end(ap);
}

static int resolve(const char *host, uint32_t port, struct sockaddr_storage *sa,
		   socklen_t *len, char *err, size_t errsize)
{
	struct addrinfo hints = { .ai_socktype = SOCK_DGRAM }, *ai;
	char ps[16];
	int rc;

	snprintf(ps, sizeof(ps), "%u", port);
	rc = getaddrinfo(host, ps, &hints, &ai);
	if (rc) {
		snprintf(err, errsize, "address '%s': %s", host, gai_strerror(rc));
		return -EHOSTUNREACH;
	}
	memcpy(sa, ai->ai_addr, ai->ai_addrlen);
	*len = ai->ai_addrlen;
	freeaddrinfo(ai);
	return 0;
}

int ls_open(struct lockstep **out, const struct ls_cfg *cfg, char *err, size_t errsize)
{
	struct sockaddr_storage self;
	socklen_t len;
	const char *skew = getenv(LS_SKEW_ENV);
	struct lockstep *s;
	uint32_t i;
	int rc;

	STRAND_ASSERT_NOT_RT();
	*out = NULL;
	s = calloc(1, sizeof(*s));
	if (!s || !(s->peer = calloc(cfg->nboards, sizeof(*s->peer)))) {
		free(s);
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	s->cfg = *cfg;
	s->fd = -1;
	atomic_init(&s->quit, false);
	atomic_init(&s->done, false);
	atomic_init(&s->has_reason, false);
	s->skew_ns = skew ? strtoll(skew, NULL, 10) : 0;
	for (i = 0; i < cfg->nboards; i++) {
		rc = resolve(cfg->boards[i].address, cfg->boards[i].port,
			     i == cfg->self ? &self : &s->peer[i].sa,
			     i == cfg->self ? &len : &s->peer[i].salen, err, errsize);
		if (rc) {
			char e[160];

			snprintf(e, sizeof(e), "%s", err);
			snprintf(err, errsize, "board '%s': %s", cfg->boards[i].name, e);
			ls_close(s);
			return rc;
		}
	}
	s->fd = socket(self.ss_family, SOCK_DGRAM | SOCK_CLOEXEC, 0);
	if (s->fd < 0 || bind(s->fd, (struct sockaddr *)&self, len)) {
		rc = -errno;
		snprintf(err, errsize, "board '%s': cannot take UDP port %u on %s (%s)%s",
			 name_of(s, cfg->self), port_of(s, cfg->self), cfg->boards[cfg->self].address,
			 strerror(-rc), rc == -EADDRNOTAVAIL ? ": not an address of this machine; is "
			 "this board the one --node names?" : "");
		ls_close(s);
		return rc;
	}
	*out = s;
	return 0;
}

/* ---- datagrams ---- */

static void send_to(struct lockstep *s, uint32_t i, struct ls_msg *m)
{
	uint8_t buf[LS_MSG_MAX];
	size_t n;

	m->from = (uint16_t)s->cfg.self;
	m->seq = ++s->seq;
	m->sent_ns = pt_now(s);
	n = ls_msg_encode(m, buf, sizeof(buf));
	/* a datagram lost is a datagram lost: every message that matters is
	 * sent again until it is answered, or more than once */
	if (n)
		(void)sendto(s->fd, buf, n, MSG_DONTWAIT, (struct sockaddr *)&s->peer[i].sa,
			     s->peer[i].salen);
}

static void send_all(struct lockstep *s, struct ls_msg *m, int64_t except)
{
	uint32_t i;

	for (i = 0; i < s->cfg.nboards; i++)
		if (i != s->cfg.self && (int64_t)i != except)
			send_to(s, i, m);
}

static bool same_addr(const struct sockaddr_storage *a, const struct sockaddr_storage *b,
		      socklen_t len)
{
	return !memcmp(a, b, len);
}

/* The next datagram within wait_ms: 1 and m (with its arrival on the PTP
 * clock in *at), 0 if none came. One from an address that is not its
 * board's, or that does not decode, is dropped and counted. */
static int recv_msg(struct lockstep *s, int wait_ms, struct ls_msg *m, int64_t *at)
{
	struct pollfd p = { .fd = s->fd, .events = POLLIN };
	struct sockaddr_storage from;
	uint8_t buf[LS_MSG_MAX + 1];

	for (;;) {
		socklen_t len = sizeof(from);
		ssize_t n;

		if (poll(&p, 1, wait_ms) <= 0)
			return 0;
		n = recvfrom(s->fd, buf, sizeof(buf), MSG_DONTWAIT, (struct sockaddr *)&from, &len);
		if (n < 0)
			return 0;
		*at = pt_now(s);
		if (ls_msg_decode(m, buf, (size_t)n, s->cfg.nboards) || m->from == s->cfg.self ||
		    len != s->peer[m->from].salen || !same_addr(&from, &s->peer[m->from].sa, len)) {
			s->st.dropped++;
			wait_ms = 0;
			continue;
		}
		return 1;
	}
}

static void stop_msg(struct ls_msg *m, unsigned kind, int level, uint32_t origin,
		     const char *text)
{
	size_t n;

	memset(m, 0, sizeof(*m));
	m->type = LS_STOP;
	m->u.stop.kind = (uint8_t)kind;
	m->u.stop.level = (uint8_t)level;
	m->u.stop.origin = (uint16_t)origin;
	/* cut to what a message carries */
	n = strnlen(text, LS_TEXT - 1);
	memcpy(m->u.stop.text, text, n);
	m->u.stop.text[n] = '\0';
}

/* Tell every board (but except) that the start is off, three times. */
static int refuse(struct lockstep *s, uint32_t origin, int64_t except, int code, char *err,
		  size_t errsize, const char *fmt, ...) __attribute__((format(printf, 7, 8)));
static int refuse(struct lockstep *s, uint32_t origin, int64_t except, int code, char *err,
		  size_t errsize, const char *fmt, ...)
{
	struct ls_msg m;
	char text[LS_TEXT];
	va_list ap;
	int i;

	va_start(ap, fmt);
	vsnprintf(text, sizeof(text), fmt, ap);
	va_end(ap);
	stop_msg(&m, LS_STOP_REFUSED, 1, origin, text);
	for (i = 0; i < LS_TELL; i++) {
		struct timespec gap = { 0, 20000000 };

		send_all(s, &m, except);
		nanosleep(&gap, NULL);
	}
	snprintf(err, errsize, "lockstep refused: %s", text);
	return code;
}

/* ---- the start ---- */

static int64_t ticks_ns(const struct lockstep *s, int64_t ticks)
{
	return (int64_t)llround((double)ticks * 1e9 / s->cfg.tick_hz);
}

/* This board's tick 0 for play at play_ns on the PTP clock. */
static int64_t t0_for(const struct lockstep *s, int64_t play_ns)
{
	return play_ns - pt_minus_mono(s) - ticks_ns(s, s->cfg.need_ticks);
}

static bool cancelled(const struct lockstep *s)
{
	return s->cfg.cancel && hal_cancelled(s->cfg.cancel);
}

static int own_ptp(struct lockstep *s, char *why, size_t size)
{
	struct ls_ptp st;
	char err[LS_TEXT];

	if (ls_ptp_query(&st, s->cfg.ptp_socket, err, sizeof(err))) {
		snprintf(why, size, "%s", err);
		return 0;
	}
	if (!ls_ptp_locked(&st, s->cfg.ptp_offset_ns, s->cfg.ptp_free_running, why, size))
		return 0;
	say(s, "PTP %s, offset %" PRId64 " ns", st.state, st.offset_ns);
	return 1;
}

static int lead_join(struct lockstep *s, int64_t *t0, char *err, size_t errsize)
{
	const struct ls_cfg *c = &s->cfg;
	char why[LS_TEXT], hex[2][13];
	int64_t deadline = hal_mono_ns() + (int64_t)(c->join_ms * 1e6), need = c->need_ticks;
	int64_t start_by, at;
	uint32_t i, have = 1, acked;
	struct ls_msg m;
	int ok = own_ptp(s, why, sizeof(why)), round;

	/* every follower's HELLO */
	while (have < c->nboards) {
		if (cancelled(s))
			return refuse(s, c->self, -1, -ECANCELED, err, errsize,
				      "board '%s' (the leader) was stopped by a signal before the "
				      "start", name_of(s, c->self));
		if (hal_mono_ns() > deadline) {
			for (i = 0; i < c->nboards && (i == c->self || s->peer[i].hello); i++)
				;
			return refuse(s, i, -1, -ETIMEDOUT, err, errsize,
				      "board '%s' (%s port %u) did not come up within %.0f s",
				      name_of(s, i), c->boards[i].address, port_of(s, i),
				      c->join_ms / 1000);
		}
		if (!recv_msg(s, 50, &m, &at))
			continue;
		if (m.type == LS_STOP)
			return refuse(s, m.u.stop.origin, m.from, -EPERM, err, errsize, "%s",
				      m.u.stop.text);
		if (m.type != LS_HELLO || s->peer[m.from].hello)
			continue;
		s->peer[m.from].hello = true;
		memcpy(s->peer[m.from].digest, m.u.hello.digest, LS_DIGEST);
		s->peer[m.from].need = m.u.hello.need_ticks;
		s->peer[m.from].ptp_ok = m.u.hello.ptp_ok;
		memcpy(s->peer[m.from].why, m.u.hello.why, LS_TEXT);
		have++;
		say(s, "board '%s' is up", name_of(s, m.from));
	}
	/* the same scene everywhere, every clock locked */
	for (i = 0; i < c->nboards; i++) {
		if (i == c->self)
			continue;
		if (memcmp(s->peer[i].digest, c->digest, LS_DIGEST)) {
			sha256_hex(hex[0], s->peer[i].digest, 6);
			sha256_hex(hex[1], c->digest, 6);
			return refuse(s, i, -1, -EPERM, err, errsize,
				      "board '%s' loaded another scene than board '%s' (SHA-256 "
				      "%s... against %s...): every board plays the same file",
				      name_of(s, i), name_of(s, c->self), hex[0], hex[1]);
		}
		if (!s->peer[i].ptp_ok)
			return refuse(s, i, -1, -EPERM, err, errsize, "board '%s': %s",
				      name_of(s, i), s->peer[i].why);
	}
	if (!ok)
		return refuse(s, c->self, -1, -EPERM, err, errsize, "board '%s' (the leader): %s",
			      name_of(s, c->self), why);
	/* the clocks compared */
	for (round = 0; round < LS_PINGS; round++) {
		int64_t until = hal_mono_ns() + LS_PING_WAIT_MS * 1000000LL;

		memset(&m, 0, sizeof(m));
		m.type = LS_PING;
		send_all(s, &m, -1);
		while (hal_mono_ns() < until) {
			struct peer *p;
			double delay, off;

			if (!recv_msg(s, LS_PING_WAIT_MS, &m, &at) || m.type != LS_PONG)
				continue;
			p = &s->peer[m.from];
			/* t1 ours, t2 theirs, t3 theirs (sent_ns), t4 ours (at) */
			delay = (double)(at - m.u.pong.t1) - (double)(m.sent_ns - m.u.pong.t2);
			off = ((double)(m.u.pong.t2 - m.u.pong.t1) + (double)(m.sent_ns - at)) / 2;
			if (!p->pongs++ || delay < p->delay_ns) {
				p->delay_ns = delay;
				p->offset_ns = off;
			}
		}
	}
	for (i = 0; i < c->nboards; i++) {
		struct peer *p = &s->peer[i];

		if (i == c->self)
			continue;
		if (!p->pongs)
			return refuse(s, i, -1, -ETIMEDOUT, err, errsize, "board '%s' did not answer "
				      "the clock comparison", name_of(s, i));
		if (fabs(p->offset_ns) / 1000 >= s->st.offset_us_max) {
			s->st.offset_us_max = fabs(p->offset_ns) / 1000;
			s->st.offset_board = i;
		}
		if (p->delay_ns / 1000 > s->st.delay_us_max)
			s->st.delay_us_max = p->delay_ns / 1000;
		say(s, "board '%s': its clock %+.1f us from this one's (round trip %.1f us)",
		    name_of(s, i), p->offset_ns / 1000, p->delay_ns / 1000);
		if (fabs(p->offset_ns) > c->max_offset_us * 1000)
			return refuse(s, i, -1, -EPERM, err, errsize,
				      "the clocks of board '%s' and board '%s' disagree by %.1f us "
				      "(max_offset_us %.6g): are ptp4l and phc2sys running on both, "
				      "in one PTP domain?", name_of(s, i), name_of(s, c->self),
				      p->offset_ns / 1000, c->max_offset_us);
		if (p->need > need)
			need = p->need;
	}
	/* the instant: after the longest pre-roll, start_ms on */
	s->play_ns = pt_now(s) + ticks_ns(s, need) + (int64_t)(c->start_ms * 1e6);
	*t0 = t0_for(s, s->play_ns);
	start_by = s->play_ns - pt_minus_mono(s) - ticks_ns(s, need) - LS_START_MARGIN_NS;
	say(s, "start: play at %" PRId64 ".%09" PRId64 " (PTP clock), the longest pre-roll %.3f s",
	    s->play_ns / 1000000000, s->play_ns % 1000000000, (double)need / c->tick_hz);
	for (;;) {
		int64_t next = hal_mono_ns() + LS_START_MS * 1000000LL;

		for (acked = 1, i = 0; i < c->nboards; i++)
			acked += i != c->self && s->peer[i].acked;
		if (acked == c->nboards)
			break;
		if (hal_mono_ns() > start_by) {
			for (i = 0; i < c->nboards && (i == c->self || s->peer[i].acked); i++)
				;
			return refuse(s, i, -1, -ETIMEDOUT, err, errsize, "board '%s' did not "
				      "confirm the start in time", name_of(s, i));
		}
		memset(&m, 0, sizeof(m));
		m.type = LS_START;
		m.u.start.play_ns = s->play_ns;
		for (i = 0; i < c->nboards; i++)
			if (i != c->self && !s->peer[i].acked)
				send_to(s, i, &m);
		while (hal_mono_ns() < next) {
			if (!recv_msg(s, LS_START_MS, &m, &at))
				continue;
			if (m.type == LS_STOP)
				return refuse(s, m.u.stop.origin, m.from, -EPERM, err, errsize, "%s",
					      m.u.stop.text);
			if (m.type == LS_ACK && m.u.start.play_ns == s->play_ns)
				s->peer[m.from].acked = true;
		}
	}
	return 0;
}

static int follow_join(struct lockstep *s, int64_t *t0, char *err, size_t errsize)
{
	const struct ls_cfg *c = &s->cfg;
	int64_t deadline = hal_mono_ns() + (int64_t)(c->join_ms * 1e6), next = 0, at;
	struct ls_msg hello, m;

	memset(&hello, 0, sizeof(hello));
	hello.type = LS_HELLO;
	memcpy(hello.u.hello.digest, c->digest, LS_DIGEST);
	hello.u.hello.need_ticks = c->need_ticks;
	hello.u.hello.ptp_ok = (uint8_t)own_ptp(s, hello.u.hello.why, sizeof(hello.u.hello.why));
	for (;;) {
		int64_t now = hal_mono_ns();

		if (cancelled(s))
			return refuse(s, c->self, -1, -ECANCELED, err, errsize, "board '%s' was "
				      "stopped by a signal before the start", name_of(s, c->self));
		if (now > deadline) {
			snprintf(err, errsize, "lockstep: the leader, board '%s' (%s port %u), did "
				 "not start the run within %.0f s", name_of(s, c->lead),
				 c->boards[c->lead].address, port_of(s, c->lead), c->join_ms / 1000);
			return -ETIMEDOUT;
		}
		if (now >= next) {
			struct ls_msg h = hello;

			send_to(s, c->lead, &h);
			next = now + LS_HELLO_MS * 1000000LL;
		}
		if (!recv_msg(s, 10, &m, &at))
			continue;
		switch (m.type) {
		case LS_PING: {
			struct ls_msg p = { .type = LS_PONG };

			p.u.pong.t1 = m.sent_ns;
			p.u.pong.t2 = at;
			send_to(s, m.from, &p);
			break;
		}
		case LS_START: {
			struct ls_msg a = { .type = LS_ACK };
			int64_t late;

			s->play_ns = m.u.start.play_ns;
			*t0 = t0_for(s, s->play_ns);
			late = hal_mono_ns() + LS_START_MARGIN_NS - *t0;
			if (late > 0)
				return refuse(s, c->self, -1, -EPERM, err, errsize,
					      "board '%s': the start instant is already past on its "
					      "clock, by %.1f ms (its pre-roll included)",
					      name_of(s, c->self), (double)late / 1e6);
			a.u.start.play_ns = s->play_ns;
			send_to(s, m.from, &a);
			return 0;
		}
		case LS_STOP:
			snprintf(err, errsize, "lockstep refused: %s", m.u.stop.text);
			return -EPERM;
		default:
			break;
		}
	}
}

int ls_join(struct lockstep *s, int64_t *t0, char *err, size_t errsize)
{
	int rc;

	STRAND_ASSERT_NOT_RT();
	say(s, "%s %u boards, UDP port %u", s->cfg.self == s->cfg.lead ? "leading" : "joining",
	    s->cfg.nboards, port_of(s, s->cfg.self));
	rc = s->cfg.self == s->cfg.lead ? lead_join(s, t0, err, errsize) :
					   follow_join(s, t0, err, errsize);
	if (!rc) {
		s->t0 = *t0;
		s->st.play_ns = s->play_ns;
		s->st.t0_ns = *t0;
		say(s, "tick 0 in %.3f s, play in %.3f s", (double)(*t0 - hal_mono_ns()) / 1e9,
		    (double)(s->play_ns - pt_now(s)) / 1e9);
	}
	return rc;
}

/* ---- the watch ---- */

static void note_reason(struct lockstep *s, int level, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));
static void note_reason(struct lockstep *s, int level, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(s->reason, sizeof(s->reason), fmt, ap);
	va_end(ap);
	s->reason_level = level;
	atomic_store_explicit(&s->has_reason, true, memory_order_release);
}

/* A message while the runs play. */
static void take(struct lockstep *s, const struct ls_msg *m, int64_t at, bool *stopping)
{
	struct peer *p = &s->peer[m->from];
	int64_t now = hal_mono_ns();

	if (p->last_seen && now - p->last_seen > s->st.beat_gap_max_ns && !p->finished)
		s->st.beat_gap_max_ns = now - p->last_seen;
	p->last_seen = now;
	switch (m->type) {
	case LS_BEAT:
		s->st.beats_got++;
		break;
	case LS_PING: {
		struct ls_msg r = { .type = LS_PONG };

		r.u.pong.t1 = m->sent_ns;
		r.u.pong.t2 = at;
		send_to(s, m->from, &r);
		break;
	}
	case LS_START: { /* our ACK was lost */
		struct ls_msg a = { .type = LS_ACK };

		a.u.start.play_ns = m->u.start.play_ns;
		if (m->u.start.play_ns == s->play_ns)
			send_to(s, m->from, &a);
		break;
	}
	case LS_STOP: {
		struct ls_msg fwd = *m;

		p->stopped = true;
		if (m->u.stop.kind == LS_STOP_FINISHED) {
			p->finished = true;
			break;
		}
		if (*stopping)
			break;
		*stopping = true;
		note_reason(s, m->u.stop.level, "board '%s': %s", name_of(s, m->u.stop.origin),
			    m->u.stop.text);
		s->hooks.stop(s->hooks.ctx, m->u.stop.level, m->u.stop.kind);
		/* passed on, in case a board did not hear it */
		send_all(s, &fwd, m->from);
		break;
	}
	default:
		break;
	}
}

static void *watch(void *arg)
{
	struct lockstep *s = arg;
	const struct ls_cfg *c = &s->cfg;
	int64_t beat = (int64_t)(c->heartbeat_ms * 1e6), lost = (int64_t)(c->lost_ms * 1e6);
	int64_t next_beat = hal_mono_ns(), at;
	struct ls_msg told;
	bool stopping = false, ended = false;
	int tell = 0;
	uint32_t i;

	for (i = 0; i < c->nboards; i++)
		s->peer[i].last_seen = hal_mono_ns();
	while (!atomic_load(&s->quit)) {
		int64_t now = hal_mono_ns(), wait = next_beat - now;
		struct ls_msg m;
		char text[LS_TEXT];
		int level = 1, k;

		if (wait > LS_WATCH_MS * 1000000LL)
			wait = LS_WATCH_MS * 1000000LL;
		while (recv_msg(s, wait > 0 ? (int)(wait / 1000000) : 0, &m, &at)) {
			take(s, &m, at, &stopping);
			wait = 0;
		}
		now = hal_mono_ns();
		/* the local run: how it ends, told to every board */
		if (!tell && (k = s->hooks.local_end(s->hooks.ctx, &level, text, sizeof(text))) != -1) {
			if (k == -2) {
				tell = -1; /* stopped for another board: it has told them */
			} else {
				stop_msg(&told, (unsigned)k, level, c->self, text);
				tell = 1;
				stopping = true;
				send_all(s, &told, -1);
			}
		}
		/* a board gone quiet */
		for (i = 0; !stopping && i < c->nboards; i++) {
			struct peer *p = &s->peer[i];

			if (i == c->self || p->stopped || now - p->last_seen <= lost)
				continue;
			stopping = true;
			note_reason(s, 1, "board '%s' lost: no heartbeat for %.0f ms", name_of(s, i),
				    (double)(now - p->last_seen) / 1e6);
			s->hooks.stop(s->hooks.ctx, 1, LS_STOP_LOST);
			stop_msg(&told, LS_STOP_LOST, 1, i, s->reason);
			send_all(s, &told, i);
		}
		if (now < next_beat)
			continue;
		next_beat = now - next_beat > beat ? now + beat : next_beat + beat;
		if (tell > 0 && tell < LS_TELL) {
			send_all(s, &told, -1);
			tell++;
		}
		if (!tell) {
			memset(&m, 0, sizeof(m));
			m.type = LS_BEAT;
			for (i = 0; i < c->nboards; i++)
				if (i != c->self && !s->peer[i].finished) {
					send_to(s, i, &m);
					s->st.beats_sent++;
				}
		}
		/* done once the loop has ended and what it had to say is said */
		if (!ended)
			ended = s->hooks.ended(s->hooks.ctx);
		if (ended && (tell < 0 || tell >= LS_TELL))
			break;
	}
	atomic_store(&s->done, true);
	return NULL;
}

int ls_watch(struct lockstep *s, const struct ls_hooks *h)
{
	STRAND_ASSERT_NOT_RT();
	s->hooks = *h;
	return hal_thread_start(&s->thread, "strand-board", &s->cfg.sched, 0, watch, s);
}

const char *ls_stop_reason(const struct lockstep *s, int *level)
{
	if (!s || !atomic_load_explicit(&s->has_reason, memory_order_acquire))
		return NULL;
	*level = s->reason_level;
	return s->reason;
}

void ls_stats(const struct lockstep *s, struct ls_stats *st)
{
	*st = s->st;
}

void ls_close(struct lockstep *s)
{
	STRAND_ASSERT_NOT_RT();
	if (!s)
		return;
	if (s->thread.running) {
		/* the watch ends by itself once the loop has ended and it has
		 * told the others (a few heartbeats); a run that never began,
		 * or a watch that takes longer, is ended here */
		int64_t until = hal_mono_ns() +
				(int64_t)((LS_TELL + 1) * s->cfg.heartbeat_ms * 1e6);
		struct timespec nap = { 0, 1000000 };

		while (!atomic_load(&s->done) && hal_mono_ns() < until)
			nanosleep(&nap, NULL);
		atomic_store(&s->quit, true);
		hal_thread_join(&s->thread);
	}
	if (s->fd >= 0)
		close(s->fd);
	free(s->peer);
	free(s);
}
