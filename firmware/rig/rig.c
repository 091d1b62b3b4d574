/* SPDX-License-Identifier: MIT */
/* rig.c - building and starting a rig (see rig.h). */
#include "rig.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rig_canopen.h"
#include "rig_modbus.h"
#include "sim/co_simbus.h"
#include "sim/sim_camera.h"
#include "sim/sim_drive.h"
#include "sim/sim_gpio.h"

static const char *const driver_name[] = {
	[RIG_DRIVER_SIM] = "sim",
	[RIG_DRIVER_MODBUS] = "modbus",
	[RIG_DRIVER_GPIO] = "gpio",
	[RIG_DRIVER_CANOPEN] = "canopen",
};

static int fail(char *err, size_t size, int code, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(err, size, fmt, ap);
	va_end(ap);
	return code;
}

double rig_file_units(enum src_unit unit, double v)
{
	return unit == SRC_UNIT_TURNS ? v * 360.0 : v;
}

const char *rig_unit_name(enum src_unit unit)
{
	switch (unit) {
	case SRC_UNIT_TURNS:
		return "deg";
	case SRC_UNIT_RPM:
		return "rpm";
	default:
		return "";
	}
}

static double to_core(enum src_unit unit, double v)
{
	return unit == SRC_UNIT_TURNS ? v / 360.0 : v;
}

static int find_device(const struct rig_desc *d, const char *name)
{
	uint32_t i;

	for (i = 0; i < d->ndevices; i++)
		if (name && !strcmp(d->devices[i].name, name))
			return (int)i;
	return -1;
}

static double sim_or(double v, double dflt)
{
	return v > 0 ? v : dflt;
}

/* Limits of output i: the output's where set, else the scene's. */
static int out_limits(struct rig_out *o, const struct rig_output_desc *od,
		      const struct src_channel *sc, uint32_t i, char *err, size_t size)
{
	const struct sd_limits *a = &od->limits, *b = &sc->limits;

	o->min = a->has_min ? to_core(o->unit, a->min) :
		 b->has_min ? to_core(o->unit, b->min) : -INFINITY;
	o->max = a->has_max ? to_core(o->unit, a->max) :
		 b->has_max ? to_core(o->unit, b->max) : INFINITY;
	o->vmax = a->has_vel ? to_core(o->unit, a->vel) : b->has_vel ? to_core(o->unit, b->vel) : 0;
	o->amax = a->has_acc ? to_core(o->unit, a->acc) : b->has_acc ? to_core(o->unit, b->acc) : 0;
	if (!(o->vmax > 0) || !isfinite(o->vmax))
		return fail(err, size, -EINVAL,
			    "outputs[%u] (%s): needs a velocity limit (on the output or its node): "
			    "pre-roll, moves and stops are planned with it", i, od->channel);
	if (!(o->amax > 0) || !isfinite(o->amax))
		return fail(err, size, -EINVAL,
			    "outputs[%u] (%s): needs an acceleration limit (on the output or its "
			    "node): pre-roll, moves and stops are planned with it", i, od->channel);
	if (o->min > o->max)
		return fail(err, size, -EINVAL, "outputs[%u] (%s): limits min > max", i,
			    od->channel);
	return 0;
}

static int build_outputs(struct rig *r, const struct rig_desc *d, struct play_source *src,
			 const int *dev_axis, char *err, size_t size)
{
	uint32_t i, *sel;
	int rc;

	sel = calloc(d->noutputs ? d->noutputs : 1, sizeof(*sel));
	if (!sel)
		return fail(err, size, -ENOMEM, "out of memory");
	for (i = 0; i < d->noutputs; i++) {
		const struct rig_output_desc *od = &d->outputs[i];
		struct rig_out *o = &r->out[i];
		struct src_channel sc;
		double per_unit;
		int dev = find_device(d, od->device), idx;

		memset(&sc, 0, sizeof(sc));
		idx = src_lookup(src, od->channel, &sc);
		if (idx < 0) {
			rc = fail(err, size, -ENOENT, "outputs[%u]: no channel '%s' in scene '%s'", i,
				  od->channel, src->name);
			goto out;
		}
		if (dev < 0) {
			rc = fail(err, size, -ENOENT, "outputs[%u] (%s): no device '%s' in devices:",
				  i, od->channel, od->device ? od->device : "");
			goto out;
		}
		o->channel = od->channel;
		o->src = (uint32_t)idx;
		sel[i] = (uint32_t)idx;
		o->dev = (uint32_t)dev_axis[dev];
		o->ch = od->axis;
		o->unit = sc.unit;
		o->vel_mode = sc.unit == SRC_UNIT_RPM;
		rc = out_limits(o, od, &sc, i, err, size);
		if (rc)
			goto out;
		per_unit = od->counts_per_unit * (sc.unit == SRC_UNIT_TURNS ? 360.0 : 1.0);
		if (!isfinite(per_unit) || per_unit == 0 || fabs(per_unit) >= 2147483648.0) {
			rc = fail(err, size, -ERANGE,
				  "outputs[%u] (%s): counts_per_unit %g: must be non-zero and below "
				  "2^31 counts per %s", i, od->channel, od->counts_per_unit,
				  sc.unit == SRC_UNIT_TURNS ? "turn" : "unit");
			goto out;
		}
		if (!isfinite(od->offset) || fabs(od->offset) > 9e18) {
			rc = fail(err, size, -ERANGE, "outputs[%u] (%s): offset out of range", i,
				  od->channel);
			goto out;
		}
		o->scale.per_unit = (mot_q32)llround(per_unit * 4294967296.0);
		o->scale.per_unit_d = (double)o->scale.per_unit / 4294967296.0;
		o->scale.offset = llround(od->offset);
		o->ferror = to_core(o->unit, od->ferror);
		o->min_ferror = to_core(o->unit, od->min_ferror);
		if (o->ferror < 0 || o->min_ferror < 0 || (o->ferror && o->min_ferror > o->ferror)) {
			rc = fail(err, size, -EINVAL,
				  "outputs[%u] (%s): need 0 <= min_ferror <= ferror", i, od->channel);
			goto out;
		}
		/* in position: half the bound at rest, or four counts */
		o->in_position = od->in_position > 0 ? to_core(o->unit, od->in_position) :
				 o->min_ferror > 0 ? o->min_ferror / 2 :
				 4.0 / fabs(o->scale.per_unit_d);
		o->home = (mot_q32)llround(to_core(o->unit, od->home) * 4294967296.0);
	}
	rc = src_select(src, sel, d->noutputs);
	if (rc)
		rc = fail(err, size, rc, "scene '%s': cannot evaluate the outputs' channels",
			  src->name);
out:
	free(sel);
	return rc;
}

/* The simulated drive standing in for device k: one channel per axis used. */
static int make_sim_drive(struct rig *r, const struct rig_desc *d, uint32_t k, uint32_t ax,
			  uint32_t tick_hz, char *err, size_t size)
{
	const struct rig_device_desc *dd = &d->devices[k];
	struct sim_drive_channel *ch;
	uint32_t i, nch = 0;
	double lf = sim_or(dd->sim.limit_factor, SIM_DRIVE_DEFAULT_LIMIT_FACTOR);
	int rc;

	for (i = 0; i < r->nout; i++)
		if (r->out[i].dev == ax && r->out[i].ch + 1 > nch)
			nch = r->out[i].ch + 1;
	ch = calloc(nch, sizeof(*ch));
	if (!ch)
		return fail(err, size, -ENOMEM, "out of memory");
	for (i = 0; i < nch; i++) {
		ch[i].bandwidth_hz = sim_or(dd->sim.bandwidth_hz, SIM_DRIVE_DEFAULT_BANDWIDTH_HZ);
		ch[i].damping = sim_or(dd->sim.damping, SIM_DRIVE_DEFAULT_DAMPING);
		ch[i].feedforward = dd->sim.feedforward > 0 ? fmin(dd->sim.feedforward, 1) :
				    SIM_DRIVE_DEFAULT_FEEDFORWARD;
	}
	for (i = 0; i < r->nout; i++) {
		const struct rig_out *o = &r->out[i];
		struct sim_drive_channel *c = &ch[o->ch];
		double pu = fabs(o->scale.per_unit_d);

		if (o->dev != ax)
			continue;
		c->vel_max = o->vel_mode ? 0 : lf * o->vmax * pu;
		c->acc_max = o->vel_mode ? 0 : lf * o->amax * pu;
		c->velocity_mode = o->vel_mode;
		c->initial = o->vel_mode ? 0 : hal_scale_counts(&o->scale, o->home, NULL);
	}
	rc = sim_drive_new(&r->sim_drive[ax], dd->name, nch, tick_hz, ch, err, size);
	free(ch);
	if (rc)
		return rc;
	r->axes[ax] = sim_drive_axis(r->sim_drive[ax]);
	return 0;
}

static int check_lines(struct rig *r, const struct rig_desc *d, const struct mot_timing *t,
		       char *err, size_t size)
{
	/* the shortest gap between two frame ticks: floor(ticks per frame) */
	int64_t gap = (int64_t)(t->ticks_den / t->num);
	uint32_t i;

	for (i = 0; i < d->ntriggers; i++) {
		const struct rig_trigger_desc *td = &d->triggers[i];
		struct rig_trig *g = &r->trig[i];

		g->name = td->name;
		g->width = (int64_t)ceil(td->pulse_ms * t->tick_hz / 1000.0 - 1e-9);
		if (g->width < 1)
			g->width = 1;
		g->offset = llround(td->offset_ms * t->tick_hz / 1000.0);
		if (g->width >= gap)
			return fail(err, size, -EINVAL,
				    "triggers[%u] (%s): a %g ms pulse is %lld ticks: it must end "
				    "before the next frame's, %lld ticks later", i, td->name,
				    td->pulse_ms, (long long)g->width, (long long)gap);
		if (llabs(g->offset) >= gap)
			return fail(err, size, -EINVAL,
				    "triggers[%u] (%s): offset %g ms is a frame or more", i,
				    td->name, td->offset_ms);
	}
	return 0;
}

/* Device k's output (trig) or input lines; the outputs are its triggers,
 * then its rig-ready line. */
static uint32_t count_role(const struct rig_desc *d, int k, bool trig)
{
	uint32_t i, n = 0;

	if (trig) {
		for (i = 0; i < d->ntriggers; i++)
			n += find_device(d, d->triggers[i].device) == k;
		n += d->devices[k].has_ready; /* the last output line */
	} else {
		for (i = 0; i < d->ninputs; i++)
			n += find_device(d, d->inputs[i].device) == k;
	}
	return n;
}

/* Is device k simulated in this run? */
static bool simulated(const struct rig_desc *d, uint32_t k, const struct rig_opts *o)
{
	return o->sim || d->devices[k].driver == RIG_DRIVER_SIM;
}

/* Index of line i among the lines of its device (triggers or inputs). */
static uint32_t line_index(const struct rig_desc *d, uint32_t i, bool trig)
{
	const char *dev = trig ? d->triggers[i].device : d->inputs[i].device;
	uint32_t k, n = 0;

	for (k = 0; k < i; k++)
		n += !strcmp(trig ? d->triggers[k].device : d->inputs[k].device, dev);
	return n;
}

/*
 * Device k's trigger (trig) or input lines on a real GPIO chip, in the
 * order rig_trig.line and rig_in.line number them, to be requested by
 * rig_start() into douts[] or dins[] at index at. The loop's thread
 * priority goes to the input event thread.
 */
static int plan_gpio(struct rig *r, const struct rig_desc *d, uint32_t k, bool trig, uint32_t n,
		     uint32_t at, const struct rig_opts *o, char *err, size_t size)
{
	const struct rig_device_desc *dd = &d->devices[k];
	struct rig_gpio *g = &r->gpio[r->ngpio];
	uint32_t i, j = 0, count = trig ? d->ntriggers : d->ninputs;

	g->lines = calloc(n, sizeof(*g->lines));
	if (!g->lines)
		return fail(err, size, -ENOMEM, "out of memory");
	r->ngpio++;
	for (i = 0; i < count; i++) {
		const char *dev = trig ? d->triggers[i].device : d->inputs[i].device;

		if (find_device(d, dev) != (int)k)
			continue;
		g->lines[j].name = trig ? d->triggers[i].line_name : d->inputs[i].line_name;
		g->lines[j].offset = trig ? d->triggers[i].line : d->inputs[i].line;
		g->lines[j].active_low = trig ? d->triggers[i].active_low : d->inputs[i].active_low;
		j++;
	}
	if (trig && dd->has_ready)
		g->lines[j] = (struct hal_gpio_line){ .name = dd->ready_line_name,
						      .offset = dd->ready_line,
						      .active_low = dd->ready_active_low };
	g->cfg = (struct hal_gpio_cfg){ .device = dd->name, .chip = dd->chip, .nlines = n,
					.lines = g->lines, .priority = o->gpio_priority };
	g->trig = trig;
	g->at = at;
	return 0;
}

/* Request the lines planned by plan_gpio(). */
static int open_gpio(struct rig *r, char *err, size_t size)
{
	uint32_t i;
	int rc;

	for (i = 0; i < r->ngpio; i++) {
		struct rig_gpio *g = &r->gpio[i];

		if (g->trig)
			rc = hal_gpio_dout_open(&r->douts[g->at], &g->cfg, err, size);
		else
			rc = hal_gpio_din_open(&r->dins[g->at], &g->cfg, err, size);
		if (rc)
			return rc;
	}
	return 0;
}

static int build_gpio(struct rig *r, const struct rig_desc *d, const struct rig_opts *o,
		      struct hal_clock *clk, const struct mot_timing *t, char *err, size_t size)
{
	double frame_ns = 1e9 * t->den / t->num;
	size_t nd = d->ndevices ? d->ndevices : 1;
	int *dev_gpio = calloc(nd, sizeof(int)), *dev_dout = calloc(nd, sizeof(int));
	int *dev_din = calloc(nd, sizeof(int));
	uint32_t i, k, nline;
	int rc = 0;

	r->sim_gpio = calloc(nd, sizeof(*r->sim_gpio));
	r->douts = calloc(nd, sizeof(*r->douts));
	r->dins = calloc(nd, sizeof(*r->dins));
	r->gpio = calloc(2 * nd, sizeof(*r->gpio));
	r->ready = calloc(nd, sizeof(*r->ready));
	r->camera = calloc(d->ntriggers ? d->ntriggers : 1, sizeof(*r->camera));
	if (!dev_gpio || !dev_dout || !dev_din || !r->sim_gpio || !r->douts || !r->dins ||
	    !r->gpio || !r->ready || !r->camera) {
		rc = fail(err, size, -ENOMEM, "out of memory");
		goto out;
	}
	for (k = 0; k < d->ndevices; k++) {
		uint32_t nt = count_role(d, (int)k, true), ni = count_role(d, (int)k, false);
		struct sim_gpio *g;

		dev_gpio[k] = dev_dout[k] = dev_din[k] = -1;
		if (!nt && !ni)
			continue;
		if (!simulated(d, k, o) && d->devices[k].driver == RIG_DRIVER_GPIO) {
			dev_dout[k] = nt ? (int)r->ndouts++ : -1;
			dev_din[k] = ni ? (int)r->ndins++ : -1;
			rc = nt ? plan_gpio(r, d, k, true, nt, (uint32_t)dev_dout[k], o, err, size) : 0;
			if (!rc && ni)
				rc = plan_gpio(r, d, k, false, ni, (uint32_t)dev_din[k], o, err, size);
			if (rc)
				goto out;
			continue;
		}
		if (!simulated(d, k, o)) {
			rc = fail(err, size, -ENOTSUP,
				  "device '%s': driver %s has no trigger or input lines; play with "
				  "--sim", d->devices[k].name, driver_name[d->devices[k].driver]);
			goto out;
		}
		/* queue: two camera-ready edges per frame in flight, and a few
		 * scheduled by tests */
		rc = sim_gpio_new(&g, d->devices[k].name, nt, ni, clk, 64, err, size);
		if (rc)
			goto out;
		dev_gpio[k] = (int)r->nsim_gpio;
		r->sim_gpio[r->nsim_gpio++] = g;
		dev_dout[k] = (int)r->ndouts;
		dev_din[k] = (int)r->ndins;
		r->douts[r->ndouts++] = sim_gpio_dout(g);
		r->dins[r->ndins++] = sim_gpio_din(g);
		if (d->devices[k].has_ready)
			sim_gpio_out_polarity(g, nt - 1, d->devices[k].ready_active_low);
	}
	for (k = 0; k < d->ndevices; k++)
		if (d->devices[k].has_ready)
			r->ready[r->nready++] = (struct rig_line){
				.dev = (uint32_t)dev_dout[k],
				.line = count_role(d, (int)k, true) - 1 };
	for (i = 0; i < d->ntriggers; i++) {
		const struct rig_trigger_desc *td = &d->triggers[i];
		int dev = find_device(d, td->device);
		struct sim_camera_params cp;
		struct sim_gpio *g;
		char why[160];

		if (dev < 0) {
			rc = fail(err, size, -ENOENT, "triggers[%u] (%s): no device '%s' in devices:",
				  i, td->name, td->device ? td->device : "");
			goto out;
		}
		nline = line_index(d, i, true);
		r->trig[i].dev = (uint32_t)dev_dout[dev];
		r->trig[i].line = nline;
		if (dev_gpio[dev] < 0)
			continue; /* a real line: a real camera, polarity set at the request */
		g = r->sim_gpio[dev_gpio[dev]];
		sim_gpio_out_polarity(g, nline, td->active_low);
		cp.exposure_ns = (int64_t)(sim_or(d->devices[dev].sim.exposure_ms,
						  SIM_CAMERA_DEFAULT_EXPOSURE_FRAC * frame_ns / 1e6) * 1e6);
		cp.readout_ns = (int64_t)(sim_or(d->devices[dev].sim.readout_ms,
						 SIM_CAMERA_DEFAULT_READOUT_FRAC * frame_ns / 1e6) * 1e6);
		rc = sim_camera_new(&r->camera[i], &cp, o->camera_cap ? o->camera_cap : 1 << 16,
				    i == 0 ? o->camera_log : NULL, why, sizeof(why));
		if (rc) {
			fail(err, size, rc, "triggers[%u] (%s): %s", i, td->name, why);
			goto out;
		}
		sim_camera_trigger(r->camera[i], g, nline);
	}
	for (i = 0; i < d->ninputs; i++) {
		const struct rig_input_desc *id = &d->inputs[i];
		int dev = find_device(d, id->device);
		struct sim_gpio *g;

		if (dev < 0) {
			rc = fail(err, size, -ENOENT, "inputs[%u] (%s): no device '%s' in devices:", i,
				  id->name, id->device ? id->device : "");
			goto out;
		}
		nline = line_index(d, i, false);
		r->in[i].name = id->name;
		r->in[i].dev = (uint32_t)dev_din[dev];
		r->in[i].line = nline;
		r->in[i].role = id->role;
		if (dev_gpio[dev] < 0)
			continue;
		g = r->sim_gpio[dev_gpio[dev]];
		sim_gpio_in_polarity(g, nline, id->active_low);
		/* the first camera tells when it is ready through this line */
		if (id->role == RIG_INPUT_CAMERA_READY && d->ntriggers && r->camera[0])
			sim_camera_ready(r->camera[0], g, nline);
	}
out:
	free(dev_gpio);
	free(dev_dout);
	free(dev_din);
	return rc;
}

int rig_build(struct rig *r, const struct rig_desc *d, struct play_source *src,
	      struct hal_clock *clk, const struct rig_opts *o, char *err, size_t errsize)
{
	int *dev_axis = NULL;
	uint32_t i, k;
	int rc;

	memset(r, 0, sizeof(*r));
	r->nout = d->noutputs;
	r->ntrig = d->ntriggers;
	r->nin = d->ninputs;
	r->out = calloc(r->nout ? r->nout : 1, sizeof(*r->out));
	r->trig = calloc(r->ntrig ? r->ntrig : 1, sizeof(*r->trig));
	r->in = calloc(r->nin ? r->nin : 1, sizeof(*r->in));
	dev_axis = calloc(d->ndevices ? d->ndevices : 1, sizeof(*dev_axis));
	r->axes = calloc(d->ndevices ? d->ndevices : 1, sizeof(*r->axes));
	r->sim_drive = calloc(d->ndevices ? d->ndevices : 1, sizeof(*r->sim_drive));
	r->co_sim = calloc(d->ndevices ? d->ndevices : 1, sizeof(*r->co_sim));
	if (!r->out || !r->trig || !r->in || !dev_axis || !r->axes || !r->sim_drive ||
	    !r->co_sim) {
		rc = fail(err, errsize, -ENOMEM, "out of memory");
		goto out;
	}
	for (i = 0; i < d->ndevices; i++)
		for (k = i + 1; k < d->ndevices; k++)
			if (!strcmp(d->devices[i].name, d->devices[k].name)) {
				rc = fail(err, errsize, -EINVAL, "devices[%u]: '%s' named twice", k,
					  d->devices[k].name);
				goto out;
			}
	/* the devices that carry outputs become axis devices, in file order */
	for (k = 0; k < d->ndevices; k++) {
		dev_axis[k] = -1;
		for (i = 0; i < d->noutputs; i++)
			if (find_device(d, d->outputs[i].device) == (int)k) {
				dev_axis[k] = (int)r->naxes++;
				break;
			}
	}
	for (i = 0; i < d->noutputs; i++)
		for (k = i + 1; k < d->noutputs; k++)
			if (!strcmp(d->outputs[i].device, d->outputs[k].device) &&
			    d->outputs[i].axis == d->outputs[k].axis) {
				rc = fail(err, errsize, -EINVAL,
					  "outputs[%u] (%s): axis %u of device '%s' is already "
					  "driven by outputs[%u] (%s)", k, d->outputs[k].channel,
					  d->outputs[k].axis, d->outputs[k].device, i,
					  d->outputs[i].channel);
				goto out;
			}
	rc = build_outputs(r, d, src, dev_axis, err, errsize);
	if (rc)
		goto out;
	for (k = 0; k < d->ndevices; k++) {
		if (dev_axis[k] < 0)
			continue;
		if (!o->sim && d->devices[k].driver == RIG_DRIVER_CANOPEN) {
			rc = rig_canopen_make(r, d, k, (uint32_t)dev_axis[k], src->timing.tick_hz,
					      clk, err, errsize);
			if (rc)
				goto out;
			continue;
		}
		if (!o->sim && d->devices[k].driver == RIG_DRIVER_MODBUS) {
			rc = rig_modbus_open(r, d, k, (uint32_t)dev_axis[k], src->timing.tick_hz,
					     clk->is_virtual, err, errsize);
			if (rc)
				goto out;
			continue;
		}
		if (!o->sim && d->devices[k].driver != RIG_DRIVER_SIM) {
			rc = fail(err, errsize, -ENOTSUP,
				  "device '%s': driver %s is not in this build yet; play with --sim",
				  d->devices[k].name, driver_name[d->devices[k].driver]);
			goto out;
		}
		rc = make_sim_drive(r, d, k, (uint32_t)dev_axis[k], src->timing.tick_hz, err,
				    errsize);
		if (rc)
			goto out;
	}
	rc = check_lines(r, d, &src->timing, err, errsize);
	if (!rc)
		rc = build_gpio(r, d, o, clk, &src->timing, err, errsize);
	if (rc)
		goto out;
	r->started_axes = calloc(r->naxes ? r->naxes : 1, sizeof(bool));
	r->started_douts = calloc(r->ndouts ? r->ndouts : 1, sizeof(bool));
	r->started_dins = calloc(r->ndins ? r->ndins : 1, sizeof(bool));
	if (!r->started_axes || !r->started_douts || !r->started_dins)
		rc = fail(err, errsize, -ENOMEM, "out of memory");
out:
	free(dev_axis);
	if (rc)
		rig_free(r);
	return rc;
}

int rig_start(struct rig *r, char *err, size_t errsize)
{
	struct hal_fault f;
	uint32_t i;
	int rc;

	/* real lines are requested now: one held by another process is a
	 * device error, with a message naming the chip and the line */
	rc = open_gpio(r, err, errsize);
	if (rc)
		return rc;

	for (i = 0; i < r->naxes; i++) {
		rc = hal_axis_start(r->axes[i]);
		if (rc)
			goto fail_axis;
		r->started_axes[i] = true;
	}
	for (i = 0; i < r->ndouts; i++) {
		rc = hal_dout_start(r->douts[i]);
		if (rc) {
			fail(err, errsize, rc, "device '%s': trigger lines: %s", r->douts[i]->name,
			     strerror(-rc));
			goto undo;
		}
		r->started_douts[i] = true;
	}
	for (i = 0; i < r->ndins; i++) {
		rc = hal_din_start(r->dins[i]);
		if (rc) {
			fail(err, errsize, rc, "device '%s': input lines: %s", r->dins[i]->name,
			     strerror(-rc));
			goto undo;
		}
		r->started_dins[i] = true;
	}
	/* every device is up: the rig is ready (rig_stop's deasserting every
	 * line says it no longer is) */
	for (i = 0; i < r->nready; i++) {
		hal_dout_set(r->douts[r->ready[i].dev], r->ready[i].line, true);
		rc = hal_dout_commit(r->douts[r->ready[i].dev], 0);
		if (rc) {
			fail(err, errsize, rc, "device '%s': rig-ready line: %s",
			     r->douts[r->ready[i].dev]->name, strerror(-rc));
			goto undo;
		}
	}
	return 0;
fail_axis:
	/* a backend that latched why names the bus, unit and register */
	if (hal_axis_fault(r->axes[i], &f) && f.cause)
		fail(err, errsize, rc, "device '%s': start: %s (%s)", r->axes[i]->name, f.cause,
		     strerror(-rc));
	else
		fail(err, errsize, rc, "device '%s': start: %s", r->axes[i]->name, strerror(-rc));
undo:
	rig_stop(r);
	return rc;
}

void rig_stop(struct rig *r)
{
	uint32_t i;

	for (i = 0; i < r->naxes; i++)
		if (r->started_axes && r->started_axes[i]) {
			hal_axis_stop(r->axes[i]);
			r->started_axes[i] = false;
		}
	for (i = 0; i < r->ndouts; i++)
		if (r->started_douts && r->started_douts[i]) {
			hal_dout_stop(r->douts[i]);
			r->started_douts[i] = false;
		}
	for (i = 0; i < r->ndins; i++)
		if (r->started_dins && r->started_dins[i]) {
			hal_din_stop(r->dins[i]);
			r->started_dins[i] = false;
		}
}

void rig_free(struct rig *r)
{
	uint32_t i;

	rig_stop(r);
	for (i = 0; i < r->naxes; i++)
		hal_axis_close(r->axes[i]);
	for (i = 0; r->camera && i < r->ntrig; i++)
		sim_camera_free(r->camera[i]);
	for (i = 0; i < r->nsim_gpio; i++)
		sim_gpio_free(r->sim_gpio[i]);
	for (i = 0; r->co_sim && i < r->naxes; i++)
		co_simbus_free(r->co_sim[i]);
	for (i = 0; i < r->ngpio; i++) {
		if (r->gpio[i].trig)
			hal_dout_close(r->douts[r->gpio[i].at]);
		else
			hal_din_close(r->dins[r->gpio[i].at]);
		free(r->gpio[i].lines);
	}
	free(r->axes);
	free(r->douts);
	free(r->dins);
	free(r->out);
	free(r->trig);
	free(r->in);
	free(r->sim_drive);
	free(r->co_sim);
	free(r->sim_gpio);
	free(r->gpio);
	free(r->ready);
	free(r->camera);
	free(r->started_axes);
	free(r->started_douts);
	free(r->started_dins);
	memset(r, 0, sizeof(*r));
}
