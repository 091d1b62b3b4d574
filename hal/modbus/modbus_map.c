/* SPDX-License-Identifier: MIT */
/* modbus_map.c - register blocks and wire time (see modbus_map.h). */
#include "modbus_map.h"

#include <errno.h>
#include <stdlib.h>

int modbus_plan_make(struct modbus_plan *p, const struct modbus_reg *reg, uint32_t n,
		     uint32_t max, uint32_t *a, uint32_t *b)
{
	uint32_t *order, i, j, k;
	int rc = 0;

	p->n = n;
	p->reg = reg;
	p->nblocks = 0;
	p->nregs = 0;
	p->off = calloc(n ? n : 1, sizeof(*p->off));
	p->block = calloc(n ? n : 1, sizeof(*p->block));
	order = calloc(n ? n : 1, sizeof(*order));
	if (!p->off || !p->block || !order) {
		rc = -ENOMEM;
		goto out;
	}
	/* by address: insertion sort, a device has a handful of values */
	for (i = 0; i < n; i++) {
		for (j = i; j > 0 && reg[order[j - 1]].addr > reg[i].addr; j--)
			order[j] = order[j - 1];
		order[j] = i;
	}
	for (k = 0; k < n; k++) {
		const struct modbus_reg *r = &reg[order[k]];
		uint32_t nr = modbus_type_nregs(r->type);
		struct modbus_block *blk = p->nblocks ? &p->block[p->nblocks - 1] : NULL;

		if ((uint32_t)r->addr + nr > 65536) {
			*a = *b = order[k];
			rc = -ERANGE;
			goto out;
		}
		if (k && reg[order[k - 1]].addr + modbus_type_nregs(reg[order[k - 1]].type) >
			 r->addr) {
			*a = order[k - 1];
			*b = order[k];
			rc = -EEXIST;
			goto out;
		}
		if (!blk || (uint32_t)blk->addr + blk->count != r->addr || blk->count + nr > max) {
			blk = &p->block[p->nblocks++];
			blk->addr = r->addr;
			blk->count = 0;
			blk->off = p->nregs;
		}
		p->off[order[k]] = p->nregs;
		blk->count = (uint16_t)(blk->count + nr);
		p->nregs += nr;
	}
out:
	free(order);
	if (rc)
		modbus_plan_free(p);
	return rc;
}

void modbus_plan_free(struct modbus_plan *p)
{
	free(p->off);
	free(p->block);
	p->off = NULL;
	p->block = NULL;
	p->nblocks = 0;
}

int64_t modbus_rtu_gap_ns(uint32_t baud, uint32_t char_bits)
{
	if (baud > 19200)
		return 1750000;
	return (int64_t)(3.5 * char_bits * 1e9 / baud + 0.5);
}

int64_t modbus_rtu_transaction_ns(uint32_t req_bytes, uint32_t rsp_bytes, uint32_t baud,
				  uint32_t char_bits, int64_t answer_ns)
{
	double wire = (double)(req_bytes + rsp_bytes) * char_bits * 1e9 / baud;

	return (int64_t)(wire + 0.5) + 2 * modbus_rtu_gap_ns(baud, char_bits) + answer_ns;
}
