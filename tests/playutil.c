/* SPDX-License-Identifier: MIT */
/* playutil.c - shared pieces of the play tests (see playutil.h). */
#include "cli/cli.h"
#include "cli/exitcode.h"
#include "hal/rt.h"
#include "playutil.h"
#include "sim/sim_camera.h"
#include "sim/sim_drive.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <errno.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int pu_lookup(struct play_source *s, const char *name, struct src_channel *info)
{
	struct pu_source *ps = (struct pu_source *)s;
	uint32_t i;

	for (i = 0; i < ps->nch; i++)
		if (!strcmp(ps->ch[i].name, name)) {
			info->unit = ps->ch[i].unit;
			info->limits = ps->ch[i].limits;
			return (int)i;
		}
	return -ENOENT;
}

static int pu_select(struct play_source *s, const uint32_t *idx, uint32_t n)
{
	struct pu_source *ps = (struct pu_source *)s;

	if (n > PU_MAX_CH)
		return -EINVAL;
	memcpy(ps->sel, idx, n * sizeof(*idx));
	ps->nsel = n;
	return 0;
}

mot_q32 pu_value(const struct pu_source *ps, uint32_t ch, mot_q32 frame)
{
	const struct pu_channel *c = &ps->ch[ch];
	double v = c->fn(c->ctx, (double)frame / 4294967296.0);

	if (c->unit == SRC_UNIT_TURNS)
		v /= 360.0;
	return (mot_q32)llround(v * 4294967296.0);
}

static void pu_eval(struct play_source *s, mot_q32 frame, mot_q32 *out, uint32_t *sat)
{
	struct pu_source *ps = (struct pu_source *)s;
	uint32_t i;

	for (i = 0; i < ps->nsel; i++)
		out[i] = pu_value(ps, ps->sel[i], frame);
}

static const struct play_source_ops pu_ops = {
	.lookup = pu_lookup,
	.select = pu_select,
	.eval = pu_eval,
};

void pu_source_init(struct pu_source *ps, const char *name, uint32_t num, uint32_t den,
		    uint32_t tick_hz, int64_t first, int64_t last)
{
	memset(ps, 0, sizeof(*ps));
	ps->s.ops = &pu_ops;
	ps->s.name = name;
	mot_timing_init(&ps->s.timing, num, den, tick_hz);
	ps->s.frame_first = first;
	ps->s.frame_last = last;
}

void pu_source_add(struct pu_source *ps, const char *name, enum src_unit unit, pu_fn fn,
		   const void *ctx, double vel, double acc)
{
	struct pu_channel *c = &ps->ch[ps->nch++];

	c->name = name;
	c->unit = unit;
	c->fn = fn;
	c->ctx = ctx;
	c->limits.has_vel = vel > 0;
	c->limits.vel = vel;
	c->limits.has_acc = acc > 0;
	c->limits.acc = acc;
}

double pu_smooth(const void *ctx, double frame)
{
	const struct pu_smooth *m = ctx;
	double s;

	if (frame <= m->f0)
		return m->base;
	if (frame >= m->f1)
		return m->base + m->amp;
	s = (frame - m->f0) / (m->f1 - m->f0);
	return m->base + m->amp * (1 - cos(M_PI * s)) / 2;
}

void pu_rig_init(struct pu_rig *r, const struct pu_source *ps, uint32_t ntrig, unsigned inputs)
{
	static const double cpu[] = { 1000, 100000, 10, 1, 1, 1, 1, 1 };
	uint32_t i;

	memset(r, 0, sizeof(*r));
	r->dev[0].name = "arm";
	r->dev[0].driver = &rig_drv_sim;
	r->dev[1].name = "io";
	r->dev[1].driver = &rig_drv_sim;
	r->dev[2].name = "arm2";
	r->dev[2].driver = &rig_drv_sim;
	for (i = 0; i < ps->nch; i++) {
		struct rig_output_desc *o = &r->out[i];

		o->channel = ps->ch[i].name;
		o->device = "arm";
		o->axis = i;
		o->counts_per_unit = cpu[i];
		o->ferror = ps->ch[i].unit == SRC_UNIT_TURNS ? 2.0 : 0.02;
		o->min_ferror = o->ferror / 10;
		o->home = ps->ch[i].fn(ps->ch[i].ctx, (double)ps->s.frame_first);
	}
	for (i = 0; i < ntrig; i++) {
		r->trig[i].name = i ? "cam2" : "cam";
		r->trig[i].device = "io";
		r->trig[i].line = i;
		r->trig[i].pulse_ms = 1;
	}
	i = 0;
	if (inputs & PU_ESTOP)
		r->in[i++] = (struct rig_input_desc){ "estop", "io", 0, RIG_INPUT_ESTOP, true, NULL };
	if (inputs & PU_READY)
		r->in[i++] = (struct rig_input_desc){ "ready", "io", 1, RIG_INPUT_CAMERA_READY, false, NULL };
	if (inputs & PU_STOP)
		r->in[i++] = (struct rig_input_desc){ "stop", "io", 2, RIG_INPUT_STOP, false, NULL };
	r->d.ndevices = 3;
	r->d.devices = r->dev;
	r->d.noutputs = ps->nch;
	r->d.outputs = r->out;
	r->d.ntriggers = ntrig;
	r->d.triggers = r->trig;
	r->d.ninputs = i;
	r->d.inputs = r->in;
}

void pu_opts(struct play_opts *o, const struct pu_source *ps)
{
	memset(o, 0, sizeof(*o));
	o->virtual_clock = true;
	o->loop.mode = LOOP_MODE_CONTINUOUS;
	o->loop.from = ps->s.frame_first;
	o->loop.to = ps->s.frame_last;
	o->loop.settle_ticks = 20;
	o->loop.exposure_ticks = 10;
	o->loop.in_position_timeout_ticks = 10 * (int64_t)ps->s.timing.tick_hz;
	o->loop.ready_timeout_ticks = 10 * (int64_t)ps->s.timing.tick_hz;
	o->loop.status_every = ps->s.timing.tick_hz / 10;
	o->rt.priority = 0;
	o->rt.cpu = -1;
	o->rt.name = "strand-rt";
	o->rig.sim = true;
}

void pu_tmpname(char *buf, size_t size, const char *what)
{
	static atomic_int seq;
	const char *dir = getenv("TMPDIR");

	snprintf(buf, size, "%s/strand-test-%d-%d-%s", dir ? dir : "/tmp", (int)getpid(),
		 atomic_fetch_add(&seq, 1), what);
}

/* ASan's hook API (sanitizer/allocator_interface.h, which gcc does not
 * install): called for every allocation the process makes, from libc's
 * insides too, in the allocating thread. */
int __sanitizer_install_malloc_and_free_hooks(void (*m)(const volatile void *, size_t),
					      void (*f)(const volatile void *)) __attribute__((weak));

static atomic_uint_fast64_t loop_allocs;

/* What the loop's thread allocates (it says so: strand_rt_enter(),
 * hal/rt.h). */
static void on_malloc(const volatile void *ptr, size_t size)
{
	if (strand_rt_here())
		atomic_fetch_add(&loop_allocs, 1);
}

static void on_free(const volatile void *ptr)
{
}

void pu_alloc_hook_install(void)
{
	static bool done;

	/* (weak: a program built without ASan, the property test's, counts none) */
	if (!done && __sanitizer_install_malloc_and_free_hooks)
		__sanitizer_install_malloc_and_free_hooks(on_malloc, on_free);
	done = true;
}

uint64_t pu_loop_allocations(void)
{
	return atomic_load(&loop_allocs);
}

int pu_csv_read(struct pu_csv *c, const char *journal_path)
{
	char msg[256], *line, *save = NULL;
	size_t len = 0;
	FILE *f;
	int rc;
	uint32_t cap = 64;

	memset(c, 0, sizeof(*c));
	f = open_memstream(&c->text, &len);
	if (!f)
		return -errno;
	rc = journal_csv(journal_path, f, msg, sizeof(msg));
	fclose(f);
	if (rc) {
		printf("journal_csv: %s\n", msg);
		return rc;
	}
	c->cell = calloc(cap, sizeof(*c->cell));
	for (line = strtok_r(c->text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
		uint32_t n = 1, k = 0;
		char *p;

		for (p = line; *p; p++)
			n += *p == ',';
		if (c->nrows == cap) {
			cap *= 2;
			c->cell = realloc(c->cell, cap * sizeof(*c->cell));
		}
		c->cell[c->nrows] = calloc(n, sizeof(char *));
		c->cell[c->nrows][k++] = line;
		for (p = line; *p; p++)
			if (*p == ',') {
				*p = '\0';
				c->cell[c->nrows][k++] = p + 1;
			}
		if (c->nrows == 0)
			c->ncols = n;
		else if (n != c->ncols)
			return -EBADMSG;
		c->nrows++;
	}
	return 0;
}

void pu_csv_free(struct pu_csv *c)
{
	uint32_t i;

	for (i = 0; i < c->nrows; i++)
		free(c->cell[i]);
	free(c->cell);
	free(c->text);
	memset(c, 0, sizeof(*c));
}

int pu_csv_col(const struct pu_csv *c, const char *name)
{
	uint32_t i;

	for (i = 0; c->nrows && i < c->ncols; i++)
		if (!strcmp(c->cell[0][i], name))
			return (int)i;
	fail_msg("no column %s in the journal", name);
	return -1;
}

struct pu_smooth pu_m_a = { 10, 200, 90, 0 };     /* degrees */
struct pu_smooth pu_m_b = { 0, 150, 0.25, 0.1 };  /* metres */

/* The arm of most tests: a revolute and a prismatic channel, 0..240 at
 * 24 fps on a 1 kHz tick. */
void pu_arm_source(struct pu_source *ps, uint32_t num, uint32_t den, uint32_t hz,
		       int64_t first, int64_t last)
{
	pu_source_init(ps, "test-arm", num, den, hz, first, last);
	pu_source_add(ps, "a.angle", SRC_UNIT_TURNS, pu_smooth, &pu_m_a, 60, 120);
	pu_source_add(ps, "b.position", SRC_UNIT_LENGTH, pu_smooth, &pu_m_b, 0.5, 2);
}

/* Run and check the things every run must satisfy: no allocation in the
 * loop, commanded speed and acceleration within every output's limits (as
 * the drive saw them), the camera never missing a trigger. */
int pu_run(struct play *p, struct pu_rig *r, struct pu_source *ps, struct play_opts *o)
{
	char err[256] = "";

	pu_alloc_hook_install();
	if (play_prepare(p, &r->d, &ps->s, o, err, sizeof(err)))
		fail_msg("play_prepare: %s", err);
	return pu_finish(p, true);
}

int pu_play(struct play *p)
{
	int rc = play_run(p);

	return rc ? STRAND_EXIT_INTERNAL : cli_play_exit(&loop_result(p->L)->rep);
}

int pu_finish(struct play *p, bool check_missed)
{
	const double hz = p->tm->tick_hz;
	uint64_t before = pu_loop_allocations();
	char err[512];
	uint32_t i;
	int code = pu_play(p);

	if (code) {
		play_describe(p, err, sizeof(err));
		printf("run ended %d: %s\n", code, err);
	}
	assert_int_equal(pu_loop_allocations() - before, 0);
	for (i = 0; i < p->rig.nout; i++) {
		const struct rig_out *ro = &p->rig.out[i];
		const struct sim_drive_watch *w =
			sim_drive_watch(sim_drive_of(p->rig.axes[ro->dev]), ro->ch);
		double pu = fabs(ro->scale.per_unit_d);

		/* counts are integers: allow a count per tick of rounding */
		if (w->cmd_vel_max > ro->vmax * pu * (1 + 1e-6) + hz ||
		    w->cmd_acc_max > ro->amax * pu * (1 + 1e-6) + 2 * hz * hz)
			fail_msg("%s: commanded %g counts/s, %g counts/s^2; limits %g, %g",
				 ro->channel, w->cmd_vel_max, w->cmd_acc_max, ro->vmax * pu,
				 ro->amax * pu);
	}
	for (i = 0; check_missed && i < p->rig.ntrig; i++)
		assert_int_equal(sim_camera_missed(rig_sim_camera(&p->rig, i)), 0);
	return code;
}

