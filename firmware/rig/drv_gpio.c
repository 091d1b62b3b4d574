/* SPDX-License-Identifier: MIT */
/* drv_gpio.c - trigger and input lines on a GPIO chip (see drv_gpio.h). */
#include "drv_gpio.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal/gpio/gpio.h"
#include "hal/gpio/gpio_line.h"
#include "rig.h"
#include "yaml/yml.h"

/* What a request has to say at start (a chip that sleeps), at most. */
#define GPIO_WARNING 512

/* One request of a device's output or input lines, made at start. */
struct gpio_plan {
	struct hal_gpio_cfg cfg;
	struct hal_gpio_line *lines;
	char warning[GPIO_WARNING];
};

struct gpio_dev {
	struct gpio_plan out, in;
	FILE *warn; /* where the warnings go, or NULL */
};

static const char *const device_keys[] = { "chip", "allow_sleeping_chip", NULL };

static int gpio_parse_device(const struct rig_parse *p, struct rig_device_desc *dev)
{
	struct rig_gpio_desc *g = pool_array(p->y->pool, 1, sizeof(*g));
	int err;

	if (!g)
		return yml_nomem(p->y);
	err = p->v[0] ? yml_str(p->y, p->v[0], &g->chip) : 0;
	if (!err && p->v[1])
		err = yml_bool(p->y, p->v[1], &g->allow_sleeping_chip);
	dev->priv = g;
	return err;
}

/* Device k's trigger (trig) or input lines, in the order rig_trig.line and
 * rig_in.line number them (the rig-ready line after the triggers). The
 * plan's scheduling of input event threads goes to the event thread. */
static int plan(struct rig_make *m, uint32_t k, bool trig, uint32_t n, struct gpio_plan *pl)
{
	const struct rig_device_desc *dd = m->r->dev[k].desc;
	const struct rig_gpio_desc *g = dd->priv;
	uint32_t i, j = 0, count = trig ? m->d->ntriggers : m->d->ninputs;

	pl->lines = calloc(n, sizeof(*pl->lines));
	if (!pl->lines)
		return -ENOMEM;
	for (i = 0; i < count; i++) {
		const char *dev = trig ? m->d->triggers[i].device : m->d->inputs[i].device;

		if (!dev || strcmp(dev, dd->name))
			continue;
		if (trig) {
			const struct rig_trigger_desc *t = &m->d->triggers[i];

			pl->lines[j] = (struct hal_gpio_line){ .name = t->line_name,
							       .offset = t->line,
							       .active_low = t->active_low };
		} else {
			const struct rig_input_desc *in = &m->d->inputs[i];

			pl->lines[j] = (struct hal_gpio_line){ .name = in->line_name,
							       .offset = in->line,
							       .active_low = in->active_low };
		}
		j++;
	}
	if (trig && dd->has_ready)
		pl->lines[j] = (struct hal_gpio_line){ .name = dd->ready_line_name,
						       .offset = dd->ready_line,
						       .active_low = dd->ready_active_low };
	/* a rig-ready line alone changes at start and at the end: on a chip
	 * that sleeps it costs the loop nothing */
	pl->cfg = (struct hal_gpio_cfg){ .device = dd->name, .chip = g ? g->chip : NULL,
					 .nlines = n, .lines = pl->lines, .sched = m->o->events,
					 .sleep_ok = (g && g->allow_sleeping_chip) || j == 0,
					 .warning = j ? pl->warning : NULL,
					 .warning_size = sizeof(pl->warning),
					 .sysfs = m->o->gpio_sysfs };
	return 0;
}

static int gpio_make_lines(struct rig_make *m, uint32_t k, uint32_t nt, uint32_t ni, char *err,
			   size_t errsize)
{
	struct gpio_dev *g = calloc(1, sizeof(*g));
	int rc = g ? 0 : -ENOMEM;

	m->r->dev[k].priv = g;
	if (g)
		g->warn = m->o->warn;
	if (!rc && nt)
		rc = plan(m, k, true, nt, &g->out);
	if (!rc && ni)
		rc = plan(m, k, false, ni, &g->in);
	if (rc)
		snprintf(err, errsize, "out of memory");
	return rc;
}

/* The lines are requested now, not when the rig is built: one held by
 * another process is a device error of the start. */
static int gpio_start(struct rig *r, uint32_t k, char *err, size_t errsize)
{
	const struct rig_dev *dv = &r->dev[k];
	const struct gpio_dev *g = dv->priv;
	int rc = 0;

	if (g && dv->dout >= 0)
		rc = hal_gpio_dout_open(&r->douts[dv->dout], &g->out.cfg, err, errsize);
	if (g && !rc && dv->din >= 0)
		rc = hal_gpio_din_open(&r->dins[dv->din], &g->in.cfg, err, errsize);
	if (g && !rc && g->warn && g->out.warning[0])
		fprintf(g->warn, "strand: warning: %s\n", g->out.warning);
	if (g && !rc && g->warn && g->in.warning[0])
		fprintf(g->warn, "strand: warning: %s\n", g->in.warning);
	return rc;
}

static void gpio_free(struct rig *r, uint32_t k)
{
	struct rig_dev *dv = &r->dev[k];
	struct gpio_dev *g = dv->priv;

	if (dv->dout >= 0) {
		hal_dout_close(r->douts[dv->dout]);
		r->douts[dv->dout] = NULL;
	}
	if (dv->din >= 0) {
		hal_din_close(r->dins[dv->din]);
		r->dins[dv->din] = NULL;
	}
	if (g) {
		free(g->out.lines);
		free(g->in.lines);
	}
	free(g);
	dv->priv = NULL;
}

const struct rig_driver rig_drv_gpio = {
	.name = "gpio",
	.device_keys = device_keys,
	.device_foreign = "chip: and allow_sleeping_chip: are for a device with driver gpio",
	.parse_device = gpio_parse_device,
	.make_lines = gpio_make_lines,
	.start = gpio_start,
	.free = gpio_free,
};

const char *rig_gpio_lib_version(void)
{
	return gpio_line_lib_version();
}
