# mk/scene.mk - the scene file loader's own checks.
#
#   make fuzz         libFuzzer (clang) on the loader, builder and evaluation,
#                     for FUZZ_SECONDS (default 300), from a corpus of the
#                     examples and every golden error case
#   make fuzz-short   the same for FUZZ_SHORT_SECONDS (default 45): a step of
#                     `make test`
#
# The render test (tests/cli/test_render.c) draws every example with
# `strand plot` and renders the SVG in headless Chromium; it needs chromium
# and libpng, installed here like every other package.

.PHONY: fuzz fuzz-short

EXTRA_TEST_STEPS += fuzz-short

DEB_FUZZ   := clang
DEB_RENDER := chromium libpng-dev

$(BUILD)/.deps-fuzz: mk/deps.sh $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_FUZZ) && touch $@
$(BUILD)/.deps-render: mk/deps.sh $(BUILD)/.deps-test
	$(Q)sh mk/deps.sh $(DEB_RENDER) && touch $@
deps: $(BUILD)/.deps-fuzz $(BUILD)/.deps-render

# ---- render test: chromium and libpng ------------------------------------------
$(BUILD)/tests/test_render: TEST_LIBS += $(shell pkg-config --libs libpng 2>/dev/null || echo -lpng)
$(BUILD)/san/tests/cli/test_render.o: | $(BUILD)/.deps-render

# ---- libFuzzer ------------------------------------------------------------------
FUZZ_SECONDS       ?= 300
FUZZ_SHORT_SECONDS ?= 30
FUZZ_DIR    := $(BUILD)/fuzz
# One clang build of every library folder and the loader's fuzz target; it
# sees the project from its roots, as the tests do (the layers are the main
# build's to enforce).
FUZZ_CFLAGS := -std=gnu11 -g -O1 -ffp-contract=off \
               -fsanitize=fuzzer,address,undefined,float-cast-overflow -fno-sanitize-recover=all \
               -iquote . -iquote firmware
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

# libFuzzer writes what it finds to the first directory: a scratch copy, so
# that the seed stays what the sources say.
define run_fuzz
	$(Q)rm -rf $(FUZZ_DIR)/corpus && mkdir -p $(FUZZ_DIR)/corpus $(FUZZ_DIR)/crashes && \
	cp $(FUZZ_DIR)/seed/* $(FUZZ_DIR)/corpus/ && \
	$(FUZZ_DIR)/fuzz_load -max_total_time=$(1) -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
		-print_final_stats=1 -artifact_prefix=$(FUZZ_DIR)/crashes/ \
		$(FUZZ_DIR)/corpus > $(FUZZ_DIR)/fuzz.log 2>&1 || \
		{ tail -n 40 $(FUZZ_DIR)/fuzz.log; echo "FAIL fuzz: see $(FUZZ_DIR)/fuzz.log"; exit 1; }
	$(Q)echo "PASS fuzz $$(grep -h -o 'stat::number_of_executed_units: *[0-9]*' $(FUZZ_DIR)/fuzz.log | \
		grep -o '[0-9]*$$') inputs in $(1) s, no crash, leak or sanitizer report"
endef

fuzz: $(FUZZ_DIR)/fuzz_load $(FUZZ_DIR)/seed
	$(call run_fuzz,$(FUZZ_SECONDS))

fuzz-short: $(FUZZ_DIR)/fuzz_load $(FUZZ_DIR)/seed
	$(call run_fuzz,$(FUZZ_SHORT_SECONDS))
