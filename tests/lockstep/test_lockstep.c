/* SPDX-License-Identifier: MIT */
/*
 * test_lockstep.c - the pieces of several boards in lockstep that need no
 * network (the whole, in namespaces with ptp4l: tests/boards/run.sh):
 *
 *   - the scene's digest: SHA-256 against FIPS 180-4's examples, and the
 *     loader's digest of a file's bytes (one byte more, another digest);
 *   - every message encoded and decoded back, field for field; every
 *     datagram cut short, one byte longer, of another version, from a
 *     board the scene has not, with a text that overruns or holds a NUL,
 *     refused;
 *   - pmc's answers as linuxptp 3.1 prints them, parsed, and the rules of
 *     "locked" (a SLAVE within the bound, a MASTER, an UNCALIBRATED port
 *     only when ptp4l runs free, LISTENING never);
 *   - a board's part of the rig: its devices, and the outputs, triggers
 *     and inputs on them, nothing of the others'.
 *
 * `test_lockstep --write-corpus DIR` writes the messages and pmc answers
 * as the seeds of the fuzzer (tests/fuzz/fuzz_board.c).
 */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "load/load.h"
#include "lockstep/ls_msg.h"
#include "lockstep/ls_ptp.h"
#include "rig/rig_desc.h"
#include "scene/sha256.h"
#include "testutil.h"

static void test_sha256(void **state)
{
	static const struct {
		const char *in, *hex;
	} v[] = {
		{ "", "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855" },
		{ "abc", "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad" },
		{ "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq",
		  "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1" },
	};
	static char million[1000000];
	uint8_t d[SHA256_BYTES];
	char hex[2 * SHA256_BYTES + 1];
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(v) / sizeof(v[0]); i++) {
		sha256(d, v[i].in, strlen(v[i].in));
		sha256_hex(hex, d, SHA256_BYTES);
		assert_string_equal(hex, v[i].hex);
	}
	memset(million, 'a', sizeof(million));
	sha256(d, million, sizeof(million));
	sha256_hex(hex, d, SHA256_BYTES);
	assert_string_equal(hex, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

/* ---- messages ---- */

static const char *const SCENE =
	"timing: {frame_rate: 25, frames: [0, 10]}\n"
	"nodes: [{name: a, joint: {type: revolute, axis: z}, limits: {velocity: 90, "
	"acceleration: 360}},\n"
	"        {name: b, joint: {type: revolute, axis: z}, limits: {velocity: 90, "
	"acceleration: 360}}]\n"
	"devices: [{name: da, driver: sim}, {name: db, driver: sim}, {name: io, driver: sim}]\n"
	"outputs: [{channel: a.angle, device: da, counts_per_unit: 100},\n"
	"          {channel: b.angle, device: db, counts_per_unit: 100}]\n"
	"triggers: [{name: cam, device: io, line: 0, pulse_ms: 2}]\n"
	"inputs: [{name: stop, device: io, line: 1, role: estop}]\n"
	"boards:\n"
	"  - {name: left, address: 10.0.0.1, lead: true, devices: [da, io]}\n"
	"  - {name: right, address: 10.0.0.2, port: 5000, devices: [db]}\n"
	"lockstep: {heartbeat_ms: 50, lost_ms: 200}\n";

/* One message of each type, filled. */
static size_t examples(struct ls_msg *m)
{
	size_t n = 0;

	memset(m, 0, 7 * sizeof(*m));
	m[n].type = LS_HELLO;
	memset(m[n].u.hello.digest, 0xa5, LS_DIGEST);
	m[n].u.hello.need_ticks = 1234;
	m[n].u.hello.ptp_ok = 0;
	strcpy(m[n++].u.hello.why, "PTP is not locked: ptp4l's port is LISTENING");
	m[n++].type = LS_PING;
	m[n].type = LS_PONG;
	m[n].u.pong.t1 = 1700000000123456789;
	m[n++].u.pong.t2 = -5;
	m[n].type = LS_START;
	m[n++].u.start.play_ns = 1700000003000000000;
	m[n].type = LS_ACK;
	m[n++].u.start.play_ns = 1700000003000000000;
	m[n].type = LS_BEAT;
	m[n].u.beat.tick = 99;
	m[n++].u.beat.state = 3;
	m[n].type = LS_STOP;
	m[n].u.stop.kind = LS_STOP_ESTOP;
	m[n].u.stop.level = 2;
	m[n].u.stop.origin = 1;
	strcpy(m[n++].u.stop.text, "e-stop: input 'estop' (line 1) at tick 5");
	for (size_t i = 0; i < n; i++) {
		m[i].from = 1;
		m[i].seq = (uint32_t)(40 + i);
		m[i].sent_ns = 1700000000000000000 + (int64_t)i;
	}
	return n;
}

static void test_msg_round_trip(void **state)
{
	struct ls_msg m[7], back;
	uint8_t buf[LS_MSG_MAX];
	size_t n = examples(m), i, len;

	(void)state;
	for (i = 0; i < n; i++) {
		len = ls_msg_encode(&m[i], buf, sizeof(buf));
		assert_true(len >= 20 && len <= LS_MSG_MAX);
		assert_int_equal(ls_msg_decode(&back, buf, len, 2), 0);
		/* every field as it was sent (the union compared by its bytes:
		 * both sides were zeroed) */
		assert_int_equal(back.type, m[i].type);
		assert_int_equal(back.from, m[i].from);
		assert_int_equal(back.seq, m[i].seq);
		assert_int_equal(back.sent_ns, m[i].sent_ns);
		assert_memory_equal(&back.u, &m[i].u, sizeof(back.u));
		/* cut short anywhere, or one byte more: refused */
		for (size_t k = 0; k < len; k++)
			assert_int_equal(ls_msg_decode(&back, buf, k, 2), -EBADMSG);
		buf[len] = 0;
		assert_int_equal(ls_msg_decode(&back, buf, len + 1, 2), -EBADMSG);
		/* a board the scene has not */
		assert_int_equal(ls_msg_decode(&back, buf, len, 1), -EBADMSG);
		/* another version */
		buf[4] = LS_VERSION + 1;
		assert_int_equal(ls_msg_decode(&back, buf, len, 2), -EBADMSG);
		/* a buffer too small to encode into */
		assert_int_equal(ls_msg_encode(&m[i], buf, len - 1), 0);
	}
	/* a text with a NUL in it, or longer than the datagram */
	len = ls_msg_encode(&m[6], buf, sizeof(buf));
	buf[len - 3] = 0;
	assert_int_equal(ls_msg_decode(&back, buf, len, 2), -EBADMSG);
	len = ls_msg_encode(&m[6], buf, sizeof(buf));
	buf[24] = 200; /* the text's length byte */
	assert_int_equal(ls_msg_decode(&back, buf, len, 2), -EBADMSG);
	/* a stop of no kind, of level 3, from an origin the scene has not */
	for (i = 0; i < 3; i++) {
		len = ls_msg_encode(&m[6], buf, sizeof(buf));
		buf[20 + i + (i == 2)] = i == 0 ? LS_STOP_KINDS : i == 1 ? 3 : 9;
		assert_int_equal(ls_msg_decode(&back, buf, len, 2), -EBADMSG);
	}
	/* an unknown type */
	len = ls_msg_encode(&m[1], buf, sizeof(buf));
	buf[5] = 99;
	assert_int_equal(ls_msg_decode(&back, buf, len, 2), -EBADMSG);
}

/* ---- pmc ---- */

/* What linuxptp 3.1's pmc printed here, for a slave, a master, a port
 * listening and no ptp4l at all. */
static const char *const PMC_SLAVE =
	"sending: GET PORT_DATA_SET\n"
	"\tf6020f.fffe.62387b-1 seq 0 RESPONSE MANAGEMENT PORT_DATA_SET \n"
	"\t\tportIdentity            f6020f.fffe.62387b-1\n"
	"\t\tportState               SLAVE\n"
	"\t\tlogMinDelayReqInterval  -4\n"
	"sending: GET TIME_STATUS_NP\n"
	"\tf6020f.fffe.62387b-0 seq 1 RESPONSE MANAGEMENT TIME_STATUS_NP \n"
	"\t\tmaster_offset              -1510\n"
	"\t\tingress_time               1796187378072012062\n"
	"\t\tgmPresent                  true\n";
static const char *const PMC_MASTER =
	"sending: GET PORT_DATA_SET\n"
	"\tda3632.fffe.73c429-1 seq 0 RESPONSE MANAGEMENT PORT_DATA_SET \n"
	"\t\tportState               MASTER\n"
	"sending: GET TIME_STATUS_NP\n"
	"\t\tmaster_offset              0\n"
	"\t\tgmPresent                  false\n";
static const char *const PMC_LISTENING =
	"\t\tportState               LISTENING\n"
	"\t\tmaster_offset              0\n"
	"\t\tgmPresent                  false\n";
static const char *const PMC_NONE =
	"sending: GET PORT_DATA_SET\nsending: GET TIME_STATUS_NP\n";

static void test_ptp(void **state)
{
	struct ls_ptp st;
	char why[256], unc[128];

	(void)state;
	assert_int_equal(ls_ptp_parse(&st, PMC_SLAVE, strlen(PMC_SLAVE)), 0);
	assert_string_equal(st.state, "SLAVE");
	assert_true(st.has_offset && st.offset_ns == -1510 && st.gm_present);
	assert_true(ls_ptp_locked(&st, 100000, false, why, sizeof(why)));
	/* beyond the bound */
	assert_false(ls_ptp_locked(&st, 1000, false, why, sizeof(why)));
	assert_non_null(strstr(why, "offset from its master is -1510 ns"));

	assert_int_equal(ls_ptp_parse(&st, PMC_MASTER, strlen(PMC_MASTER)), 0);
	assert_string_equal(st.state, "MASTER");
	assert_true(ls_ptp_locked(&st, 1, false, why, sizeof(why)));

	assert_int_equal(ls_ptp_parse(&st, PMC_LISTENING, strlen(PMC_LISTENING)), 0);
	assert_false(ls_ptp_locked(&st, 100000, true, why, sizeof(why)));
	assert_string_equal(why, "PTP is not locked: ptp4l's port is LISTENING (no master heard)");

	/* UNCALIBRATED: locked only when ptp4l runs free */
	strcpy(unc, "\t\tportState UNCALIBRATED\n\t\tmaster_offset -20\n\t\tgmPresent true\n");
	assert_int_equal(ls_ptp_parse(&st, unc, strlen(unc)), 0);
	assert_false(ls_ptp_locked(&st, 100000, false, why, sizeof(why)));
	assert_non_null(strstr(why, "servo has not locked"));
	assert_true(ls_ptp_locked(&st, 100000, true, why, sizeof(why)));

	/* no answer at all, and a line that only begins like a key */
	assert_int_equal(ls_ptp_parse(&st, PMC_NONE, strlen(PMC_NONE)), -EBADMSG);
	assert_int_equal(ls_ptp_parse(&st, "portStateX SLAVE\n", 17), -EBADMSG);
	assert_int_equal(ls_ptp_parse(&st, "", 0), -EBADMSG);
}

/* ---- a board's part of the rig ---- */

static void test_board_part(void **state)
{
	struct scene_file sf;
	struct load_err e;
	struct rig_desc left, right;
	uint8_t other[SHA256_BYTES];

	(void)state;
	assert_int_equal(scene_file_parse(&sf, "t.yaml", SCENE, strlen(SCENE), &e), 0);
	assert_int_equal(sf.rig.nboards, 2);
	assert_true(sf.rig.boards[0].lead && !sf.rig.boards[1].lead);
	assert_int_equal(sf.rig.boards[1].port, 5000);
	assert_int_equal(sf.rig.boards[0].port, 0);
	assert_int_equal(sf.rig.lockstep.port, RIG_LOCKSTEP_PORT);
	assert_true(sf.rig.lockstep.heartbeat_ms == 50 && sf.rig.lockstep.lost_ms == 200);
	assert_true(sf.rig.lockstep.start_ms == 2000);
	/* the digest is the file's bytes' */
	sha256(other, SCENE, strlen(SCENE));
	assert_memory_equal(sf.digest, other, SHA256_BYTES);

	assert_int_equal(rig_desc_board(&sf.rig, 0, &left), 0);
	assert_int_equal(rig_desc_board(&sf.rig, 1, &right), 0);
	assert_int_equal(left.ndevices, 2);
	assert_string_equal(left.devices[0].name, "da");
	assert_string_equal(left.devices[1].name, "io");
	assert_int_equal(left.noutputs, 1);
	assert_string_equal(left.outputs[0].channel, "a.angle");
	assert_int_equal(left.ntriggers, 1);
	assert_int_equal(left.ninputs, 1);
	assert_int_equal(right.ndevices, 1);
	assert_int_equal(right.noutputs, 1);
	assert_string_equal(right.outputs[0].channel, "b.angle");
	assert_int_equal(right.ntriggers, 0);
	assert_int_equal(right.ninputs, 0);
	rig_desc_board_free(&left);
	rig_desc_board_free(&right);
	scene_file_free(&sf);

	/* one byte more: another digest */
	{
		char more[2048];

		snprintf(more, sizeof(more), "%s\n", SCENE);
		assert_int_equal(scene_file_parse(&sf, "t.yaml", more, strlen(more), &e), 0);
		assert_memory_not_equal(sf.digest, other, SHA256_BYTES);
		scene_file_free(&sf);
	}
}

static int write_corpus(const char *dir)
{
	struct ls_msg m[7];
	uint8_t buf[LS_MSG_MAX];
	const char *pmc[] = { PMC_SLAVE, PMC_MASTER, PMC_LISTENING, PMC_NONE };
	char path[512];
	size_t n = examples(m), i, len;
	FILE *f;

	mkdir(dir, 0755);
	/* the fuzzer's first byte says which parser: 0 messages, 1 pmc */
	for (i = 0; i < n + 4; i++) {
		snprintf(path, sizeof(path), "%s/seed-%zu", dir, i);
		f = fopen(path, "wb");
		if (!f)
			return 1;
		if (i < n) {
			len = ls_msg_encode(&m[i], buf, sizeof(buf));
			fputc(0, f);
			fwrite(buf, 1, len, f);
		} else {
			fputc(1, f);
			fputs(pmc[i - n], f);
		}
		fclose(f);
	}
	return 0;
}

int main(int argc, char **argv)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sha256),
		cmocka_unit_test(test_msg_round_trip),
		cmocka_unit_test(test_ptp),
		cmocka_unit_test(test_board_part),
	};

	if (argc == 3 && !strcmp(argv[1], "--write-corpus"))
		return write_corpus(argv[2]);
	return cmocka_run_group_tests(tests, NULL, NULL);
}
