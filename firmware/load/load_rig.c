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
#include <stdio.h>
#include <string.h>

#include "scene/channel.h"

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

/* `line:`, a number (the line's offset on its chip) or the line's name
 * (the chip's gpio-line-names, as gpioinfo shows them). */
static int line_spec(struct ld *l, yaml_node_t *n, uint32_t *line, const char **name)
{
	long long v = 0;
	int err;

	*name = NULL;
	if (n->type == YAML_SCALAR_NODE && n->data.scalar.length &&
	    (n->data.scalar.value[0] < '0' || n->data.scalar.value[0] > '9'))
		return ld_str(l, n, name);
	err = ld_int(l, n, 0, 4095, &v);
	*line = (uint32_t)v;
	return err;
}

/* `ready: {line: L, active_low: B}`: the device's rig-ready output. */
static int ready_output(struct ld *l, yaml_node_t *map, struct rig_device_desc *dev)
{
	static const char *const keys[] = { "line", "active_low", NULL };
	yaml_node_t *v[2];
	int err = ld_map(l, map, "ready", keys, v);

	if (!err)
		err = ld_require(l, map, "ready", v[0], "line");
	if (!err)
		err = line_spec(l, v[0], &dev->ready_line, &dev->ready_line_name);
	if (!err && v[1])
		err = ld_bool(l, v[1], &dev->ready_active_low);
	dev->has_ready = !err;
	return err;
}

static int devices(struct rl *rl, yaml_node_t *seq)
{
	static const char *const keys[] = { "name", "driver", "sim", "chip", "ready", "modbus",
					    "canopen", NULL };
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
		yaml_node_t *map = ld_node(l, it[i]), *v[7];
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
		if (!err && v[3] && drv != RIG_DRIVER_GPIO)
			err = ld_fail(l, v[3], -EINVAL, "chip: is for a device with driver gpio");
		if (!err && v[3])
			err = ld_str(l, v[3], &dev[i].chip);
		if (!err && v[4])
			err = ready_output(l, v[4], &dev[i]);
		if (!err && (drv == RIG_DRIVER_CANOPEN) != !!v[6])
			err = ld_fail(l, v[6] ? v[6] : map, -EINVAL, v[6] ?
				      "a canopen: section belongs to a device of driver canopen" :
				      "a device of driver canopen needs its canopen: section");
		if (!err && v[6])
			err = ld_canopen_bus(l, v[6], &dev[i].canopen);
		if (err)
			return err;
		rl->co_at[i] = v[6];
		dev[i].driver = (enum rig_driver)drv;
		/* a Modbus device's bus and register map (load_modbus.c) */
		if ((dev[i].driver == RIG_DRIVER_MODBUS) != !!v[5])
			return ld_fail(l, v[5] ? v[5] : map, -EINVAL, v[5] ?
				       "a modbus: section belongs to a device of driver modbus" :
				       "a device of driver modbus needs its modbus: section");
		if (v[5] && (err = ld_modbus(l, v[5], &dev[i])))
			return err;
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
		err = ld_canopen_output(l, map, v[O_AXIS], v[O_NODE], v[O_MODE], c, o, &axis);
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

static bool same_line(const char *dev_a, uint32_t a, const char *name_a, const char *dev_b,
		      uint32_t b, const char *name_b)
{
	if (strcmp(dev_a, dev_b) || !name_a != !name_b)
		return false;
	return name_a ? !strcmp(name_a, name_b) : a == b;
}

/* A line of a device: not taken by an earlier trigger or input. (A line
 * given by number and by name at once is the backend's to find.) */
static int line_free(struct rl *rl, yaml_node_t *at, const char *dev, uint32_t line,
		     const char *name)
{
	char what[80];
	uint32_t j;

	if (name)
		snprintf(what, sizeof(what), "line '%s'", name);
	else
		snprintf(what, sizeof(what), "line %u", line);
	for (j = 0; j < rl->r->ntriggers; j++) {
		const struct rig_trigger_desc *t = &rl->r->triggers[j];

		if (same_line(t->device, t->line, t->line_name, dev, line, name))
			return ld_fail(rl->l, at, -EINVAL, "%s of '%s' is trigger '%s' already",
				       what, dev, t->name);
	}
	for (j = 0; j < rl->r->ninputs; j++) {
		const struct rig_input_desc *in = &rl->r->inputs[j];

		if (same_line(in->device, in->line, in->line_name, dev, line, name))
			return ld_fail(rl->l, at, -EINVAL, "%s of '%s' is input '%s' already",
				       what, dev, in->name);
	}
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
		err = line_spec(l, v[G_LINE], &t->line, &t->line_name);
	if (err)
		return err;
	t->device = rl->dev_names[dev];
	t->pulse_ms = 1;
	if (v[G_PULSE])
		err = positive(l, v[G_PULSE], &t->pulse_ms);
	if (!err && v[G_LOW])
		err = ld_bool(l, v[G_LOW], &t->active_low);
	if (!err && v[G_OFF])
		err = ld_num(l, v[G_OFF], &t->offset_ms);
	if (!err)
		err = line_free(rl, v[G_LINE], t->device, t->line, t->line_name);
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
		err = line_spec(l, v[I_LINE], &in->line, &in->line_name);
	if (!err)
		err = ld_enum(l, v[I_ROLE], "input role", roles, &role);
	if (err)
		return err;
	in->device = rl->dev_names[dev];
	in->role = role == 0 ? RIG_INPUT_ESTOP : role == 1 ? RIG_INPUT_STOP :
							     RIG_INPUT_CAMERA_READY;
	/* an e-stop chain is wired normally closed: asserted when it opens */
	in->active_low = in->role == RIG_INPUT_ESTOP;
	if (v[I_LOW])
		err = ld_bool(l, v[I_LOW], &in->active_low);
	if (!err)
		err = line_free(rl, v[I_LINE], in->device, in->line, in->line_name);
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
		err = ld_modbus_outputs(l, rl.r, s->outputs);
	if (!err)
		err = ld_canopen_buses(l, rl.r, rl.co_at);
	if (!err && s->triggers)
		err = lines(&rl, s->triggers, true);
	if (!err && s->inputs)
		err = lines(&rl, s->inputs, false);
	chan_list_free(&rl.ch);
	return err;
}
