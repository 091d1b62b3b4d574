/* SPDX-License-Identifier: MIT */
/*
 * test_render.c - `strand plot` pictures as a browser shows them: every
 * example's SVG, and a --compare page, rendered to PNG by headless Chromium
 * (Debian's chromium, installed by mk/scene.mk) and checked not blank: some
 * ink on the page, and coloured lines, not only the frame and text.
 */
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/exitcode.h"
#include "testutil.h"

static const char *const plots[][2] = {
	{ "examples/robot_arm.yaml", NULL },	{ "examples/propeller.yaml", NULL },
	{ "examples/camera_move.yaml", NULL },	{ "examples/cycled_data.yaml", NULL },
	{ "examples/curves.yaml", NULL },	{ "examples/curves.yaml", "loop" },
	{ "examples/propeller.yaml", "sting" },
};

struct ink {
	size_t pixels, dark, colour;
};

static void measure(const char *png_path, struct ink *ink)
{
	png_image img;
	png_bytep buf;
	size_t i;

	memset(&img, 0, sizeof(img));
	img.version = PNG_IMAGE_VERSION;
	if (!png_image_begin_read_from_file(&img, png_path))
		fail_msg("%s: %s", png_path, img.message);
	img.format = PNG_FORMAT_RGB;
	buf = malloc(PNG_IMAGE_SIZE(img));
	assert_non_null(buf);
	assert_true(png_image_finish_read(&img, NULL, buf, 0, NULL));
	ink->pixels = (size_t)img.width * img.height;
	ink->dark = ink->colour = 0;
	for (i = 0; i < ink->pixels; i++) {
		int r = buf[3 * i], g = buf[3 * i + 1], b = buf[3 * i + 2];
		int hi = r > g ? (r > b ? r : b) : (g > b ? g : b);
		int lo = r < g ? (r < b ? r : b) : (g < b ? g : b);

		ink->dark += hi < 200;
		ink->colour += hi - lo > 80;
	}
	free(buf);
	png_image_free(&img);
}

static void test_render(void **state)
{
	char dir[] = "/tmp/strand-render-XXXXXX", svg[512], png[512], cmd[2048], log[512];
	size_t i;

	assert_non_null(mkdtemp(dir));
	snprintf(log, sizeof(log), "%s/chromium.log", dir);
	for (i = 0; i < sizeof(plots) / sizeof(plots[0]); i++) {
		char *argv[8] = { "strand", "plot", (char *)plots[i][0], "-o", svg, NULL, NULL, NULL };
		struct ink ink;
		int argc = 5;

		snprintf(svg, sizeof(svg), "%s/plot%zu.svg", dir, i);
		snprintf(png, sizeof(png), "%s/plot%zu.png", dir, i);
		if (plots[i][1]) {
			argv[argc++] = "--compare";
			argv[argc++] = (char *)plots[i][1];
		}
		assert_int_equal(cli_main(argc, argv, stdout, stderr), STRAND_EXIT_OK);
		snprintf(cmd, sizeof(cmd),
			 "timeout 120 chromium --headless --no-sandbox --disable-gpu "
			 "--disable-background-networking --disable-component-update --disable-sync "
			 "--no-first-run --user-data-dir=%s/profile --hide-scrollbars "
			 "--window-size=1300,1000 --screenshot=%s file://%s >>%s 2>&1",
			 dir, png, svg, log);
		if (system(cmd) != 0 || access(png, R_OK) != 0)
			fail_msg("chromium did not render %s (log: %s)", svg, log);
		measure(png, &ink);
		print_message("%s%s%s: %zu px, %.1f%% ink, %.2f%% colour\n", plots[i][0],
			      plots[i][1] ? " --compare " : "", plots[i][1] ? plots[i][1] : "",
			      ink.pixels, 100.0 * ink.dark / ink.pixels,
			      100.0 * ink.colour / ink.pixels);
		/* a blank or failed page is white (or one flat colour) */
		assert_true(ink.dark > ink.pixels / 200);
		assert_true(ink.colour > ink.pixels / 1000);
	}
	snprintf(cmd, sizeof(cmd), "rm -rf %s", dir);
	assert_int_equal(system(cmd), 0);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_render),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
