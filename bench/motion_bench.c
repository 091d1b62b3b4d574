/* SPDX-License-Identifier: MIT */
/*
 * motion_bench.c - issue 2's benchmark: the fixed-point motion core against
 * a double-precision twin doing the same work (dbl_scene.h), side by side
 * in one run, and the core's errors against the tests' reference. Prints
 *
 *     BENCH <name> <value> <unit>
 *
 * lines (bench.h), preceded by a few '#' lines that say what machine they
 * were measured on. A program, not a test: it exits 1 only when a check
 * that makes the timings meaningful fails (the double twin must agree with
 * tests/ref_scene.c, or it would not be doing the same work).
 */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "bench.h"
#include "motion_bench.h"

/* The CPU's name and clock as the kernel reports them (a VM's "MHz" is the
 * host's nominal clock, not a measured one). */
static void print_machine(void)
{
	FILE *f = fopen("/proc/cpuinfo", "r");
	char line[256], model[128] = "unknown", mhz[32] = "?";
	int ncpu = 0;

	while (f && fgets(line, sizeof(line), f)) {
		char *v = strchr(line, ':');

		if (!v)
			continue;
		v += 1 + (v[1] == ' ');
		v[strcspn(v, "\n")] = 0;
		if (!strncmp(line, "model name", 10))
			snprintf(model, sizeof(model), "%s", v);
		else if (!strncmp(line, "cpu MHz", 7))
			snprintf(mhz, sizeof(mhz), "%s", v);
		else if (!strncmp(line, "processor", 9))
			ncpu++;
	}
	if (f)
		fclose(f);
	printf("# cpu: %s, %d cpu(s), %s MHz as reported; compiler: gcc %s, -O2\n", model, ncpu,
	       mhz, __VERSION__);
	printf("# medians of %d interleaved repeats; ratios are fixed / double\n", BENCH_REPEATS);
}

/* motion_bench [prim|pipe|scenes]...: the parts named, all by default */
int main(int argc, char **argv)
{
	static const struct {
		const char *name;
		int (*run)(void);
	} part[] = { { "prim", bench_primitives }, { "pipe", bench_pipeline },
		     { "scenes", bench_scenes } };
	int bad = 0, i, k;

	print_machine();
	for (k = 0; k < 3; k++) {
		bool on = argc < 2;

		for (i = 1; i < argc; i++)
			on = on || !strcmp(argv[i], part[k].name);
		if (on)
			bad |= part[k].run();
	}
	return bad ? 1 : 0;
}
