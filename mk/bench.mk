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

# The play loop's wake-up latency on the wall clock against cyclictest
# (Debian's rt-tests), 30 s each at 1 kHz and the same priority, and the
# CPU time per tick of the robot arm on the simulated rig (mk/bench-play.sh).
DEB_BENCH_PLAY := rt-tests
.PHONY: bench-play
bench: bench-play
$(BUILD)/.deps-bench-play: mk/deps.sh $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_BENCH_PLAY) && touch $@
bench-play: $(BUILD)/strand | $(BUILD)/.deps-bench-play
	$(Q)sh mk/bench-play.sh $(BUILD)/strand $(RUN_SCENE) $(BUILD)/bench-play
