# mk/bench.mk - `make bench`: each benchmark is a target that `bench` depends
# on; it builds its program and runs it, which prints BENCH lines.

.PHONY: bench-fixmath

BENCH_CFLAGS := -std=c11 -O2 $(WARN) -Werror

# libfixmath's Q16.16 on a 5-joint chain, against double (the measurement
# behind fix.h's choice of Q32.32). Debian ships only a static library,
# /usr/lib/<triplet>/liblibfixmath.a, with its headers in
# /usr/include/libfixmath/.
bench: bench-fixmath

$(BUILD)/bench/fixmath_chain: bench/fixmath_chain.c | $(BUILD)/.deps-bench
	@mkdir -p $(@D)
	$(Q)$(CC) $(BENCH_CFLAGS) $< -llibfixmath -lm -o $@

bench-fixmath: $(BUILD)/bench/fixmath_chain
	$(Q)$<
