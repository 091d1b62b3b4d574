# mk/cross.mk - the same bits on every target.
#
#   make check-cross   build tests/digest/digest.c with the motion core for
#                      each variant below, run them (the foreign ones under
#                      qemu-user) and require one DIGEST from all
#
# A variant is a compiler, extra flags for the core and the program, link
# flags and a runner. The core is compiled as everywhere else (CORE_CFLAGS,
# the compiler's own freestanding headers); the digest program is hosted.

.PHONY: check-cross

CROSS_VARIANTS := native noint128 sanitized clang-ubsan aarch64 armhf

cross_cc.native    := $(CC)
cross_cc.noint128  := $(CC)
cross_cc.sanitized := $(CC)
cross_cc.clang-ubsan := clang
cross_cc.aarch64   := aarch64-linux-gnu-gcc
cross_cc.armhf     := arm-linux-gnueabihf-gcc
# the portable two-word path of fix.h on a 64-bit host
cross_def.noint128 := -DMOT_NO_INT128
# undefined behaviour is what would make targets disagree: look for it
cross_def.sanitized := $(SAN)
cross_ld.sanitized := $(SAN)
# gcc drops a sanitizer check whose result goes unused (an overflowing
# product in code a constant argument made dead after inlining); clang keeps
# it. Such an overflow in curve_solve.c passed gcc's sanitized build and
# was found by the fuzzer's clang build only: the digest runs under clang's
# UBSan too, without ASan (the gcc variant has it), so it stays quick.
cross_def.clang-ubsan := -fsanitize=undefined,float-cast-overflow -fno-sanitize-recover=all
cross_ld.clang-ubsan := -fsanitize=undefined,float-cast-overflow
cross_ld.aarch64   := -static
cross_ld.armhf     := -static
cross_run.aarch64  := qemu-aarch64
cross_run.armhf    := qemu-arm

# The scene workloads build scenes in code through the firmware's builder.
DIGEST_SRC := tests/digest/digest.c tests/synth.c firmware/scene/scene_build.c \
              firmware/scene/scene_build_sys.c \
              firmware/scene/scene_desc.c
DIGEST_CFLAGS := -std=gnu11 -O2 $(WARN) -Werror -ffp-contract=off -iquote . -iquote firmware \
                 -iquote tests

# The core's flags for variant $(1). '=' and $(shell) at recipe time: a cross
# compiler is asked for its include directory after mk/deps.sh installed it.
cross_core_cflags = $(filter-out -isystem $(GCC_INC),$(CORE_CFLAGS)) \
                    -isystem $(shell $(cross_cc.$(1)) -print-file-name=include) \
                    -O2 $(cross_def.$(1))

# The list of core sources, rewritten only when it changes: a digest program
# is relinked when a motion/*.c goes away (another branch), not only when
# one is added or edited.
CROSS_SOURCES := $(BUILD)/cross/sources
$(shell mkdir -p $(BUILD)/cross && { echo '$(MOTION_SRC)' | cmp -s - $(CROSS_SOURCES) || \
	echo '$(MOTION_SRC)' >$(CROSS_SOURCES); })

define cross_variant
$(BUILD)/cross/$(1)/motion/%.o: motion/%.c | $(BUILD)/.deps-cross
	@mkdir -p $$(@D)
	$$(Q)$$(cross_cc.$(1)) $$(call cross_core_cflags,$(1)) $(DEPFLAGS) -c $$< -o $$@

$(BUILD)/cross/$(1)/digest: $(DIGEST_SRC) $(MOTION_SRC:%.c=$(BUILD)/cross/$(1)/%.o) \
		$(MOTION_HDR) $(ALL_HDR) tests/synth.h $(CROSS_SOURCES) | $(BUILD)/.deps-cross
	$$(Q)$$(cross_cc.$(1)) $$(DIGEST_CFLAGS) $$(cross_def.$(1)) $(DIGEST_SRC) \
		$$(filter %.o,$$^) $$(cross_ld.$(1)) -lm -o $$@
endef
$(foreach v,$(CROSS_VARIANTS),$(eval $(call cross_variant,$(v))))

# built in make test's parallel build, before the steps
TEST_PREBUILD += $(foreach v,$(CROSS_VARIANTS),$(BUILD)/cross/$(v)/digest)

check-cross: $(CROSS_VARIANTS:%=$(BUILD)/cross/%/digest) | $(BUILD)/.deps-cross
	$(Q)sh mk/check-cross.sh $(foreach v,$(CROSS_VARIANTS),\
		'$(v)=$(strip $(cross_run.$(v)) $(BUILD)/cross/$(v)/digest)')
