/* SPDX-License-Identifier: MIT */
/* drv_sim.c - the simulated twins (see drv_sim.h). */
#include "drv_sim.h"
#include "scene/num.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* What the twin of one device is made of. */
struct sim_dev {
	struct sim_drive *drive;   /* its outputs, or NULL */
	struct sim_gpio *gpio;     /* its lines, or NULL */
	uint32_t ncam;
	struct sim_camera **cam;   /* ncam: a camera on each trigger line, by line */
};

static double or_default(double v, double dflt)
{
	return v > 0 ? v : dflt;
}

void rig_sim_plant(const struct rig_sim_desc *s, struct sim_drive_channel *ch)
{
	*ch = (struct sim_drive_channel){
		.bandwidth_hz = or_default(s->bandwidth_hz, SIM_DRIVE_DEFAULT_BANDWIDTH_HZ),
		.damping = or_default(s->damping, SIM_DRIVE_DEFAULT_DAMPING),
		.feedforward = s->feedforward > 0 ? fmin(s->feedforward, 1) :
						    SIM_DRIVE_DEFAULT_FEEDFORWARD,
	};
}

void rig_sim_channel(const struct rig_out *o, const struct rig_sim_desc *s,
		     struct sim_drive_channel *ch)
{
	double lf = or_default(s->limit_factor, SIM_DRIVE_DEFAULT_LIMIT_FACTOR);
	double pu = fabs(o->scale.per_unit_d);

	rig_sim_plant(s, ch);
	ch->vel_max = o->vel_mode ? 0 : lf * o->vmax * pu;
	ch->acc_max = o->vel_mode ? 0 : lf * o->amax * pu;
	ch->velocity_mode = o->vel_mode;
	ch->initial = rig_out_initial(o);
}

int rig_sim_drive_new(struct sim_drive **out, const struct rig *r, uint32_t k,
		      uint32_t tick_hz, char *err, size_t errsize)
{
	const struct rig_device_desc *dd = r->dev[k].desc;
	uint32_t ax = (uint32_t)r->dev[k].axis, nch = rig_axis_channels(r, ax), i;
	struct sim_drive_channel *ch = calloc(nch ? nch : 1, sizeof(*ch));
	int rc;

	*out = NULL;
	if (!ch) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	/* a channel no output uses is a plant at rest */
	for (i = 0; i < nch; i++)
		rig_sim_plant(&dd->sim, &ch[i]);
	for (i = 0; i < r->nout; i++)
		if (r->out[i].dev == ax)
			rig_sim_channel(&r->out[i], &dd->sim, &ch[r->out[i].ch]);
	rc = sim_drive_new(out, dd->name, nch, tick_hz, ch, err, errsize);
	free(ch);
	return rc;
}

/* Device k's twin, made on first use. */
static struct sim_dev *dev_of(struct rig *r, uint32_t k)
{
	if (!r->dev[k].priv)
		r->dev[k].priv = calloc(1, sizeof(struct sim_dev));
	return r->dev[k].priv;
}

static int sim_make_axes(struct rig_make *m, uint32_t k, char *err, size_t errsize)
{
	struct sim_dev *sd = dev_of(m->r, k);
	int rc;

	if (!sd) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	rc = rig_sim_drive_new(&sd->drive, m->r, k, m->t->tick_hz, err, errsize);
	if (rc)
		return rc;
	m->r->axes[m->r->dev[k].axis] = sim_drive_axis(sd->drive);
	return 0;
}

static int sim_make_lines(struct rig_make *m, uint32_t k, uint32_t nt, uint32_t ni, char *err,
			  size_t errsize)
{
	const struct rig_dev *dv = &m->r->dev[k];
	struct sim_dev *sd = dev_of(m->r, k);
	int rc;

	if (!sd || !(sd->cam = calloc(nt ? nt : 1, sizeof(*sd->cam)))) {
		snprintf(err, errsize, "out of memory");
		return -ENOMEM;
	}
	sd->ncam = nt;
	/* queue: two camera-ready edges per frame in flight, and a few
	 * scheduled by tests */
	rc = sim_gpio_new(&sd->gpio, dv->desc->name, nt, ni, m->clk, 64, err, errsize);
	if (rc)
		return rc;
	if (dv->dout >= 0)
		m->r->douts[dv->dout] = sim_gpio_dout(sd->gpio);
	if (dv->din >= 0)
		m->r->dins[dv->din] = sim_gpio_din(sd->gpio);
	if (dv->desc->has_ready)
		sim_gpio_out_polarity(sd->gpio, nt - 1, dv->desc->ready_active_low);
	return 0;
}

/* A trigger line: its polarity, and a camera on it (exposure and readout
 * from the device's sim: settings, else fractions of a frame); an input:
 * its polarity, and the first camera saying when it is ready. */
static int sim_bind(struct rig_make *m, uint32_t k, bool trig, uint32_t i, uint32_t line,
		    char *err, size_t errsize)
{
	const struct rig_sim_desc *s = &m->r->dev[k].desc->sim;
	struct sim_dev *sd = m->r->dev[k].priv;
	double frame_ns = 1e9 * m->t->den / m->t->num;
	struct sim_camera_params cp;
	struct sim_camera *c0;
	char why[160];
	int rc;

	if (!trig) {
		const struct rig_input_desc *id = &m->d->inputs[i];

		sim_gpio_in_polarity(sd->gpio, line, id->active_low);
		c0 = m->d->ntriggers ? rig_sim_camera(m->r, 0) : NULL;
		if (id->role == RIG_INPUT_CAMERA_READY && c0)
			sim_camera_ready(c0, sd->gpio, line);
		return 0;
	}
	sim_gpio_out_polarity(sd->gpio, line, m->d->triggers[i].active_low);
	/* a scene's are up to a day each (rig_sim_check), the defaults a
	 * fraction of a frame; 2^60 ns (36 years) each keeps their sum with a
	 * trigger's time inside int64_t nanoseconds */
	if (num_ms_to_ns(or_default(s->exposure_ms, SIM_CAMERA_DEFAULT_EXPOSURE_FRAC *
				    frame_ns / 1e6), NUM_ROUND_DOWN, 0,
			 INT64_C(1) << 60, &cp.exposure_ns) ||
	    num_ms_to_ns(or_default(s->readout_ms, SIM_CAMERA_DEFAULT_READOUT_FRAC *
				    frame_ns / 1e6), NUM_ROUND_DOWN, 0,
			 INT64_C(1) << 60, &cp.readout_ns)) {
		snprintf(err, errsize, "triggers[%u] (%s): the simulated camera's exposure_ms or "
			 "readout_ms is more than 36 years", i, m->d->triggers[i].name);
		return -ERANGE;
	}
	rc = sim_camera_new(&sd->cam[line], &cp, m->o->camera_cap ? m->o->camera_cap : 1 << 16,
			    i == 0 ? m->o->camera_log : NULL, why, sizeof(why));
	if (rc) {
		snprintf(err, errsize, "triggers[%u] (%s): %s", i, m->d->triggers[i].name, why);
		return rc;
	}
	sim_camera_trigger(sd->cam[line], sd->gpio, line);
	return 0;
}

static void sim_free(struct rig *r, uint32_t k)
{
	struct sim_dev *sd = r->dev[k].priv;
	uint32_t i;

	if (!sd)
		return;
	if (sd->drive)
		hal_axis_close(sim_drive_axis(sd->drive));
	for (i = 0; sd->cam && i < sd->ncam; i++)
		sim_camera_free(sd->cam[i]);
	free(sd->cam);
	sim_gpio_free(sd->gpio);
	free(sd);
	r->dev[k].priv = NULL;
}

struct sim_gpio *rig_sim_gpio(const struct rig *r, const char *name)
{
	int k = rig_device(r, name);
	const struct sim_dev *sd;

	if (k < 0 || r->dev[k].drv != &rig_drv_sim)
		return NULL;
	sd = r->dev[k].priv;
	return sd ? sd->gpio : NULL;
}

struct sim_camera *rig_sim_camera(const struct rig *r, uint32_t trig)
{
	uint32_t k;

	if (trig >= r->ntrig)
		return NULL;
	for (k = 0; k < r->ndev; k++) {
		const struct sim_dev *sd = r->dev[k].priv;

		if (r->dev[k].drv == &rig_drv_sim && sd &&
		    r->dev[k].dout == (int32_t)r->trig[trig].dev)
			return r->trig[trig].line < sd->ncam ? sd->cam[r->trig[trig].line] : NULL;
	}
	return NULL;
}

const struct rig_driver rig_drv_sim = {
	.name = "sim",
	.make_axes = sim_make_axes,
	.make_lines = sim_make_lines,
	.bind = sim_bind,
	.free = sim_free,
};

uint32_t rig_sim_press_estop(struct rig *r)
{
	uint32_t i, k, n = 0;

	for (i = 0; i < r->nin; i++) {
		const struct sim_dev *sd = NULL;

		if (r->in[i].role != RIG_INPUT_ESTOP)
			continue;
		for (k = 0; k < r->ndev; k++)
			if (r->dev[k].din == (int32_t)r->in[i].dev && r->dev[k].drv == &rig_drv_sim)
				sd = r->dev[k].priv;
		if (!sd || !sd->gpio)
			continue;
		sim_gpio_inject(sd->gpio, r->in[i].line, true);
		sim_gpio_inject(sd->gpio, r->in[i].line, false);
		n++;
	}
	return n;
}
