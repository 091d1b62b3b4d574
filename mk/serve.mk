# mk/serve.mk - strand serve's JSON-RPC decoder under libFuzzer:
#
#   make fuzz-rpc         for FUZZ_SECONDS (default 300), a step of make fuzz
#   make fuzz-rpc-short   for FUZZ_RPC_SECONDS (default 6), a step of make test
#
# The target is the decoder alone (firmware/serve/rpc.c) and jansson; the
# seed corpus is tests/fuzz/rpc/, one request of each kind.
.PHONY: fuzz-rpc fuzz-rpc-short
EXTRA_TEST_STEPS += fuzz-rpc-short
FUZZ_RPC_SECONDS ?= 6

$(FUZZ_DIR)/fuzz_rpc: tests/fuzz/fuzz_rpc.c firmware/serve/rpc.c $(ALL_HDR) | \
		$(BUILD)/.deps-fuzz
	@mkdir -p $(@D)
	$(Q)clang $(FUZZ_CFLAGS) $(shell pkg-config --cflags jansson) tests/fuzz/fuzz_rpc.c \
		firmware/serve/rpc.c $(shell pkg-config --libs jansson) -o $@

fuzz-rpc: $(FUZZ_DIR)/fuzz_rpc
	$(call fuzz_run,rpc,tests/fuzz/rpc,4096,$(FUZZ_SECONDS))

fuzz-rpc-short: $(FUZZ_DIR)/fuzz_rpc
	$(call fuzz_run,rpc,tests/fuzz/rpc,4096,$(FUZZ_RPC_SECONDS))

fuzz: fuzz-rpc

# ---- the benchmark -----------------------------------------------------------------
# bench/serve_bench.py: a command's arrival to the tick that acts on it,
# status updates a second to 1 and 10 clients, and the loop's wake-up
# latency with the server up and ten clients streaming beside strand play's
# and cyclictest's (BENCH_SERVE_SECONDS each, default 30).
.PHONY: bench-serve
bench: bench-serve
bench-serve: $(BUILD)/strand | $(BUILD)/.deps-serve $(BUILD)/.deps-bench-play
	$(Q)/usr/bin/python3 bench/serve_bench.py $(BUILD)/strand examples/robot_arm.yaml \
		$(BUILD)/bench-serve

# built in make test's parallel build (mk/test.mk)
TEST_PREBUILD += $(FUZZ_DIR)/fuzz_rpc
