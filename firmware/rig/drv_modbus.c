/* SPDX-License-Identifier: MIT */
/*
 * drv_modbus.c - Modbus drives (see drv_modbus.h): a device's `modbus:`
 * section (hal/modbus/modbus_desc.h has the meaning of each setting),
 *
 *   - name: drives
 *     driver: modbus
 *     modbus:
 *       tcp: {host: 192.168.1.20, port: 502}      # or
 *       rtu: {port: /dev/ttyUSB0, baud: 115200, parity: even, stop_bits: 1}
 *       unit: 1
 *       response_timeout_ms: 20     # default 20
 *       byte_timeout_ms: 5          # default 5
 *       update_hz: 250              # default: every tick
 *       read_every: 10              # ticks between reads of actual and status (0: never)
 *       max_faults: 3               # failed requests in a row that stop the run
 *       max_silence_ms: 100         # default: from the timeouts (modbus_axis.c)
 *       answer_ms: 1                # the drive's answer time, for strand check
 *       enable: {coil: 0}           # or {register: 40, on: 1, off: 0}
 *       status: {register: 50, fault_mask: 0x0008}
 *       heartbeat: {register: 8, type: uint32}   # the loop's tick
 *       axes:                       # axis 0, 1, ... of the device
 *         - {register: 0, type: int32, word_order: high_first, actual: {register: 100}}
 *
 * and what follows from it: everything `strand play` would refuse is
 * refused when the file is read, at its place (overlapping registers, an
 * axis an output uses that the map lacks, an update that takes longer on
 * the bus than the time between two updates); strand check's line about
 * the bus; the backend (hal/modbus/modbus_dev.h) with a channel per axis
 * the outputs use; the run's summary of the bus.
 */
#include "drv_modbus.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hal/modbus/modbus_dev.h"
#include "rig.h"
#include "yaml/yml.h"

static const char *const type_names[] = { "int16", "uint16", "int32", "uint32", NULL };
static const char *const order_names[] = { "high_first", "low_first", NULL };

static int u16(struct yml *y, yaml_node_t *n, uint16_t *out)
{
	long long v;
	int err = yml_int(y, n, 0, 65535, &v);

	*out = (uint16_t)v;
	return err;
}

/* A bit mask: decimal or 0x hexadecimal, 16 bits. */
static int mask16(struct yml *y, yaml_node_t *n, uint16_t *out)
{
	const char *s;
	char *end;
	unsigned long v;
	int err = yml_str(y, n, &s);

	if (err)
		return err;
	errno = 0;
	v = strtoul(s, &end, 0);
	if (errno || end == s || *end || v > 0xffff || s[0] == '-')
		return yml_fail(y, n, -EINVAL, "expected a 16-bit mask (8, 0x0008), found '%s'", s);
	*out = (uint16_t)v;
	return 0;
}

/* {register, type, word_order}; type and order default to *dflt's. */
static int reg(struct yml *y, yaml_node_t *map, const char *what, const struct modbus_reg *dflt,
	       struct modbus_reg *r)
{
	static const char *const keys[] = { "register", "type", "word_order", NULL };
	yaml_node_t *v[3];
	int err = yml_map(y, map, what, keys, v), t = dflt->type, o = dflt->words;

	if (!err)
		err = yml_require(y, map, what, v[0], "register");
	if (!err)
		err = u16(y, v[0], &r->addr);
	if (!err && v[1])
		err = yml_enum(y, v[1], "register type", type_names, &t);
	if (!err && v[2])
		err = yml_enum(y, v[2], "word order", order_names, &o);
	r->type = (enum modbus_type)t;
	r->words = (enum modbus_words)o;
	return err;
}

static int axis(struct yml *y, yaml_node_t *map, struct modbus_axis_desc *a)
{
	static const char *const keys[] = { "register", "type", "word_order", "actual", NULL };
	static const struct modbus_reg dflt = { 0, MODBUS_TYPE_INT32, MODBUS_WORDS_HIGH_FIRST };
	yaml_node_t *v[4];
	int err = yml_map(y, map, "axis", keys, v), t = dflt.type, o = dflt.words;

	if (!err)
		err = yml_require(y, map, "axis", v[0], "register");
	if (!err)
		err = u16(y, v[0], &a->target.addr);
	if (!err && v[1])
		err = yml_enum(y, v[1], "register type", type_names, &t);
	if (!err && v[2])
		err = yml_enum(y, v[2], "word order", order_names, &o);
	a->target.type = (enum modbus_type)t;
	a->target.words = (enum modbus_words)o;
	if (!err && v[3]) {
		a->has_actual = true;
		err = reg(y, v[3], "actual", &a->target, &a->actual);
	}
	return err;
}

static int tcp(struct yml *y, yaml_node_t *map, struct modbus_desc *m)
{
	static const char *const keys[] = { "host", "port", NULL };
	yaml_node_t *v[2];
	long long port = 502;
	int err = yml_map(y, map, "tcp", keys, v);

	if (!err)
		err = yml_require(y, map, "tcp", v[0], "host");
	if (!err)
		err = yml_str(y, v[0], &m->host);
	if (!err && !m->host[0])
		err = yml_fail(y, v[0], -EINVAL, "an empty host name");
	if (!err && v[1])
		err = yml_int(y, v[1], 1, 65535, &port);
	m->transport = MODBUS_TCP;
	m->port = (uint16_t)port;
	return err;
}

static int rtu(struct yml *y, yaml_node_t *map, struct modbus_desc *m)
{
	static const char *const keys[] = { "port", "baud", "parity", "stop_bits", NULL };
	static const char *const parities[] = { "none", "even", "odd", NULL };
	/* the rates libmodbus sets on Linux */
	static const long long bauds[] = { 1200, 2400, 4800, 9600, 19200, 38400, 57600,
					   115200, 230400, 460800, 921600 };
	yaml_node_t *v[4];
	long long baud = 19200, stop = 1;
	int err = yml_map(y, map, "rtu", keys, v), par = 1;
	size_t i;

	if (!err)
		err = yml_require(y, map, "rtu", v[0], "port");
	if (!err)
		err = yml_str(y, v[0], &m->serial);
	if (!err && v[1])
		err = yml_int(y, v[1], 1, 4000000, &baud);
	for (i = 0; !err && i < sizeof(bauds) / sizeof(bauds[0]) && bauds[i] != baud; i++)
		;
	if (!err && i == sizeof(bauds) / sizeof(bauds[0]))
		err = yml_fail(y, v[1], -EINVAL, "baud %lld: not a standard rate (1200 to 921600)",
			       baud);
	if (!err && v[2])
		err = yml_enum(y, v[2], "parity", parities, &par);
	if (!err && v[3])
		err = yml_int(y, v[3], 1, 2, &stop);
	m->transport = MODBUS_RTU;
	m->baud = (uint32_t)baud;
	m->parity = "NEO"[par];
	m->stop_bits = (uint32_t)stop;
	return err;
}

static int enable(struct yml *y, yaml_node_t *map, struct modbus_desc *m)
{
	static const char *const keys[] = { "coil", "register", "on", "off", NULL };
	yaml_node_t *v[4];
	int err = yml_map(y, map, "enable", keys, v);

	if (err)
		return err;
	if (!v[0] == !v[1])
		return yml_fail(y, map, -EINVAL, "enable: a coil or a register, one of them");
	if (v[0] && (v[2] || v[3]))
		return yml_fail(y, v[2] ? v[2] : v[3], -EINVAL,
				"a coil is on or off: 'on' and 'off' are a register's values");
	m->has_enable = true;
	m->enable_coil = v[0] != NULL;
	m->enable_on = 1;
	m->enable_off = 0;
	err = u16(y, v[0] ? v[0] : v[1], &m->enable_addr);
	if (!err && v[2])
		err = u16(y, v[2], &m->enable_on);
	if (!err && v[3])
		err = u16(y, v[3], &m->enable_off);
	if (!err && m->enable_on == m->enable_off)
		err = yml_fail(y, map, -EINVAL, "enable: 'on' and 'off' are the same value");
	return err;
}

static int status(struct yml *y, yaml_node_t *map, struct modbus_desc *m)
{
	static const char *const keys[] = { "register", "fault_mask", NULL };
	yaml_node_t *v[2];
	int err = yml_map(y, map, "status", keys, v);

	if (!err)
		err = yml_require(y, map, "status", v[0], "register");
	if (!err)
		err = yml_require(y, map, "status", v[1], "fault_mask");
	if (!err)
		err = u16(y, v[0], &m->status_addr);
	if (!err)
		err = mask16(y, v[1], &m->status_fault_mask);
	if (!err && !m->status_fault_mask)
		err = yml_fail(y, v[1], -EINVAL, "a fault mask of 0 never sees a fault");
	m->has_status = true;
	return err;
}

static int axes(struct yml *y, yaml_node_t *seq, struct modbus_desc *m)
{
	struct modbus_axis_desc *a;
	yaml_node_item_t *it;
	size_t count, i;
	int err = yml_seq(y, seq, "axes", &it, &count);

	if (err)
		return err;
	if (!count)
		return yml_fail(y, seq, -EINVAL, "a Modbus device needs at least one axis");
	if (count > 1024)
		return yml_fail(y, seq, -EINVAL, "%zu axes: at most 1024", count);
	a = pool_array(y->pool, count, sizeof(*a));
	if (!a)
		return yml_nomem(y);
	for (i = 0; !err && i < count; i++)
		err = axis(y, yml_node(y, it[i]), &a[i]);
	m->axes = a;
	m->naxes = (uint32_t)count;
	return err;
}

/* Registers that overlap, named with the map's place; then whether an
 * update fits between two updates. */
static int check_bus(struct yml *y, uint32_t tick_hz, yaml_node_t *map, yaml_node_t *rate,
		     struct modbus_desc *m, const char *name)
{
	uint32_t every = modbus_update_every(m, tick_hz);
	bool read = m->read_every > 0;
	double period_ms = 1000.0 * every / tick_hz, take_ms;
	int64_t ns;
	int err = modbus_update_ns(m, read, &ns);

	if (err == -ENOMEM)
		return yml_nomem(y);
	if (err)
		return yml_fail(y, map, -EINVAL,
				"device '%s': two of its registers overlap (axes, actual, status, "
				"heartbeat)", name);
	if (m->update_hz > tick_hz)
		return yml_fail(y, rate, -EINVAL, "update_hz %g is above the tick rate %u",
				m->update_hz, tick_hz);
	take_ms = ns / 1e6;
	if (take_ms > period_ms)
		return yml_fail(y, rate ? rate : map, -EINVAL,
				"device '%s': an update%s takes %.3g ms on the bus (%s), more "
				"than the %.3g ms between updates at %.4g Hz; it reaches %.4g Hz "
				"(set update_hz)", name, read ? " with its reads" : "", take_ms,
				m->transport == MODBUS_RTU ? "RTU frames at the baud rate" :
				"answer_ms per request", period_ms, 1000 / period_ms,
				1000 / take_ms);
	return 0;
}

/* The modbus: section of a device of driver modbus. */
static int section(struct yml *y, uint32_t tick_hz, yaml_node_t *map,
		   struct rig_device_desc *dev)
{
	static const char *const keys[] = {
		"tcp", "rtu", "unit", "response_timeout_ms", "byte_timeout_ms", "update_hz",
		"read_every", "max_faults", "max_silence_ms", "answer_ms", "enable", "status",
		"heartbeat", "axes", NULL,
	};
	enum { M_TCP, M_RTU, M_UNIT, M_RTO, M_BTO, M_HZ, M_READ, M_MAXF, M_SIL, M_ANS, M_EN,
	       M_ST, M_HB, M_AXES, M_N };
	static const struct modbus_reg hb = { 0, MODBUS_TYPE_UINT32, MODBUS_WORDS_HIGH_FIRST };
	struct modbus_desc *m = pool_array(y->pool, 1, sizeof(*m));
	yaml_node_t *v[M_N];
	long long n;
	int err;

	if (!m)
		return yml_nomem(y);
	err = yml_map(y, map, "modbus", keys, v);
	if (!err && !v[M_TCP] == !v[M_RTU])
		err = yml_fail(y, map, -EINVAL, "modbus: a tcp: or an rtu: connection, one of them");
	if (!err)
		err = yml_require(y, map, "modbus", v[M_UNIT], "unit");
	if (!err)
		err = yml_require(y, map, "modbus", v[M_AXES], "axes");
	if (!err)
		err = v[M_TCP] ? tcp(y, v[M_TCP], m) : rtu(y, v[M_RTU], m);
	if (!err)
		err = yml_int(y, v[M_UNIT], m->transport == MODBUS_TCP ? 0 : 1,
			      m->transport == MODBUS_TCP ? 255 : 247, &n);
	m->unit = (uint32_t)n;
	m->response_timeout_ms = MODBUS_DEFAULT_RESPONSE_TIMEOUT_MS;
	m->byte_timeout_ms = MODBUS_DEFAULT_BYTE_TIMEOUT_MS;
	m->max_faults = MODBUS_DEFAULT_MAX_FAULTS;
	m->answer_ms = MODBUS_DEFAULT_ANSWER_MS;
	/* libmodbus takes timeouts in whole microseconds (a shorter one
	 * would be none) and whole seconds as uint32_t; a drive silent for a
	 * minute is lost anyway */
	if (!err && v[M_RTO])
		err = yml_range(y, v[M_RTO], "response_timeout_ms", MODBUS_TIMEOUT_MS_MIN,
				MODBUS_TIMEOUT_MS_MAX, " ms", &m->response_timeout_ms);
	if (!err && v[M_BTO])
		err = yml_range(y, v[M_BTO], "byte_timeout_ms", MODBUS_TIMEOUT_MS_MIN,
				MODBUS_TIMEOUT_MS_MAX, " ms", &m->byte_timeout_ms);
	/* at most tick_hz (check_bus); an update every 100 s is the slowest
	 * that still streams setpoints */
	if (!err && v[M_HZ])
		err = yml_range(y, v[M_HZ], "update_hz", MODBUS_UPDATE_HZ_MIN, MOT_TICK_HZ_MAX,
				" Hz", &m->update_hz);
	if (!err && v[M_READ] && !(err = yml_int(y, v[M_READ], 0, 1000000, &n)))
		m->read_every = (uint32_t)n;
	if (!err && v[M_MAXF] && !(err = yml_int(y, v[M_MAXF], 1, 1000000, &n)))
		m->max_faults = (uint32_t)n;
	/* at least a tick's worth is made of it (modbus_axis.c); a bus that
	 * may be silent for more than an hour while setpoints wait is not
	 * watched at all */
	if (!err && v[M_SIL])
		err = yml_range(y, v[M_SIL], "max_silence_ms", MODBUS_TIMEOUT_MS_MIN,
				MODBUS_SILENCE_MS_MAX, " ms", &m->max_silence_ms);
	if (!err && v[M_ANS])
		err = yml_num(y, v[M_ANS], &m->answer_ms);
	if (!err && (m->answer_ms < 0 || m->answer_ms > 10000))
		err = yml_fail(y, v[M_ANS], -EINVAL, "answer_ms: 0 to 10000");
	if (!err && v[M_EN])
		err = enable(y, v[M_EN], m);
	if (!err && v[M_ST])
		err = status(y, v[M_ST], m);
	if (!err && v[M_HB]) {
		m->has_heartbeat = true;
		err = reg(y, v[M_HB], "heartbeat", &hb, &m->heartbeat);
	}
	if (!err && m->has_heartbeat && (m->heartbeat.type == MODBUS_TYPE_INT16 ||
					 m->heartbeat.type == MODBUS_TYPE_INT32))
		err = yml_fail(y, v[M_HB], -EINVAL, "a heartbeat counts ticks: uint16 or uint32");
	if (!err)
		err = axes(y, v[M_AXES], m);
	if (!err)
		err = check_bus(y, tick_hz, map, v[M_HZ], m, dev->name);
	dev->priv = m;
	return err;
}

static const char *const device_keys[] = { "modbus", NULL };

static int mb_parse_device(const struct rig_parse *p, struct rig_device_desc *dev)
{
	if (!p->v[0])
		return yml_fail(p->y, p->map, -EINVAL,
				"a device of driver modbus needs its modbus: section");
	return section(p->y, p->tick_hz, p->v[0], dev);
}

const struct modbus_desc *rig_modbus_desc(const struct rig_device_desc *dev)
{
	return dev->driver == &rig_drv_modbus ? dev->priv : NULL;
}

/* Every output's axis against its device's register map. */
static int mb_validate(const struct rig_desc *d, uint32_t tick_hz, struct rig_desc_err *e)
{
	uint32_t i, k;

	for (k = 0; k < d->ndevices; k++)
		if (d->devices[k].driver == &rig_drv_modbus && !d->devices[k].priv) {
			e->device = (int32_t)k;
			snprintf(e->msg, sizeof(e->msg), "device '%s': driver modbus without its "
				 "modbus: settings", d->devices[k].name);
			return -EINVAL;
		}
	for (i = 0; i < d->noutputs; i++) {
		const struct rig_output_desc *o = &d->outputs[i];

		for (k = 0; k < d->ndevices; k++) {
			const struct rig_device_desc *dd = &d->devices[k];
			const struct modbus_desc *m = rig_modbus_desc(dd);

			if (!m || !o->device || strcmp(dd->name, o->device))
				continue;
			if (o->axis >= m->naxes) {
				e->output = (int32_t)i;
				snprintf(e->msg, sizeof(e->msg),
					 "axis %u of Modbus device '%s': its register map "
					 "(modbus: axes:) has %u ax%s", o->axis, dd->name,
					 m->naxes, m->naxes == 1 ? "is" : "es");
				return -EINVAL;
			}
		}
	}
	return 0;
}

/* What one update takes on the bus and the rate it reaches. */
static void mb_check(FILE *out, const struct rig_desc *d, uint32_t k, uint32_t tick_hz)
{
	const struct rig_device_desc *dd = &d->devices[k];
	const struct modbus_desc *m = dd->priv;
	uint32_t every;
	int64_t w = 0, wr = 0;
	char how[96], where[300];

	if (!m || modbus_update_ns(m, false, &w) || modbus_update_ns(m, true, &wr))
		return;
	every = modbus_update_every(m, tick_hz);
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

/* The backend with a channel per axis its outputs use, velocity-mode where
 * the output is, standing at home where the drive has no actual-position
 * register; in lockstep on the virtual clock. */
static int mb_make_axes(struct rig_make *m, uint32_t k, char *err, size_t errsize)
{
	struct rig *r = m->r;
	const struct rig_dev *dv = &r->dev[k];
	uint32_t ax = (uint32_t)dv->axis, i;
	struct modbus_cfg c = { .name = dv->desc->name, .d = dv->desc->priv,
				.tick_hz = m->t->tick_hz, .lockstep = m->clk->is_virtual,
				.nch = rig_axis_channels(r, ax), .cancel = m->o->cancel,
				.sched = m->o->io };
	int64_t *initial = calloc(c.nch ? c.nch : 1, sizeof(*initial));
	bool *velocity = calloc(c.nch ? c.nch : 1, sizeof(*velocity));
	int rc = -ENOMEM;

	if (!initial || !velocity) {
		snprintf(err, errsize, "out of memory");
		goto out;
	}
	for (i = 0; i < r->nout; i++) {
		const struct rig_out *o = &r->out[i];

		if (o->dev != ax)
			continue;
		velocity[o->ch] = o->vel_mode;
		initial[o->ch] = rig_out_initial(o);
	}
	c.initial = initial;
	c.velocity = velocity;
	rc = hal_modbus_open(&r->axes[ax], &c, err, errsize);
out:
	free(initial);
	free(velocity);
	return rc;
}

static void mb_report(const struct rig *r, uint32_t k, FILE *f)
{
	if (r->dev[k].axis >= 0)
		hal_modbus_report(r->axes[r->dev[k].axis], f);
}

static void mb_free(struct rig *r, uint32_t k)
{
	if (r->dev[k].axis >= 0) {
		hal_axis_close(r->axes[r->dev[k].axis]);
		r->axes[r->dev[k].axis] = NULL;
	}
}

const struct rig_driver rig_drv_modbus = {
	.name = "modbus",
	.device_keys = device_keys,
	.device_foreign = "a modbus: section belongs to a device of driver modbus",
	.parse_device = mb_parse_device,
	.validate = mb_validate,
	.check = mb_check,
	.make_axes = mb_make_axes,
	.report = mb_report,
	.free = mb_free,
};
