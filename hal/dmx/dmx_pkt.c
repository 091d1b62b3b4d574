/* SPDX-License-Identifier: MIT */
/*
 * dmx_pkt.c - E1.31 and Art-Net packets (see dmx.h). The layouts, byte by
 * byte, are ANSI E1.31-2016 section 4 (root layer 0-37, framing layer
 * 38-114, DMP layer 115 on) and Art-Net 4's ArtDmx; multi-byte fields are
 * big-endian in E1.31, Art-Net's OpCode little-endian.
 */
#include "dmx.h"

#include <string.h>

static void be16(uint8_t *p, uint16_t v)
{
	p[0] = (uint8_t)(v >> 8);
	p[1] = (uint8_t)v;
}

size_t dmx_e131_packet(uint8_t *buf, const uint8_t cid[16], const char *source, uint8_t priority,
		       uint8_t seq, uint8_t options, uint16_t universe, const uint8_t *slots,
		       uint16_t n)
{
	static const uint8_t acn_id[12] = { 'A', 'S', 'C', '-', 'E', '1', '.', '1', '7', 0, 0, 0 };
	size_t len = DMX_E131_HEADER + n;

	memset(buf, 0, DMX_E131_HEADER);
	/* root layer */
	be16(buf + 0, 0x0010);                       /* preamble size */
	be16(buf + 2, 0x0000);                       /* post-amble size */
	memcpy(buf + 4, acn_id, sizeof(acn_id));
	be16(buf + 16, (uint16_t)(0x7000 | (len - 16))); /* flags and length */
	buf[21] = 0x04;                              /* VECTOR_ROOT_E131_DATA */
	memcpy(buf + 22, cid, 16);
	/* framing layer */
	be16(buf + 38, (uint16_t)(0x7000 | (len - 38)));
	buf[43] = 0x02;                              /* VECTOR_E131_DATA_PACKET */
	strncpy((char *)buf + 44, source ? source : "", 63); /* 64 bytes, NUL-terminated */
	buf[108] = priority;
	be16(buf + 109, 0);                          /* no synchronization */
	buf[111] = seq;
	buf[112] = options;
	be16(buf + 113, universe);
	/* DMP layer */
	be16(buf + 115, (uint16_t)(0x7000 | (len - 115)));
	buf[117] = 0x02;                             /* VECTOR_DMP_SET_PROPERTY */
	buf[118] = 0xa1;                             /* address and data type */
	be16(buf + 119, 0x0000);                     /* first property address */
	be16(buf + 121, 0x0001);                     /* address increment */
	be16(buf + 123, (uint16_t)(n + 1));          /* the START code and the slots */
	buf[125] = 0x00;                             /* START code: dimmer data */
	memcpy(buf + DMX_E131_HEADER, slots, n);
	return len;
}

size_t dmx_artnet_packet(uint8_t *buf, uint8_t seq, uint16_t port_address, const uint8_t *slots,
			 uint16_t n)
{
	uint16_t len = (uint16_t)((n + 1) & ~1u);

	if (len < 2)
		len = 2;
	memcpy(buf, "Art-Net", 8);                   /* with its NUL */
	buf[8] = 0x00;                               /* OpDmx 0x5000, low byte first */
	buf[9] = 0x50;
	buf[10] = 0;                                 /* ProtVerHi */
	buf[11] = 14;                                /* ProtVerLo */
	buf[12] = seq;
	buf[13] = 0;                                 /* Physical */
	buf[14] = (uint8_t)port_address;             /* SubUni: Sub-Net and Universe */
	buf[15] = (uint8_t)(port_address >> 8) & 0x7f; /* Net */
	be16(buf + 16, len);
	memset(buf + DMX_ARTNET_HEADER, 0, len);
	memcpy(buf + DMX_ARTNET_HEADER, slots, n);
	return DMX_ARTNET_HEADER + len;
}

void dmx_cid(uint8_t cid[16], const char *name)
{
	/* two FNV-1a hashes of the name, different offsets */
	uint64_t h[2] = { 0xcbf29ce484222325ull, 0x84222325cbf29ce4ull };
	int i, k;

	for (k = 0; k < 2; k++)
		for (i = 0; name && name[i]; i++)
			h[k] = (h[k] ^ (uint8_t)name[i]) * 0x100000001b3ull;
	for (i = 0; i < 16; i++)
		cid[i] = (uint8_t)(h[i / 8] >> (8 * (i % 8)));
	cid[6] = (uint8_t)((cid[6] & 0x0f) | 0x40); /* version 4 */
	cid[8] = (uint8_t)((cid[8] & 0x3f) | 0x80); /* RFC 4122 variant */
}
