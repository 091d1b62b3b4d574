/* SPDX-License-Identifier: MIT */
/*
 * test_dmx.c - DMX over UDP (hal/dmx/): E1.31 and ArtDmx packets byte by
 * byte against the standards' layouts; the backend on loopback against a
 * socket of the test's: the first frame at start, a frame every `every`
 * ticks with 16-bit values coarse then fine and the tick in its slots, a
 * value out of range refused (never sent), the three terminated packets at
 * stop. The real peers (olad, tshark) are tests/dmx/dmx-ola.sh's.
 */
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <poll.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "hal/dmx/dmx.h"
#include "testutil.h"

static uint16_t be16(const uint8_t *p)
{
	return (uint16_t)(p[0] << 8 | p[1]);
}

static void test_e131_packet(void **state)
{
	uint8_t buf[DMX_E131_MAX], slots[DMX_SLOTS], cid[16];
	size_t len;
	int i;

	for (i = 0; i < DMX_SLOTS; i++)
		slots[i] = (uint8_t)i;
	dmx_cid(cid, "movers");
	len = dmx_e131_packet(buf, cid, "movers", 100, 7, 0, 1, slots, DMX_SLOTS);
	assert_int_equal(len, 638);
	assert_int_equal(be16(buf), 0x0010);
	assert_memory_equal(buf + 4, "ASC-E1.17\0\0\0", 12);
	assert_int_equal(be16(buf + 16), 0x7000 | 622);      /* root: 638 - 16 */
	assert_int_equal(buf[21], 4);                         /* VECTOR_ROOT_E131_DATA */
	assert_memory_equal(buf + 22, cid, 16);
	assert_int_equal(be16(buf + 38), 0x7000 | 600);      /* framing */
	assert_int_equal(buf[43], 2);                         /* VECTOR_E131_DATA_PACKET */
	assert_string_equal((const char *)buf + 44, "movers");
	assert_int_equal(buf[108], 100);
	assert_int_equal(buf[111], 7);
	assert_int_equal(buf[112], 0);
	assert_int_equal(be16(buf + 113), 1);
	assert_int_equal(be16(buf + 115), 0x7000 | 523);     /* DMP */
	assert_int_equal(buf[117], 2);
	assert_int_equal(buf[118], 0xa1);
	assert_int_equal(be16(buf + 119), 0);
	assert_int_equal(be16(buf + 121), 1);
	assert_int_equal(be16(buf + 123), 513);
	assert_int_equal(buf[125], 0);                        /* START code */
	assert_memory_equal(buf + 126, slots, DMX_SLOTS);
	/* a stable RFC 4122 version 4 CID per name, another for another */
	assert_int_equal(cid[6] >> 4, 4);
	assert_int_equal(cid[8] >> 6, 2);
	{
		uint8_t again[16], other[16];

		dmx_cid(again, "movers");
		dmx_cid(other, "pars");
		assert_memory_equal(again, cid, 16);
		assert_memory_not_equal(other, cid, 16);
	}
	/* terminated */
	dmx_e131_packet(buf, cid, "movers", 200, 8, DMX_E131_TERMINATED, 63999, slots, 24);
	assert_int_equal(buf[112], 0x40);
	assert_int_equal(be16(buf + 113), 63999);
	assert_int_equal(be16(buf + 123), 25);
}

static void test_artnet_packet(void **state)
{
	uint8_t buf[DMX_ARTNET_MAX], slots[DMX_SLOTS] = { 1, 2, 3 };
	size_t len = dmx_artnet_packet(buf, 9, 0x1234, slots, 3);

	assert_memory_equal(buf, "Art-Net\0", 8);
	assert_int_equal(buf[8], 0x00); /* OpDmx 0x5000, low byte first */
	assert_int_equal(buf[9], 0x50);
	assert_int_equal(buf[10], 0);
	assert_int_equal(buf[11], 14);
	assert_int_equal(buf[12], 9);
	assert_int_equal(buf[14], 0x34); /* SubUni */
	assert_int_equal(buf[15], 0x12); /* Net */
	assert_int_equal(be16(buf + 16), 4); /* even */
	assert_int_equal(len, 18 + 4);
	assert_int_equal(buf[18], 1);
	assert_int_equal(buf[21], 0);
}

/* A receiver on 127.0.0.1 at an ephemeral port. */
static int rx_socket(uint16_t *port)
{
	struct sockaddr_in a;
	socklen_t n = sizeof(a);
	int fd = socket(AF_INET, SOCK_DGRAM, 0);

	memset(&a, 0, sizeof(a));
	a.sin_family = AF_INET;
	a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
	assert_int_equal(bind(fd, (struct sockaddr *)&a, sizeof(a)), 0);
	assert_int_equal(getsockname(fd, (struct sockaddr *)&a, &n), 0);
	*port = ntohs(a.sin_port);
	return fd;
}

static ssize_t rx(int fd, uint8_t *buf, int timeout_ms)
{
	struct pollfd p = { fd, POLLIN, 0 };

	if (poll(&p, 1, timeout_ms) != 1)
		return -1;
	return recv(fd, buf, DMX_E131_MAX, 0);
}

static void test_backend(void **state)
{
	static const uint16_t univ[2] = { 3, 4 };
	struct dmx_desc d = { .protocol = DMX_E131, .destination = "127.0.0.1",
			      .refresh_hz = 100, .nuniverses = 2, .universes = univ,
			      .priority = 150, .source_name = "test", .has_tick_slot = true,
			      .tick_slot = 512 + 508 };
	struct dmx_chan chan[600];
	int64_t initial[600];
	struct dmx_cfg c = { .name = "lights", .d = &d, .tick_hz = 1000, .nch = 600,
			     .chan = chan, .initial = initial, .lockstep = true };
	struct hal_setpoint sp = { 0, 0 };
	struct hal_fault f;
	struct hal_axis *ax;
	uint8_t buf[DMX_E131_MAX];
	char err[256];
	int64_t k;
	int fd, n;

	memset(chan, 0, sizeof(chan));
	memset(initial, 0, sizeof(initial));
	chan[0] = (struct dmx_chan){ true, 16 };
	chan[5] = (struct dmx_chan){ true, 8 };
	chan[512 + 10] = (struct dmx_chan){ true, 8 };
	initial[0] = 0x1234;
	initial[5] = 200;
	fd = rx_socket(&d.port);
	assert_int_equal(dmx_every(&d, 1000), 10);
	assert_int_equal(hal_dmx_open(&ax, &c, err, sizeof(err)), 0);
	assert_int_equal(hal_axis_start(ax), 0);
	/* the start's frame: two universes, the initial values */
	assert_int_equal(rx(fd, buf, 2000), 638);
	assert_int_equal(be16(buf + 113), 3);
	assert_int_equal(buf[108], 150);
	assert_int_equal(buf[126], 0x12);
	assert_int_equal(buf[127], 0x34);
	assert_int_equal(buf[126 + 5], 200);
	assert_int_equal(rx(fd, buf, 2000), 638);
	assert_int_equal(be16(buf + 113), 4);
	for (k = 0; k <= 30; k++) {
		assert_int_equal(hal_axis_input(ax, k), 0);
		sp.pos = 1000 * k;
		hal_axis_set(ax, 0, &sp);
		sp.pos = k;
		hal_axis_set(ax, 5, &sp);
		hal_axis_set(ax, 512 + 10, &sp);
		assert_int_equal(hal_axis_commit(ax, k), 0);
	}
	assert_int_equal(hal_axis_input(ax, 31), 0); /* lockstep: the last frame is out */
	/* ticks 0, 10, 20, 30: each universe's packet in order, sequence forward */
	for (k = 0; k <= 30; k += 10) {
		assert_int_equal(rx(fd, buf, 2000), 638);
		assert_int_equal(be16(buf + 113), 3);
		assert_int_equal(buf[111], (uint8_t)(k / 10 + 1));
		assert_int_equal(be16(buf + 126), 1000 * k); /* coarse, fine */
		assert_int_equal(buf[126 + 5], k);
		assert_int_equal(rx(fd, buf, 2000), 638);
		assert_int_equal(be16(buf + 113), 4);
		assert_int_equal(buf[126 + 10], k);
		/* the tick, big-endian, in slots 509-512 of the second universe */
		assert_int_equal((buf[126 + 508] << 24) | (buf[126 + 509] << 16) |
				 (buf[126 + 510] << 8) | buf[126 + 511], k);
	}
	/* out of range: never sent, the device faults naming the slot */
	sp.pos = 256;
	hal_axis_set(ax, 5, &sp);
	assert_int_equal(hal_axis_commit(ax, 40), -ERANGE);
	assert_int_equal(hal_axis_fault(ax, &f), -ERANGE);
	assert_non_null(strstr(f.cause, "slot 6 of universe 3"));
	assert_int_equal(rx(fd, buf, 100), -1);
	/* the stop: three terminated packets a universe */
	assert_int_equal(hal_axis_stop(ax), 0);
	for (n = 0; n < 6; n++) {
		assert_int_equal(rx(fd, buf, 2000), 638);
		assert_int_equal(buf[112], DMX_E131_TERMINATED);
	}
	assert_int_equal(rx(fd, buf, 100), -1);
	hal_axis_close(ax);
	close(fd);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_e131_packet),
		cmocka_unit_test(test_artnet_packet),
		cmocka_unit_test(test_backend),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
