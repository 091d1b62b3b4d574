/* SPDX-License-Identifier: MIT */
/*
 * co_master_priv.h - what the master's files share (co_master.c, the
 * core; co_config.c, the configuration by SDO; co_describe.c, the words).
 * Not an interface.
 */
#ifndef CO_MASTER_PRIV_H
#define CO_MASTER_PRIV_H

#include "co_master.h"

#define CO_MS 1000000LL

/* Send frames unless the master is mute; a refusal latches CO_FAULT_SEND
 * and mutes it. */
void co_send(struct co_master *m, const struct co_frame *f, uint32_t n);

/* Latch a fault unless one is latched already; a fault during start-up
 * ends it (phase FAILED). */
void co_latch(struct co_master *m, const struct co_fault *f);
void co_fail(struct co_master *m, enum co_fault_kind kind, int code, const struct co_node *n,
	     uint32_t detail);

/* An NMT command to one node. */
void co_nmt(struct co_master *m, enum co_nmt_cmd cmd, uint8_t node);

/* co_config.c: the node booted: configure it, step by step. */
void co_config_begin(struct co_master *m, struct co_node *n, int64_t now);
/* Its SDO transfer ended (done or aborted): take the result, go on. */
void co_config_next(struct co_master *m, struct co_node *n, int64_t now);

#endif /* CO_MASTER_PRIV_H */
