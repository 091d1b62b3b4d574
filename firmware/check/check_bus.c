/* SPDX-License-Identifier: MIT */
/*
 * check_bus.c - `strand check`'s lines about the rig's buses: for each
 * Modbus device, what one update takes on its bus and the rate it reaches;
 * for each CANopen bus, the worst-case bits of a tick against what a tick
 * holds (the loader has already refused a rate or a load it cannot carry).
 */
#include "check_bus.h"

#include "hal/modbus/modbus_desc.h"
#include "rig/rig_canopen.h"

static void modbus_line(FILE *out, const struct rig_device_desc *dd, uint32_t tick_hz)
{
	const struct modbus_desc *m = dd->modbus;
	uint32_t every = modbus_update_every(m, tick_hz);
	int64_t w = 0, wr = 0;
	char how[96], where[300];

	if (modbus_update_ns(m, false, &w) || modbus_update_ns(m, true, &wr))
		return;
	if (m->transport == MODBUS_RTU)
		snprintf(how, sizeof(how), "RTU frames at %u baud 8%c%u, %g ms answers assumed",
			 m->baud, m->parity, m->stop_bits, m->answer_ms);
	else
		snprintf(how, sizeof(how), "TCP, %g ms per answer assumed", m->answer_ms);
	modbus_where(where, sizeof(where), m);
	fprintf(out, "device '%s': modbus %s", dd->name, where);
	fprintf(out, ": an update takes %.3g ms", w / 1e6);
	if (m->read_every && wr > w)
		fprintf(out, ", %.3g ms with its reads", wr / 1e6);
	fprintf(out, " (%s); reachable %.4g updates/s, the scene asks %.4g/s (every %u tick%s)\n",
		how, 1e9 / (m->read_every ? wr : w), (double)tick_hz / every, every,
		every == 1 ? "" : "s");
}

/* A CANopen bus: its worst-case bits per tick against what a tick holds. */
static void canopen_line(FILE *out, const struct rig_desc *rig, uint32_t k, uint32_t tick_hz)
{
	const struct rig_device_desc *dd = &rig->devices[k];
	struct co_load l;

	rig_canopen_load(rig, k, tick_hz, &l);
	if (!l.drives || !l.capacity)
		return;
	fprintf(out, "device '%s': canopen %s at %u bit/s: %u drive%s, worst case %u of %u bits "
		"per tick with bit stuffing (%.0f%%, at most %d%%)\n", dd->name,
		dd->canopen.interface, dd->canopen.bitrate, l.drives, l.drives == 1 ? "" : "s",
		l.bits, l.capacity, 100.0 * l.bits / l.capacity, CO_LOAD_MAX_PERCENT);
}

void check_buses(FILE *out, const struct rig_desc *rig, uint32_t tick_hz)
{
	uint32_t k;

	for (k = 0; k < rig->ndevices; k++) {
		if (rig->devices[k].modbus)
			modbus_line(out, &rig->devices[k], tick_hz);
		if (rig->devices[k].driver == RIG_DRIVER_CANOPEN)
			canopen_line(out, rig, k, tick_hz);
	}
}
