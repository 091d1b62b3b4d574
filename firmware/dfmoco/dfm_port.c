/* SPDX-License-Identifier: MIT */
/* dfm_port.c - DFMoco's serial line, pseudo-terminal or TCP client (see dfm_port.h). */
#define _GNU_SOURCE
#include "dfm_port.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

static void port_clear(struct dfm_port *p, enum dfm_port_kind kind)
{
	memset(p, 0, sizeof(*p));
	p->kind = kind;
	p->fd = p->listen_fd = p->slave_fd = -1;
}

static int fail(char *err, size_t errsize, int rc, const char *fmt, const char *what)
{
	snprintf(err, errsize, fmt, what, strerror(-rc));
	return rc;
}

/* Raw bytes, 8N1, no flow control, as Dragonframe's serial settings say. */
static int make_raw(int fd, speed_t speed)
{
	struct termios t;

	if (tcgetattr(fd, &t))
		return -errno;
	cfmakeraw(&t);
	t.c_cflag |= CLOCAL | CREAD;
	t.c_cflag &= ~(CSTOPB | CRTSCTS);
	t.c_cc[VMIN] = 0;
	t.c_cc[VTIME] = 0;
	if (speed && (cfsetispeed(&t, speed) || cfsetospeed(&t, speed)))
		return -EINVAL;
	return tcsetattr(fd, TCSANOW, &t) ? -errno : 0;
}

static speed_t speed_of(unsigned baud)
{
	static const struct {
		unsigned baud;
		speed_t s;
	} table[] = {
		{ 9600, B9600 },     { 19200, B19200 },	  { 38400, B38400 },   { 57600, B57600 },
		{ 115200, B115200 }, { 230400, B230400 }, { 460800, B460800 }, { 921600, B921600 },
	};
	size_t i;

	for (i = 0; i < sizeof(table) / sizeof(table[0]); i++)
		if (table[i].baud == baud)
			return table[i].s;
	return 0;
}

int dfm_port_serial(struct dfm_port *p, const char *dev, unsigned baud, char *err,
		    size_t errsize)
{
	speed_t s = speed_of(baud);
	int rc;

	port_clear(p, DFM_PORT_SERIAL);
	snprintf(p->name, sizeof(p->name), "%s", dev);
	if (!s) {
		snprintf(err, errsize, "%s: %u baud: 9600, 19200, 38400, 57600, 115200, 230400, "
			 "460800 or 921600", dev, baud);
		return -EINVAL;
	}
	p->fd = open(dev, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
	if (p->fd < 0)
		return fail(err, errsize, -errno, "%s: %s", dev);
	rc = make_raw(p->fd, s);
	if (rc) {
		dfm_port_close(p);
		return fail(err, errsize, rc, "%s: not a serial line (%s)", dev);
	}
	tcflush(p->fd, TCIOFLUSH);
	return 0;
}

int dfm_port_pty(struct dfm_port *p, const char *link, char *err, size_t errsize)
{
	const char *slave;
	int rc;

	port_clear(p, DFM_PORT_PTY);
	snprintf(p->name, sizeof(p->name), "%s", link);
	p->fd = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
	if (p->fd < 0)
		return fail(err, errsize, -errno, "%s: a pseudo-terminal: %s", link);
	if (grantpt(p->fd) || unlockpt(p->fd) || !(slave = ptsname(p->fd))) {
		rc = -errno;
		goto out;
	}
	p->slave_fd = open(slave, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
	if (p->slave_fd < 0) {
		rc = -errno;
		goto out;
	}
	/* raw on the client's side: no echo, no line editing, no CR/LF
	 * translation, as a serial line to a microcontroller */
	rc = make_raw(p->slave_fd, 0);
	if (rc)
		goto out;
	unlink(link);
	if (symlink(slave, link)) {
		rc = -errno;
		goto out;
	}
	snprintf(p->link, sizeof(p->link), "%s", link);
	return 0;
out:
	dfm_port_close(p);
	return fail(err, errsize, rc, "%s: a pseudo-terminal: %s", link);
}

int dfm_port_listen(struct dfm_port *p, const char *addr, unsigned port, const char *peer,
		    char *err, size_t errsize)
{
	struct addrinfo hints, *ai = NULL, *pa = NULL;
	char service[16];
	int rc, one = 1;

	port_clear(p, DFM_PORT_TCP);
	snprintf(p->name, sizeof(p->name), "%s:%u", addr, port);
	memset(&hints, 0, sizeof(hints));
	hints.ai_socktype = SOCK_STREAM;
	hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
	snprintf(service, sizeof(service), "%u", port);
	rc = getaddrinfo(addr, service, &hints, &ai);
	if (rc) {
		snprintf(err, errsize, "%s: %s", p->name, gai_strerror(rc));
		return -EINVAL;
	}
	if (peer) {
		hints.ai_flags = AI_NUMERICHOST;
		if (getaddrinfo(peer, NULL, &hints, &pa)) {
			freeaddrinfo(ai);
			snprintf(err, errsize, "--peer %s: a numeric IPv4 or IPv6 address", peer);
			return -EINVAL;
		}
		memcpy(&p->peer, pa->ai_addr, pa->ai_addrlen);
		freeaddrinfo(pa);
	} else {
		p->any_peer = true;
	}
	p->listen_fd = socket(ai->ai_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
	if (p->listen_fd < 0 ||
	    setsockopt(p->listen_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one)) ||
	    bind(p->listen_fd, ai->ai_addr, ai->ai_addrlen) || listen(p->listen_fd, 2)) {
		rc = -errno;
		freeaddrinfo(ai);
		dfm_port_close(p);
		return fail(err, errsize, rc, "%s: %s", p->name);
	}
	freeaddrinfo(ai);
	return 0;
}

void dfm_port_close(struct dfm_port *p)
{
	if (p->fd >= 0)
		close(p->fd);
	if (p->slave_fd >= 0)
		close(p->slave_fd);
	if (p->listen_fd >= 0)
		close(p->listen_fd);
	if (p->link[0])
		unlink(p->link);
	p->fd = p->slave_fd = p->listen_fd = -1;
	p->link[0] = 0;
}

bool dfm_port_up(const struct dfm_port *p)
{
	return p->fd >= 0;
}

/* The address a client came from against the one allowed. */
static bool allowed(const struct dfm_port *p, const struct sockaddr_storage *a)
{
	if (p->any_peer)
		return true;
	if (a->ss_family != p->peer.ss_family)
		return false;
	if (a->ss_family == AF_INET)
		return ((const struct sockaddr_in *)a)->sin_addr.s_addr ==
		       ((const struct sockaddr_in *)&p->peer)->sin_addr.s_addr;
	if (a->ss_family == AF_INET6)
		return !memcmp(&((const struct sockaddr_in6 *)a)->sin6_addr,
			       &((const struct sockaddr_in6 *)&p->peer)->sin6_addr,
			       sizeof(struct in6_addr));
	return false;
}

/* A client knocking: taken when none is connected and it may, else shut. */
static bool take_client(struct dfm_port *p)
{
	struct sockaddr_storage a;
	socklen_t len = sizeof(a);
	int fd = accept4(p->listen_fd, (struct sockaddr *)&a, &len, SOCK_NONBLOCK | SOCK_CLOEXEC);

	if (fd < 0)
		return false;
	if (p->fd >= 0 || !allowed(p, &a)) {
		close(fd);
		return false;
	}
	p->fd = fd;
	return true;
}

int dfm_port_wait(struct dfm_port *p, int timeout_ms, bool out, bool *joined)
{
	struct pollfd fds[2];
	int n = 0, rc, line = -1;

	*joined = false;
	if (p->listen_fd >= 0) {
		fds[n].fd = p->listen_fd;
		fds[n++].events = POLLIN;
	}
	if (p->fd >= 0) {
		line = n;
		fds[n].fd = p->fd;
		fds[n++].events = POLLIN | (out ? POLLOUT : 0);
	}
	rc = poll(fds, (nfds_t)n, timeout_ms);
	if (rc < 0)
		return errno == EINTR ? 0 : -errno;
	if (p->listen_fd >= 0 && (fds[0].revents & POLLIN))
		*joined = take_client(p);
	return line >= 0 && (fds[line].revents & (POLLIN | POLLHUP | POLLERR)) ? 1 : 0;
}

static ssize_t client_gone(struct dfm_port *p)
{
	if (p->kind != DFM_PORT_TCP)
		return 0;
	close(p->fd);
	p->fd = -1;
	return -ENOTCONN;
}

ssize_t dfm_port_read(struct dfm_port *p, char *buf, size_t n)
{
	ssize_t got;

	if (p->fd < 0)
		return 0; /* a TCP port between clients */
	got = read(p->fd, buf, n);
	if (got > 0)
		return got;
	if (got == 0)
		return client_gone(p);
	if (errno == EAGAIN || errno == EINTR)
		return 0;
	/* a pty whose client closed (EIO) reads again when one opens it */
	if (p->kind == DFM_PORT_PTY && errno == EIO)
		return 0;
	return p->kind == DFM_PORT_TCP ? client_gone(p) : -errno;
}

ssize_t dfm_port_write(struct dfm_port *p, const char *buf, size_t n)
{
	ssize_t put;

	if (p->fd < 0)
		return -ENOTCONN;
	put = send(p->fd, buf, n, MSG_NOSIGNAL | MSG_DONTWAIT);
	if (put < 0 && errno == ENOTSOCK)
		put = write(p->fd, buf, n);
	if (put >= 0)
		return put;
	if (errno == EAGAIN || errno == EINTR)
		return 0;
	return p->kind == DFM_PORT_TCP ? client_gone(p) : -errno;
}
