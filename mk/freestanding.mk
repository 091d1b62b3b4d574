# mk/freestanding.mk - the motion core as a freestanding target sees it.
#
#   make check-freestanding   every motion/*.c for x86_64 with no floating-point
#                             registers; only mem* may be undefined, no
#                             mutable state, only the core's own headers
#   make check-cortexm        every motion/*.c for a Cortex-M4 (soft float):
#                             no float helpers, no libc but mem*; prints the
#                             integer helpers it needs and a size line
#
# Both run a self-test first: good and deliberately bad files from
# tests/freestanding/ go through the same stages and must be accepted or
# rejected as each expects, so neither check can pass by checking nothing.

.PHONY: check-freestanding check-cortexm

# The libc the core may rely on: what the compiler emits for struct copies.
MEM_FUNCS := memcpy|memset|memmove|memcmp
FS_SELFTEST = pass:tests/freestanding/good.c \
              includes:tests/freestanding/bad_include.c \
              objects:tests/freestanding/bad_libc.c \
              objects:tests/freestanding/bad_static.c

# ---- x86_64, general registers only --------------------------------------------
# -fno-pic: in a position-independent object a const table of pointers is
# writable data (.data.rel.ro), which would hide real mutable state.
FS_CFLAGS = $(CORE_CFLAGS) -mgeneral-regs-only -O2 -fno-pic
FS_ALLOW  := ^($(MEM_FUNCS))$$
FS_OBJ    := $(MOTION_SRC:%.c=$(BUILD)/fs/%.o)

$(BUILD)/fs/motion/%.o: motion/%.c $(MOTION_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FS_CFLAGS) -c $< -o $@

check-freestanding: $(FS_OBJ) | $(BUILD)/.deps-build
	$(Q)CC='$(CC)' CFLAGS='$(FS_CFLAGS)' NM=nm ALLOW='$(FS_ALLOW)' \
		sh mk/check-selftest.sh $(BUILD)/fs/selftest $(FS_SELFTEST) \
		compiler:tests/freestanding/bad_float.c
	$(Q)test -n '$(FS_OBJ)' || { echo "check-freestanding: no motion/*.c to check" >&2; exit 1; }
	$(Q)sh mk/check-includes.sh $(MOTION_SRC) $(MOTION_HDR)
	$(Q)sh mk/check-objects.sh nm '$(FS_ALLOW)' $(FS_OBJ)
	@echo "FREESTANDING ok: $(words $(FS_OBJ)) object(s), x86_64 -mgeneral-regs-only, self-test passed"

# ---- Cortex-M4, soft float ---------------------------------------------------------
# Integer helpers of libgcc and the ARM EABI are fine on a Cortex-M4 (64-bit
# division, shifts, compares); they are listed, not refused. Everything else,
# the float helpers above all, fails.
M4_CC     := arm-none-eabi-gcc
M4_AEABI  := __aeabi_(u?ldivmod|u?idiv|u?idivmod|llsl|llsr|lasr|lmul|u?lcmp)
M4_LIBGCC := __(u?(div|mod)di3|u?divmoddi4|(ashl|ashr|lshr|mul)di3|u?cmpdi2|(clz|ctz|popcount|ffs|parity|bswap)[sd]i2)
M4_ALLOW  := ^($(MEM_FUNCS)|$(M4_AEABI)|$(M4_LIBGCC))$$
# '=': the compiler's include directory is asked for when a recipe runs,
# after mk/deps.sh has installed the compiler.
M4_CFLAGS = $(filter-out -isystem $(GCC_INC),$(CORE_CFLAGS)) \
            -isystem $(shell $(M4_CC) -print-file-name=include) \
            -mthumb -mcpu=cortex-m4 -mfloat-abi=soft -Os
M4_OBJ    := $(MOTION_SRC:%.c=$(BUILD)/m4/%.o)

$(BUILD)/m4/motion/%.o: motion/%.c $(MOTION_HDR) | $(BUILD)/.deps-cross
	@mkdir -p $(@D)
	$(Q)$(M4_CC) $(M4_CFLAGS) -c $< -o $@

check-cortexm: $(M4_OBJ) | $(BUILD)/.deps-cross
	$(Q)CC='$(M4_CC)' CFLAGS='$(M4_CFLAGS)' NM=arm-none-eabi-nm ALLOW='$(M4_ALLOW)' \
		sh mk/check-selftest.sh $(BUILD)/m4/selftest $(FS_SELFTEST) \
		objects:tests/freestanding/bad_float.c
	$(Q)test -n '$(M4_OBJ)' || { echo "check-cortexm: no motion/*.c to check" >&2; exit 1; }
	$(Q)sh mk/check-objects.sh arm-none-eabi-nm '$(M4_ALLOW)' $(M4_OBJ)
	@# all of the core in one relocatable object, as an application links it
	$(Q)arm-none-eabi-ld -r -o $(BUILD)/m4/motion.o $(M4_OBJ)
	$(Q)echo "CORTEX-M4 integer helpers:" $$(arm-none-eabi-nm -u $(BUILD)/m4/motion.o | \
		awk '{ print $$NF }' | grep -v -E '^($(MEM_FUNCS))$$' || echo none)
	$(Q)arm-none-eabi-size $(BUILD)/m4/motion.o | \
		awk 'NR == 2 { print "CORTEX-M4 text=" $$1 " data=" $$2 " bss=" $$3 }'
