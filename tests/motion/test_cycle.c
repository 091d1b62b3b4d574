/* SPDX-License-Identifier: MIT */
/*
 * test_cycle.c - cycled objects (FORMULAS section 9): the index sequence of
 * each mode, written out by hand, and long runs against a direct simulation
 * of the sequence.
 */
#include "motion/cycle.h"
#include "testutil.h"

static void expect_seq(const struct mot_cycle *c, const int32_t *seq, int n, int64_t from)
{
	int i;

	for (i = 0; i < n; i++)
		assert_int_equal(mot_cycle_index(c, from + i), seq[i]);
}

static void test_modes(void **state)
{
	struct mot_cycle c;
	/* first 1, last 9, skip 2: objects 1 3 5 7 9 */
	static const int32_t loop[] = { 1, 3, 5, 7, 9, 1, 3, 5, 7, 9, 1 };
	static const int32_t bounce[] = { 1, 3, 5, 7, 9, 7, 5, 3, 1, 3, 5, 7, 9, 7 };
	/* last not reached exactly: 1 4 7 (10 > 9) */
	static const int32_t loop3[] = { 1, 4, 7, 1, 4, 7 };
	static const int32_t bounce3[] = { 1, 4, 7, 4, 1, 4, 7, 4 };

	assert_int_equal(mot_cycle_init(&c, 1, 9, 2, MOT_CYCLE_LOOP, 1, 0), MOT_OK);
	expect_seq(&c, loop, 11, 0);
	assert_int_equal(mot_cycle_init(&c, 1, 9, 2, MOT_CYCLE_BOUNCE, 1, 0), MOT_OK);
	expect_seq(&c, bounce, 14, 0);
	assert_int_equal(mot_cycle_init(&c, 1, 9, 2, MOT_CYCLE_GROWTH, 1, 0), MOT_OK);
	expect_seq(&c, loop, 11, 0); /* growth's channel is the last object shown */
	assert_int_equal(mot_cycle_init(&c, 1, 9, 3, MOT_CYCLE_LOOP, 1, 0), MOT_OK);
	expect_seq(&c, loop3, 6, 0);
	assert_int_equal(mot_cycle_init(&c, 1, 9, 3, MOT_CYCLE_BOUNCE, 1, 0), MOT_OK);
	expect_seq(&c, bounce3, 8, 0);
	/* a single object */
	assert_int_equal(mot_cycle_init(&c, 5, 5, 1, MOT_CYCLE_BOUNCE, 1, 0), MOT_OK);
	assert_int_equal(mot_cycle_index(&c, 0), 5);
	assert_int_equal(mot_cycle_index(&c, 1000), 5);
}

static void test_steps_and_start(void **state)
{
	struct mot_cycle c;

	/* two frames per step, starting at frame 10 */
	assert_int_equal(mot_cycle_init(&c, 0, 2, 1, MOT_CYCLE_LOOP, 2, 10), MOT_OK);
	assert_int_equal(mot_cycle_index(&c, -5), 0); /* before the start: first */
	assert_int_equal(mot_cycle_index(&c, 9), 0);
	assert_int_equal(mot_cycle_index(&c, 10), 0);
	assert_int_equal(mot_cycle_index(&c, 11), 0);
	assert_int_equal(mot_cycle_index(&c, 12), 1);
	assert_int_equal(mot_cycle_index(&c, 14), 2);
	assert_int_equal(mot_cycle_index(&c, 16), 0);
}

/* A long run against a step-by-step simulation of the sequence. */
static void test_long(void **state)
{
	static const enum mot_cycle_mode modes[] = { MOT_CYCLE_LOOP, MOT_CYCLE_BOUNCE,
						     MOT_CYCLE_GROWTH };
	struct tu_rng rng;
	int m, trial;

	tu_seed(&rng, 9);
	for (trial = 0; trial < 200; trial++) {
		for (m = 0; m < 3; m++) {
			int32_t first = (int32_t)(tu_u64(&rng) % 100) - 50;
			int32_t skip = 1 + (int32_t)(tu_u64(&rng) % 7);
			int32_t last = first + (int32_t)(tu_u64(&rng) % 60);
			int64_t fps = 1 + (int64_t)(tu_u64(&rng) % 5);
			int64_t start = (int64_t)(tu_u64(&rng) % 20);
			struct mot_cycle c;
			int32_t idx = first, dir = 1, lastr = first + (last - first) / skip * skip;
			int64_t f;

			assert_int_equal(mot_cycle_init(&c, first, last, skip, modes[m], fps, start),
					 MOT_OK);
			for (f = start; f < start + 5000; f++) {
				if (f > start && (f - start) % fps == 0) {
					/* advance one step */
					if (modes[m] != MOT_CYCLE_BOUNCE) {
						idx = idx + skip > lastr ? first : idx + skip;
					} else if (lastr != first) {
						if (idx + dir * skip > lastr || idx + dir * skip < first)
							dir = -dir;
						idx += dir * skip;
					}
				}
				assert_int_equal(mot_cycle_index(&c, f), idx);
			}
		}
	}
}

static void test_invalid(void **state)
{
	struct mot_cycle c;

	assert_int_equal(mot_cycle_init(&c, 1, 9, 0, MOT_CYCLE_LOOP, 1, 0), MOT_E_INVAL);
	assert_int_equal(mot_cycle_init(&c, 9, 1, 1, MOT_CYCLE_LOOP, 1, 0), MOT_E_INVAL);
	assert_int_equal(mot_cycle_init(&c, 1, 9, 1, MOT_CYCLE_LOOP, 0, 0), MOT_E_INVAL);
	assert_int_equal(mot_cycle_init(&c, 1, 9, 1, (enum mot_cycle_mode)7, 1, 0), MOT_E_INVAL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_modes),
		cmocka_unit_test(test_steps_and_start),
		cmocka_unit_test(test_long),
		cmocka_unit_test(test_invalid),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
