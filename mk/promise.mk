# mk/promise.mk - the property test of strand's promise (tests/promise/promise.c):
# random valid scenes through `strand check --sim` and `strand play --sim
# --clock virtual`, a scene check passes played to its last frame, one it
# rejects refused for the same first reason.
#
#   make check-promise   the step of `make test`: 2000 scenes of up to 5000
#                        ticks, journals on /dev/shm
#   make soak            the long runs, not part of `make test`: 3000 other
#                        scenes of up to 300000 ticks, 20 of up to 8.64 million
#                        (a day at 100 Hz), and every example played for 24
#                        hours of virtual time (mk/soak.sh); BENCH lines
#
# Built -O2 without sanitizers, from the programs' own -O2 objects: the
# sanitized build is ten times slower, and every module the test runs is
# also under the sanitized unit tests.

PROMISE_SRC    := tests/promise/promise.c tests/cliutil.c tests/playutil.c tests/testutil.c \
                  tests/scenegen.c
PROMISE_OBJ    := $(PROMISE_SRC:%.c=$(BUILD)/promise/%.o)
PROMISE_BIN    := $(BUILD)/promise/promise
PROMISE_CFLAGS  = $(filter-out $(SAN),$(TEST_CFLAGS)) -O2

$(BUILD)/promise/%.o: %.c | $(BUILD)/.deps-test
	@mkdir -p $(@D)
	$(Q)$(CC) $(PROMISE_CFLAGS) $(DEPFLAGS) -c $< -o $@

$(PROMISE_BIN): $(PROMISE_OBJ) $(CLI_LIB_SRC:%.c=$(BUILD)/%.o) $(LIB_OBJ) $(BUILD)/libmotion.a
	$(Q)$(CC) $(filter %.o %.a,$^) $(TEST_LIBS) -o $@

.PHONY: check-promise soak
check-promise: $(PROMISE_BIN)
	$(Q)TMPDIR=$${TMPDIR:-$$(test -d /dev/shm && echo /dev/shm || echo /tmp)} $(PROMISE_BIN)

soak: $(PROMISE_BIN) $(BUILD)/strand
	$(Q)TMPDIR=$${TMPDIR:-$$(test -d /dev/shm && echo /dev/shm || echo /tmp)} \
		STRAND_PROMISE_SCENES=3000 STRAND_PROMISE_TICKS=300000 STRAND_PROMISE_SEED=1000001 \
		$(PROMISE_BIN)
	$(Q)TMPDIR=$${TMPDIR:-$$(test -d /dev/shm && echo /dev/shm || echo /tmp)} \
		STRAND_PROMISE_SCENES=20 STRAND_PROMISE_TICKS=8640000 STRAND_PROMISE_SEED=2000001 \
		$(PROMISE_BIN)
	$(Q)sh mk/soak.sh $(BUILD)/strand

EXTRA_TEST_STEPS += check-promise
TEST_PREBUILD += $(PROMISE_BIN)
