/* SPDX-License-Identifier: MIT */
/* co_emcy.c - emergency messages (see co_emcy.h). */
#include "co_emcy.h"

#include <string.h>

#include "hal/rt.h"

/*
 * CiA 301 table 21, "emergency error codes": a code matches an entry when
 * (code & mask) == value; the table is searched from its most specific
 * entries (full codes) to the classes of the top nibble.
 */
static const struct {
	uint16_t value, mask;
	const char *name;
} classes[] = {
	{ 0x8110, 0xffff, "communication, CAN overrun, objects lost" },
	{ 0x8120, 0xffff, "communication, CAN in error passive mode" },
	{ 0x8130, 0xffff, "communication, heartbeat or life guard error" },
	{ 0x8140, 0xffff, "communication, recovered from bus-off" },
	{ 0x8150, 0xffff, "communication, CAN-ID collision" },
	{ 0x8210, 0xffff, "protocol error, PDO not processed, length error" },
	{ 0x8220, 0xffff, "protocol error, PDO length exceeded" },
	{ 0x8240, 0xffff, "protocol error, unexpected SYNC data length" },
	{ 0x8250, 0xfff0, "protocol error, RPDO timeout" },
	{ 0x8611, 0xffff, "monitoring, following error" },
	{ 0x2100, 0xff00, "current, device input side" },
	{ 0x2200, 0xff00, "current inside the device" },
	{ 0x2300, 0xff00, "current, device output side" },
	{ 0x3100, 0xff00, "voltage, mains" },
	{ 0x3200, 0xff00, "voltage inside the device" },
	{ 0x3300, 0xff00, "voltage, output" },
	{ 0x4100, 0xff00, "temperature, ambient" },
	{ 0x4200, 0xff00, "temperature, device" },
	{ 0x6100, 0xff00, "software, internal" },
	{ 0x6200, 0xff00, "software, user" },
	{ 0x6300, 0xff00, "software, data set" },
	{ 0x8100, 0xff00, "communication" },
	{ 0x8200, 0xff00, "protocol error" },
	{ 0x0000, 0xff00, "error reset or no error" },
	{ 0x1000, 0xff00, "generic error" },
	{ 0xf000, 0xff00, "additional functions" },
	{ 0xff00, 0xff00, "device specific" },
	{ 0x2000, 0xf000, "current" },
	{ 0x3000, 0xf000, "voltage" },
	{ 0x4000, 0xf000, "temperature" },
	{ 0x5000, 0xf000, "device hardware" },
	{ 0x6000, 0xf000, "device software" },
	{ 0x7000, 0xf000, "additional modules" },
	{ 0x8000, 0xf000, "monitoring" },
	{ 0x9000, 0xf000, "external error" },
};

const char STRAND_RT *co_emcy_class(uint16_t code)
{
	size_t i;

	for (i = 0; i < sizeof(classes) / sizeof(classes[0]); i++)
		if ((code & classes[i].mask) == classes[i].value)
			return classes[i].name;
	return "unknown error class";
}

uint8_t STRAND_RT co_emcy_register_bit(uint16_t code)
{
	switch (code >> 12) {
	case 0x2:
		return 0x02;
	case 0x3:
		return 0x04;
	case 0x4:
		return 0x08;
	case 0x8:
		return (code & 0xff00) == 0x8100 || (code & 0xff00) == 0x8200 ? 0x10 : 0x20;
	default:
		return 0x01;
	}
}

bool STRAND_RT co_emcy_parse(const struct co_frame *f, uint16_t sync_id, struct co_emcy *e)
{
	if (f->id <= CO_ID_EMCY || f->id > CO_ID_EMCY + CO_NODE_MAX || f->id == sync_id ||
	    f->len != 8)
		return false;
	e->node = (uint8_t)(f->id - CO_ID_EMCY);
	e->code = co_get16(&f->data[0]);
	e->reg = f->data[2];
	memcpy(e->vendor, &f->data[3], sizeof(e->vendor));
	return true;
}

void STRAND_RT co_emcy_frame(struct co_frame *f, uint8_t node, uint16_t code, uint8_t reg)
{
	co_frame_init(f, (uint16_t)(CO_ID_EMCY + node), 8);
	co_put16(&f->data[0], code);
	f->data[2] = reg;
}
