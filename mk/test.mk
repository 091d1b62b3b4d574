# mk/test.mk - `make test`: every check, one after the other, and a summary.
#
# Each step runs in a make of its own and a failing step does not stop the
# others, so one run (one CI run) reports everything. Add a check by naming
# its target in TEST_STEPS, or from another mk/*.mk in EXTRA_TEST_STEPS.


TEST_STEPS = unit check-layers check-freestanding check-cross check-cortexm $(EXTRA_TEST_STEPS)

test:
	$(Q)sh mk/run-steps.sh '$(MAKE)' $(BUILD)/test-logs $(TEST_STEPS)
