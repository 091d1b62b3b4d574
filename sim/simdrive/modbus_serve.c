/* SPDX-License-Identifier: MIT */
/*
 * modbus_serve.c - strand-simdrive's Modbus server (see simdrive.h), with
 * libmodbus on the server side: TCP with any number of clients at once (the
 * loop and, say, mbpoll), or RTU on a pseudo-terminal whose other end is
 * linked where the scene says the serial port is.
 *
 * Each request is read whole, the faults asked for are applied (counted in
 * setpoint writes: a function 16 that covers a target register), reads of
 * the actual and status registers are filled from the model first, and
 * after the answer a setpoint write moves the model and goes to the log.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <modbus.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "modbus_dev.h"
#include "simdrive.h"

#define FC_WRITE_COIL 0x05
#define FC_WRITE_REG 0x06
#define FC_READ_REGS 0x03
#define FC_WRITE_REGS 0x10

enum { ANSWERED, SILENT, DROP };

struct mbs {
	struct simdrive *sd;
	const struct modbus_desc *d;
	modbus_t *ctx;
	modbus_mapping_t *map;
	struct modbus_reg *w, *r;
	uint32_t nw, nr;
	int32_t *rfield, rstatus;
	int64_t *vals;
	int64_t hb_tick;
	bool dropped, tripped;
};

static volatile sig_atomic_t stop_sig;

static void on_signal(int sig)
{
	stop_sig = sig;
}

static void nap_ns(int64_t ns)
{
	struct timespec ts = { ns / 1000000000, ns % 1000000000 };

	while (nanosleep(&ts, &ts) && errno == EINTR && !stop_sig)
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
	struct simdrive *sd = s->sd;
	int64_t tick = s->d->has_heartbeat ? heartbeat_tick(s) : -1;
	uint32_t i;

	for (i = 0; i < sd->nch; i++)
		s->vals[i] = modbus_reg_decode(&s->w[i], s->map->tab_registers + s->w[i].addr);
	simdrive_targets(sd, s->vals, tick);
	if (sd->log) {
		fprintf(sd->log, "W %lld %lld", (long long)sd->writes, (long long)tick);
		for (i = 0; i < sd->nch; i++)
			fprintf(sd->log, " %lld", (long long)s->vals[i]);
		fputc('\n', sd->log);
		fflush(sd->log);
	}
}

static void took_enable(struct mbs *s, bool on)
{
	simdrive_enable(s->sd, on);
	if (s->sd->log) {
		fprintf(s->sd->log, "E %d\n", on);
		fflush(s->sd->log);
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
	struct simdrive *sd = s->sd;
	const struct simdrive_faults *f = &sd->faults;
	int hl = modbus_get_header_length(s->ctx), fc = q[hl];
	uint32_t addr = (uint32_t)q[hl + 1] << 8 | q[hl + 2];
	uint32_t count = (uint32_t)q[hl + 3] << 8 | q[hl + 4];
	bool targets = false;
	uint32_t i;

	if (fc == FC_WRITE_REGS)
		for (i = 0; i < sd->nch; i++)
			targets |= covers(addr, count, &s->w[i]);
	if (f->die_after && sd->writes >= f->die_after) {
		if (sd->log) {
			fprintf(sd->log, "X die\n");
			fflush(sd->log);
		}
		_exit(0);
	}
	if (f->silent_after && sd->writes >= f->silent_after)
		return SILENT;
	if (f->drop_after && sd->writes >= f->drop_after && !s->dropped) {
		s->dropped = true;
		return DROP;
	}
	if (f->trip_after && sd->writes >= f->trip_after && !s->tripped) {
		s->tripped = true;
		simdrive_trip(sd);
	}
	if (f->exception_after && sd->writes >= f->exception_after) {
		modbus_reply_exception(s->ctx, q, (unsigned)f->exception);
		return ANSWERED;
	}
	if (f->late_after && sd->writes >= f->late_after)
		nap_ns((int64_t)(f->late_ms * 1e6));
	if (f->wire_time && s->d->transport == MODBUS_RTU)
		nap_ns(wire_ns(s, len, fc, count));
	if (fc == FC_READ_REGS) {
		for (i = 0; i < sd->nch; i++) {
			int32_t k = s->rfield[i];

			if (k >= 0)
				modbus_reg_encode(&s->r[k], simdrive_actual(sd, i),
						  s->map->tab_registers + s->r[k].addr);
		}
		if (s->rstatus >= 0)
			s->map->tab_registers[s->d->status_addr] =
				simdrive_faulted(sd) ? s->d->status_fault_mask : 0;
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

	snprintf(host, sizeof(host), "%s", s->sd->listen ? s->sd->listen : d->host);
	snprintf(port, sizeof(port), "%u", d->port);
	colon = s->sd->listen ? strrchr(host, ':') : NULL;
	if (colon) {
		*colon = 0;
		snprintf(port, sizeof(port), "%s", colon + 1);
	}
	s->ctx = modbus_new_tcp_pi(host, port);
	if (!s->ctx)
		return 8;
	lfd = modbus_tcp_pi_listen(s->ctx, 8);
	if (lfd < 0) {
		fprintf(stderr, "strand-simdrive: listen on %s:%s: %s\n", host, port,
			modbus_strerror(errno));
		return 4;
	}
	getsockname(lfd, (struct sockaddr *)&sa, &salen);
	if (!s->sd->quiet) {
		printf("strand-simdrive: '%s': modbus tcp %s:%u unit %u, serving\n",
		       s->sd->dd->name, host,
		       ntohs(sa.ss_family == AF_INET6 ? ((struct sockaddr_in6 *)&sa)->sin6_port :
			     ((struct sockaddr_in *)&sa)->sin_port), d->unit);
		fflush(stdout);
	}
	FD_ZERO(&all);
	FD_SET(lfd, &all);
	fdmax = lfd;
	while (!stop_sig) {
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
	const char *link = s->sd->pty ? s->sd->pty : d->serial;
	uint8_t q[MODBUS_RTU_MAX_ADU_LENGTH];
	struct termios tio;
	struct stat st;
	const char *slave;
	int master, hold, rc;
	fd_set rd;

	master = posix_openpt(O_RDWR | O_NOCTTY);
	if (master < 0 || grantpt(master) || unlockpt(master) || !(slave = ptsname(master))) {
		fprintf(stderr, "strand-simdrive: pseudo-terminal: %s\n", strerror(errno));
		return 4;
	}
	/* an open slave keeps the master readable only when there is data
	 * (with none open, it reads EIO until the loop opens its end) */
	hold = open(slave, O_RDWR | O_NOCTTY);
	if (hold < 0 || tcgetattr(hold, &tio)) {
		fprintf(stderr, "strand-simdrive: %s: %s\n", slave, strerror(errno));
		return 4;
	}
	cfmakeraw(&tio);
	tcsetattr(hold, TCSANOW, &tio);
	/* replace a link, never a device or a file */
	if (!lstat(link, &st) && !S_ISLNK(st.st_mode)) {
		fprintf(stderr, "strand-simdrive: %s exists and is not a link\n", link);
		return 4;
	}
	unlink(link);
	if (symlink(slave, link)) {
		fprintf(stderr, "strand-simdrive: link %s -> %s: %s\n", link, slave, strerror(errno));
		return 4;
	}
	s->ctx = modbus_new_rtu(link, (int)d->baud, d->parity, 8, (int)d->stop_bits);
	if (!s->ctx) {
		unlink(link);
		return 8;
	}
	modbus_set_slave(s->ctx, (int)d->unit);
	modbus_set_socket(s->ctx, master);
	if (!s->sd->quiet) {
		printf("strand-simdrive: '%s': modbus rtu %s (%s) %u baud unit %u, serving\n",
		       s->sd->dd->name, link, slave, d->baud, d->unit);
		fflush(stdout);
	}
	while (!stop_sig) {
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

static int serve(struct simdrive *sd)
{
	const struct modbus_desc *d = sd->dd->modbus;
	struct mbs s = { .sd = sd, .d = d, .hb_tick = -1 };
	struct sigaction sa;
	uint32_t top = 0, i, nw, nr;
	int rc = 8;

	memset(&sa, 0, sizeof(sa));
	sa.sa_handler = on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	signal(SIGPIPE, SIG_IGN);
	s.w = calloc(sd->nch + 1, sizeof(*s.w));
	s.r = calloc(sd->nch + 1, sizeof(*s.r));
	s.rfield = calloc(sd->nch, sizeof(*s.rfield));
	s.vals = calloc(sd->nch, sizeof(*s.vals));
	if (!s.w || !s.r || !s.rfield || !s.vals)
		goto out;
	modbus_desc_regs(d, sd->nch, s.w, &nw, s.r, &nr, s.rfield, &s.rstatus);
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
	if (!s.map)
		goto out;
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
	return rc;
}

const struct simdrive_proto simdrive_modbus = {
	.name = "modbus",
	.serve = serve,
};
