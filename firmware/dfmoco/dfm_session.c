/* SPDX-License-Identifier: MIT */
/* dfm_session.c - DFMoco on a live session (see dfm_session.h). */
#include "dfm_session.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* The protocol and the sketch version whose messages these are (1.3.1:
 * bf -1 when go-motion's speed cannot be reached). */
#define DFM_PROTOCOL 1
#define DFM_VERSION "1.3.1"
/* jm's speed before a pr says otherwise: half the velocity limit */
#define DFM_JOG_DEFAULT 0.5
/* im's step, in positions (the sketch's) */
#define DFM_INCH 2
/* mm lines that come one after another within this much are one move */
#define DFM_GATHER_NS 3000000
/* the client's number for live_jog */
#define DFM_CLIENT 1

/* ---- output ---- */

static void put(struct dfm_session *s, const char *text, size_t n)
{
	if (n > DFM_OUT_MAX)
		return;
	if (s->out_len + n > DFM_OUT_MAX) {
		/* nobody reads: the oldest replies go */
		size_t drop = s->out_len + n - DFM_OUT_MAX;

		memmove(s->out, s->out + drop, s->out_len - drop);
		s->out_len -= drop;
		s->dropped += drop;
	}
	memcpy(s->out + s->out_len, text, n);
	s->out_len += n;
}

static void __attribute__((format(printf, 2, 3))) say(struct dfm_session *s, const char *fmt,
						      ...)
{
	char line[512];
	va_list ap;
	int n;

	va_start(ap, fmt);
	n = vsnprintf(line, sizeof(line) - 2, fmt, ap);
	va_end(ap);
	if (n < 0)
		return;
	if ((size_t)n > sizeof(line) - 3)
		n = (int)sizeof(line) - 3;
	line[n++] = '\r';
	line[n++] = '\n';
	put(s, line, (size_t)n);
}

/* A refusal, said to Dragonframe in the sketch's form and to the log. */
static void __attribute__((format(printf, 2, 3))) why(struct dfm_session *s, const char *fmt,
						      ...)
{
	char text[400];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(text, sizeof(text), fmt, ap);
	va_end(ap);
	say(s, "error: %s", text);
	if (s->log)
		fprintf(s->log, "strand dfmoco: %s\n", text);
}

const char *dfm_session_output(const struct dfm_session *s, size_t *len)
{
	*len = s->out_len;
	return s->out;
}

void dfm_session_consumed(struct dfm_session *s, size_t n)
{
	if (n >= s->out_len) {
		s->out_len = 0;
		return;
	}
	memmove(s->out, s->out + n, s->out_len - n);
	s->out_len -= n;
}

/* ---- motors ---- */

static int64_t now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* Where output i's setpoint stands, in its device's counts. */
static int64_t at_dev(struct dfm_session *s, uint32_t i)
{
	return live_counts(s->lv, i, s->snap.out[i].sp);
}

/* ... and in Dragonframe's numbering. */
static int64_t at(struct dfm_session *s, uint32_t i)
{
	return at_dev(s, i) - s->zero[i];
}

static void say_mp(struct dfm_session *s, uint32_t i)
{
	say(s, "mp %u %lld", i + 1, (long long)at(s, i));
}

/* Motor number m (from 1) as an output index: true, or false having said
 * the protocol's error reply. */
static bool motor(struct dfm_session *s, int32_t m, uint32_t *i)
{
	if (m < 1 || (uint32_t)m > s->n) {
		say(s, "parse error");
		if (s->log)
			fprintf(s->log, "strand dfmoco: motor %d: there are %u\n", m, s->n);
		return false;
	}
	*i = (uint32_t)m - 1;
	return true;
}

/* A motor Dragonframe may position (not a speed channel). */
static bool positioned(struct dfm_session *s, uint32_t i)
{
	if (s->info[i].jog)
		return true;
	why(s, "motor %u (%s) is a speed, not a position: strand plays it from the scene",
	    i + 1, s->info[i].channel);
	say(s, "parse error");
	return false;
}

/* A command that moves was sent: its motors move until a sample at rest
 * has seen it. */
static void busy(struct dfm_session *s)
{
	live_snapshot(s->lv, &s->snap);
	s->busy_seq = s->snap.cmd_sent;
	s->report_ns = 0;
}

static bool at_rest(const struct dfm_session *s)
{
	return s->snap.state == LIVE_ENABLED && s->snap.cmd_seen >= s->busy_seq;
}

static bool rig_moving(const struct dfm_session *s)
{
	return (s->snap.state == LIVE_MOVING || s->snap.state == LIVE_STOPPING) &&
	       strcmp(s->snap.loop_state ? s->snap.loop_state : "", "armed");
}

static bool moving(struct dfm_session *s, uint32_t i)
{
	bool alive = s->snap.state == LIVE_ENABLED || s->snap.state == LIVE_MOVING ||
		     s->snap.state == LIVE_STOPPING;

	/* a command sent moves its motors from then on, before the loop has
	 * taken it: Dragonframe polls ms at once */
	return s->snap.out[i].jog || (alive && s->has_want[i] && s->want[i] != at_dev(s, i)) ||
	       (s->involved[i] && (rig_moving(s) || s->snap.cmd_seen < s->busy_seq));
}

/* Dragonframe's position P of motor i as device counts: false, having
 * said why, when it is beyond the output's position limits. */
static bool target(struct dfm_session *s, uint32_t i, int64_t p, int64_t *dev)
{
	const struct live_out_info *o = &s->info[i];
	double u;

	if (__builtin_add_overflow(p, s->zero[i], dev)) {
		why(s, "motor %u: position %lld is beyond its device's counts", i + 1,
		    (long long)p);
		return false;
	}
	u = live_units(s->lv, i, *dev);
	if (u < o->min - 1e-9 || u > o->max + 1e-9) {
		why(s, "motor %u (%s): position %lld (%.7g %s) is beyond its limits, %lld to %lld: "
		    "refused, nothing moves", i + 1, o->channel, (long long)p, u, o->unit,
		    (long long)(live_counts(s->lv, i, o->min) - s->zero[i]),
		    (long long)(live_counts(s->lv, i, o->max) - s->zero[i]));
		return false;
	}
	return true;
}

/* The drives able to move, else said why: false. */
static bool live_ok(struct dfm_session *s)
{
	switch (s->snap.state) {
	case LIVE_ESTOPPED:
		why(s, "e-stopped (%s): release the e-stop and say hi again", s->snap.reason);
		return false;
	case LIVE_FAULTED:
		why(s, "faulted (%s): say hi again to reset", s->snap.reason);
		return false;
	case LIVE_DISABLED:
		why(s, "the drives are disabled: say hi to enable them");
		return false;
	default:
		return true;
	}
}

static void want(struct dfm_session *s, uint32_t i, int64_t dev)
{
	s->want[i] = dev;
	s->has_want[i] = true;
	s->report_ns = 0;
}

/* A go-motion armed and not run (bf without its go) gives way to the next
 * motion Dragonframe asks for, as the sketch's does: stopped, and the rig
 * at rest again (200 ms at most; it stands still already). */
static void disarm(struct dfm_session *s)
{
	char msg[LIVE_MSG];
	int k;

	if (!s->gomo_ready)
		return;
	s->gomo_ready = false;
	if (s->gomo_still)
		return;
	if (live_stop(s->lv, msg, sizeof(msg)))
		why(s, "%s", msg);
	for (k = 0; k < 200; k++) {
		live_service(s->lv);
		live_snapshot(s->lv, &s->snap);
		if (s->snap.state == LIVE_ENABLED && s->snap.cmd_seen >= s->snap.cmd_sent)
			break;
		nanosleep(&(struct timespec){ .tv_nsec = 1000000 }, NULL);
	}
	memset(s->involved, 0, sizeof(s->involved));
}

/* ---- the commands ---- */

static void hi(struct dfm_session *s)
{
	char msg[LIVE_MSG];

	say(s, "hi %d %u %s", DFM_PROTOCOL, s->n, DFM_VERSION);
	if (s->snap.state == LIVE_ESTOPPED || s->snap.state == LIVE_FAULTED) {
		if (live_reset(s->lv, msg, sizeof(msg))) {
			why(s, "%s", msg);
			return;
		}
	}
	if (s->snap.state != LIVE_ENABLED && s->snap.state != LIVE_MOVING &&
	    s->snap.state != LIVE_STOPPING && live_enable(s->lv, msg, sizeof(msg)))
		why(s, "%s", msg);
	/* a new run of the loop counts its commands afresh */
	memset(s->has_want, 0, sizeof(s->has_want));
	memset(s->involved, 0, sizeof(s->involved));
	s->move_sent = false;
	s->busy_seq = 0;
	s->gomo_ready = false;
	/* the loop's first sample, so that what follows sees the drives on
	 * (a loop that starts takes a tick or two; 200 ms at most) */
	for (int k = 0; k < 200; k++) {
		live_service(s->lv);
		live_snapshot(s->lv, &s->snap);
		if (s->snap.state == LIVE_ENABLED || s->snap.state == LIVE_MOVING ||
		    s->snap.state == LIVE_STOPPING)
			break;
		nanosleep(&(struct timespec){ .tv_nsec = 1000000 }, NULL);
	}
	s->last_state = s->snap.state;
}

static void ms(struct dfm_session *s)
{
	char bits[LOOP_LIVE_OUT_MAX + 1];
	uint32_t i;

	for (i = 0; i < s->n; i++)
		bits[i] = moving(s, i) ? '1' : '0';
	bits[i] = 0;
	say(s, "ms %s", bits);
}

static void mm(struct dfm_session *s, const struct dfm_cmd *c, bool inch)
{
	int64_t dev, p = c->arg[1], here;
	uint32_t i;

	if (!motor(s, c->arg[0], &i) || !positioned(s, i))
		return;
	here = at(s, i);
	if (inch) /* a step towards P, not past it */
		p = here + (p > here ? 1 : p < here ? -1 : 0) *
				   (llabs(p - here) < DFM_INCH ? llabs(p - here) : DFM_INCH);
	if (!live_ok(s) || !target(s, i, p, &dev)) {
		say_mp(s, i);
		return;
	}
	disarm(s);
	want(s, i, dev);
	s->gather_ns = now_ns();
	if (inch)
		say(s, "im %u", i + 1);
	else if (p == here)
		say(s, "mp %u %lld", i + 1, (long long)p);
	else
		say(s, "mm %u %lld", i + 1, (long long)p);
}

static void stop_all(struct dfm_session *s)
{
	char msg[LIVE_MSG];

	memset(s->has_want, 0, sizeof(s->has_want));
	s->gomo_ready = false;
	if (live_stop(s->lv, msg, sizeof(msg)))
		why(s, "%s", msg);
}

static void sm(struct dfm_session *s, const struct dfm_cmd *c)
{
	char msg[LIVE_MSG];
	uint32_t i;

	if (!motor(s, c->arg[0], &i))
		return;
	if (s->snap.out[i].jog) {
		/* a jog's release: that motor alone */
		if (live_jog(s->lv, DFM_CLIENT, i, 0, ++s->jog_seq, msg, sizeof(msg)))
			why(s, "%s", msg);
		s->has_want[i] = false;
	} else if (rig_moving(s) || s->gomo_ready) {
		/* a move carries every motor together: they stop together */
		stop_all(s);
	} else {
		s->has_want[i] = false;
	}
	say(s, "sm %u", i + 1);
	say_mp(s, i);
}

static void pr(struct dfm_session *s, const struct dfm_cmd *c)
{
	double rate;
	uint32_t i;

	if (!motor(s, c->arg[0], &i))
		return;
	if (c->arg[1] < 1) {
		say(s, "parse error");
		return;
	}
	/* positions a second at the velocity limit */
	rate = fabs((double)(live_counts(s->lv, i, s->info[i].vmax) - live_counts(s->lv, i, 0)));
	if (!(rate >= 1)) {
		s->jog[i] = 1;
		say(s, "pr %u %d", i + 1, c->arg[1]);
		return;
	}
	s->jog[i] = fmin(1, c->arg[1] / rate);
	say(s, "pr %u %lld", i + 1, (long long)floor(s->jog[i] * rate));
}

static void zero(struct dfm_session *s, const struct dfm_cmd *c)
{
	int64_t p = c->kind == DFM_NP ? c->arg[1] : 0;
	uint32_t i;

	if (!motor(s, c->arg[0], &i))
		return;
	s->zero[i] = at_dev(s, i) - p;
	if (c->kind == DFM_NP)
		say(s, "np %u %lld", i + 1, (long long)p);
	else
		say(s, "zm %u", i + 1);
	say(s, "mp %u %lld", i + 1, (long long)p);
}

static void jm(struct dfm_session *s, const struct dfm_cmd *c)
{
	char msg[LIVE_MSG];
	int64_t here;
	double speed;
	uint32_t i;

	if (!motor(s, c->arg[0], &i) || !positioned(s, i))
		return;
	if (!live_ok(s)) {
		say_mp(s, i);
		return;
	}
	here = at(s, i);
	speed = c->arg[1] > here ? s->jog[i] : c->arg[1] < here ? -s->jog[i] : 0;
	s->has_want[i] = false;
	disarm(s);
	if (live_jog(s->lv, DFM_CLIENT, i, speed, ++s->jog_seq, msg, sizeof(msg))) {
		why(s, "%s", msg);
		say_mp(s, i);
		return;
	}
	say(s, "jm %u", i + 1);
}

static void bf(struct dfm_session *s, const struct dfm_cmd *c)
{
	int64_t prev[LOOP_LIVE_OUT_MAX], here[LOOP_LIVE_OUT_MAX], next[LOOP_LIVE_OUT_MAX];
	bool seen[LOOP_LIVE_OUT_MAX] = { false };
	struct live_gomo g;
	char msg[LIVE_MSG];
	int64_t delay;
	uint32_t i, k, m = (c->nargs - 2) / 4;
	int rc;

	if (c->arg[0] < 1 || c->arg[0] > 3600000 || c->arg[1] < 0 || c->arg[1] > 1000 ||
	    m > s->n) {
		say(s, "parse error");
		return;
	}
	for (i = 0; i < s->n; i++)
		prev[i] = here[i] = next[i] = at_dev(s, i);
	for (k = 0; k < m; k++) {
		const int32_t *a = c->arg + 2 + 4 * k;
		int64_t p[3];
		uint32_t j;

		if (!motor(s, a[0], &i))
			return;
		if (seen[i]) {
			say(s, "parse error");
			return;
		}
		if (!positioned(s, i))
			return;
		seen[i] = true;
		for (j = 0; j < 3; j++)
			if (__builtin_add_overflow((int64_t)a[1 + j], s->zero[i], &p[j])) {
				say(s, "parse error");
				return;
			}
		prev[i] = p[0];
		here[i] = p[1];
		next[i] = p[2];
	}
	if (!live_ok(s)) {
		say(s, "bf -1");
		return;
	}
	disarm(s);
	if (c->arg[1] == 0) {
		/* no blur: a still frame at this pose, nothing moves at go */
		for (i = 0; i < s->n; i++)
			if (seen[i] && !target(s, i, here[i] - s->zero[i], &here[i])) {
				say(s, "bf -1");
				return;
			}
		for (i = 0; i < s->n; i++)
			if (seen[i])
				want(s, i, here[i]);
		s->gather_ns = 0;
		s->gomo_ready = s->gomo_still = true;
		say(s, "bf 0");
		return;
	}
	g = (struct live_gomo){ .frame = s->shots + 1, .exposure_ms = (uint32_t)c->arg[0],
				.shutter = (uint32_t)c->arg[1], .prev = prev, .at = here,
				.next = next };
	rc = live_gomo(s->lv, &g, &delay, msg, sizeof(msg));
	if (rc) {
		why(s, "%s", msg);
		say(s, rc == -EDOM ? "bf -1" : "parse error");
		return;
	}
	memset(s->has_want, 0, sizeof(s->has_want));
	for (i = 0; i < s->n; i++)
		s->involved[i] = true;
	busy(s);
	s->gomo_ready = true;
	s->gomo_still = false;
	s->report_ns = 0;
	say(s, "bf %lld", (long long)delay);
}

static void go(struct dfm_session *s)
{
	char msg[LIVE_MSG];

	if (!s->gomo_ready) {
		why(s, "go: no go-motion prepared (bf first)");
		say(s, "parse error");
		return;
	}
	if (!s->gomo_still && live_gomo_go(s->lv, msg, sizeof(msg))) {
		why(s, "%s", msg);
		say(s, "parse error");
		return;
	}
	if (!s->gomo_still) {
		/* a frame shot: the next bf's number is the next */
		s->shots++;
		for (uint32_t i = 0; i < s->n; i++)
			s->involved[i] = true;
		busy(s);
	}
	s->gomo_ready = false;
	say(s, "go");
}

void dfm_session_line(struct dfm_session *s, const char *line, size_t len, bool overlong)
{
	struct dfm_cmd c;
	char msg[160];
	uint32_t i;

	if (overlong || dfm_parse(line, len, &c, msg, sizeof(msg))) {
		if (overlong)
			snprintf(msg, sizeof(msg), "a line longer than %d bytes", DFM_LINE_MAX);
		say(s, "parse error");
		if (s->log)
			fprintf(s->log, "strand dfmoco: %s\n", msg);
		return;
	}
	live_service(s->lv);
	live_snapshot(s->lv, &s->snap);
	switch (c.kind) {
	case DFM_HI:
		hi(s);
		break;
	case DFM_MS:
		ms(s);
		break;
	case DFM_MM:
		mm(s, &c, false);
		break;
	case DFM_IM:
		mm(s, &c, true);
		break;
	case DFM_MP:
		if (motor(s, c.arg[0], &i))
			say_mp(s, i);
		break;
	case DFM_SM:
		sm(s, &c);
		break;
	case DFM_SA:
		stop_all(s);
		say(s, "sa");
		break;
	case DFM_PR:
		pr(s, &c);
		break;
	case DFM_ZM:
	case DFM_NP:
		zero(s, &c);
		break;
	case DFM_JM:
		jm(s, &c);
		break;
	case DFM_BF:
		bf(s, &c);
		break;
	case DFM_GO:
		go(s);
		break;
	default:
		say(s, "parse error");
		break;
	}
}

static void on_line(void *ctx, const char *line, size_t len, bool overlong)
{
	dfm_session_line(ctx, line, len, overlong);
}

void dfm_session_input(struct dfm_session *s, const char *in, size_t n)
{
	dfm_lines_feed(&s->lines, in, n, on_line, s);
}

/* ---- the round ---- */

/* The wants, once the rig rests: one move, every motor together. */
static void move_wants(struct dfm_session *s, int64_t now)
{
	double pose[LOOP_LIVE_OUT_MAX];
	char msg[LIVE_MSG];
	bool any = false;
	uint32_t i;

	if (s->move_sent) {
		/* until a sample has taken it and the rig rests again */
		if (!at_rest(s))
			return;
		s->move_sent = false;
	}
	if (s->snap.state != LIVE_ENABLED || now - s->gather_ns < DFM_GATHER_NS)
		return;
	for (i = 0; i < s->n; i++) {
		pose[i] = NAN;
		if (s->has_want[i] && s->want[i] != at_dev(s, i)) {
			pose[i] = live_units(s->lv, i, s->want[i]);
			any = true;
		}
	}
	if (!any)
		return;
	if (live_move(s->lv, pose, s->n, msg, sizeof(msg))) {
		why(s, "%s", msg);
		for (i = 0; i < s->n; i++)
			if (s->has_want[i] && s->want[i] != at_dev(s, i))
				say_mp(s, i);
		memset(s->has_want, 0, sizeof(s->has_want));
		return;
	}
	for (i = 0; i < s->n; i++)
		s->involved[i] = !isnan(pose[i]);
	busy(s);
	s->move_sent = true;
}

void dfm_session_tick(struct dfm_session *s, int64_t now)
{
	uint32_t i;
	bool report;

	live_service(s->lv);
	live_snapshot(s->lv, &s->snap);
	if (s->snap.state != s->last_state &&
	    (s->snap.state == LIVE_ESTOPPED || s->snap.state == LIVE_FAULTED)) {
		/* the reason names it: "e-stop: input 'estop' ...", "device
		 * fault: ..." */
		why(s, "%s; every motor stopped", s->snap.reason[0] ? s->snap.reason :
		    s->snap.state == LIVE_ESTOPPED ? "e-stop" : "fault");
		memset(s->has_want, 0, sizeof(s->has_want));
		memset(s->involved, 0, sizeof(s->involved));
		s->move_sent = false;
		s->busy_seq = 0;
		s->gomo_ready = false;
		for (i = 0; i < s->n; i++)
			say_mp(s, i);
	}
	s->last_state = s->snap.state;
	if (at_rest(s))
		memset(s->involved, 0, sizeof(s->involved));
	move_wants(s, now);
	report = now >= s->report_ns;
	if (report)
		s->report_ns = now + DFM_REPORT_NS;
	for (i = 0; i < s->n; i++) {
		bool m = moving(s, i);

		/* while it moves, and once more where it stopped */
		if ((m && report) || (!m && s->was_moving[i]))
			say_mp(s, i);
		s->was_moving[i] = m;
	}
}

int dfm_session_init(struct dfm_session *s, struct live *lv, FILE *log)
{
	uint32_t i;

	memset(s, 0, sizeof(*s));
	s->lv = lv;
	s->log = log;
	s->n = live_outputs(lv, s->info, LOOP_LIVE_OUT_MAX);
	for (i = 0; i < s->n; i++)
		s->jog[i] = DFM_JOG_DEFAULT;
	live_service(lv);
	live_snapshot(lv, &s->snap);
	s->last_state = s->snap.state;
	return 0;
}
