# strand - top-level Makefile. Plain make; objects under $(BUILD)/.
#
#   make          build the core library, the program and the tests
#   make test     build and run every test (unit, freestanding, cross-arch,
#                 Cortex-M4) and print a summary
#   make bench    build and run the benchmarks (prints BENCH lines)
#   make clean    remove $(BUILD)/
#
# Every target first makes sure the Debian packages it needs are installed
# (mk/deps.sh: apt-get when root, else it prints the command and stops).

BUILD   ?= build
CC      ?= cc
Q       := $(if $(V),,@)

# ---- Debian packages -------------------------------------------------------
DEB_BUILD := gcc make pkg-config libc6-dev libyaml-dev
DEB_TEST  := libcmocka-dev
DEB_CROSS := gcc-aarch64-linux-gnu gcc-arm-linux-gnueabihf libc6-dev-arm64-cross \
             libc6-dev-armhf-cross qemu-user gcc-arm-none-eabi binutils-arm-none-eabi
DEB_BENCH := libfixmath-dev

# ---- flags -------------------------------------------------------------------
WARN    := -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes \
           -Wvla -Wno-unused-parameter
OPT     ?= -O2
# The core sees only the compiler's own freestanding headers: an #include of
# anything from libc fails to compile, on every build of it.
GCC_INC := $(shell $(CC) -print-file-name=include)
CORE_CFLAGS := -std=c11 -ffreestanding -nostdinc -isystem $(GCC_INC) -fno-builtin \
               $(WARN) -Werror
SAN     := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# '=': pkg-config is asked when a recipe runs, after mk/deps.sh has
# installed cmocka (on a fresh machine it is not there when make starts).
TEST_CFLAGS  = -std=gnu11 -g -O1 $(filter-out -Wpedantic,$(WARN)) -Werror -ffp-contract=off \
               $(SAN) -Imotion -Itests -Ifirmware \
               $(shell pkg-config --cflags cmocka 2>/dev/null)
TEST_LIBS    = $(shell pkg-config --libs cmocka 2>/dev/null) $(FW_LIBS)

MOTION_SRC := $(wildcard motion/*.c)
MOTION_HDR := $(wildcard motion/*.h)
MOTION_OBJ := $(MOTION_SRC:%.c=$(BUILD)/%.o)
MOTION_SAN_OBJ := $(MOTION_SRC:%.c=$(BUILD)/san/%.o)

# firmware/: the strand program; everything but main.c is also linked into tests
# No fused multiply-add contraction: the loader's double arithmetic must round
# the same way on x86_64, aarch64 and armhf.
FW_CFLAGS   = -std=gnu11 $(WARN) -Werror -ffp-contract=off -Imotion -Ifirmware -Ihal -Isim \
              $(shell pkg-config --cflags yaml-0.1 2>/dev/null)
FW_LIBS     = $(shell pkg-config --libs yaml-0.1 2>/dev/null) -lm -lpthread
FW_SRC     := $(wildcard firmware/*.c)
FW_LIB_SRC := $(filter-out firmware/main.c,$(FW_SRC))
FW_HDR     := $(wildcard firmware/*.h)
FW_LIB_SAN_OBJ := $(FW_LIB_SRC:%.c=$(BUILD)/san/%.o)
FW_OBJ     := $(FW_SRC:%.c=$(BUILD)/%.o)

TEST_SRC   := $(wildcard tests/test_*.c)
TEST_BIN   := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
TEST_COMMON_SRC := $(filter-out $(TEST_SRC),$(wildcard tests/*.c))
TEST_COMMON_OBJ := $(TEST_COMMON_SRC:%.c=$(BUILD)/san/%.o)

.PHONY: all test bench clean deps deps-test deps-cross deps-bench unit
.DELETE_ON_ERROR:
.SECONDARY:

all: $(BUILD)/libmotion.a $(if $(wildcard firmware/main.c),$(BUILD)/strand) $(TEST_BIN)

# ---- dependencies ------------------------------------------------------------
$(BUILD)/.deps-build: mk/deps.sh
	$(Q)mkdir -p $(BUILD) && sh mk/deps.sh $(DEB_BUILD) && touch $@
$(BUILD)/.deps-test: mk/deps.sh $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_TEST) && touch $@
$(BUILD)/.deps-cross: mk/deps.sh $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_CROSS) && touch $@
$(BUILD)/.deps-bench: mk/deps.sh $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_BENCH) && touch $@
deps: $(BUILD)/.deps-build $(BUILD)/.deps-test $(BUILD)/.deps-cross $(BUILD)/.deps-bench

# ---- the motion core -----------------------------------------------------------
$(BUILD)/motion/%.o: motion/%.c $(MOTION_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(CORE_CFLAGS) $(OPT) -c $< -o $@

$(BUILD)/libmotion.a: $(MOTION_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^

# Sanitized copies for the tests.
$(BUILD)/san/motion/%.o: motion/%.c $(MOTION_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(CORE_CFLAGS) -g -O1 $(SAN) -c $< -o $@

$(BUILD)/firmware/%.o: firmware/%.c $(MOTION_HDR) $(FW_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) $(OPT) -g -c $< -o $@

$(BUILD)/strand: $(FW_OBJ) $(BUILD)/libmotion.a
	$(Q)$(CC) $^ $(FW_LIBS) -o $@

$(BUILD)/san/firmware/%.o: firmware/%.c $(MOTION_HDR) $(FW_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) -g -O1 $(SAN) -c $< -o $@

# ---- unit tests ------------------------------------------------------------------
# Test objects depend on the core sources too: tests/*_portable.c include them;
# and on firmware/'s headers: a test must see a changed struct.
$(BUILD)/san/tests/%.o: tests/%.c $(MOTION_HDR) $(MOTION_SRC) $(FW_HDR) $(wildcard tests/*.h) | $(BUILD)/.deps-test
	@mkdir -p $(@D)
	$(Q)$(CC) $(TEST_CFLAGS) -c $< -o $@

# Archives, so that a test pulls in only the objects it uses.
$(BUILD)/san/libmotion.a: $(MOTION_SAN_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^
$(BUILD)/san/libfw.a: $(FW_LIB_SAN_OBJ)
	$(Q)rm -f $@ && ar rcs $@ $^

$(BUILD)/tests/test_%: $(BUILD)/san/tests/test_%.o $(TEST_COMMON_OBJ) $(BUILD)/san/libfw.a \
		$(BUILD)/san/libmotion.a
	@mkdir -p $(@D)
	$(Q)$(CC) $(TEST_CFLAGS) $^ $(TEST_LIBS) -o $@

unit: $(TEST_BIN)
	$(Q)fail=0; for t in $(TEST_BIN); do \
		if ! $$t > $$t.log 2>&1; then echo "FAIL $$t (log: $$t.log)"; tail -n 30 $$t.log; fail=1; \
		else echo "PASS $$(basename $$t)  $$(grep -h '^BOUND' $$t.log | wc -l) bounds checked"; fi; \
	done; exit $$fail

# test: unit and the checks of mk/*.mk, with a summary (mk/test.mk)

# ---- benchmarks ---------------------------------------------------------------------
bench:

clean:
	rm -rf $(BUILD)

-include mk/*.mk

# Test-side copies of core sources compiled on the portable path.
$(BUILD)/san/tests/fix_portable.o: motion/fix.c
$(BUILD)/san/tests/trig_portable.o: motion/trig.c
