/* SPDX-License-Identifier: MIT */
/*
 * modbus_desc.c - what follows from a Modbus device's description: its
 * update period in ticks, the registers it writes and reads, and the time
 * an update takes on the bus (see modbus_dev.h).
 */
#include "modbus_desc.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

void modbus_where(char *buf, size_t size, const struct modbus_desc *d)
{
	if (d->transport == MODBUS_TCP)
		snprintf(buf, size, "tcp %s:%u unit %u", d->host, d->port, d->unit);
	else
		snprintf(buf, size, "rtu %s unit %u", d->serial, d->unit);
}

uint32_t modbus_update_every(const struct modbus_desc *d, uint32_t tick_hz)
{
	double e = d->update_hz > 0 ? round(tick_hz / d->update_hz) : 1;

	return e < 1 ? 1 : e > UINT32_MAX ? UINT32_MAX : (uint32_t)e;
}

void modbus_desc_regs(const struct modbus_desc *d, uint32_t nch, struct modbus_reg *w,
		      uint32_t *nw, struct modbus_reg *r, uint32_t *nr, int32_t *rfield,
		      int32_t *rstatus)
{
	uint32_t i;

	*nw = 0;
	*nr = 0;
	for (i = 0; i < nch; i++) {
		w[(*nw)++] = d->axes[i].target;
		rfield[i] = -1;
		if (d->axes[i].has_actual) {
			rfield[i] = (int32_t)*nr;
			r[(*nr)++] = d->axes[i].actual;
		}
	}
	if (d->has_heartbeat)
		w[(*nw)++] = d->heartbeat;
	*rstatus = -1;
	if (d->has_status) {
		*rstatus = (int32_t)*nr;
		r[(*nr)++] = (struct modbus_reg){ .addr = d->status_addr,
						  .type = MODBUS_TYPE_UINT16 };
	}
}

/* The requests of one plan, each on the bus. */
static int64_t plan_ns(const struct modbus_desc *d, const struct modbus_plan *p, bool write)
{
	int64_t answer = llround(d->answer_ms * 1e6), ns = 0;
	uint32_t i, bits = modbus_rtu_char_bits(d->parity != 'N', d->stop_bits);

	for (i = 0; i < p->nblocks; i++) {
		uint32_t n = p->block[i].count;

		if (d->transport == MODBUS_TCP)
			ns += answer;
		else if (write)
			ns += modbus_rtu_transaction_ns(modbus_rtu_write_req_bytes(n),
							MODBUS_RTU_WRITE_RSP_BYTES, d->baud, bits,
							answer);
		else
			ns += modbus_rtu_transaction_ns(MODBUS_RTU_READ_REQ_BYTES,
							modbus_rtu_read_rsp_bytes(n), d->baud, bits,
							answer);
	}
	return ns;
}

int modbus_update_ns(const struct modbus_desc *d, bool read, int64_t *ns)
{
	uint32_t n = d->naxes + 1, nw, nr, a, b;
	struct modbus_reg *w = calloc(n, sizeof(*w)), *r = calloc(n, sizeof(*r));
	int32_t *rfield = calloc(n, sizeof(*rfield)), rstatus;
	struct modbus_plan pw = { 0 }, pr = { 0 };
	int rc = -ENOMEM;

	if (!w || !r || !rfield)
		goto out;
	modbus_desc_regs(d, d->naxes, w, &nw, r, &nr, rfield, &rstatus);
	rc = modbus_plan_make(&pw, w, nw, MODBUS_MAP_WRITE_MAX, &a, &b);
	if (!rc)
		rc = modbus_plan_make(&pr, r, nr, MODBUS_MAP_READ_MAX, &a, &b);
	if (!rc)
		*ns = plan_ns(d, &pw, true) + (read ? plan_ns(d, &pr, false) : 0);
	modbus_plan_free(&pw);
	modbus_plan_free(&pr);
out:
	free(w);
	free(r);
	free(rfield);
	return rc;
}
