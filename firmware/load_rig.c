/* SPDX-License-Identifier: MIT */
/*
 * load_rig.c - the rig sections of a scene file: `devices:`, `outputs:`,
 * `triggers:` and `inputs:` (rig_desc.h has the schema). Everything the
 * player would otherwise refuse at start is reported here, at its place in
 * the file: an unknown device or channel (with the closest name), an axis
 * or line used twice, an output without speed and acceleration limits, a
 * trigger pulse that would overlap the next frame's.
 */
#include "load_priv.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "channel.h"
#include "rig_canopen.h"

/* What the rig sections need while they are read. */
struct rl {
	struct ld *l;
	struct rig_desc *r;
	struct chan_list ch;
	const char **chan_names; /* NULL-terminated, for suggestions */
	const char **dev_names;
	struct ld_mark *dev_at;
	yaml_node_t **co_at; /* each device's canopen: mapping, or NULL */
};

static int find(const char *const *names, const char *name)
{
	int i;

	for (i = 0; names && names[i]; i++)
		if (!strcmp(names[i], name))
			return i;
	return -1;
}

/* A name from a list given by another section: its index, or an error
 * with the closest valid one. */
static int lookup(struct rl *rl, yaml_node_t *n, const char *what, const char *const *names,
		  const char *section, int *out)
{
	const char *name, *best;
	int err = ld_str(rl->l, n, &name);

	if (err)
		return err;
	*out = find(names, name);
	if (*out >= 0)
		return 0;
	best = ld_suggest(name, names);
	if (best)
		return ld_fail(rl->l, n, -EINVAL, "unknown %s '%s'; did you mean '%s'?", what, name,
			       best);
	return ld_fail(rl->l, n, -EINVAL, "unknown %s '%s' (not in %s)", what, name, section);
}

static int positive(struct ld *l, yaml_node_t *n, double *out)
{
	int err = ld_num(l, n, out);

	if (!err && !(*out > 0))
		err = ld_fail(l, n, -EINVAL, "must be above zero");
	return err;
}

static int sim_params(struct ld *l, yaml_node_t *map, struct rig_sim_desc *s)
{
	static const char *const keys[] = { "bandwidth", "damping", "feedforward",
					    "limit_factor", "exposure_ms", "readout_ms", NULL };
	yaml_node_t *v[6];
	double *out[6] = { &s->bandwidth_hz, &s->damping, &s->feedforward, &s->limit_factor,
			   &s->exposure_ms, &s->readout_ms };
	int i, err = ld_map(l, map, "sim", keys, v);

	for (i = 0; !err && i < 6; i++)
		if (v[i])
			err = positive(l, v[i], out[i]);
	if (!err && v[2] && s->feedforward > 1)
		err = ld_fail(l, v[2], -EINVAL, "feedforward is a fraction, 0 to 1");
	return err;
}

/* A COB-ID, in decimal or 0x hex: 1..0x7ff. */
static int cob_id(struct ld *l, yaml_node_t *n, uint32_t *out)
{
	const char *text;
	char *end;
	unsigned long v;
	int err = ld_str(l, n, &text);

	if (err)
		return err;
	errno = 0;
	v = strtoul(text, &end, 0);
	if (errno || end == text || *end || v < 1 || v > 0x7ff)
		return ld_fail(l, n, -EINVAL, "'%s' is not an 11-bit COB-ID (1 to 0x7ff)", text);
	*out = (uint32_t)v;
	return 0;
}

/* A canopen device's bus: {interface, bitrate, sync_id, heartbeat_ms}. */
static int canopen_bus(struct ld *l, yaml_node_t *map, struct rig_canopen_desc *c)
{
	static const char *const keys[] = { "interface", "bitrate", "sync_id", "heartbeat_ms",
					    NULL };
	yaml_node_t *v[4];
	long long n;
	int err = ld_map(l, map, "canopen", keys, v);

	if (!err)
		err = ld_require(l, map, "canopen", v[0], "interface");
	if (!err)
		err = ld_require(l, map, "canopen", v[1], "bitrate");
	if (!err)
		err = ld_str(l, v[0], &c->interface);
	if (!err && (!c->interface[0] || strlen(c->interface) > 15))
		err = ld_fail(l, v[0], -EINVAL, "interface '%s': a network interface name "
			      "(1 to 15 characters: can0, vcan0) or sim", c->interface);
	if (!err)
		err = ld_int(l, v[1], 10000, 1000000, &n);
	c->bitrate = (uint32_t)n;
	c->sync_id = CO_ID_SYNC;
	if (!err && v[2])
		err = cob_id(l, v[2], &c->sync_id);
	c->heartbeat_ms = RIG_CO_HEARTBEAT_MS;
	if (!err && v[3])
		err = ld_int(l, v[3], 1, 10000, &n);
	if (!err && v[3])
		c->heartbeat_ms = (uint32_t)n;
	return err;
}

static int devices(struct rl *rl, yaml_node_t *seq)
{
	static const char *const keys[] = { "name", "driver", "sim", "canopen", NULL };
	static const char *const drivers[] = { "sim", "modbus", "gpio", "canopen", NULL };
	struct ld *l = rl->l;
	struct rig_device_desc *dev;
	yaml_node_item_t *it;
	size_t count, i;
	int err = ld_seq(l, seq, "devices", &it, &count);

	if (err)
		return err;
	dev = pool_array(l->pool, count ? count : 1, sizeof(*dev));
	rl->dev_names = pool_array(l->pool, count + 1, sizeof(*rl->dev_names));
	rl->co_at = pool_array(l->pool, count ? count : 1, sizeof(*rl->co_at));
	if (!dev || !rl->dev_names || !rl->co_at)
		return ld_nomem(l);
	for (i = 0; i < count; i++) {
		yaml_node_t *map = ld_node(l, it[i]), *v[4];
		int drv, k;

		err = ld_map(l, map, "device", keys, v);
		if (!err)
			err = ld_require(l, map, "device", v[0], "name");
		if (!err)
			err = ld_require(l, map, "device", v[1], "driver");
		if (!err)
			err = ld_name(l, v[0], &dev[i].name);
		if (!err)
			err = ld_enum(l, v[1], "driver", drivers, &drv);
		if (!err && v[2])
			err = sim_params(l, v[2], &dev[i].sim);
		if (!err && drv == RIG_DRIVER_CANOPEN)
			err = ld_require(l, map, "canopen device", v[3], "canopen");
		if (!err && v[3] && drv != RIG_DRIVER_CANOPEN)
			err = ld_fail(l, v[3], -EINVAL, "canopen: settings of a canopen device, "
				      "not of a %s one", drivers[drv]);
		if (!err && v[3])
			err = canopen_bus(l, v[3], &dev[i].canopen);
		if (err)
			return err;
		rl->co_at[i] = v[3];
		dev[i].driver = (enum rig_driver)drv;
		k = find(rl->dev_names, dev[i].name);
		if (k >= 0)
			return ld_fail(l, v[0], -EINVAL, "device '%s' is already listed (line %u)",
				       dev[i].name, (unsigned)ld_mark_of(ld_node(l, it[k])).line);
		rl->dev_names[i] = dev[i].name;
	}
	rl->r->devices = dev;
	rl->r->ndevices = (uint32_t)count;
	return 0;
}

/* Is channel c an angle (limits and tolerances in degrees)? */
static bool is_angle(const struct rl *rl, const struct chan *c)
{
	if (c->kind == CHAN_VALUE)
		return rl->l->d->nodes[c->index].kind == MOT_NODE_REVOLUTE;
	return c->kind == CHAN_CAMERA && c->comp >= 3;
}

/* An output on a canopen device: node: (its axis), mode: checked against
 * the channel (cyclic synchronous velocity for spin speeds only). */
static int canopen_output(struct rl *rl, yaml_node_t *map, yaml_node_t *axis_at,
			  yaml_node_t *node_at, yaml_node_t *mode_at, const struct chan *c,
			  struct rig_output_desc *o, long long *node)
{
	static const char *const modes[] = { "csp", "csv", NULL };
	struct ld *l = rl->l;
	bool spin = c->kind == CHAN_RPM;
	int mode, err;

	if (axis_at)
		return ld_fail(l, axis_at, -EINVAL,
			       "an output on canopen device '%s' is placed by node:, not axis:",
			       o->device);
	err = ld_require(l, map, "output on a canopen device", node_at, "node");
	if (!err)
		err = ld_int(l, node_at, 1, CO_NODE_MAX, node);
	if (err || !mode_at) {
		o->canopen.mode = spin ? 9 : 8;
		return err;
	}
	err = ld_enum(l, mode_at, "mode", modes, &mode);
	if (!err && mode != spin)
		err = ld_fail(l, mode_at, -EINVAL, "mode %s: '%s' is %s; it needs mode %s",
			      modes[mode], o->channel, spin ? "a spin speed" : "not a spin speed",
			      modes[spin]);
	o->canopen.mode = mode ? 9 : 8;
	return err;
}

/* Each canopen bus carries its tick with margin, in the 0x60C2 format, and
 * its SYNC's identifier is no drive's. */
static int canopen_buses(struct rl *rl)
{
	struct ld *l = rl->l;
	const struct rig_desc *r = rl->r;
	uint32_t k, i, hz = l->d->tick_hz;
	uint8_t ip;
	int8_t ex;

	for (k = 0; k < r->ndevices; k++) {
		const struct rig_canopen_desc *c = &r->devices[k].canopen;
		struct co_load load;

		if (r->devices[k].driver != RIG_DRIVER_CANOPEN || !rig_canopen_drives(r, k))
			continue;
		rig_canopen_load(r, k, hz, &load);
		if (!co_load_fits(&load))
			return ld_fail(l, rl->co_at[k], -EINVAL,
				       "canopen bus '%s': the worst case of a tick is %u bits (%u "
				       "drive%s, bit stuffing) of the %u a tick holds at %u bit/s "
				       "and %u ticks/s: %.0f%%, above %d%%; lower tick_hz, drive "
				       "fewer outputs on this bus or raise the bitrate",
				       r->devices[k].name, load.bits, load.drives,
				       load.drives == 1 ? "" : "s", load.capacity,
				       c->bitrate, hz, 100.0 * load.bits / load.capacity,
				       CO_LOAD_MAX_PERCENT);
		if (co_interp_period(hz, &ip, &ex) < 0)
			return ld_fail(l, rl->co_at[k], -EINVAL,
				       "canopen bus '%s': tick_hz %u: a drive's interpolation period "
				       "(0x60C2: 1 to 255 times a power of ten seconds) cannot say "
				       "%.6g us within 0.1%%", r->devices[k].name, hz, 1e6 / hz);
		for (i = 0; i < r->noutputs; i++) {
			uint32_t n = r->outputs[i].axis, id = c->sync_id;

			if (strcmp(r->outputs[i].device, r->devices[k].name))
				continue;
			if (id == CO_ID_EMCY + n || id == co_tpdo_id(1, (uint8_t)n) ||
			    id == co_rpdo_id(1, (uint8_t)n) || id == CO_ID_SDO_TX + n ||
			    id == CO_ID_SDO_RX + n || id == CO_ID_HEARTBEAT + n)
				return ld_fail(l, rl->co_at[k], -EINVAL,
					       "canopen bus '%s': sync_id 0x%x is an identifier of "
					       "node %u", r->devices[k].name, id, n);
		}
	}
	return 0;
}

static int output(struct rl *rl, yaml_node_t *map, uint32_t i, struct rig_output_desc *o,
		  const yaml_node_item_t *it)
{
	static const char *const keys[] = { "channel", "device", "axis", "counts_per_unit",
					    "offset", "limits", "ferror", "min_ferror",
					    "in_position", "home", "node", "mode", NULL };
	enum { O_CH, O_DEV, O_AXIS, O_CPU, O_OFF, O_LIM, O_FE, O_MINFE, O_INPOS, O_HOME,
	       O_NODE, O_MODE, O_N };
	struct ld *l = rl->l;
	yaml_node_t *v[O_N];
	const struct chan *c;
	double scale, *num[4] = { &o->ferror, &o->min_ferror, &o->in_position, &o->home };
	long long axis;
	int err, ch, dev, k;
	uint32_t j, used = 0;
	bool deg;

	err = ld_map(l, map, "output", keys, v);
	if (!err)
		err = ld_require(l, map, "output", v[O_CH], "channel");
	if (!err)
		err = ld_require(l, map, "output", v[O_DEV], "device");
	if (!err)
		err = ld_require(l, map, "output", v[O_CPU], "counts_per_unit");
	if (!err)
		err = lookup(rl, v[O_CH], "channel", rl->chan_names, "the scene's channels", &ch);
	if (!err)
		err = lookup(rl, v[O_DEV], "device", rl->dev_names, "devices:", &dev);
	if (err)
		return err;
	c = &rl->ch.c[ch];
	deg = is_angle(rl, c);
	o->channel = rl->chan_names[ch];
	o->device = rl->dev_names[dev];
	for (j = 0; j < i; j++)
		used += !strcmp(rl->r->outputs[j].device, o->device);
	axis = used; /* by default the next axis of the device */
	if (rl->r->devices[dev].driver == RIG_DRIVER_CANOPEN)
		err = canopen_output(rl, map, v[O_AXIS], v[O_NODE], v[O_MODE], c, o, &axis);
	else if (v[O_NODE] || v[O_MODE])
		err = ld_fail(l, v[O_NODE] ? v[O_NODE] : v[O_MODE], -EINVAL,
			      "node: and mode: place an output on a canopen device; '%s' is not one",
			      o->device);
	else if (v[O_AXIS])
		err = ld_int(l, v[O_AXIS], 0, 1023, &axis);
	if (err)
		return err;
	o->axis = (uint32_t)axis;
	for (j = 0; j < i; j++)
		if (!strcmp(rl->r->outputs[j].device, o->device) && rl->r->outputs[j].axis == o->axis)
			return ld_fail(l, v[O_NODE] ? v[O_NODE] : v[O_AXIS] ? v[O_AXIS] : map,
				       -EINVAL, "%s %u of device '%s' already drives '%s' (line %u)",
				       v[O_NODE] ? "node" : "axis", o->axis, o->device,
				       rl->r->outputs[j].channel,
				       (unsigned)ld_mark_of(ld_node(l, it[j])).line);
	err = ld_num(l, v[O_CPU], &o->counts_per_unit);
	if (err)
		return err;
	scale = fabs(o->counts_per_unit) * (deg ? 360 : 1);
	if (o->counts_per_unit == 0 || scale >= 2147483648.0)
		return ld_fail(l, v[O_CPU], -ERANGE,
			       "counts_per_unit must be non-zero and below 2^31 counts per %s",
			       deg ? "turn" : "unit");
	if (v[O_OFF])
		err = ld_num(l, v[O_OFF], &o->offset);
	if (!err && v[O_OFF] && fabs(o->offset) > 9e18)
		err = ld_fail(l, v[O_OFF], -ERANGE, "offset out of range");
	if (!err && v[O_LIM])
		err = ld_limits(l, v[O_LIM], deg, &o->limits);
	for (k = 0; !err && k < 4; k++)
		if (v[O_FE + k])
			err = k < 3 ? ld_num(l, v[O_FE + k], num[k]) :
				      ld_q32(l, v[O_FE + k], deg ? 1.0 / 360 : 1.0,
					     deg ? "degrees" : "scene units", num[k]);
	if (err)
		return err;
	if (o->ferror < 0 || o->min_ferror < 0 || o->in_position < 0)
		return ld_fail(l, map, -EINVAL, "ferror, min_ferror and in_position cannot be negative");
	if (o->ferror > 0 && o->min_ferror > o->ferror)
		return ld_fail(l, v[O_MINFE], -EINVAL, "min_ferror %.10g is above ferror %.10g",
			       o->min_ferror, o->ferror);
	/* moves and stops are planned with these: the output's, else its node's */
	if (c->kind == CHAN_VALUE) {
		const struct sd_limits *n = &l->d->nodes[c->index].limits;

		if (!o->limits.has_vel && n->has_vel) {
			o->limits.has_vel = true;
			o->limits.vel = n->vel;
		}
		if (!o->limits.has_acc && n->has_acc) {
			o->limits.has_acc = true;
			o->limits.acc = n->acc;
		}
	}
	if (!o->limits.has_vel || !o->limits.has_acc)
		return ld_fail(l, map, -EINVAL,
			       "output '%s' needs velocity and acceleration limits (here%s): the "
			       "pre-roll, the moves and every stop are planned with them",
			       o->channel, c->kind == CHAN_VALUE ? " or on its node" : "");
	return 0;
}

static int outputs(struct rl *rl, yaml_node_t *seq)
{
	struct ld *l = rl->l;
	struct rig_output_desc *out;
	yaml_node_item_t *it;
	size_t count, i;
	int err = ld_seq(l, seq, "outputs", &it, &count);

	if (err)
		return err;
	out = pool_array(l->pool, count ? count : 1, sizeof(*out));
	if (!out)
		return ld_nomem(l);
	rl->r->outputs = out;
	for (i = 0; i < count; i++) {
		err = output(rl, ld_node(l, it[i]), (uint32_t)i, &out[i], it);
		if (err)
			return err;
		rl->r->noutputs = (uint32_t)i + 1;
	}
	return 0;
}

/* A line of a device: not taken by an earlier trigger or input. */
static int line_free(struct rl *rl, yaml_node_t *at, const char *dev, uint32_t line)
{
	uint32_t j;

	for (j = 0; j < rl->r->ntriggers; j++)
		if (!strcmp(rl->r->triggers[j].device, dev) && rl->r->triggers[j].line == line)
			return ld_fail(rl->l, at, -EINVAL, "line %u of '%s' is trigger '%s' already",
				       line, dev, rl->r->triggers[j].name);
	for (j = 0; j < rl->r->ninputs; j++)
		if (!strcmp(rl->r->inputs[j].device, dev) && rl->r->inputs[j].line == line)
			return ld_fail(rl->l, at, -EINVAL, "line %u of '%s' is input '%s' already",
				       line, dev, rl->r->inputs[j].name);
	return 0;
}

static int trigger(struct rl *rl, yaml_node_t *map, struct rig_trigger_desc *t)
{
	static const char *const keys[] = { "name", "device", "line", "pulse_ms", "active_low",
					    "offset_ms", NULL };
	enum { G_NAME, G_DEV, G_LINE, G_PULSE, G_LOW, G_OFF, G_N };
	struct ld *l = rl->l;
	const struct scene_desc *d = l->d;
	yaml_node_t *v[G_N];
	double frame_ms = 1000.0 * d->rate_den / d->rate_num, tick_ms = 1000.0 / d->tick_hz;
	long long line;
	int err, dev;

	err = ld_map(l, map, "trigger", keys, v);
	if (!err)
		err = ld_require(l, map, "trigger", v[G_NAME], "name");
	if (!err)
		err = ld_require(l, map, "trigger", v[G_DEV], "device");
	if (!err)
		err = ld_require(l, map, "trigger", v[G_LINE], "line");
	if (!err)
		err = ld_name(l, v[G_NAME], &t->name);
	if (!err)
		err = lookup(rl, v[G_DEV], "device", rl->dev_names, "devices:", &dev);
	if (!err)
		err = ld_int(l, v[G_LINE], 0, 4095, &line);
	if (err)
		return err;
	t->device = rl->dev_names[dev];
	t->line = (uint32_t)line;
	t->pulse_ms = 1;
	if (v[G_PULSE])
		err = positive(l, v[G_PULSE], &t->pulse_ms);
	if (!err && v[G_LOW])
		err = ld_bool(l, v[G_LOW], &t->active_low);
	if (!err && v[G_OFF])
		err = ld_num(l, v[G_OFF], &t->offset_ms);
	if (!err)
		err = line_free(rl, v[G_LINE], t->device, t->line);
	if (err)
		return err;
	/* the player's rule (rig.c): whole ticks, at least one, ending before
	 * the next frame's edge; an offset of less than a frame */
	if (fmax(ceil(t->pulse_ms / tick_ms - 1e-9), 1) >= floor(frame_ms / tick_ms + 1e-9))
		return ld_fail(l, v[G_PULSE] ? v[G_PULSE] : map, -EINVAL,
			       "a %.10g ms pulse does not end before the next frame's (frames are "
			       "%.6g ms apart, ticks %.6g ms)", t->pulse_ms, frame_ms, tick_ms);
	if (fabs(t->offset_ms) >= frame_ms)
		return ld_fail(l, v[G_OFF], -EINVAL, "offset %.10g ms is a frame (%.6g ms) or more",
			       t->offset_ms, frame_ms);
	return 0;
}

static int input(struct rl *rl, yaml_node_t *map, struct rig_input_desc *in)
{
	static const char *const keys[] = { "name", "device", "line", "role", "active_low", NULL };
	static const char *const roles[] = { "estop", "stop", "camera_ready", NULL };
	enum { I_NAME, I_DEV, I_LINE, I_ROLE, I_LOW, I_N };
	struct ld *l = rl->l;
	yaml_node_t *v[I_N];
	long long line;
	int err, dev, role;

	err = ld_map(l, map, "input", keys, v);
	if (!err)
		err = ld_require(l, map, "input", v[I_NAME], "name");
	if (!err)
		err = ld_require(l, map, "input", v[I_DEV], "device");
	if (!err)
		err = ld_require(l, map, "input", v[I_LINE], "line");
	if (!err)
		err = ld_require(l, map, "input", v[I_ROLE], "role");
	if (!err)
		err = ld_name(l, v[I_NAME], &in->name);
	if (!err)
		err = lookup(rl, v[I_DEV], "device", rl->dev_names, "devices:", &dev);
	if (!err)
		err = ld_int(l, v[I_LINE], 0, 4095, &line);
	if (!err)
		err = ld_enum(l, v[I_ROLE], "input role", roles, &role);
	if (err)
		return err;
	in->device = rl->dev_names[dev];
	in->line = (uint32_t)line;
	in->role = role == 0 ? RIG_INPUT_ESTOP : role == 1 ? RIG_INPUT_STOP :
							     RIG_INPUT_CAMERA_READY;
	/* an e-stop chain is wired normally closed: asserted when it opens */
	in->active_low = in->role == RIG_INPUT_ESTOP;
	if (v[I_LOW])
		err = ld_bool(l, v[I_LOW], &in->active_low);
	if (!err)
		err = line_free(rl, v[I_LINE], in->device, in->line);
	return err;
}

static int lines(struct rl *rl, yaml_node_t *seq, bool trig)
{
	struct ld *l = rl->l;
	yaml_node_item_t *it;
	size_t count, i, size = trig ? sizeof(struct rig_trigger_desc) :
				       sizeof(struct rig_input_desc);
	void *arr;
	int err = ld_seq(l, seq, trig ? "triggers" : "inputs", &it, &count);

	if (err)
		return err;
	arr = pool_array(l->pool, count ? count : 1, size);
	if (!arr)
		return ld_nomem(l);
	if (trig)
		rl->r->triggers = arr;
	else
		rl->r->inputs = arr;
	for (i = 0; i < count; i++) {
		yaml_node_t *map = ld_node(l, it[i]);

		if (trig) {
			err = trigger(rl, map, (struct rig_trigger_desc *)arr + i);
			rl->r->ntriggers = (uint32_t)i + !err;
		} else {
			err = input(rl, map, (struct rig_input_desc *)arr + i);
			rl->r->ninputs = (uint32_t)i + !err;
		}
		if (err)
			return err;
	}
	return 0;
}

int ld_rig(struct ld *l, const struct ld_rig_sections *s)
{
	struct rl rl = { .l = l, .r = &l->sf->rig };
	uint32_t i;
	int err;

	if (!s->devices && !s->outputs && !s->triggers && !s->inputs)
		return 0;
	if (!s->devices)
		return ld_fail(l, s->outputs ? s->outputs : s->triggers ? s->triggers : s->inputs,
			       -EINVAL, "a rig needs its devices: section first");
	if (chan_list_make(&rl.ch, l->d))
		return ld_nomem(l);
	rl.chan_names = pool_array(l->pool, rl.ch.n + 1, sizeof(*rl.chan_names));
	err = rl.chan_names ? 0 : ld_nomem(l);
	for (i = 0; !err && i < rl.ch.n; i++) {
		rl.chan_names[i] = pool_strndup(l->pool, rl.ch.c[i].name, strlen(rl.ch.c[i].name));
		if (!rl.chan_names[i])
			err = ld_nomem(l);
	}
	if (!err)
		err = devices(&rl, s->devices);
	if (!err && s->outputs)
		err = outputs(&rl, s->outputs);
	if (!err)
		err = canopen_buses(&rl);
	if (!err && s->triggers)
		err = lines(&rl, s->triggers, true);
	if (!err && s->inputs)
		err = lines(&rl, s->inputs, false);
	chan_list_free(&rl.ch);
	return err;
}
