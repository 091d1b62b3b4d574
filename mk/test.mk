# mk/test.mk - `make test`: every check, one after the other, and a summary.
#
# Each step runs in a make of its own and a failing step does not stop the
# others, so one run (one CI run) reports everything. Add a check by naming
# its target in TEST_STEPS, or from another mk/*.mk in EXTRA_TEST_STEPS.


# The short fuzz runs are one step, two of them at a time: each is one
# thread for a fixed wall time, so a pair on two CPUs takes the time of one.
FUZZ_SHORTS = $(filter fuzz-short fuzz-%-short,$(EXTRA_TEST_STEPS))
TEST_STEPS = unit check-layers check-freestanding check-cross check-cortexm \
             $(filter-out $(FUZZ_SHORTS),$(EXTRA_TEST_STEPS)) fuzz-shorts

# The packages first, one apt-get at a time; then everything the steps
# share built on every CPU: the programs and tests, and what other mk/*.mk
# add to TEST_PREBUILD (the fuzzers, the property test); the steps
# themselves run one after the other: several of them time what they run.
NPROC := $(shell nproc 2>/dev/null || echo 2)

.PHONY: fuzz-shorts
fuzz-shorts:
	$(Q)$(MAKE) --no-print-directory -j$(NPROC) -Otarget $(FUZZ_SHORTS)

test:
	$(Q)$(MAKE) --no-print-directory deps
	$(Q)$(MAKE) --no-print-directory -j$(NPROC) all $(BUILD)/strand-simdrive $(TEST_PREBUILD)
	$(Q)sh mk/run-steps.sh '$(MAKE)' $(BUILD)/test-logs $(TEST_STEPS)
