/* SPDX-License-Identifier: MIT */
/*
 * modbus_bench.c - `make bench-modbus`: how fast strand drives a Modbus
 * drive, against the limit of the bus as libmodbus alone reaches it. The
 * drive is strand-simdrive in a process of its own (tests/mbpeer.h).
 *
 *   BENCH modbus_tcp_bare_updates_per_s N    a bare libmodbus client writing the
 *                                            same 6 registers (function 16) in a loop
 *   BENCH modbus_tcp_strand_ticks_per_s N    strand play on the virtual clock, one
 *                                            update a tick, each waited for (lockstep):
 *                                            the loop, the slot, the I/O thread, libmodbus
 *   BENCH modbus_tcp_strand_over_bare R      their ratio
 *   BENCH modbus_tcp_update_rtt_us P50 P99   the bare loop's round trips
 *   BENCH modbus_rtu_update_ms_model M       strand check's figure for one update at
 *                                            115200 baud 8N1 (frames, t3.5, no answer time)
 *   BENCH modbus_rtu_update_ms_pty M         one update over a pty with the server
 *                                            holding each answer for the line's time
 *   BENCH modbus_rtu_pty_overhead_us U       the same without the line's time: what
 *                                            libmodbus, the pty and two processes add
 *
 * Each figure is the median of ROUNDS rounds.
 */
#include <errno.h>
#include <modbus.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "hal/modbus/modbus_dev.h"
#include "tests/mbpeer.h"

#define ROUNDS 5
#define BARE_UPDATES 20000

static const char *strand_bin = "build/strand";

static int64_t mono_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

static int cmp_d(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
	qsort(v, (size_t)n, sizeof(*v), cmp_d);
	return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

/* The bare client: updates per second, and its round trips' p50 and p99. */
static double bare(int port, double *p50, double *p99)
{
	static double rtt[BARE_UPDATES];
	char ps[16];
	uint16_t regs[6] = { 0 };
	modbus_t *mb;
	int64_t t0, t;
	int i;

	snprintf(ps, sizeof(ps), "%d", port);
	mb = modbus_new_tcp_pi("127.0.0.1", ps);
	if (!mb || modbus_connect(mb)) {
		fprintf(stderr, "modbus_bench: connect: %s\n", modbus_strerror(errno));
		exit(1);
	}
	modbus_set_slave(mb, 1);
	t0 = mono_ns();
	for (i = 0; i < BARE_UPDATES; i++) {
		t = mono_ns();
		regs[1] = (uint16_t)i; /* a moving target, a tick in the heartbeat */
		regs[5] = (uint16_t)i;
		if (modbus_write_registers(mb, 0, 6, regs) != 6) {
			fprintf(stderr, "modbus_bench: write: %s\n", modbus_strerror(errno));
			exit(1);
		}
		rtt[i] = (mono_ns() - t) / 1e3;
	}
	t = mono_ns() - t0;
	modbus_close(mb);
	modbus_free(mb);
	*p50 = median(rtt, BARE_UPDATES);
	*p99 = rtt[BARE_UPDATES * 99 / 100];
	return BARE_UPDATES / (t / 1e9);
}

/* strand play's summary: ticks run and the run's time; the round trip
 * per update (avg). */
static int play(const char *scene, const char *opts, double *ticks_per_s, double *rtt_us)
{
	char cmd[1024], line[512];
	long long ticks = 0;
	double s = 0, mn, avg = 0, mx;
	FILE *p;

	snprintf(cmd, sizeof(cmd), "%s play %s --clock virtual --no-journal %s 2>&1", strand_bin,
		 scene, opts);
	p = popen(cmd, "r");
	if (!p)
		return -1;
	while (fgets(line, sizeof(line), p)) {
		const char *at = strstr(line, "ticks ");

		if (at && strstr(line, "frames fired"))
			sscanf(at, "ticks %lld (%*f s of motion) in %lf s", &ticks, &s);
		at = strstr(line, "round trip us:");
		if (at)
			sscanf(at, "round trip us: min %lf avg %lf max %lf", &mn, &avg, &mx);
	}
	if (pclose(p) || !s)
		return -1;
	*ticks_per_s = ticks / s;
	*rtt_us = avg;
	return 0;
}

static void tcp(void)
{
	double b[ROUNDS], st[ROUNDS], p50[ROUNDS], p99[ROUNDS], rtt;
	char scene[] = "/tmp/strand-bench-modbus-tcp.yaml", conn[96];
	struct mbp_peer peer;
	int port = mbp_free_port(), i;

	snprintf(conn, sizeof(conn), "tcp: {host: 127.0.0.1, port: %d}", port);
	/* writes only, every tick: 6 registers in one request, as the bare loop */
	mbp_scene(scene, 1000, conn, "answer_ms: 0.1\n", NULL);
	if (mbp_start(&peer, scene, "")) {
		fprintf(stderr, "modbus_bench: strand-simdrive did not start\n");
		exit(1);
	}
	for (i = 0; i < ROUNDS; i++) {
		b[i] = bare(port, &p50[i], &p99[i]);
		if (play(scene, "--loop --passes 5", &st[i], &rtt)) {
			fprintf(stderr, "modbus_bench: strand play failed\n");
			exit(1);
		}
	}
	mbp_stop(&peer);
	unlink(scene);
	printf("BENCH modbus_tcp_bare_updates_per_s %.0f\n", median(b, ROUNDS));
	printf("BENCH modbus_tcp_strand_ticks_per_s %.0f\n", median(st, ROUNDS));
	printf("BENCH modbus_tcp_strand_over_bare %.2f\n", median(st, ROUNDS) / median(b, ROUNDS));
	printf("BENCH modbus_tcp_update_rtt_us %.1f %.1f\n", median(p50, ROUNDS),
	       median(p99, ROUNDS));
}

static void rtu(void)
{
	char scene[] = "/tmp/strand-bench-modbus-rtu.yaml", pty[] = "/tmp/strand-bench-modbus-pty";
	char conn[160];
	double wire[ROUNDS], bare_pty[ROUNDS], tps;
	struct modbus_desc d = { .transport = MODBUS_RTU, .baud = 115200, .parity = 'N',
				 .stop_bits = 1 };
	struct modbus_axis_desc ax[2] = {
		{ .target = { 0, MODBUS_TYPE_INT32, MODBUS_WORDS_HIGH_FIRST } },
		{ .target = { 2, MODBUS_TYPE_INT32, MODBUS_WORDS_LOW_FIRST } },
	};
	struct mbp_peer peer;
	int64_t model;
	int i, k;

	d.axes = ax;
	d.naxes = 2;
	d.has_heartbeat = true;
	d.heartbeat = (struct modbus_reg){ 4, MODBUS_TYPE_UINT32, MODBUS_WORDS_HIGH_FIRST };
	modbus_update_ns(&d, false, &model);
	snprintf(conn, sizeof(conn), "rtu: {port: %s, baud: 115200, parity: none, stop_bits: 1}",
		 pty);
	mbp_scene(scene, 1000, conn, "update_hz: 100\nanswer_ms: 0\n", NULL);
	for (k = 0; k < 2; k++) {
		if (mbp_start(&peer, scene, k ? "" : "--wire-time")) {
			fprintf(stderr, "modbus_bench: strand-simdrive (rtu) did not start\n");
			exit(1);
		}
		for (i = 0; i < ROUNDS; i++) {
			double rtt;

			if (play(scene, "", &tps, &rtt)) {
				fprintf(stderr, "modbus_bench: strand play (rtu) failed\n");
				exit(1);
			}
			(k ? bare_pty : wire)[i] = rtt;
		}
		mbp_stop(&peer);
	}
	unlink(scene);
	printf("BENCH modbus_rtu_update_ms_model %.3f\n", model / 1e6);
	printf("BENCH modbus_rtu_update_ms_pty %.3f\n", median(wire, ROUNDS) / 1e3);
	printf("BENCH modbus_rtu_pty_overhead_us %.0f\n", median(bare_pty, ROUNDS));
}

int main(int argc, char **argv)
{
	if (argc > 1)
		strand_bin = argv[1];
	tcp();
	rtu();
	return 0;
}
