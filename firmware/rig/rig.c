/* SPDX-License-Identifier: MIT */
/*
 * rig.c - building and starting a rig (see rig.h): what every device has in
 * common, the outputs' scales and limits, the lines' places; each device
 * itself is its driver's (rig_driver.h).
 */
#include "rig.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rig_driver.h"
#include "hal/rt.h"
#include "plan/limit.h"

static int fail(char *err, size_t size, int code, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

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
	return lim_file_units(unit, v);
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

int rig_device(const struct rig *r, const char *name)
{
	uint32_t k;

	for (k = 0; k < r->ndev; k++)
		if (name && !strcmp(r->dev[k].desc->name, name))
			return (int)k;
	return -1;
}

uint32_t rig_axis_channels(const struct rig *r, uint32_t ax)
{
	uint32_t i, n = 0;

	for (i = 0; i < r->nout; i++)
		if (r->out[i].dev == ax && r->out[i].ch + 1 > n)
			n = r->out[i].ch + 1;
	return n;
}

int64_t rig_out_initial(const struct rig_out *o)
{
	return o->vel_mode ? 0 : hal_scale_counts(&o->scale, o->home, NULL);
}

/* Output i from its description: the rules of rig_desc.c, then the scale
 * and the limits in core units. */
static int make_output(struct rig_out *o, const struct rig_output_desc *od,
		       const struct src_channel *sc, uint32_t i, char *err, size_t size)
{
	struct sd_limits lim;
	double per_unit;
	char msg[256];
	bool at_min;
	int rc;

	o->unit = sc->unit;
	o->vel_mode = sc->unit == SRC_UNIT_RPM;
	rig_output_limits(&od->limits, &sc->limits, &lim);
	rc = rig_output_check_scale(od, sc->unit == SRC_UNIT_TURNS, msg, sizeof(msg));
	if (!rc)
		rc = rig_output_check_offset(od, msg, sizeof(msg));
	if (!rc)
		rc = rig_output_check_home(od, msg, sizeof(msg));
	if (!rc)
		rc = rig_output_check_ferror(od, &at_min, msg, sizeof(msg));
	if (!rc)
		rc = rig_output_check_limits(od->channel, &lim, true, msg, sizeof(msg));
	if (rc)
		return fail(err, size, rc, "outputs[%u] (%s): %s", i, od->channel, msg);
	/* the predicate's units, as strand check converts them (plan/limit.h) */
	{
		struct lim_bounds b = lim_bounds_of(&lim, o->unit);

		o->min = b.min;
		o->max = b.max;
		o->vmax = b.vel;
		o->amax = b.acc;
	}
	per_unit = od->counts_per_unit * (sc->unit == SRC_UNIT_TURNS ? 360.0 : 1.0);
	o->scale.per_unit = (mot_q32)llround(per_unit * 4294967296.0);
	o->scale.per_unit_d = (double)o->scale.per_unit / 4294967296.0;
	o->scale.offset = llround(od->offset);
	o->ferror = to_core(o->unit, od->ferror);
	o->min_ferror = to_core(o->unit, od->min_ferror);
	/* in position: half the bound at rest, or four counts */
	o->in_position = od->in_position > 0 ? to_core(o->unit, od->in_position) :
			 o->min_ferror > 0 ? o->min_ferror / 2 :
			 4.0 / fabs(o->scale.per_unit_d);
	o->home = (mot_q32)llround(to_core(o->unit, od->home) * 4294967296.0);
	return 0;
}

static int build_outputs(struct rig *r, const struct rig_desc *d, struct play_source *src,
			 char *err, size_t size)
{
	uint32_t i, *sel;
	int rc = 0;

	sel = calloc(d->noutputs ? d->noutputs : 1, sizeof(*sel));
	if (!sel)
		return fail(err, size, -ENOMEM, "out of memory");
	for (i = 0; !rc && i < d->noutputs; i++) {
		const struct rig_output_desc *od = &d->outputs[i];
		struct rig_out *o = &r->out[i];
		struct src_channel sc;
		int dev = find_device(d, od->device), idx;

		memset(&sc, 0, sizeof(sc));
		idx = src_lookup(src, od->channel, &sc);
		if (idx < 0) {
			rc = fail(err, size, -ENOENT, "outputs[%u]: no channel '%s' in scene '%s'", i,
				  od->channel, src->name);
			break;
		}
		if (dev < 0) {
			rc = fail(err, size, -ENOENT, "outputs[%u] (%s): no device '%s' in devices:",
				  i, od->channel, od->device ? od->device : "");
			break;
		}
		o->channel = od->channel;
		o->src = (uint32_t)idx;
		sel[i] = (uint32_t)idx;
		o->dev = (uint32_t)r->dev[dev].axis;
		o->ch = od->axis;
		rc = make_output(o, od, &sc, i, err, size);
	}
	if (!rc) {
		rc = src_select(src, sel, d->noutputs);
		if (rc)
			rc = fail(err, size, rc, "scene '%s': cannot evaluate the outputs' channels",
				  src->name);
	}
	free(sel);
	return rc;
}

int rig_bind(struct rig *r, const struct rig_desc *d, struct play_source *src, char *err,
	     size_t errsize)
{
	size_t nd = d->ndevices ? d->ndevices : 1;
	uint32_t i, k;
	int rc;

	memset(r, 0, sizeof(*r));
	r->nout = d->noutputs;
	r->ntrig = d->ntriggers;
	r->nin = d->ninputs;
	r->ndev = d->ndevices;
	r->out = calloc(r->nout ? r->nout : 1, sizeof(*r->out));
	r->trig = calloc(r->ntrig ? r->ntrig : 1, sizeof(*r->trig));
	r->in = calloc(r->nin ? r->nin : 1, sizeof(*r->in));
	r->dev = calloc(nd, sizeof(*r->dev));
	r->axes = calloc(nd, sizeof(*r->axes));
	r->douts = calloc(nd, sizeof(*r->douts));
	r->dins = calloc(nd, sizeof(*r->dins));
	r->ready = calloc(nd, sizeof(*r->ready));
	if (!r->out || !r->trig || !r->in || !r->dev || !r->axes || !r->douts || !r->dins ||
	    !r->ready) {
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
	for (k = 0; k < d->ndevices; k++) {
		const char *key;
		char msg[160];

		rc = rig_sim_check(&d->devices[k].sim, &key, msg, sizeof(msg));
		if (rc) {
			rc = fail(err, errsize, rc, "devices[%u] (%s): sim: %s", k,
				  d->devices[k].name, msg);
			goto out;
		}
	}
	/* the devices that carry outputs become axis devices, in file order */
	for (k = 0; k < d->ndevices; k++) {
		struct rig_dev *dv = &r->dev[k];

		dv->desc = &d->devices[k];
		dv->axis = dv->dout = dv->din = -1;
		for (i = 0; i < d->noutputs; i++)
			if (find_device(d, d->outputs[i].device) == (int)k) {
				dv->axis = (int32_t)r->naxes++;
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
	rc = build_outputs(r, d, src, err, errsize);
out:
	if (rc)
		rig_free(r);
	return rc;
}

/* The drivers' checks of the whole description, for one made in code (a
 * loaded one has passed them, at their places in the file). */
static int validate(const struct rig_desc *d, uint32_t tick_hz, char *err, size_t size)
{
	struct rig_desc_err e;
	int rc = rig_desc_validate(d, tick_hz, &e);

	if (!rc)
		return 0;
	if (e.output >= 0)
		return fail(err, size, rc, "outputs[%u] (%s): %s", (unsigned)e.output,
			    d->outputs[e.output].channel, e.msg);
	return fail(err, size, rc, "%s", e.msg);
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

/* Index of line i among the lines of its device (triggers or inputs). */
static uint32_t line_index(const struct rig_desc *d, uint32_t i, bool trig)
{
	const char *dev = trig ? d->triggers[i].device : d->inputs[i].device;
	uint32_t k, n = 0;

	for (k = 0; k < i; k++)
		n += !strcmp(trig ? d->triggers[k].device : d->inputs[k].device, dev);
	return n;
}

/* Every device's lines by its driver, then each trigger's and input's place
 * on them. */
static int build_lines(struct rig_make *m, char *err, size_t size)
{
	const struct rig_desc *d = m->d;
	struct rig *r = m->r;
	uint32_t i, k;
	int rc;

	for (k = 0; k < d->ndevices; k++) {
		uint32_t nt = count_role(d, (int)k, true), ni = count_role(d, (int)k, false);
		struct rig_dev *dv = &r->dev[k];

		if (!nt && !ni)
			continue;
		if (!dv->drv->make_lines)
			return fail(err, size, -ENOTSUP,
				    "device '%s': driver %s has no trigger or input lines; play with "
				    "--sim", dv->desc->name, dv->desc->driver->name);
		dv->dout = nt ? (int32_t)r->ndouts++ : -1;
		dv->din = ni ? (int32_t)r->ndins++ : -1;
		rc = dv->drv->make_lines(m, k, nt, ni, err, size);
		if (rc)
			return rc;
		if (dv->desc->has_ready)
			r->ready[r->nready++] = (struct rig_line){ .dev = (uint32_t)dv->dout,
								   .line = nt - 1 };
	}
	for (i = 0; i < d->ntriggers; i++) {
		const struct rig_trigger_desc *td = &d->triggers[i];
		int dev = find_device(d, td->device);

		if (dev < 0)
			return fail(err, size, -ENOENT, "triggers[%u] (%s): no device '%s' in devices:",
				    i, td->name, td->device ? td->device : "");
		r->trig[i].dev = (uint32_t)r->dev[dev].dout;
		r->trig[i].line = line_index(d, i, true);
		if (r->dev[dev].drv->bind &&
		    (rc = r->dev[dev].drv->bind(m, (uint32_t)dev, true, i, r->trig[i].line, err,
						size)))
			return rc;
	}
	for (i = 0; i < d->ninputs; i++) {
		const struct rig_input_desc *id = &d->inputs[i];
		int dev = find_device(d, id->device);

		if (dev < 0)
			return fail(err, size, -ENOENT, "inputs[%u] (%s): no device '%s' in devices:",
				    i, id->name, id->device ? id->device : "");
		r->in[i].name = id->name;
		r->in[i].dev = (uint32_t)r->dev[dev].din;
		r->in[i].line = line_index(d, i, false);
		r->in[i].role = id->role;
		if (r->dev[dev].drv->bind &&
		    (rc = r->dev[dev].drv->bind(m, (uint32_t)dev, false, i, r->in[i].line, err,
						size)))
			return rc;
	}
	return 0;
}

int rig_build(struct rig *r, const struct rig_desc *d, struct play_source *src,
	      struct hal_clock *clk, const struct rig_opts *o, char *err, size_t errsize)
{
	struct rig_make m = { .r = r, .d = d, .clk = clk, .o = o, .t = &src->timing };
	uint32_t i, k;
	int rc;

	STRAND_ASSERT_NOT_RT();
	rc = rig_bind(r, d, src, err, errsize);
	if (rc)
		return rc;
	r->cancel = o->cancel;
	rc = validate(d, src->timing.tick_hz, err, errsize);
	if (rc)
		goto out;
	for (k = 0; k < d->ndevices; k++) {
		struct rig_dev *dv = &r->dev[k];

		if (!dv->desc->driver) {
			rc = fail(err, errsize, -EINVAL, "device '%s': no driver", dv->desc->name);
			goto out;
		}
		/* under --sim every device is its simulated twin */
		dv->drv = o->sim ? rig_driver_twin : dv->desc->driver;
		if (dv->axis < 0)
			continue;
		if (!dv->drv->make_axes) {
			rc = fail(err, errsize, -ENOTSUP,
				  "device '%s': driver %s is not in this build yet; play with --sim",
				  dv->desc->name, dv->desc->driver->name);
			goto out;
		}
		rc = dv->drv->make_axes(&m, k, err, errsize);
		if (rc)
			goto out;
	}
	for (i = 0; i < d->ntriggers; i++) {
		const struct rig_trigger_desc *td = &d->triggers[i];
		char msg[256];
		bool at_offset;

		r->trig[i].name = td->name;
		rc = rig_trigger_check(td, &src->timing, &r->trig[i].width, &r->trig[i].offset,
				       &at_offset, msg, sizeof(msg));
		if (rc) {
			fail(err, errsize, rc, "triggers[%u] (%s): %s", i, td->name, msg);
			goto out;
		}
	}
	rc = build_lines(&m, err, errsize);
	if (rc)
		goto out;
	r->started_axes = calloc(r->naxes ? r->naxes : 1, sizeof(bool));
	r->started_douts = calloc(r->ndouts ? r->ndouts : 1, sizeof(bool));
	r->started_dins = calloc(r->ndins ? r->ndins : 1, sizeof(bool));
	if (!r->started_axes || !r->started_douts || !r->started_dins)
		rc = fail(err, errsize, -ENOMEM, "out of memory");
out:
	if (rc)
		rig_free(r);
	return rc;
}

/* A stop asked for while the devices start (a signal): no device starts
 * after it, those started are stopped. 0, or -ECANCELED saying where. */
static int given_up(const struct rig *r, const char *before, char *err, size_t size)
{
	if (!hal_cancelled(r->cancel))
		return 0;
	if (before)
		return fail(err, size, -ECANCELED, "start given up before device '%s'", before);
	return fail(err, size, -ECANCELED, "start given up after every device had started");
}

int rig_start(struct rig *r, char *err, size_t errsize)
{
	struct hal_fault f;
	uint32_t i;
	int rc;

	STRAND_ASSERT_NOT_RT();
	/* what only a run takes (real GPIO lines: one held by another process
	 * is a device error, with a message naming the chip and the line) */
	for (i = 0; i < r->ndev; i++) {
		if ((rc = given_up(r, r->dev[i].desc->name, err, errsize)))
			return rc;
		if (r->dev[i].drv && r->dev[i].drv->start &&
		    (rc = r->dev[i].drv->start(r, i, err, errsize)))
			return rc;
	}

	for (i = 0; i < r->naxes; i++) {
		/* a backend's start that waits looks at r->cancel itself */
		if ((rc = given_up(r, r->axes[i]->name, err, errsize)))
			goto undo;
		rc = hal_axis_start(r->axes[i]);
		if (rc)
			goto fail_axis;
		r->started_axes[i] = true;
	}
	for (i = 0; i < r->ndouts; i++) {
		if ((rc = given_up(r, r->douts[i]->name, err, errsize)))
			goto undo;
		rc = hal_dout_start(r->douts[i]);
		if (rc) {
			fail(err, errsize, rc, "device '%s': trigger lines: %s", r->douts[i]->name,
			     strerror(-rc));
			goto undo;
		}
		r->started_douts[i] = true;
	}
	for (i = 0; i < r->ndins; i++) {
		if ((rc = given_up(r, r->dins[i]->name, err, errsize)))
			goto undo;
		rc = hal_din_start(r->dins[i]);
		if (rc) {
			fail(err, errsize, rc, "device '%s': input lines: %s", r->dins[i]->name,
			     strerror(-rc));
			goto undo;
		}
		r->started_dins[i] = true;
	}
	if ((rc = given_up(r, NULL, err, errsize)))
		goto undo;
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
	if (rc == -ECANCELED)
		fail(err, errsize, rc, "device '%s': start given up", r->axes[i]->name);
	else if (hal_axis_fault(r->axes[i], &f) && f.cause)
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

	STRAND_ASSERT_NOT_RT();
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

void rig_report(const struct rig *r, FILE *f)
{
	uint32_t k;

	for (k = 0; k < r->ndev; k++)
		if (r->dev[k].drv && r->dev[k].drv->report)
			r->dev[k].drv->report(r, k, f);
}

void rig_free(struct rig *r)
{
	uint32_t k;

	STRAND_ASSERT_NOT_RT();
	rig_stop(r);
	/* each driver releases what it made, its HAL objects included */
	for (k = 0; r->dev && k < r->ndev; k++)
		if (r->dev[k].drv && r->dev[k].drv->free)
			r->dev[k].drv->free(r, k);
	free(r->axes);
	free(r->douts);
	free(r->dins);
	free(r->out);
	free(r->trig);
	free(r->in);
	free(r->dev);
	free(r->ready);
	free(r->started_axes);
	free(r->started_douts);
	free(r->started_dins);
	memset(r, 0, sizeof(*r));
}
