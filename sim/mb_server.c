/* SPDX-License-Identifier: MIT */
/* mb_server.c - a simulated drive behind a libmodbus server (see
 * mb_server.h). */
#define _GNU_SOURCE
#include "mb_server.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <modbus.h>
#include <netinet/in.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "hal/clock.h"
#include "hal/rt.h"

#define FC_WRITE_COIL 0x05
#define FC_WRITE_REG 0x06
#define FC_READ_REGS 0x03
#define FC_WRITE_REGS 0x10

enum { ANSWERED, SILENT, DROP };

struct mbs {
	const struct mb_server_cfg *c;
	const struct modbus_desc *d;
	char *err;
	size_t errsize;
	modbus_t *ctx;
	modbus_mapping_t *map;
	struct modbus_reg *w, *r;
	uint32_t nw, nr;
	int32_t *rfield, rstatus;
	int64_t *vals;
	int64_t hb_tick;
	bool dropped, tripped;

	/* the plant's state */
	bool enabled;
	int64_t tick;             /* the plant's */
	int64_t writes;           /* setpoint writes received */
	int64_t t0_ns;            /* wall clock of the first write, without a heartbeat */
	int64_t *prev;            /* nch: the last targets, for the velocity feed-forward */
	int64_t prev_tick;
	bool rebase;              /* enabled again: the client's ticks count afresh */
};

/* The plant never catches up more than this at once (a stalled client). */
#define MODEL_MAX_STEPS 100000

/* The plant to tick t. */
static void advance(struct mbs *sd, int64_t t)
{
	struct hal_axis *ax = sim_drive_axis(sd->c->drive);
	int64_t n = 0;

	if (t - sd->tick > MODEL_MAX_STEPS)
		sd->tick = t - MODEL_MAX_STEPS;
	while (sd->tick < t && n++ < MODEL_MAX_STEPS)
		hal_axis_input(ax, ++sd->tick);
}

static void model_enable(struct mbs *sd, bool on)
{
	struct hal_axis *ax = sim_drive_axis(sd->c->drive);

	if (on && !sd->enabled) {
		hal_axis_start(ax);
		/* a client enables its drive for each run of its loop, whose
		 * ticks (the heartbeat, or the wall clock since its first
		 * write) start again: the plant goes on from the next write */
		sd->rebase = true;
		sd->t0_ns = 0;
	}
	else if (!on && sd->enabled)
		hal_axis_disable(ax);
	sd->enabled = on;
}

static void model_targets(struct mbs *sd, const int64_t *val, int64_t tick)
{
	struct hal_axis *ax = sim_drive_axis(sd->c->drive);
	int64_t now = hal_mono_ns(), dt;
	uint32_t i;

	if (tick < 0) {
		/* no heartbeat: the wall clock since the first setpoint */
		if (!sd->t0_ns)
			sd->t0_ns = now;
		tick = (now - sd->t0_ns) * sd->c->tick_hz / 1000000000;
	}
	if (sd->rebase) {
		sd->rebase = false;
		sd->tick = tick - 1;
		sd->prev_tick = tick;
	}
	advance(sd, tick);
	dt = tick - sd->prev_tick;
	for (i = 0; i < sd->c->nch; i++) {
		struct hal_setpoint sp = { 0, 0 };

		if (sd->c->velocity[i]) {
			sp.vel = val[i];
		} else {
			/* a drive given positions only differentiates them for its
			 * velocity feed-forward */
			sp.pos = val[i];
			sp.vel = dt > 0 && sd->writes ? (val[i] - sd->prev[i]) * sd->c->tick_hz / dt : 0;
			sd->prev[i] = val[i];
		}
		hal_axis_set(ax, i, &sp);
	}
	sd->prev_tick = tick;
	hal_axis_commit(ax, tick);
	sd->writes++;
}

static int64_t model_actual(struct mbs *sd, uint32_t ch)
{
	int64_t c = 0;

	hal_axis_actual(sim_drive_axis(sd->c->drive), ch, &c);
	return c;
}

static bool model_faulted(struct mbs *sd)
{
	struct hal_fault f;

	return hal_axis_fault(sim_drive_axis(sd->c->drive), &f) != 0;
}

static void model_trip(struct mbs *sd)
{
	uint32_t i;

	for (i = 0; i < sd->c->nch; i++)
		sim_drive_inject(sd->c->drive, i, sd->tick + 1, SIM_DRIVE_TRIP);
	advance(sd, sd->tick + 1);
}
/* The first error, as a message for the program to print. */
static int fail(struct mbs *s, int code, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(s->err, s->errsize, fmt, ap);
	va_end(ap);
	return code < 0 ? code : -EIO;
}

static void nap_ns(const struct mbs *s, int64_t ns)
{
	struct timespec ts = { ns / 1000000000, ns % 1000000000 };

	while (nanosleep(&ts, &ts) && errno == EINTR && !*s->c->stop)
		;
}

static bool covers(uint32_t addr, uint32_t count, const struct modbus_reg *r)
{
	return r->addr < addr + count && addr < r->addr + modbus_type_nregs(r->type);
}

/* The loop's tick from the heartbeat: it counts modulo the register's
 * width, so unwrap it forward from the last one (all ones: tick -1). */
static int64_t heartbeat_tick(struct mbs *s)
{
	const struct modbus_reg *hb = &s->w[s->nw - 1];
	uint32_t raw = (uint32_t)modbus_reg_decode(hb, s->map->tab_registers + hb->addr);

	if (modbus_type_nregs(hb->type) == 2)
		s->hb_tick += (int32_t)(raw - (uint32_t)s->hb_tick);
	else
		s->hb_tick += (int16_t)(uint16_t)(raw - (uint16_t)s->hb_tick);
	return s->hb_tick;
}

static void took_targets(struct mbs *s)
{
	FILE *log = s->c->log;
	int64_t tick = s->d->has_heartbeat ? heartbeat_tick(s) : -1;
	uint32_t i;

	for (i = 0; i < s->c->nch; i++)
		s->vals[i] = modbus_reg_decode(&s->w[i], s->map->tab_registers + s->w[i].addr);
	model_targets(s, s->vals, tick);
	if (log) {
		fprintf(log, "W %lld %lld", (long long)s->writes, (long long)tick);
		for (i = 0; i < s->c->nch; i++)
			fprintf(log, " %lld", (long long)s->vals[i]);
		fputc('\n', log);
		fflush(log);
	}
}

static void took_enable(struct mbs *s, bool on)
{
	model_enable(s, on);
	if (s->c->log) {
		fprintf(s->c->log, "E %d\n", on);
		fflush(s->c->log);
	}
}

/* What a real line at the scene's baud rate would take for this request
 * and its answer (RTU framing, modbus_map.h). */
static int64_t wire_ns(const struct mbs *s, int len, int fc, uint32_t count)
{
	uint32_t bits = modbus_rtu_char_bits(s->d->parity != 'N', s->d->stop_bits);
	uint32_t rsp = fc == FC_READ_REGS ? modbus_rtu_read_rsp_bytes(count) : 8;

	return modbus_rtu_transaction_ns((uint32_t)len, rsp, s->d->baud, bits, 0);
}

static int handle(struct mbs *s, const uint8_t *q, int len)
{
	const struct mb_server_faults *f = &s->c->faults;
	int hl = modbus_get_header_length(s->ctx), fc = q[hl];
	uint32_t addr = (uint32_t)q[hl + 1] << 8 | q[hl + 2];
	uint32_t count = (uint32_t)q[hl + 3] << 8 | q[hl + 4];
	bool targets = false;
	uint32_t i;

	if (fc == FC_WRITE_REGS)
		for (i = 0; i < s->c->nch; i++)
			targets |= covers(addr, count, &s->w[i]);
	if (f->die_after && s->writes >= f->die_after) {
		if (s->c->log) {
			fprintf(s->c->log, "X die\n");
			fflush(s->c->log);
		}
		_exit(0);
	}
	if (f->silent_after && s->writes >= f->silent_after)
		return SILENT;
	if (f->drop_after && s->writes >= f->drop_after && !s->dropped) {
		s->dropped = true;
		return DROP;
	}
	if (f->trip_after && s->writes >= f->trip_after && !s->tripped) {
		s->tripped = true;
		model_trip(s);
	}
	if (f->exception_after && s->writes >= f->exception_after) {
		modbus_reply_exception(s->ctx, q, (unsigned)f->exception);
		return ANSWERED;
	}
	if (f->late_after && s->writes >= f->late_after)
		nap_ns(s, (int64_t)(f->late_ms * 1e6));
	if (f->wire_time && s->d->transport == MODBUS_RTU)
		nap_ns(s, wire_ns(s, len, fc, count));
	if (fc == FC_READ_REGS) {
		for (i = 0; i < s->c->nch; i++) {
			int32_t k = s->rfield[i];

			if (k >= 0)
				modbus_reg_encode(&s->r[k], model_actual(s, i),
						  s->map->tab_registers + s->r[k].addr);
		}
		if (s->rstatus >= 0)
			s->map->tab_registers[s->d->status_addr] =
				model_faulted(s) ? s->d->status_fault_mask : 0;
	}
	if (modbus_reply(s->ctx, q, len, s->map) < 0)
		return ANSWERED;
	if (targets)
		took_targets(s);
	if (s->d->has_enable) {
		const struct modbus_desc *d = s->d;

		if (d->enable_coil && fc == FC_WRITE_COIL && addr == d->enable_addr)
			took_enable(s, s->map->tab_bits[d->enable_addr]);
		else if (!d->enable_coil && (fc == FC_WRITE_REG ? addr == d->enable_addr :
					     fc == FC_WRITE_REGS && addr <= d->enable_addr &&
					     d->enable_addr < addr + count))
			took_enable(s, s->map->tab_registers[d->enable_addr] == d->enable_on);
	}
	return ANSWERED;
}

static int serve_tcp(struct mbs *s)
{
	const struct modbus_desc *d = s->d;
	char host[256], port[16], *colon;
	uint8_t q[MODBUS_TCP_MAX_ADU_LENGTH];
	struct sockaddr_storage sa;
	socklen_t salen = sizeof(sa);
	int lfd, fdmax, fd, rc;
	fd_set all, rd;

	snprintf(host, sizeof(host), "%s", s->c->listen ? s->c->listen : d->host);
	snprintf(port, sizeof(port), "%u", d->port);
	colon = s->c->listen ? strrchr(host, ':') : NULL;
	if (colon) {
		*colon = 0;
		snprintf(port, sizeof(port), "%s", colon + 1);
	}
	s->ctx = modbus_new_tcp_pi(host, port);
	if (!s->ctx)
		return fail(s, -errno, "modbus tcp %s:%s: %s", host, port, modbus_strerror(errno));
	lfd = modbus_tcp_pi_listen(s->ctx, 8);
	if (lfd < 0)
		return fail(s, -errno, "listen on %s:%s: %s", host, port, modbus_strerror(errno));
	getsockname(lfd, (struct sockaddr *)&sa, &salen);
	if (!s->c->quiet) {
		/* where it listens: the map's unit at the address bound */
		struct modbus_desc at = *d;
		char where[320];

		at.host = host;
		at.port = ntohs(sa.ss_family == AF_INET6 ? ((struct sockaddr_in6 *)&sa)->sin6_port :
				((struct sockaddr_in *)&sa)->sin_port);
		modbus_where(where, sizeof(where), &at);
		printf("strand-simdrive: '%s': modbus %s, serving\n", s->c->name, where);
		fflush(stdout);
	}
	FD_ZERO(&all);
	FD_SET(lfd, &all);
	fdmax = lfd;
	while (!*s->c->stop) {
		rd = all;
		if (select(fdmax + 1, &rd, NULL, NULL, NULL) < 0)
			continue; /* EINTR: a signal, seen above */
		for (fd = 0; fd <= fdmax; fd++) {
			if (!FD_ISSET(fd, &rd))
				continue;
			if (fd == lfd) {
				int c = accept(lfd, NULL, NULL);

				if (c >= 0 && c < FD_SETSIZE) {
					FD_SET(c, &all);
					fdmax = c > fdmax ? c : fdmax;
				} else if (c >= 0) {
					close(c);
				}
				continue;
			}
			modbus_set_socket(s->ctx, fd);
			rc = modbus_receive(s->ctx, q);
			if (rc > 0 && handle(s, q, rc) != DROP)
				continue;
			if (rc == 0)
				continue;
			/* closed by the client, broken, or dropped on purpose */
			close(fd);
			FD_CLR(fd, &all);
		}
	}
	close(lfd);
	return 0;
}

static int serve_rtu(struct mbs *s)
{
	const struct modbus_desc *d = s->d;
	const char *link = s->c->pty ? s->c->pty : d->serial;
	uint8_t q[MODBUS_RTU_MAX_ADU_LENGTH];
	struct termios tio;
	struct stat st;
	const char *slave;
	int master, hold, rc;
	fd_set rd;

	master = posix_openpt(O_RDWR | O_NOCTTY);
	if (master < 0 || grantpt(master) || unlockpt(master) || !(slave = ptsname(master))) {
		return fail(s, -errno, "pseudo-terminal: %s", strerror(errno));
	}
	/* an open slave keeps the master readable only when there is data
	 * (with none open, it reads EIO until the loop opens its end) */
	hold = open(slave, O_RDWR | O_NOCTTY);
	if (hold < 0 || tcgetattr(hold, &tio)) {
		return fail(s, -errno, "%s: %s", slave, strerror(errno));
	}
	cfmakeraw(&tio);
	tcsetattr(hold, TCSANOW, &tio);
	/* replace a link, never a device or a file */
	if (!lstat(link, &st) && !S_ISLNK(st.st_mode)) {
		return fail(s, -EEXIST, "%s exists and is not a link", link);
	}
	unlink(link);
	if (symlink(slave, link)) {
		return fail(s, -errno, "link %s -> %s: %s", link, slave, strerror(errno));
	}
	s->ctx = modbus_new_rtu(link, (int)d->baud, d->parity, 8, (int)d->stop_bits);
	if (!s->ctx) {
		rc = fail(s, -errno, "modbus rtu %s: %s", link, modbus_strerror(errno));
		unlink(link);
		return rc;
	}
	modbus_set_slave(s->ctx, (int)d->unit);
	modbus_set_socket(s->ctx, master);
	if (!s->c->quiet) {
		/* where it serves: the link, the pseudo-terminal behind it and
		 * the line's rate, as the port of the map's unit */
		struct modbus_desc at = *d;
		char port[PATH_MAX + 64], where[PATH_MAX + 96];

		snprintf(port, sizeof(port), "%s (%s) %u baud", link, slave, d->baud);
		at.serial = port;
		modbus_where(where, sizeof(where), &at);
		printf("strand-simdrive: '%s': modbus %s, serving\n", s->c->name, where);
		fflush(stdout);
	}
	while (!*s->c->stop) {
		FD_ZERO(&rd);
		FD_SET(master, &rd);
		if (select(master + 1, &rd, NULL, NULL, NULL) <= 0)
			continue;
		rc = modbus_receive(s->ctx, q);
		if (rc > 0)
			handle(s, q, rc);
		else if (rc < 0)
			modbus_flush(s->ctx); /* a broken frame: start afresh */
	}
	unlink(link);
	close(hold);
	close(master);
	return 0;
}

int mb_server_run(const struct mb_server_cfg *c, char *err, size_t errsize)
{
	const struct modbus_desc *d = c->d;
	struct mbs s = { .c = c, .d = d, .err = err, .errsize = errsize, .hb_tick = -1,
			 .tick = -1, .prev_tick = -1 };
	uint32_t top = 0, i, nw, nr;
	int rc = -ENOMEM;

	STRAND_ASSERT_NOT_RT();
	s.w = calloc(c->nch + 1, sizeof(*s.w));
	s.r = calloc(c->nch + 1, sizeof(*s.r));
	s.rfield = calloc(c->nch ? c->nch : 1, sizeof(*s.rfield));
	s.vals = calloc(c->nch ? c->nch : 1, sizeof(*s.vals));
	s.prev = calloc(c->nch ? c->nch : 1, sizeof(*s.prev));
	if (!s.w || !s.r || !s.rfield || !s.vals || !s.prev) {
		snprintf(err, errsize, "out of memory");
		goto out;
	}
	/* a drive without an enable is powered from the start */
	if (!d->has_enable)
		model_enable(&s, true);
	modbus_desc_regs(d, c->nch, s.w, &nw, s.r, &nr, s.rfield, &s.rstatus);
	s.nw = nw;
	s.nr = nr;
	/* every register the map names, and the ones in between */
	for (i = 0; i < nw; i++)
		top = top > s.w[i].addr + 2u ? top : s.w[i].addr + 2u;
	for (i = 0; i < nr; i++)
		top = top > s.r[i].addr + 2u ? top : s.r[i].addr + 2u;
	if (d->has_enable && !d->enable_coil)
		top = top > d->enable_addr + 1u ? top : d->enable_addr + 1u;
	s.map = modbus_mapping_new(d->has_enable && d->enable_coil ? d->enable_addr + 1 : 0, 0,
				   (int)(top < 65536 ? top : 65536), 0);
	if (!s.map) {
		snprintf(err, errsize, "out of memory");
		goto out;
	}
	rc = d->transport == MODBUS_TCP ? serve_tcp(&s) : serve_rtu(&s);
out:
	if (s.map)
		modbus_mapping_free(s.map);
	if (s.ctx)
		modbus_free(s.ctx);
	free(s.w);
	free(s.r);
	free(s.rfield);
	free(s.vals);
	free(s.prev);
	return rc;
}
