/* SPDX-License-Identifier: MIT */
/*
 * load_rig.c - the rig sections of a scene file: `devices:`, `outputs:`,
 * `triggers:` and `inputs:` (rig_desc.h has the schema). Everything the
 * player would otherwise refuse at start is reported here, at its place in
 * the file: an unknown device or channel (with the closest name), an axis
 * or line used twice, an output without speed and acceleration limits, a
 * trigger pulse that would overlap the next frame's, by the rules of
 * rig_desc.c. A device's driver reads its own settings, and those of an
 * output on it, and checks the whole rig once every output is read
 * (rig_driver.h); this file never tests which driver a device has.
 */
#include "load_priv.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rig/rig_driver.h"
#include "scene/channel.h"

/* Keys of a mapping at most, drivers at most. */
#define RL_KEYS_MAX 48
#define RL_DRIVERS_MAX 16

/* The keys of a device's or an output's mapping: the loader's own, then the
 * drivers' settings; owner[i] is the driver of key[i], NULL for the
 * loader's. A driver's keys are consecutive. */
struct rl_keys {
	const char *key[RL_KEYS_MAX + 1];
	const struct rig_driver *owner[RL_KEYS_MAX];
	uint32_t n;
	uint32_t ready;   /* a device's: the index of ready: */
};

/* What the rig sections need while they are read. */
struct rl {
	struct ld *l;
	struct rig_desc *r;
	struct chan_list ch;
	const char **chan_names; /* NULL-terminated, for suggestions */
	const char **dev_names;
	yaml_node_t **dev_map;   /* each device's mapping */
	yaml_node_item_t *out_it; /* the outputs' items */
	uint32_t *out_item;      /* each output's item (a pattern makes several) */
	struct rl_keys dk, ok;   /* a device's keys, an output's */
	const char *drv_names[RL_DRIVERS_MAX + 1];
	struct mot_timing t;     /* the scene's, for the triggers */
};

static void keys_add(struct rl_keys *k, const char *const *names, const struct rig_driver *owner)
{
	for (; names && *names && k->n < RL_KEYS_MAX; names++) {
		k->owner[k->n] = owner;
		k->key[k->n++] = *names;
	}
	k->key[k->n] = NULL;
}

/* A device's keys: name, driver, sim, then the drivers' settings; those of
 * a driver of lines before ready: (the rig-ready line is one of its
 * lines), the others' after it. */
static void device_keys(struct rl *rl)
{
	static const char *const head[] = { "name", "driver", "sim", NULL };
	static const char *const ready[] = { "ready", NULL };
	const struct rig_driver *const *d;
	struct rl_keys *k = &rl->dk;

	k->n = 0;
	keys_add(k, head, NULL);
	for (d = rig_drivers; *d; d++)
		if ((*d)->make_lines)
			keys_add(k, (*d)->device_keys, *d);
	k->ready = k->n;
	keys_add(k, ready, NULL);
	for (d = rig_drivers; *d; d++)
		if (!(*d)->make_lines)
			keys_add(k, (*d)->device_keys, *d);
}

/* The values of driver drv's keys among v[] into dv[], in its order;
 * returns the first one present, or NULL. */
static yaml_node_t *driver_values(const struct rl_keys *k, yaml_node_t *const *v,
				  const struct rig_driver *drv, yaml_node_t **dv)
{
	yaml_node_t *first = NULL;
	uint32_t i, j = 0;

	for (i = 0; i < k->n; i++)
		if (k->owner[i] == drv) {
			dv[j++] = v[i];
			first = first ? first : v[i];
		}
	return first;
}

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

static int sim_params(struct ld *l, yaml_node_t *map, struct rig_sim_desc *s)
{
	static const char *const keys[] = { "bandwidth", "damping", "feedforward",
					    "limit_factor", "exposure_ms", "readout_ms", NULL };
	yaml_node_t *v[6];
	double *out[6] = { &s->bandwidth_hz, &s->damping, &s->feedforward, &s->limit_factor,
			   &s->exposure_ms, &s->readout_ms };
	int i, err = ld_map(l, map, "sim", keys, v);

	const char *key;
	char msg[160];

	for (i = 0; !err && i < 6; i++)
		if (v[i])
			err = ld_positive(l, v[i], out[i]);
	if (!err && v[2] && s->feedforward > 1)
		err = ld_fail(l, v[2], -EINVAL, "feedforward is a fraction, 0 to 1");
	/* the ranges rig_build() holds a description to (rig_desc.h) */
	if (!err && (err = rig_sim_check(s, &key, msg, sizeof(msg))))
		for (i = 0; i < 6; i++)
			if (!strcmp(keys[i], key))
				return ld_fail(l, v[i], err, "%s", msg);
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
	int err = ld_map_req(l, map, "ready", keys, v, YML_REQ(0));

	if (!err)
		err = line_spec(l, v[0], &dev->ready_line, &dev->ready_line_name);
	if (!err && v[1])
		err = ld_bool(l, v[1], &dev->ready_active_low);
	dev->has_ready = !err;
	return err;
}

static int devices(struct rl *rl, yaml_node_t *seq)
{
	struct ld *l = rl->l;
	struct rig_device_desc *dev;
	yaml_node_item_t *it;
	size_t count, i;
	int err = ld_seq(l, seq, "devices", &it, &count);

	if (err)
		return err;
	dev = pool_array(l->pool, count ? count : 1, sizeof(*dev));
	rl->dev_names = pool_array(l->pool, count + 1, sizeof(*rl->dev_names));
	rl->dev_map = pool_array(l->pool, count ? count : 1, sizeof(*rl->dev_map));
	if (!dev || !rl->dev_names || !rl->dev_map)
		return ld_nomem(l);
	for (i = 0; i < count; i++) {
		yaml_node_t *map = ld_node(l, it[i]), *v[RL_KEYS_MAX], *dv[RL_KEYS_MAX];
		struct rig_parse p = { .y = &l->y, .tick_hz = l->d->tick_hz, .map = map, .v = dv };
		const struct rig_driver *drv = NULL;
		uint32_t j;
		int d, k;

		rl->dev_map[i] = map;
		err = ld_map(l, map, "device", rl->dk.key, v);
		if (!err)
			err = ld_require(l, map, "device", v[0], "name");
		if (!err)
			err = ld_require(l, map, "device", v[1], "driver");
		if (!err)
			err = ld_name(l, v[0], &dev[i].name);
		if (!err)
			err = ld_enum(l, v[1], "driver", rl->drv_names, &d);
		if (!err && v[2])
			err = sim_params(l, v[2], &dev[i].sim);
		if (!err)
			drv = rig_drivers[d];
		/* the drivers' settings and ready:, in the keys' order: a
		 * driver reads its own, another's is refused */
		for (j = 3; !err && j < rl->dk.n; j++) {
			const struct rig_driver *o = rl->dk.owner[j];
			yaml_node_t *first;

			if (j == rl->dk.ready) {
				if (v[j])
					err = ready_output(l, v[j], &dev[i]);
				continue;
			}
			if (!o || rl->dk.owner[j - 1] == o)
				continue; /* a driver once, at its first key */
			first = driver_values(&rl->dk, v, o, dv);
			if (o != drv && first)
				err = ld_fail(l, first, -EINVAL, "%s", o->device_foreign);
			else if (o == drv && o->parse_device)
				err = o->parse_device(&p, &dev[i]);
		}
		/* a driver without keys of its own reads its settings last */
		if (!err && !drv->device_keys && drv->parse_device)
			err = drv->parse_device(&p, &dev[i]);
		if (err)
			return err;
		dev[i].driver = drv;
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
	return (c->kind == CHAN_CAMERA && c->comp >= 3) || c->kind == CHAN_AIM ||
	       (c->kind == CHAN_SYS && chan_is_angle(c));
}

/* An output's keys: the loader's, then the drivers' (in the table's order). */
enum { O_CH, O_DEV, O_AXIS, O_CPU, O_OFF, O_LIM, O_FE, O_MINFE, O_INPOS, O_HOME, O_STRIDE,
       O_N };

static void output_keys(struct rl *rl)
{
	static const char *const own[] = { "channel", "device", "axis", "counts_per_unit",
					   "offset", "limits", "ferror", "min_ferror",
					   "in_position", "home", "stride", NULL };
	const struct rig_driver *const *d;

	rl->ok.n = 0;
	keys_add(&rl->ok, own, NULL);
	for (d = rig_drivers; *d; d++)
		keys_add(&rl->ok, (*d)->output_keys, *d);
}

/* The axis of output o on its device: axis:, or what its driver reads;
 * another driver's keys are refused. */
static int output_axis(struct rl *rl, yaml_node_t *map, yaml_node_t *const *v,
		       const struct chan *c, const struct rig_driver *drv,
		       struct rig_output_desc *o, long long *axis, yaml_node_t **at)
{
	const struct rig_driver *const *d;
	struct ld *l = rl->l;
	yaml_node_t *dv[RL_KEYS_MAX], *first;
	struct rig_parse p = { .y = &l->y, .tick_hz = l->d->tick_hz, .map = map, .v = dv };

	for (d = rig_drivers; *d; d++)
		if (*d != drv && (first = driver_values(&rl->ok, v, *d, dv)))
			return ld_fail(l, first, -EINVAL, "%s; '%s' is not one",
				       (*d)->output_foreign, o->device);
	*at = v[O_AXIS];
	p.dev = &rl->r->devices[find(rl->dev_names, o->device)];
	if (drv->parse_output) {
		driver_values(&rl->ok, v, drv, dv);
		return drv->parse_output(&p, v[O_AXIS], c, o, axis, at);
	}
	return v[O_AXIS] ? ld_int(l, v[O_AXIS], 0, 1023, axis) : 0;
}

/* A channel pattern: '*' stands for one or more characters other than '.'. */
static bool glob(const char *pat, const char *name)
{
	if (!*pat)
		return !*name;
	if (*pat == '*') {
		const char *n = name;

		if (!*n || *n == '.')
			return false;
		for (; *n && *n != '.'; n++)
			if (glob(pat + 1, n + 1))
				return true;
		return false;
	}
	return *pat == *name && glob(pat + 1, name + 1);
}

/* The channels a pattern matches, in the channels' order (row by row for
 * a surface's samples): their count, and their indices into idx when not
 * NULL. */
static uint32_t matches(const struct rl *rl, const char *pat, uint32_t *idx)
{
	uint32_t i, n = 0;

	for (i = 0; i < rl->ch.n; i++)
		if (glob(pat, rl->chan_names[i])) {
			if (idx)
				idx[n] = i;
			n++;
		}
	return n;
}

/* An output's item: a channel, or a pattern and the one of its matches
 * this output is (k, ch). */
struct out_item {
	bool pattern;
	uint32_t k;
	int ch;
};

static int output(struct rl *rl, yaml_node_t *map, uint32_t i, struct rig_output_desc *o,
		  const yaml_node_item_t *it, const struct out_item *pi)
{
	struct ld *l = rl->l;
	yaml_node_t *v[RL_KEYS_MAX], *axis_at = NULL;
	const struct rig_driver *drv;
	const struct chan *c;
	double *num[4] = { &o->ferror, &o->min_ferror, &o->in_position, &o->home };
	char msg[256];
	long long axis;
	int err, ch, dev, k;
	uint32_t j, used = 0;
	bool deg, at_min;

	err = ld_map(l, map, "output", rl->ok.key, v);
	if (!err)
		err = ld_require(l, map, "output", v[O_CH], "channel");
	if (!err)
		err = ld_require(l, map, "output", v[O_DEV], "device");
	if (!err)
		err = ld_require(l, map, "output", v[O_CPU], "counts_per_unit");
	if (!err && pi->pattern)
		ch = pi->ch;
	else if (!err)
		err = lookup(rl, v[O_CH], "channel", rl->chan_names, "the scene's channels", &ch);
	if (!err)
		err = lookup(rl, v[O_DEV], "device", rl->dev_names, "devices:", &dev);
	if (!err && v[O_STRIDE] && !pi->pattern)
		err = ld_fail(l, v[O_STRIDE], -EINVAL,
			      "stride spaces the outputs of a channel pattern (a channel with '*')");
	if (err)
		return err;
	c = &rl->ch.c[ch];
	deg = is_angle(rl, c);
	drv = rl->r->devices[dev].driver;
	o->channel = rl->chan_names[ch];
	o->device = rl->dev_names[dev];
	for (j = 0; j < i; j++)
		used += !strcmp(rl->r->outputs[j].device, o->device);
	axis = used; /* by default the next axis of the device */
	err = output_axis(rl, map, v, c, drv, o, &axis, &axis_at);
	if (err)
		return err;
	if (pi->pattern && pi->k) {
		/* the pattern's k-th match: stride axes on from the first's (the
		 * first's own default is the device's next axis) */
		long long stride = 1;

		if (v[O_STRIDE] && (err = ld_int(l, v[O_STRIDE], 1, 1 << 20, &stride)))
			return err;
		axis = (long long)rl->r->outputs[i - pi->k].axis + stride * (long long)pi->k;
		if (axis > (1 << 24))
			return ld_fail(l, map, -EINVAL, "the pattern's %u-th channel would take axis "
				       "%lld", pi->k + 1, axis);
	}
	o->axis = (uint32_t)axis;
	for (j = 0; j < i; j++)
		if (!strcmp(rl->r->outputs[j].device, o->device) && rl->r->outputs[j].axis == o->axis)
			return ld_fail(l, axis_at ? axis_at : map, -EINVAL,
				       "%s %u of device '%s' already drives '%s' (line %u)",
				       drv->axis_name ? drv->axis_name : "axis", o->axis, o->device,
				       rl->r->outputs[j].channel,
				       (unsigned)ld_mark_of(ld_node(l, it[rl->out_item[j]])).line);
	err = ld_num(l, v[O_CPU], &o->counts_per_unit);
	if (err)
		return err;
	err = rig_output_check_scale(o, deg, msg, sizeof(msg));
	if (err)
		return ld_fail(l, v[O_CPU], err, "%s", msg);
	if (v[O_OFF])
		err = ld_num(l, v[O_OFF], &o->offset);
	if (!err && v[O_OFF] && (err = rig_output_check_offset(o, msg, sizeof(msg))))
		err = ld_fail(l, v[O_OFF], err, "%s", msg);
	if (!err && v[O_LIM])
		err = ld_limits(l, v[O_LIM], deg, &o->limits);
	/* distances, in the core's range as every distance of a scene */
	for (k = 0; !err && k < 4; k++)
		if (v[O_FE + k])
			err = ld_q32(l, v[O_FE + k], deg ? 1.0 / 360 : 1.0,
				     deg ? "degrees" : c->kind == CHAN_RPM ? "rpm" : "scene units",
				     num[k]);
	if (!err && v[O_HOME] && (err = rig_output_check_home(o, msg, sizeof(msg))))
		err = ld_fail(l, v[O_HOME], err, "%s", msg);
	if (err)
		return err;
	err = rig_output_check_ferror(o, &at_min, msg, sizeof(msg));
	if (err)
		return ld_fail(l, at_min ? v[O_MINFE] : map, err, "%s", msg);
	/* moves and stops are planned with these: the output's, else its node's */
	rig_output_limits(&o->limits, chan_limits(c, l->d), &o->limits);
	err = rig_output_check_limits(o->channel, &o->limits, chan_limits(c, l->d) != NULL, msg,
				      sizeof(msg));
	if (err)
		return ld_fail(l, map, err, "%s", msg);
	return 0;
}

/* The pattern of an item's channel: the string, if it has a '*'. */
static const char *pattern_of(struct rl *rl, yaml_node_t *map)
{
	yaml_node_t *c = map->type == YAML_MAPPING_NODE ? yml_value(&rl->l->y, map, "channel") :
							  NULL;
	const char *s = c && c->type == YAML_SCALAR_NODE ? (const char *)c->data.scalar.value :
							    NULL;

	return s && strchr(s, '*') ? s : NULL;
}

static int outputs(struct rl *rl, yaml_node_t *seq)
{
	struct ld *l = rl->l;
	struct rig_output_desc *out;
	yaml_node_item_t *it;
	size_t count, i, total = 0;
	uint32_t *idx = NULL, n = 0, k;
	int err = ld_seq(l, seq, "outputs", &it, &count);

	if (err)
		return err;
	/* a channel pattern is an output for each channel it matches */
	for (i = 0; i < count; i++) {
		const char *pat = pattern_of(rl, ld_node(l, it[i]));

		n = pat ? matches(rl, pat, NULL) : 1;
		if (!n)
			return ld_fail(l, yml_value(&l->y, ld_node(l, it[i]), "channel"), -EINVAL,
				       "channel pattern '%s' matches no channel of the scene ('*' "
				       "stands for a part between dots: skin.*.*.y)", pat);
		total += n;
	}
	out = pool_array(l->pool, total ? total : 1, sizeof(*out));
	rl->out_item = pool_array(l->pool, total ? total : 1, sizeof(*rl->out_item));
	idx = pool_array(l->pool, rl->ch.n ? rl->ch.n : 1, sizeof(*idx));
	if (!out || !rl->out_item || !idx)
		return ld_nomem(l);
	rl->r->outputs = out;
	rl->out_it = it;
	for (i = 0, total = 0; i < count; i++) {
		yaml_node_t *map = ld_node(l, it[i]);
		const char *pat = pattern_of(rl, map);
		struct out_item pi = { pat != NULL, 0, -1 };

		n = pat ? matches(rl, pat, idx) : 1;
		for (k = 0; k < n; k++, total++) {
			pi.k = k;
			pi.ch = pat ? (int)idx[k] : -1;
			rl->out_item[total] = (uint32_t)i;
			err = output(rl, map, (uint32_t)total, &out[total], it, &pi);
			if (err)
				return err;
			rl->r->noutputs = (uint32_t)total + 1;
		}
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
	yaml_node_t *v[G_N];
	int64_t width, offset;
	char msg[256];
	bool at_offset;
	int err, dev;

	err = ld_map_req(l, map, "trigger", keys, v,
			 YML_REQ(G_NAME) | YML_REQ(G_DEV) | YML_REQ(G_LINE));
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
		err = ld_positive(l, v[G_PULSE], &t->pulse_ms);
	if (!err && v[G_LOW])
		err = ld_bool(l, v[G_LOW], &t->active_low);
	if (!err && v[G_OFF])
		err = ld_num(l, v[G_OFF], &t->offset_ms);
	if (!err)
		err = line_free(rl, v[G_LINE], t->device, t->line, t->line_name);
	if (err)
		return err;
	/* the player's rules (rig_desc.c): whole ticks, at least one, ending
	 * before the next frame's edge; an offset of less than a frame */
	err = rig_trigger_check(t, &rl->t, &width, &offset, &at_offset, msg, sizeof(msg));
	if (err)
		return ld_fail(l, at_offset ? v[G_OFF] : v[G_PULSE] ? v[G_PULSE] : map, err, "%s",
			       msg);
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

	err = ld_map_req(l, map, "input", keys, v,
			 YML_REQ(I_NAME) | YML_REQ(I_DEV) | YML_REQ(I_LINE) | YML_REQ(I_ROLE));
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

/* The drivers' checks of the whole rig, at the place they name. */
static int validate(struct rl *rl)
{
	struct ld *l = rl->l;
	struct rig_desc_err e;
	yaml_node_t *at = NULL;
	int err = rig_desc_validate(rl->r, l->d->tick_hz, &e);

	if (!err)
		return 0;
	if (e.output >= 0) {
		at = ld_node(l, rl->out_it[rl->out_item[e.output]]);
		if (e.key && yml_value(&l->y, at, e.key))
			at = yml_value(&l->y, at, e.key);
	} else if (e.device >= 0)
		at = e.key ? yml_value(&l->y, rl->dev_map[e.device], e.key) : NULL;
	if (!at && e.device >= 0)
		at = rl->dev_map[e.device];
	return ld_fail(l, at, err, "%s", e.msg);
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
	for (i = 0; rig_drivers[i] && i < RL_DRIVERS_MAX; i++)
		rl.drv_names[i] = rig_drivers[i]->name;
	device_keys(&rl);
	output_keys(&rl);
	/* ld_timing has checked what mot_timing_init checks */
	mot_timing_init(&rl.t, l->d->rate_num, l->d->rate_den, l->d->tick_hz);
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
		err = validate(&rl);
	if (!err && s->triggers)
		err = lines(&rl, s->triggers, true);
	if (!err && s->inputs)
		err = lines(&rl, s->inputs, false);
	chan_list_free(&rl.ch);
	return err;
}
