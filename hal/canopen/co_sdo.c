/* SPDX-License-Identifier: MIT */
/*
 * co_sdo.c - the SDO client (see co_sdo.h).
 *
 * Byte 0 of every SDO frame is the command specifier (CiA 301 7.2.4.3): its
 * top three bits say what the frame is, the rest are flags:
 *
 *   client                              server
 *   001 0 nn e s  initiate download  -> 011 0 0000  initiate download response
 *   000 t nnn c   download segment   -> 001 t 0000  download segment response
 *   010 0 0000    initiate upload    -> 010 0 nn e s  initiate upload response
 *   011 t 0000    upload segment     -> 000 t nnn c   upload segment response
 *   100 0 0000    abort (either side), code in bytes 4..7
 *
 * e: expedited (data in bytes 4..7), s: size indicated, nn: bytes of 4 not
 * holding data (expedited), nnn: bytes of 7 not holding data (segment), c:
 * last segment, t: the toggle bit, 0 on the first segment and alternating.
 * Initiating frames carry the multiplexer: index (bytes 1..2), sub-index (3).
 */
#include "co_sdo.h"

#include <string.h>

#include "hal/rt.h"

enum {
	PH_DL_INIT,
	PH_DL_SEG,
	PH_UL_INIT,
	PH_UL_SEG,
};

#define CS_MASK 0xe0
#define CS_ABORT 0x80
/* client */
#define CCS_DL_INIT 0x20
#define CCS_UL_INIT 0x40
#define CCS_UL_SEG 0x60
/* server */
#define SCS_UL_SEG 0x00
#define SCS_DL_SEG 0x20
#define SCS_UL_INIT 0x40
#define SCS_DL_INIT 0x60

#define F_EXPEDITED 0x02
#define F_SIZE 0x01
#define F_LAST 0x01
#define TOGGLE 0x10

static void STRAND_RT request(struct co_sdo *s, struct co_frame *out, uint8_t cs, int64_t now)
{
	co_frame_init(out, (uint16_t)(CO_ID_SDO_RX + s->node), 8);
	out->data[0] = cs;
	s->deadline = now + s->timeout_ns;
}

static void STRAND_RT mux(struct co_frame *f, uint16_t index, uint8_t sub)
{
	co_put16(&f->data[1], index);
	f->data[3] = sub;
}

void STRAND_RT co_sdo_abort_frame(struct co_frame *out, uint16_t id, uint16_t index, uint8_t sub,
				  uint32_t code)
{
	co_frame_init(out, id, 8);
	out->data[0] = CS_ABORT;
	mux(out, index, sub);
	co_put32(&out->data[4], code);
}

/* End the transfer with an abort of ours; true: send it. */
static bool STRAND_RT abort_ours(struct co_sdo *s, uint32_t code, struct co_frame *out)
{
	s->state = CO_SDO_ABORTED;
	s->abort = code;
	s->abort_sent = true;
	co_sdo_abort_frame(out, (uint16_t)(CO_ID_SDO_RX + s->node), s->index, s->sub, code);
	return true;
}

void co_sdo_init(struct co_sdo *s, uint8_t node, int64_t timeout_ns)
{
	memset(s, 0, sizeof(*s));
	s->node = node;
	s->timeout_ns = timeout_ns;
}

static void STRAND_RT begin(struct co_sdo *s, uint16_t index, uint8_t sub)
{
	s->state = CO_SDO_BUSY;
	s->index = index;
	s->sub = sub;
	s->abort = 0;
	s->abort_sent = false;
	s->pos = 0;
	s->announced = 0;
	s->toggle = 0;
}

void STRAND_RT co_sdo_download(struct co_sdo *s, uint16_t index, uint8_t sub, const void *data,
			       uint32_t n, int64_t now, struct co_frame *out)
{
	begin(s, index, sub);
	s->src = data;
	s->dst = NULL;
	s->size = n;
	s->phase = PH_DL_INIT;
	if (n >= 1 && n <= 4) {
		request(s, out, (uint8_t)(CCS_DL_INIT | (4 - n) << 2 | F_EXPEDITED | F_SIZE), now);
		memcpy(&out->data[4], data, n);
		s->pos = n;
	} else {
		request(s, out, CCS_DL_INIT | F_SIZE, now);
		co_put32(&out->data[4], n);
	}
	mux(out, index, sub);
}

void STRAND_RT co_sdo_upload(struct co_sdo *s, uint16_t index, uint8_t sub, void *dst, uint32_t cap,
			     int64_t now, struct co_frame *out)
{
	begin(s, index, sub);
	s->dst = dst;
	s->src = NULL;
	s->size = cap;
	s->phase = PH_UL_INIT;
	request(s, out, CCS_UL_INIT, now);
	mux(out, index, sub);
}

/* The next download segment: up to 7 bytes, the last one flagged. */
static bool STRAND_RT next_segment(struct co_sdo *s, int64_t now, struct co_frame *out)
{
	uint32_t n = s->size - s->pos;
	uint8_t cs;

	if (n > 7)
		n = 7;
	cs = (uint8_t)(s->toggle | (7 - n) << 1);
	if (s->pos + n == s->size)
		cs |= F_LAST;
	request(s, out, cs, now);
	memcpy(&out->data[1], s->src + s->pos, n);
	s->pos += n;
	s->phase = PH_DL_SEG;
	return true;
}

static bool STRAND_RT upload_init(struct co_sdo *s, const uint8_t *d, int64_t now,
				  struct co_frame *out)
{
	uint32_t n;

	if (d[0] & F_EXPEDITED) {
		n = (d[0] & F_SIZE) ? 4 - ((d[0] >> 2) & 3) : 4;
		if (n > s->size) {
			/* the drive considers it done: nothing to send */
			s->state = CO_SDO_ABORTED;
			s->abort = CO_ABORT_NO_MEMORY;
			return false;
		}
		memcpy(s->dst, &d[4], n);
		s->pos = n;
		s->state = CO_SDO_DONE;
		return false;
	}
	if (d[0] & F_SIZE) {
		s->announced = co_get32(&d[4]);
		if (s->announced > s->size)
			return abort_ours(s, CO_ABORT_NO_MEMORY, out);
	}
	request(s, out, (uint8_t)(CCS_UL_SEG | s->toggle), now);
	s->phase = PH_UL_SEG;
	return true;
}

static bool STRAND_RT upload_seg(struct co_sdo *s, const uint8_t *d, int64_t now,
				 struct co_frame *out)
{
	uint32_t n = 7 - ((d[0] >> 1) & 7);

	if ((d[0] & TOGGLE) != s->toggle)
		return abort_ours(s, CO_ABORT_TOGGLE, out);
	if (s->pos + n > s->size)
		return abort_ours(s, CO_ABORT_NO_MEMORY, out);
	memcpy(s->dst + s->pos, &d[1], n);
	s->pos += n;
	s->toggle ^= TOGGLE;
	if (d[0] & F_LAST) {
		if (s->announced && s->pos != s->announced) {
			/* the transfer is over for the drive: no abort to send */
			s->state = CO_SDO_ABORTED;
			s->abort = CO_ABORT_TYPE_LEN;
			return false;
		}
		s->state = CO_SDO_DONE;
		return false;
	}
	request(s, out, (uint8_t)(CCS_UL_SEG | s->toggle), now);
	return true;
}

bool STRAND_RT co_sdo_rx(struct co_sdo *s, const struct co_frame *in, int64_t now,
			 struct co_frame *out)
{
	const uint8_t *d = in->data;
	uint8_t cs = d[0] & CS_MASK;
	bool init = s->phase == PH_DL_INIT || s->phase == PH_UL_INIT;

	if (s->state != CO_SDO_BUSY || in->id != CO_ID_SDO_TX + s->node || in->len < 8)
		return false;
	/* an answer to an initiate, or an abort, names what it is about: a
	 * late answer to an earlier, timed-out request is not this one's */
	if ((init || cs == CS_ABORT) && (co_get16(&d[1]) != s->index || d[3] != s->sub))
		return false;
	if (cs == CS_ABORT) {
		s->state = CO_SDO_ABORTED;
		s->abort = co_get32(&d[4]);
		return false;
	}
	switch (s->phase) {
	case PH_DL_INIT:
		if (cs != SCS_DL_INIT)
			break;
		if (s->pos == s->size) {
			s->state = CO_SDO_DONE;
			return false;
		}
		return next_segment(s, now, out);
	case PH_DL_SEG:
		if (cs != SCS_DL_SEG)
			break;
		if ((d[0] & TOGGLE) != s->toggle)
			return abort_ours(s, CO_ABORT_TOGGLE, out);
		s->toggle ^= TOGGLE;
		if (s->pos == s->size) {
			s->state = CO_SDO_DONE;
			return false;
		}
		return next_segment(s, now, out);
	case PH_UL_INIT:
		if (cs != SCS_UL_INIT)
			break;
		return upload_init(s, d, now, out);
	case PH_UL_SEG:
		if (cs != SCS_UL_SEG)
			break;
		return upload_seg(s, d, now, out);
	}
	return abort_ours(s, CO_ABORT_COMMAND, out);
}

bool STRAND_RT co_sdo_poll(struct co_sdo *s, int64_t now, struct co_frame *out)
{
	if (s->state != CO_SDO_BUSY || now < s->deadline)
		return false;
	return abort_ours(s, CO_ABORT_TIMEOUT, out);
}

static const struct {
	uint32_t code;
	const char *name;
} abort_names[] = {
	{ CO_ABORT_TOGGLE, "toggle bit not alternated" },
	{ CO_ABORT_TIMEOUT, "SDO protocol timed out" },
	{ CO_ABORT_COMMAND, "command specifier not valid or unknown" },
	{ 0x05040002, "invalid block size" },
	{ 0x05040003, "invalid sequence number" },
	{ 0x05040004, "CRC error" },
	{ CO_ABORT_NO_MEMORY, "out of memory" },
	{ CO_ABORT_ACCESS, "unsupported access to an object" },
	{ CO_ABORT_WRITE_ONLY, "attempt to read a write-only object" },
	{ CO_ABORT_READ_ONLY, "attempt to write a read-only object" },
	{ CO_ABORT_NO_OBJECT, "object does not exist in the object dictionary" },
	{ CO_ABORT_NO_MAP, "object cannot be mapped to the PDO" },
	{ CO_ABORT_MAP_LEN, "mapped objects would exceed the PDO length" },
	{ CO_ABORT_PARAM, "general parameter incompatibility" },
	{ CO_ABORT_INTERNAL, "general internal incompatibility in the device" },
	{ CO_ABORT_HARDWARE, "access failed due to a hardware error" },
	{ CO_ABORT_TYPE_LEN, "data type does not match, length does not match" },
	{ CO_ABORT_TYPE_LEN_HIGH, "data type does not match, length too high" },
	{ CO_ABORT_TYPE_LEN_LOW, "data type does not match, length too low" },
	{ CO_ABORT_NO_SUB, "sub-index does not exist" },
	{ CO_ABORT_VALUE, "invalid value for parameter" },
	{ CO_ABORT_VALUE_HIGH, "value of parameter written too high" },
	{ CO_ABORT_VALUE_LOW, "value of parameter written too low" },
	{ 0x06090036, "maximum value is less than minimum value" },
	{ 0x060a0023, "resource not available: SDO connection" },
	{ CO_ABORT_GENERAL, "general error" },
	{ CO_ABORT_DATA, "data cannot be transferred or stored to the application" },
	{ CO_ABORT_DATA_LOCAL, "data cannot be transferred or stored because of local control" },
	{ CO_ABORT_DATA_STATE,
	  "data cannot be transferred or stored because of the present device state" },
	{ 0x08000023, "object dictionary not present or its generation failed" },
	{ 0x08000024, "no data available" },
};

const char *co_abort_name(uint32_t code)
{
	size_t i;

	for (i = 0; i < sizeof(abort_names) / sizeof(abort_names[0]); i++)
		if (abort_names[i].code == code)
			return abort_names[i].name;
	return "unknown abort code";
}
