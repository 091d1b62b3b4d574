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
FUZZ_DFMOCO := $(BUILD)/fuzz/fuzz_dfmoco

$(FUZZ_DFMOCO): tests/fuzz/fuzz_dfmoco.c firmware/dfmoco/dfm_parse.c firmware/dfmoco/dfm_parse.h \
		| $(BUILD)/.deps-fuzz
	@mkdir -p $(@D)
	$(Q)clang $(FUZZ_CFLAGS) tests/fuzz/fuzz_dfmoco.c firmware/dfmoco/dfm_parse.c -o $@

define run_fuzz_dfmoco
	$(Q)rm -rf $(BUILD)/fuzz/corpus-dfmoco && mkdir -p $(BUILD)/fuzz/corpus-dfmoco \
		$(BUILD)/fuzz/crashes && cp tests/fuzz/dfmoco/* $(BUILD)/fuzz/corpus-dfmoco/ && \
	$(FUZZ_DFMOCO) -max_total_time=$(1) -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
		-print_final_stats=1 -artifact_prefix=$(BUILD)/fuzz/crashes/dfmoco- \
		$(BUILD)/fuzz/corpus-dfmoco > $(BUILD)/fuzz/fuzz-dfmoco.log 2>&1 || \
		{ tail -n 40 $(BUILD)/fuzz/fuzz-dfmoco.log; \
		  echo "FAIL fuzz dfmoco: see $(BUILD)/fuzz/fuzz-dfmoco.log"; exit 1; }
	$(Q)echo "PASS fuzz dfmoco $$(grep -h -o 'stat::number_of_executed_units: *[0-9]*' \
		$(BUILD)/fuzz/fuzz-dfmoco.log | grep -o '[0-9]*$$') inputs in $(1) s, no crash, \
		leak or sanitizer report"
endef

fuzz-dfmoco: $(FUZZ_DFMOCO)
	$(call run_fuzz_dfmoco,$(FUZZ_SECONDS))

fuzz-dfmoco-short: $(FUZZ_DFMOCO)
	$(call run_fuzz_dfmoco,$(FUZZ_DFMOCO_SECONDS))

fuzz: fuzz-dfmoco
EXTRA_TEST_STEPS += fuzz-dfmoco-short
TEST_PREBUILD += $(FUZZ_DFMOCO)
