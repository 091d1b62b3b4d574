/* SPDX-License-Identifier: MIT */
/*
 * test_rt.c - the dynamic half of the real-time boundary (hal/rt.h): the
 * loop thread's flag, STRAND_ASSERT_NOT_RT() in [init] functions (each
 * called on a thread that said strand_rt_enter() must abort with its name,
 * in a child process), rt operations that must not, and the tests'
 * allocation counter keyed on the same flag. The static half is
 * `make check-rt`.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hal/clock.h"
#include "hal/rt.h"
#include "playutil.h"
#include "sim/co_simbus.h"
#include "sim/sim_camera.h"
#include "sim/sim_drive.h"
#include "sim/sim_gpio.h"

/* The tests are the debug build: without it the assertions are nothing. */
#ifndef STRAND_DEBUG
#error "tests are built with STRAND_DEBUG (Makefile: SAN)"
#endif

static const struct sim_drive_channel chan = {
	.bandwidth_hz = 20, .damping = 1, .feedforward = 1,
};

static struct hal_clock clk;

static void call_sim_drive_new(void)
{
	struct sim_drive *d;

	sim_drive_new(&d, "x", 1, 1000, &chan, NULL, 0);
}

static void call_sd_close(void)
{
	struct sim_drive *d;

	strand_rt_leave();
	assert_int_equal(sim_drive_new(&d, "x", 1, 1000, &chan, NULL, 0), 0);
	strand_rt_enter();
	hal_axis_close(sim_drive_axis(d));
}

static void call_sim_gpio_new(void)
{
	struct sim_gpio *g;

	sim_gpio_new(&g, "x", 1, 1, &clk, 16, NULL, 0);
}

static void call_go_start(void)
{
	struct sim_gpio *g;

	strand_rt_leave();
	assert_int_equal(sim_gpio_new(&g, "x", 1, 1, &clk, 16, NULL, 0), 0);
	strand_rt_enter();
	hal_dout_start(sim_gpio_dout(g));
}

static void call_co_simbus_new(void)
{
	struct co_simbus *b;

	co_simbus_new(&b, &clk, 64, 0, NULL, 0);
}

static void call_sim_camera_new(void)
{
	const struct sim_camera_params p = { .exposure_ns = 1000, .readout_ns = 1000 };

	struct sim_camera *c;

	sim_camera_new(&c, &p, 16, NULL, NULL, 0);
}

/* Runs call() in a child on a thread that entered the loop: it must die
 * of SIGABRT, saying that `name` is [init]. */
static void aborts(void (*call)(void), const char *name)
{
	char out[512] = "", want[128];
	int fd[2], status;
	ssize_t n, got = 0;
	pid_t pid;

	assert_int_equal(pipe(fd), 0);
	pid = fork();
	assert_true(pid >= 0);
	if (pid == 0) {
		dup2(fd[1], 2);
		close(fd[0]);
		hal_clock_init(&clk, true);
		strand_rt_enter();
		call();
		_exit(0); /* it returned: the parent fails */
	}
	close(fd[1]);
	while ((n = read(fd[0], out + got, sizeof(out) - 1 - (size_t)got)) > 0)
		got += n;
	close(fd[0]);
	assert_int_equal(waitpid(pid, &status, 0), pid);
	snprintf(want, sizeof(want), "strand: %s is [init] and was called from the real-time thread",
		 name);
	if (!strstr(out, want))
		fail_msg("%s: no \"%s\" on stderr; it said: %s", name, want, out);
	assert_true(WIFSIGNALED(status));
	assert_int_equal(WTERMSIG(status), SIGABRT);
}

static void test_init_in_rt_aborts(void **state)
{
	aborts(call_sim_drive_new, "sim_drive_new");
	aborts(call_sd_close, "sd_close");
	aborts(call_sim_gpio_new, "sim_gpio_new");
	aborts(call_go_start, "go_start");
	aborts(call_co_simbus_new, "co_simbus_new");
	aborts(call_sim_camera_new, "sim_camera_new");
}

static void *other_thread(void *arg)
{
	*(bool *)arg = strand_rt_here();
	return NULL;
}

/* The flag is the thread's: set between enter and leave, on it alone. */
static void test_flag_is_per_thread(void **state)
{
	bool seen = true;
	pthread_t t;

	assert_false(strand_rt_here());
	strand_rt_enter();
	assert_true(strand_rt_here());
	assert_int_equal(pthread_create(&t, NULL, other_thread, &seen), 0);
	assert_int_equal(pthread_join(t, NULL), 0);
	assert_false(seen);
	strand_rt_leave();
	assert_false(strand_rt_here());
}

/* Outside the loop [init] runs; inside it the rt operations do, and the
 * simulated drive's start, which a simulated CANopen drive calls from the
 * loop (sim/co_slave.c: plant_on). */
static void test_rt_ops_in_rt(void **state)
{
	struct hal_setpoint sp = { .pos = 100 };
	struct sim_drive *d = NULL;
	struct hal_axis *ax;
	struct hal_fault f;
	int64_t counts;

	assert_int_equal(sim_drive_new(&d, "x", 1, 1000, &chan, NULL, 0), 0);
	ax = sim_drive_axis(d);
	assert_int_equal(hal_axis_start(ax), 0);
	strand_rt_enter();
	assert_int_equal(hal_axis_input(ax, 0), 0);
	hal_axis_set(ax, 0, &sp);
	assert_int_equal(hal_axis_commit(ax, 0), 0);
	assert_true(hal_axis_actual(ax, 0, &counts));
	assert_int_equal(hal_axis_fault(ax, &f), 0);
	hal_axis_disable(ax);
	assert_int_equal(hal_axis_start(ax), 0);
	strand_rt_leave();
	assert_int_equal(hal_axis_stop(ax), 0);
	hal_axis_close(ax);
}

/* The tests' allocation counter counts what the loop's thread allocates
 * once it said so (play.c's rt_main does, around loop_run). */
static void test_alloc_counter_keys_on_flag(void **state)
{
	uint64_t before;
	void *volatile x;

	pu_alloc_hook_install();
	before = pu_loop_allocations();
	x = malloc(16);
	free(x);
	assert_int_equal(pu_loop_allocations() - before, 0);
	/* volatile: the compiler may assume malloc reads no variable of ours
	 * and move plain stores across it */
	*(volatile bool *)&strand_rt_thread = true;
	x = malloc(16);
	*(volatile bool *)&strand_rt_thread = false;
	free(x);
	assert_int_equal(pu_loop_allocations() - before, 1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_flag_is_per_thread),
		cmocka_unit_test(test_init_in_rt_aborts),
		cmocka_unit_test(test_rt_ops_in_rt),
		cmocka_unit_test(test_alloc_counter_keys_on_flag),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
