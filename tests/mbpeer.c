/* SPDX-License-Identifier: MIT */
/* mbpeer.c - strand-simdrive as a peer for tests and benchmarks (see mbpeer.h). */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include "mbpeer.h"

#include <errno.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

int mbp_free_port(void)
{
	struct sockaddr_in a = { .sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK) };
	socklen_t len = sizeof(a);
	int fd = socket(AF_INET, SOCK_STREAM, 0), port = -1;

	if (fd >= 0 && !bind(fd, (struct sockaddr *)&a, sizeof(a)) &&
	    !getsockname(fd, (struct sockaddr *)&a, &len))
		port = ntohs(a.sin_port);
	if (fd >= 0)
		close(fd);
	return port;
}

void mbp_scene(const char *path, uint32_t tick_hz, const char *conn, const char *modbus_extra,
	       const char *out_extra)
{
	FILE *f = fopen(path, "w");
	char extra[1024] = "", *line, *save = NULL, buf[1024];

	if (!f)
		return;
	snprintf(buf, sizeof(buf), "%s", modbus_extra ? modbus_extra : "");
	for (line = strtok_r(buf, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
		strncat(extra, "      ", sizeof(extra) - strlen(extra) - 1);
		strncat(extra, line, sizeof(extra) - strlen(extra) - 1);
		strncat(extra, "\n", sizeof(extra) - strlen(extra) - 1);
	}
	fprintf(f,
		"scene: mb\n"
		"timing: {tick_hz: %u, frame_rate: 24, frames: [0, 72]}\n"
		"nodes:\n"
		"  - {name: a, pivot: [0, 0, 0], joint: {type: revolute, axis: y},\n"
		"     limits: {min: -170, max: 170, velocity: 90, acceleration: 360}}\n"
		"  - {name: b, parent: a, pivot: [0, 0.3, 0], joint: {type: revolute, axis: z},\n"
		"     limits: {min: -90, max: 90, velocity: 60, acceleration: 240}}\n"
		"strands:\n"
		"  - {node: a, interpolation: hermite, ease: {in: 12, out: 12},\n"
		"     keys: [{frame: 0, angle: 0}, {frame: 36, angle: 40}, {frame: 72, angle: 0}]}\n"
		"  - {node: b, interpolation: hermite, ease: {in: 12, out: 12},\n"
		"     keys: [{frame: 0, angle: 0}, {frame: 48, angle: -20}, {frame: 72, angle: 0}]}\n"
		"devices:\n"
		"  - name: drives\n"
		"    driver: modbus\n"
		"    modbus:\n"
		"      %s\n"
		"      unit: 1\n"
		"%s"
		"      enable: {coil: 0}\n"
		"      status: {register: 50, fault_mask: 8}\n"
		"      heartbeat: {register: 4, type: uint32}\n"
		"      axes:\n"
		"        - {register: 0, type: int32, actual: {register: 100}}\n"
		"        - {register: 2, type: int32, word_order: low_first, actual: {register: 102}}\n"
		"  - {name: io, driver: sim}\n"
		"outputs:\n"
		"  - {channel: a.angle, device: drives, axis: 0, counts_per_unit: %g%s}\n"
		"  - {channel: b.angle, device: drives, axis: 1, counts_per_unit: %g, offset: %g%s}\n"
		"triggers:\n"
		"  - {name: camera, device: io, line: 0, pulse_ms: 2}\n",
		tick_hz, conn, extra, MBP_A_CPU, out_extra ? out_extra : "", MBP_B_CPU, MBP_B_OFFSET,
		out_extra ? out_extra : "");
	fclose(f);
}

int mbp_start(struct mbp_peer *p, const char *scene, const char *args)
{
	const char *bin = getenv("STRAND_SIMDRIVE") ? getenv("STRAND_SIMDRIVE") :
						      "build/strand-simdrive";
	char buf[1024], *argv[32], *save = NULL, *tok;
	int fds[2], argc = 0;
	size_t got = 0;

	memset(p, 0, sizeof(*p));
	p->pid = -1;
	if (pipe(fds))
		return -1;
	snprintf(buf, sizeof(buf), "%s", args ? args : "");
	argv[argc++] = (char *)bin;
	argv[argc++] = (char *)scene;
	for (tok = strtok_r(buf, " ", &save); tok && argc < 31; tok = strtok_r(NULL, " ", &save))
		argv[argc++] = tok;
	argv[argc] = NULL;
	p->pid = fork();
	if (p->pid < 0)
		return -1;
	if (p->pid == 0) {
		dup2(fds[1], 1);
		close(fds[0]);
		close(fds[1]);
		execv(bin, argv);
		_exit(127);
	}
	close(fds[1]);
	p->out = fds[0];
	while (got < sizeof(p->line) - 1 && !strchr(p->line, '\n')) {
		struct pollfd pf = { .fd = p->out, .events = POLLIN };
		ssize_t n;

		if (poll(&pf, 1, 5000) <= 0)
			return -1;
		n = read(p->out, p->line + got, sizeof(p->line) - 1 - got);
		if (n <= 0)
			return -1;
		got += (size_t)n;
	}
	return strstr(p->line, "serving") ? 0 : -1;
}

static int status_of(int st)
{
	return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

int mbp_wait(struct mbp_peer *p, int ms)
{
	struct timespec nap = { 0, 1000000 };
	int st, i;

	for (i = 0; i < ms && p->pid > 0; i++) {
		if (waitpid(p->pid, &st, WNOHANG) == p->pid) {
			p->pid = -1;
			close(p->out);
			return status_of(st);
		}
		nanosleep(&nap, NULL);
	}
	return -1;
}

int mbp_stop(struct mbp_peer *p)
{
	int st;

	if (p->pid <= 0)
		return -1;
	kill(p->pid, SIGTERM);
	if (waitpid(p->pid, &st, 0) != p->pid)
		return -1;
	p->pid = -1;
	close(p->out);
	return status_of(st);
}

int64_t mbp_log_read(const char *path, struct mbp_write **w, int *on, int *off)
{
	FILE *f = fopen(path, "r");
	int64_t n = 0, cap = 1024;
	char line[256];

	*w = NULL;
	if (!f)
		return -1;
	*w = malloc((size_t)cap * sizeof(**w));
	if (on)
		*on = 0;
	if (off)
		*off = 0;
	while (*w && fgets(line, sizeof(line), f)) {
		struct mbp_write r;
		long long a, b, c, d;
		int e;

		if (sscanf(line, "E %d", &e) == 1) {
			if (e && on)
				(*on)++;
			if (!e && off)
				(*off)++;
			continue;
		}
		if (sscanf(line, "W %lld %lld %lld %lld", &a, &b, &c, &d) != 4)
			continue;
		r = (struct mbp_write){ a, b, { c, d } };
		if (n == cap)
			*w = realloc(*w, (size_t)(cap *= 2) * sizeof(**w));
		if (*w)
			(*w)[n++] = r;
	}
	fclose(f);
	return *w ? n : -1;
}
