/* SPDX-License-Identifier: MIT */
/*
 * co_slave_od.c - the simulated drive's object dictionary and its SDO
 * server (see co_slave.h; the protocol's command specifiers are listed in
 * hal/canopen/co_sdo.c).
 */
#include "co_slave_priv.h"

#include <stddef.h>
#include <string.h>

#include "hal/canopen/co_sdo.h"
#include "hal/rt.h"

enum {
	R = 1,      /* readable */
	W = 2,      /* writable */
	MAP_RX = 4, /* may be mapped into an RPDO */
	MAP_TX = 8, /* may be mapped into a TPDO */
	STR = 16,   /* a string: 0x1008 from the configuration, 0x2001 the note */
	K = 32,     /* a constant: the value is in off */
};

struct od {
	uint16_t index;
	uint8_t sub;
	uint8_t size; /* bytes */
	uint8_t flags;
	uint16_t off; /* offsetof(struct co_slave, the field), or the constant */
};

#define F(field) ((uint16_t)offsetof(struct co_slave, field))

/* A PDO's communication and mapping parameters: comm, map, array, k. */
#define PDO(c, m, a, k)                                                                     \
	{ (c) + (k), 0, 1, R | K, 2 }, { (c) + (k), 1, 4, R | W, F(a[k].cobid) },             \
	{ (c) + (k), 2, 1, R | W, F(a[k].type) }, { (m) + (k), 0, 1, R | W, F(a[k].count) },   \
	{ (m) + (k), 1, 4, R | W, F(a[k].map[0]) }, { (m) + (k), 2, 4, R | W, F(a[k].map[1]) }, \
	{ (m) + (k), 3, 4, R | W, F(a[k].map[2]) }, { (m) + (k), 4, 4, R | W, F(a[k].map[3]) }

static const struct od od[] = {
	{ 0x1000, 0, 4, R, F(device_type) },
	{ 0x1001, 0, 1, R | MAP_TX, F(error_register) },
	{ 0x1005, 0, 4, R | W, F(sync_id) },
	{ 0x1008, 0, 0, R | STR, 0 },
	{ 0x1017, 0, 2, R | W, F(heartbeat_ms) },
	PDO(0x1400, 0x1600, rpdo, 0),
	PDO(0x1400, 0x1600, rpdo, 1),
	PDO(0x1400, 0x1600, rpdo, 2),
	PDO(0x1400, 0x1600, rpdo, 3),
	PDO(0x1800, 0x1a00, tpdo, 0),
	PDO(0x1800, 0x1a00, tpdo, 1),
	PDO(0x1800, 0x1a00, tpdo, 2),
	PDO(0x1800, 0x1a00, tpdo, 3),
	{ 0x2000, 0, 2, W, F(inject) },
	{ 0x2001, 0, 0, R | W | STR, 0 },
	{ 0x603f, 0, 2, R | MAP_TX, F(error_code) },
	{ 0x6040, 0, 2, R | W | MAP_RX, F(cw) },
	{ 0x6041, 0, 2, R | MAP_TX, F(sw) },
	{ 0x605a, 0, 2, R | W, F(qs_option) },
	{ 0x6060, 0, 1, R | W, F(mode) },
	{ 0x6061, 0, 1, R | MAP_TX, F(mode_display) },
	{ 0x6064, 0, 4, R | MAP_TX, F(actual_pos) },
	{ 0x606c, 0, 4, R | MAP_TX, F(actual_vel) },
	{ 0x607a, 0, 4, R | W | MAP_RX, F(target_pos) },
	{ 0x6085, 0, 4, R | W, F(qs_dec) },
	{ 0x60c2, 0, 1, R | K, 2 },
	{ 0x60c2, 1, 1, R | W, F(ip_value) },
	{ 0x60c2, 2, 1, R | W, F(ip_exp) },
	{ 0x60ff, 0, 4, R | W | MAP_RX, F(target_vel) },
};

#define NOD (sizeof(od) / sizeof(od[0]))

static const struct od STRAND_RT *find(uint16_t index, uint8_t sub, uint32_t *abort)
{
	bool index_found = false;
	size_t i;

	for (i = 0; i < NOD; i++) {
		if (od[i].index != index)
			continue;
		index_found = true;
		if (od[i].sub == sub)
			return &od[i];
	}
	*abort = index_found ? CO_ABORT_NO_SUB : CO_ABORT_NO_OBJECT;
	return NULL;
}

static uint32_t STRAND_RT get(const struct co_slave *s, const struct od *e)
{
	const uint8_t *p = (const uint8_t *)s + e->off;
	uint32_t v32;
	uint16_t v16;

	if (e->flags & K)
		return e->off;
	switch (e->size) {
	case 1:
		return *p;
	case 2:
		memcpy(&v16, p, 2);
		return v16;
	default:
		memcpy(&v32, p, 4);
		return v32;
	}
}

static void STRAND_RT put(struct co_slave *s, const struct od *e, uint32_t v)
{
	uint8_t *p = (uint8_t *)s + e->off;
	uint16_t v16 = (uint16_t)v;

	switch (e->size) {
	case 1:
		*p = (uint8_t)v;
		break;
	case 2:
		memcpy(p, &v16, 2);
		break;
	default:
		memcpy(p, &v, 4);
		break;
	}
}

bool STRAND_RT co_slave_mappable(uint32_t map, bool tx)
{
	uint32_t abort;
	const struct od *e = find((uint16_t)(map >> 16), (uint8_t)(map >> 8), &abort);

	return e && (e->flags & (tx ? MAP_TX : MAP_RX)) && (map & 0xff) == e->size * 8u;
}

bool STRAND_RT co_slave_map_get(struct co_slave *s, uint32_t map, uint32_t *v)
{
	uint32_t abort;
	const struct od *e = find((uint16_t)(map >> 16), (uint8_t)(map >> 8), &abort);

	if (!e || !(e->flags & MAP_TX))
		return false;
	*v = get(s, e);
	return true;
}

bool STRAND_RT co_slave_map_set(struct co_slave *s, uint32_t map, uint32_t v)
{
	uint32_t abort;
	const struct od *e = find((uint16_t)(map >> 16), (uint8_t)(map >> 8), &abort);

	if (!e || !(e->flags & MAP_RX))
		return false;
	put(s, e, v);
	return true;
}

/* The PDO an entry of 0x1400..0x1403, 0x1600.., 0x1800.., 0x1A00.. belongs to. */
static struct co_pdo STRAND_RT *pdo_of(struct co_slave *s, uint16_t index, bool *tx, bool *mapping)
{
	unsigned base = index & 0xfe00, k = index & 0x1ff;

	if (k > 3)
		return NULL;
	*tx = base == 0x1800 || base == 0x1a00;
	*mapping = base == 0x1600 || base == 0x1a00;
	if (base == 0x1400 || base == 0x1600)
		return &s->rpdo[k];
	if (base == 0x1800 || base == 0x1a00)
		return &s->tpdo[k];
	return NULL;
}

/* CiA 301 7.5.2.35-38: what a PDO parameter may be set to, and when. */
static uint32_t STRAND_RT check_pdo(struct co_slave *s, const struct od *e, uint32_t v)
{
	bool tx, mapping;
	struct co_pdo *p = pdo_of(s, e->index, &tx, &mapping);
	uint32_t bits = 0;
	unsigned i;

	if (!p)
		return 0;
	if (!mapping && e->sub == 1) {
		/* the identifier changes only while the PDO is off */
		if (!(p->cobid & CO_PDO_COBID_OFF) && !(v & CO_PDO_COBID_OFF) &&
		    (v & 0x7ff) != (p->cobid & 0x7ff))
			return CO_ABORT_VALUE;
		return 0;
	}
	if (!mapping && e->sub == 2)
		return v <= 240 || v >= 252 ? 0 : CO_ABORT_VALUE;
	if (mapping && e->sub == 0) {
		if (v > 4)
			return CO_ABORT_VALUE_HIGH;
		if (!(p->cobid & CO_PDO_COBID_OFF))
			return CO_ABORT_DATA_STATE;
		for (i = 0; i < v; i++) {
			if (!co_slave_mappable(p->map[i], tx))
				return CO_ABORT_NO_MAP;
			bits += p->map[i] & 0xff;
		}
		return bits <= 64 ? 0 : CO_ABORT_MAP_LEN;
	}
	if (mapping) {
		if (p->count)
			return CO_ABORT_DATA_STATE;
		return v == 0 || co_slave_mappable(v, tx) ? 0 : CO_ABORT_NO_MAP;
	}
	return 0;
}

static uint32_t STRAND_RT check(struct co_slave *s, const struct od *e, uint32_t v)
{
	switch (e->index) {
	case 0x1005:
		/* a consumer of the SYNC: no "generate" bit, a real identifier */
		return (v & 0x40000000) || !(v & 0x7ff) ? CO_ABORT_VALUE : 0;
	case 0x6060:
		if ((int8_t)v != CO402_MODE_CSP && (int8_t)v != CO402_MODE_CSV)
			return CO_ABORT_VALUE;
		return s->state == CO402_ENABLED ? CO_ABORT_DATA_STATE : 0;
	case 0x60c2:
		return e->sub == 1 && v == 0 ? CO_ABORT_VALUE_LOW : 0;
	}
	return check_pdo(s, e, v);
}

/* Read an object into buf; 0 or an abort code. */
static uint32_t STRAND_RT read_obj(struct co_slave *s, const struct od *e, uint8_t *buf,
				   uint32_t *n)
{
	if (!(e->flags & R))
		return CO_ABORT_WRITE_ONLY;
	if (e->flags & STR) {
		const char *str = e->index == 0x1008 ? (s->cfg.name ? s->cfg.name : "") : s->note;
		size_t len = strlen(str);

		if (len > CO_SLAVE_NOTE_MAX)
			len = CO_SLAVE_NOTE_MAX;
		memcpy(buf, str, len);
		*n = (uint32_t)len;
		return 0;
	}
	co_put(buf, get(s, e), e->size);
	*n = e->size;
	return 0;
}

/* Write n bytes to an object; 0 or an abort code. */
static uint32_t STRAND_RT write_obj(struct co_slave *s, const struct od *e, const uint8_t *buf,
				    uint32_t n, int64_t now)
{
	uint32_t v, abort;

	if (!(e->flags & W))
		return CO_ABORT_READ_ONLY;
	if (e->flags & STR) {
		if (n > CO_SLAVE_NOTE_MAX)
			return CO_ABORT_TYPE_LEN_HIGH;
		memcpy(s->note, buf, n);
		s->note[n] = '\0';
		return 0;
	}
	if (n != e->size)
		return n > e->size ? CO_ABORT_TYPE_LEN_HIGH : CO_ABORT_TYPE_LEN_LOW;
	v = co_get(buf, n);
	abort = check(s, e, v);
	if (abort)
		return abort;
	put(s, e, v);
	switch (e->index) {
	case 0x6040:
		co_slave_controlword(s, now);
		break;
	case 0x1017:
		co_slave_heartbeat_changed(s, now);
		break;
	case 0x6060:
		s->mode_display = s->mode;
		break;
	case 0x2000:
		if (v)
			co_slave_fault(s, (uint16_t)v, now);
		break;
	}
	return 0;
}

/* ---- the SDO server ---- */

enum { SRV_IDLE, SRV_DOWNLOAD, SRV_UPLOAD };

static void STRAND_RT reply(struct co_slave *s, uint8_t cs, const uint8_t *data, uint32_t n)
{
	struct co_frame f;

	co_frame_init(&f, (uint16_t)(CO_ID_SDO_TX + s->cfg.node), 8);
	f.data[0] = cs;
	if (n)
		memcpy(&f.data[1], data, n);
	co_slave_send(s, &f);
}

static void STRAND_RT reply_mux(struct co_slave *s, uint8_t cs, const uint8_t *data, uint32_t n)
{
	uint8_t d[7] = { (uint8_t)s->srv.index, (uint8_t)(s->srv.index >> 8), s->srv.sub };

	if (n)
		memcpy(&d[3], data, n);
	reply(s, cs, d, 7);
}

static void STRAND_RT abort_srv(struct co_slave *s, uint32_t code)
{
	struct co_frame f;

	co_sdo_abort_frame(&f, (uint16_t)(CO_ID_SDO_TX + s->cfg.node), s->srv.index, s->srv.sub,
			   code);
	co_slave_send(s, &f);
	s->srv.phase = SRV_IDLE;
}

static void STRAND_RT upload_segment(struct co_slave *s, uint8_t cs)
{
	struct co_sdo_server *v = &s->srv;
	uint32_t n = v->size - v->pos;
	uint8_t c;

	if ((cs & 0x10) != v->toggle) {
		abort_srv(s, CO_ABORT_TOGGLE);
		return;
	}
	if (n > 7)
		n = 7;
	c = (uint8_t)(v->toggle | (7 - n) << 1 | (v->pos + n == v->size));
	reply(s, c, v->buf + v->pos, n);
	v->pos += n;
	v->toggle ^= 0x10;
	if (v->pos == v->size)
		v->phase = SRV_IDLE;
}

static void STRAND_RT download_segment(struct co_slave *s, const uint8_t *d, int64_t now)
{
	struct co_sdo_server *v = &s->srv;
	uint32_t n = 7 - ((d[0] >> 1) & 7), abort;
	uint8_t t = d[0] & 0x10;
	const struct od *e;

	if (t != v->toggle) {
		abort_srv(s, CO_ABORT_TOGGLE);
		return;
	}
	if (v->pos + n > sizeof(v->buf)) {
		abort_srv(s, CO_ABORT_NO_MEMORY);
		return;
	}
	memcpy(v->buf + v->pos, &d[1], n);
	v->pos += n;
	v->toggle ^= 0x10;
	if (!(d[0] & 1)) {
		reply(s, (uint8_t)(0x20 | t), NULL, 0);
		return;
	}
	if (v->size && v->pos != v->size) {
		abort_srv(s, CO_ABORT_TYPE_LEN);
		return;
	}
	e = find(v->index, v->sub, &abort);
	abort = e ? write_obj(s, e, v->buf, v->pos, now) : abort;
	if (abort) {
		abort_srv(s, abort);
		return;
	}
	reply(s, (uint8_t)(0x20 | t), NULL, 0);
	v->phase = SRV_IDLE;
}

static void STRAND_RT initiate(struct co_slave *s, const uint8_t *d, int64_t now)
{
	struct co_sdo_server *v = &s->srv;
	uint8_t cs = d[0] & 0xe0, buf[CO_SLAVE_NOTE_MAX];
	uint32_t abort = 0, n;
	const struct od *e;

	v->index = co_get16(&d[1]);
	v->sub = d[3];
	v->phase = SRV_IDLE;
	if (s->refuse_abort && v->index == s->refuse_index && v->sub == s->refuse_sub) {
		abort_srv(s, s->refuse_abort);
		return;
	}
	e = find(v->index, v->sub, &abort);
	if (!e) {
		abort_srv(s, abort);
		return;
	}
	if (cs == 0x20 && (d[0] & 0x02)) { /* expedited download */
		n = (d[0] & 0x01) ? 4 - ((d[0] >> 2) & 3) : (e->size ? e->size : 4);
		abort = write_obj(s, e, &d[4], n, now);
		if (abort)
			abort_srv(s, abort);
		else
			reply_mux(s, 0x60, NULL, 0);
	} else if (cs == 0x20) { /* segmented download */
		v->size = (d[0] & 0x01) ? co_get32(&d[4]) : 0;
		if (v->size > sizeof(v->buf)) {
			abort_srv(s, CO_ABORT_NO_MEMORY);
			return;
		}
		v->pos = 0;
		v->toggle = 0;
		v->phase = SRV_DOWNLOAD;
		reply_mux(s, 0x60, NULL, 0);
	} else { /* upload */
		abort = read_obj(s, e, buf, &n);
		if (abort) {
			abort_srv(s, abort);
		} else if (n >= 1 && n <= 4 && !(e->flags & STR)) {
			reply_mux(s, (uint8_t)(0x43 | (4 - n) << 2), buf, n);
		} else {
			uint8_t size[4];

			memcpy(v->buf, buf, n);
			v->size = n;
			v->pos = 0;
			v->toggle = 0;
			v->phase = SRV_UPLOAD;
			co_put32(size, n);
			reply_mux(s, 0x41, size, 4);
		}
	}
}

void STRAND_RT co_slave_sdo(struct co_slave *s, const struct co_frame *f, int64_t now)
{
	const uint8_t *d = f->data;
	uint8_t cs = d[0] & 0xe0;

	if (s->deaf || f->len != 8)
		return;
	s->w.sdo_requests++;
	switch (cs) {
	case 0x20: /* initiate download */
	case 0x40: /* initiate upload */
		initiate(s, d, now);
		break;
	case 0x00: /* download segment */
		if (s->srv.phase == SRV_DOWNLOAD)
			download_segment(s, d, now);
		else
			abort_srv(s, CO_ABORT_COMMAND);
		break;
	case 0x60: /* upload segment */
		if (s->srv.phase == SRV_UPLOAD)
			upload_segment(s, d[0]);
		else
			abort_srv(s, CO_ABORT_COMMAND);
		break;
	case 0x80: /* the client aborts */
		s->srv.phase = SRV_IDLE;
		break;
	default:
		abort_srv(s, CO_ABORT_COMMAND);
		break;
	}
}

void STRAND_RT co_slave_od_defaults(struct co_slave *s, bool application)
{
	unsigned k;

	/* communication objects: every PDO off and unmapped */
	s->device_type = 0x00020192; /* CiA 402, servo drive */
	s->sync_id = CO_ID_SYNC;
	s->heartbeat_ms = 0;
	for (k = 0; k < 4; k++) {
		memset(&s->rpdo[k], 0, sizeof(s->rpdo[k]));
		memset(&s->tpdo[k], 0, sizeof(s->tpdo[k]));
		s->rpdo[k].cobid = CO_PDO_COBID_OFF | co_rpdo_id(k + 1, s->cfg.node);
		s->tpdo[k].cobid = CO_PDO_COBID_OFF | co_tpdo_id(k + 1, s->cfg.node);
		s->rpdo[k].type = 255;
		s->tpdo[k].type = 255;
	}
	s->srv.phase = SRV_IDLE;
	if (!application)
		return;
	s->qs_option = CO402_QUICK_STOP_RAMP_THEN_DISABLE;
	s->mode = 0;
	s->mode_display = 0;
	s->qs_dec = 0;
	s->ip_value = 1;
	s->ip_exp = -3;
	s->target_pos = s->actual_pos;
	s->target_vel = 0;
	s->inject = 0;
	s->note[0] = '\0';
}
