/* SPDX-License-Identifier: MIT */
/*
 * dfm_port.h - where DFMoco's lines come and go: a serial line (a USB
 * serial adapter, or on a board with a USB device port the CDC-ACM gadget
 * /dev/ttyGS0, which the Dragonframe computer sees as a serial port), a
 * pseudo-terminal linked at a path (tests, a bridge), or one TCP client.
 * Every descriptor is non-blocking; nothing here knows the protocol.
 *
 * A TCP port takes one client at a time (Dragonframe); another is turned
 * away while it is connected. DFMoco has no authentication, so a port
 * listening beyond loopback takes only the peer address it was given.
 */
#ifndef STRAND_DFM_PORT_H
#define STRAND_DFM_PORT_H

#include <limits.h>
#include <netinet/in.h>
#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

enum dfm_port_kind { DFM_PORT_SERIAL, DFM_PORT_PTY, DFM_PORT_TCP };

struct dfm_port {
	enum dfm_port_kind kind;
	int fd;          /* the line (-1: no TCP client) */
	int listen_fd;   /* TCP, else -1 */
	int slave_fd;    /* pty: held open, so that the line stays up between clients */
	char link[PATH_MAX]; /* pty: the link made, removed at close */
	bool any_peer;   /* TCP: any client address (a loopback listener) */
	struct sockaddr_storage peer; /* ... else only this one */
	char name[PATH_MAX + 32]; /* for messages */
};

/* [init] Each 0, or a negative errno with a message in err naming the
 * device or address. */
int dfm_port_serial(struct dfm_port *p, const char *dev, unsigned baud, char *err,
		    size_t errsize);
int dfm_port_pty(struct dfm_port *p, const char *link, char *err, size_t errsize);
/* addr:port; peer: the only client address taken, NULL for any (only a
 * loopback listener may take any). */
int dfm_port_listen(struct dfm_port *p, const char *addr, unsigned port, const char *peer,
		    char *err, size_t errsize);
void dfm_port_close(struct dfm_port *p);

/* Wait up to timeout_ms for input (or room to write, when `out`), taking
 * a TCP client that knocks: 1 when the line may be read, 0 otherwise, or
 * a negative errno. *joined: a new client came (a new session of it). */
int dfm_port_wait(struct dfm_port *p, int timeout_ms, bool out, bool *joined);

/* Non-blocking: bytes read or written (0: none now, or no client), or a
 * negative errno; -ENOTCONN once when a TCP client left (the port waits
 * for the next). */
ssize_t dfm_port_read(struct dfm_port *p, char *buf, size_t n);
ssize_t dfm_port_write(struct dfm_port *p, const char *buf, size_t n);

/* Whether there is a line to talk on (a TCP port: a client). */
bool dfm_port_up(const struct dfm_port *p);

#endif /* STRAND_DFM_PORT_H */
