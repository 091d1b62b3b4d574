/* SPDX-License-Identifier: MIT */
/*
 * co_slave_priv.h - the simulated drive's insides, shared by co_slave.c
 * (NMT, PDOs, the 402 state machine, the plant) and co_slave_od.c (the
 * object dictionary and the SDO server). Not an interface.
 */
#ifndef CO_SLAVE_PRIV_H
#define CO_SLAVE_PRIV_H

#include "co_slave.h"

#define CO_SLAVE_NOTE_MAX 64

struct co_pdo {
	uint32_t cobid; /* sub 1: bit 31 set = off */
	uint8_t type;   /* sub 2: transmission type */
	uint8_t count;  /* mapping sub 0 */
	uint32_t map[4];
	uint8_t syncs;  /* SYNCs counted towards type */
};

struct co_sdo_server {
	uint8_t phase;  /* co_slave_od.c */
	uint8_t toggle;
	uint16_t index;
	uint8_t sub;
	uint32_t pos, size;
	uint8_t buf[CO_SLAVE_NOTE_MAX + 8];
};

struct co_slave {
	struct co_slave_cfg cfg;
	bool powered;
	/* communication objects */
	uint32_t device_type;   /* 0x1000 */
	uint8_t error_register; /* 0x1001 */
	uint32_t sync_id;       /* 0x1005 */
	uint16_t heartbeat_ms;  /* 0x1017 */
	struct co_pdo rpdo[4], tpdo[4];
	/* drive objects */
	uint16_t error_code;    /* 0x603F */
	uint16_t cw, sw;        /* 0x6040, 0x6041 */
	int16_t qs_option;      /* 0x605A */
	int8_t mode;            /* 0x6060 */
	int8_t mode_display;    /* 0x6061 */
	int32_t actual_pos;     /* 0x6064 */
	int32_t actual_vel;     /* 0x606C */
	int32_t target_pos;     /* 0x607A */
	uint32_t qs_dec;        /* 0x6085 */
	uint8_t ip_count;       /* 0x60C2:00 */
	uint8_t ip_value;       /* 0x60C2:01 */
	int8_t ip_exp;          /* 0x60C2:02 */
	int32_t target_vel;     /* 0x60FF */
	uint16_t inject;        /* 0x2000 */
	char note[CO_SLAVE_NOTE_MAX + 1]; /* 0x2001 */
	/* RPDO1 data waiting for the SYNC */
	bool rpdo_pending;
	uint8_t rpdo_len;
	uint8_t rpdo_data[8];
	/* the 402 state machine and the plant */
	uint8_t state;          /* enum co402_state */
	bool stuck;
	struct sim_drive *plant;
	uint32_t plant_hz;
	bool plant_vel;
	int64_t plant_tick;
	int32_t prev_target;
	int64_t qs_t0, qs_next; /* quick stop ramp */
	double qs_x0, qs_v0;
	int64_t next_hb;
	/* SDO server, and the tests' hooks */
	struct co_sdo_server srv;
	uint16_t refuse_index;
	uint8_t refuse_sub;
	uint32_t refuse_abort;
	bool deaf;
	int64_t inject_at;      /* co_slave_inject: INT64_MAX when none */
	uint16_t inject_code;
	int32_t *trace;
	uint32_t trace_cap, traced;
	struct co_slave_watch w;
};

void co_slave_send(struct co_slave *s, const struct co_frame *f);

/* co_slave_od.c */
void co_slave_od_defaults(struct co_slave *s, bool application);
void co_slave_sdo(struct co_slave *s, const struct co_frame *f, int64_t now);
/* Read or write a mapped object of bits bits; false when it is not one. */
bool co_slave_map_get(struct co_slave *s, uint32_t map, uint32_t *v);
bool co_slave_map_set(struct co_slave *s, uint32_t map, uint32_t v);
/* Would this mapping entry be accepted in a PDO (tx: a TPDO)? */
bool co_slave_mappable(uint32_t map, bool tx);

/* co_slave.c: effects of writes */
void co_slave_controlword(struct co_slave *s, int64_t now);
void co_slave_heartbeat_changed(struct co_slave *s, int64_t now);

#endif /* CO_SLAVE_PRIV_H */
