# mk/dfmoco.mk - DFMoco's line reader under libFuzzer (tests/fuzz/fuzz_dfmoco.c).
#
#   make fuzz-dfmoco        FUZZ_SECONDS (default 300), from tests/fuzz/dfmoco/
#   make fuzz-dfmoco-short  FUZZ_DFMOCO_SECONDS (default 3): a step of `make test`
#   make fuzz               runs it with the other fuzzers
#
# The reader is one small file without dependencies: built alone, it runs
# a million lines in the short run's seconds. (The session above it speaks
# to a live rig; tests/dfmoco/test_dfmoco.c drives it through a pty.)

.PHONY: fuzz-dfmoco fuzz-dfmoco-short

FUZZ_DFMOCO_SECONDS ?= 3

$(FUZZ_DIR)/fuzz_dfmoco: tests/fuzz/fuzz_dfmoco.c firmware/dfmoco/dfm_parse.c \
		firmware/dfmoco/dfm_parse.h | $(BUILD)/.deps-fuzz
	@mkdir -p $(@D)
	$(Q)clang $(FUZZ_CFLAGS) tests/fuzz/fuzz_dfmoco.c firmware/dfmoco/dfm_parse.c -o $@

fuzz-dfmoco: $(FUZZ_DIR)/fuzz_dfmoco
	$(call fuzz_run,dfmoco,tests/fuzz/dfmoco,8192,$(FUZZ_SECONDS))

fuzz-dfmoco-short: $(FUZZ_DIR)/fuzz_dfmoco
	$(call fuzz_run,dfmoco,tests/fuzz/dfmoco,8192,$(FUZZ_DFMOCO_SECONDS))

fuzz: fuzz-dfmoco
EXTRA_TEST_STEPS += fuzz-dfmoco-short
TEST_PREBUILD += $(FUZZ_DIR)/fuzz_dfmoco
