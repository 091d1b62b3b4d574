/* SPDX-License-Identifier: MIT */
/* co_load.c - bus load of a tick (see co_load.h). */
#include "co_load.h"

uint32_t co_frame_bits_max(unsigned n)
{
	/* SOF 1, identifier 11, RTR 1, IDE 1, r0 1, DLC 4, data 8n, CRC 15:
	 * 34 + 8n stuffed bits; CRC delimiter 1, ACK 2, EOF 7, IFS 3: 13 */
	return 34 + 8 * n + 13 + (34 + 8 * n - 1) / 4;
}

void co_load_tick(struct co_load *l, uint32_t ndrives, uint32_t bitrate, uint32_t tick_hz,
		  uint32_t heartbeat_ms)
{
	/* heartbeats of one drive that can fall into one tick */
	uint64_t per_tick = heartbeat_ms ? (1000ULL + (uint64_t)heartbeat_ms * tick_hz - 1) /
					   ((uint64_t)heartbeat_ms * tick_hz) : 0;

	l->drives = ndrives;
	l->bits = co_frame_bits_max(0) +
		  ndrives * (co_frame_bits_max(CO_RPDO_BYTES) + co_frame_bits_max(CO_TPDO_BYTES) +
			     (uint32_t)per_tick * co_frame_bits_max(1));
	l->capacity = tick_hz ? bitrate / tick_hz : 0;
}

bool co_load_fits(const struct co_load *l)
{
	return (uint64_t)l->bits * 100 <= (uint64_t)l->capacity * CO_LOAD_MAX_PERCENT;
}
