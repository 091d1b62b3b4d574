# mk/scene.mk - the scene file loader's own checks.
#
#   make fuzz-load    libFuzzer on the loader, builder and evaluation, for
#                     FUZZ_SECONDS (default 300), from a corpus of the
#                     examples and every golden error case (mk/fuzz.mk)
#   make fuzz-short   the same for FUZZ_SHORT_SECONDS (default 30): a step of
#                     `make test`
#
# The render test (tests/cli/test_render.c) draws every example with
# `strand plot` and renders the SVG in headless Chromium; it needs chromium
# and libpng, installed here like every other package.

.PHONY: fuzz-load fuzz-short

EXTRA_TEST_STEPS += fuzz-short

DEB_RENDER := chromium libpng-dev

$(BUILD)/.deps-render: mk/deps.sh $(BUILD)/.deps-test
	$(Q)sh mk/deps.sh $(DEB_RENDER) && touch $@
deps: $(BUILD)/.deps-render

# ---- render test: chromium and libpng ------------------------------------------
$(BUILD)/tests/test_render: TEST_LIBS += $(shell pkg-config --libs libpng 2>/dev/null || echo -lpng)
$(BUILD)/san/tests/cli/test_render.o: | $(BUILD)/.deps-render

# ---- libFuzzer ------------------------------------------------------------------
FUZZ_SHORT_SECONDS ?= 30
# One clang build of every library folder and the loader's fuzz target.
FUZZ_SRC    := tests/fuzz/fuzz_load.c $(LIB_SRC) $(CLI_LIB_SRC) $(MOTION_SRC)
# one object a source, so that `make -j` builds them side by side
FUZZ_OBJ    := $(FUZZ_SRC:%.c=$(FUZZ_DIR)/load/%.o)

$(FUZZ_DIR)/load/%.o: %.c $(ALL_HDR) | $(BUILD)/.deps-fuzz
	@mkdir -p $(@D)
	$(Q)clang $(FUZZ_CFLAGS) $(shell pkg-config --cflags $(FW_PKGS)) -c $< -o $@

$(FUZZ_DIR)/fuzz_load: $(FUZZ_OBJ) | $(BUILD)/.deps-fuzz
	$(Q)clang $(FUZZ_CFLAGS) $(FUZZ_OBJ) $(FW_LIBS) -o $@

TEST_PREBUILD += $(FUZZ_DIR)/fuzz_load

# The seed corpus: the examples, the test scenes and the golden error cases
# of the loader tests.
$(FUZZ_DIR)/seed: $(BUILD)/tests/test_load_errors $(wildcard examples/*.yaml tests/scenes/*.yaml)
	$(Q)rm -rf $@ && mkdir -p $@ && cp examples/*.yaml $@/ && \
		for f in tests/scenes/*.yaml; do cp $$f $@/scene-$$(basename $$f); done && \
		$(BUILD)/tests/test_load_errors --write-corpus $@

fuzz-load: $(FUZZ_DIR)/fuzz_load $(FUZZ_DIR)/seed
	$(call fuzz_run,load,$(FUZZ_DIR)/seed,16384,$(FUZZ_SECONDS))

fuzz-short: $(FUZZ_DIR)/fuzz_load $(FUZZ_DIR)/seed
	$(call fuzz_run,load,$(FUZZ_DIR)/seed,16384,$(FUZZ_SHORT_SECONDS))

fuzz: fuzz-load
