/* SPDX-License-Identifier: MIT */
/*
 * mbpeer.h - what the Modbus tests and the Modbus benchmark share: a scene
 * with a Modbus drive written for a free port or a pseudo-terminal, and
 * strand-simdrive run as the drive's server in a process of its own.
 */
#ifndef MBPEER_H
#define MBPEER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

/* A loopback TCP port nobody listens on right now. */
int mbp_free_port(void);

/*
 * A scene: nodes a and b over frames 0..72 at 24 fps and tick_hz, driven by
 * Modbus device 'drives' over `conn` (a tcp: or rtu: mapping's text) with
 * `modbus_extra` lines added to its modbus: section (each "key: value\n",
 * indented by the function) and `out_extra` added to both outputs'
 * mappings (", ferror: 1"). The register map:
 *
 *   a.angle  axis 0  target int32 high_first at 0, actual at 100, 1000 counts/deg
 *   b.angle  axis 1  target int32 low_first at 2, actual at 102, -500 counts/deg + 5000
 *   heartbeat        uint32 high_first at 4 (the loop's tick)
 *   enable coil 0, status register 50 (fault mask 8)
 *
 * and a simulated io device with the camera trigger.
 */
void mbp_scene(const char *path, uint32_t tick_hz, const char *conn, const char *modbus_extra,
	       const char *out_extra);

#define MBP_A_CPU 1000.0
#define MBP_B_CPU -500.0
#define MBP_B_OFFSET 5000.0

struct mbp_peer {
	pid_t pid;
	int out;          /* its stdout */
	char line[256];   /* the line it printed when serving */
};

/* Start build/strand-simdrive (or $STRAND_SIMDRIVE) on the scene with the
 * options in args (split at spaces) and wait until it serves: 0, or -1 when
 * it did not within 5 s. */
int mbp_start(struct mbp_peer *p, const char *scene, const char *args);
/* SIGTERM, then its exit status (128 + signal when killed). */
int mbp_stop(struct mbp_peer *p);
/* Its exit status once it exited by itself within ms, else -1. */
int mbp_wait(struct mbp_peer *p, int ms);

/* The server's log: one row per setpoint write. */
struct mbp_write {
	int64_t n, tick;
	int64_t v[2];
};
/* Read the W lines of a log (free *w); the number of E lines with value
 * 1 and 0 into *on, *off when given. -1 when it cannot be read. */
int64_t mbp_log_read(const char *path, struct mbp_write **w, int *on, int *off);

#endif /* MBPEER_H */
