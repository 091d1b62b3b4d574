/* SPDX-License-Identifier: MIT */
/*
 * test_import_table.c - a table of positions per frame through `strand
 * import` and back out of `strand export`: every column the table has comes
 * back with its values at every frame (within the core's resolution and
 * the 10 digits export prints), for linear, step and hermite; and a bad table is one line with
 * the line it found wrong, exit 2.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cliutil.h"
#include "testutil.h"

#include <cmocka.h>

static char *write_tmp(const char *text, const char *ext)
{
	static char named[3][64];
	static int slot;
	char *out = named[slot++ % 3];

	tmp_file(out, 64, ext, text, strlen(text));
	return out;
}

static void round_trip(const char *interp)
{
	static const char *const cols[] = { "arm.angle", "slide.position", "Pan", "dye" };
	struct tu_rng g;
	struct tu_worst w = { 0, 0 };
	char *table = malloc(1 << 16), *csv, *yaml, args[256], name[64];
	double v[200][4];
	size_t len = 0;
	struct run r;
	int row, k, rows = 97;

	tu_seed(&g, 2024);
	len += (size_t)sprintf(table + len, "frame,%s,%s,%s,%s\n", cols[0], cols[1], cols[2], cols[3]);
	for (row = 0; row < rows; row++) {
		len += (size_t)sprintf(table + len, "%d", row);
		for (k = 0; k < 4; k++) {
			v[row][k] = round(tu_uniform(&g, -500, 500) * 1000) / 1000;
			len += (size_t)sprintf(table + len, ",%.10g", v[row][k]);
		}
		table[len++] = '\n';
	}
	table[len] = 0;
	csv = write_tmp(table, ".csv");
	yaml = write_tmp("", ".yaml");
	snprintf(args, sizeof(args), "import %s -o %s --interpolation %s", csv, yaml, interp);
	strand(&r, args);
	assert_int_equal(r.rc, 0);
	run_free(&r);
	snprintf(args, sizeof(args), "export %s", yaml);
	strand(&r, args);
	assert_int_equal(r.rc, 0);
	{
		char *line = r.out, *next = strchr(line, '\n'), *f;
		int idx[4], c, n = 0;

		*next = 0;
		for (k = 0; k < 4; k++) {
			idx[k] = -1;
			for (c = 0, f = strtok(line, ","); f; f = strtok(NULL, ","), c++)
				if (!strcmp(f, cols[k]))
					idx[k] = c;
			/* strtok cut the header: restore it for the next name */
			for (f = line; f < next; f++)
				if (!*f)
					*f = ',';
			assert_true(idx[k] >= 0);
		}
		for (row = 0, line = next + 1; *line; row++, line = next + 1) {
			double cells[64];

			next = strchr(line, '\n');
			*next = 0;
			for (c = 0, f = line; c < 64 && *f; c++) {
				cells[c] = strtod(f, &f);
				if (*f == ',')
					f++;
			}
			assert_true(cells[1] == row);
			for (k = 0; k < 4; k++) {
				tu_worst_add(&w, cells[idx[k]] - v[row][k], row);
				n++;
			}
		}
		assert_int_equal(row, rows);
		assert_int_equal(n, rows * 4);
	}
	run_free(&r);
	snprintf(name, sizeof(name), "table_round_trip_%s", interp);
	/* the core holds an angle to 2^-33 turn (4.2e-8 deg) and export prints
	 * 10 digits (5e-8 at 500) */
	tu_bound(name, &w, 1e-7, "deg or units");
	unlink(csv);
	unlink(yaml);
	free(table);
}

static void test_round_trip(void **state)
{
	(void)state;
	round_trip("linear");
	round_trip("step");
	round_trip("hermite");
}

static void bad(const char *text, const char *want)
{
	import_error(".csv", text, strlen(text), want);
}

static void test_errors(void **state)
{
	(void)state;
	bad("a.angle\n1\n", ": line 1: no 'frame' column");
	bad("frame,a.angle\n0,1\n1,nan\n", ": line 3, column 2: 'nan' is not a finite number");
	bad("frame,a.angle\n0,1\n0,2\n", ": line 3: frame 0 is not after the previous row's");
	bad("frame,a.angle\n0,1,2\n", ": line 2: 3 fields, the header has 2");
	/* frames the core cannot hold: caught when the scene made is read back */
	bad("frame,a.angle\n0,1\n2e9,2\n", ": the scene it makes is refused at its line 5: ");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_round_trip),
		cmocka_unit_test(test_errors),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
