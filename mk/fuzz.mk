# mk/fuzz.mk - libFuzzer (clang) on every parser, and the one way they run.
#
#   make fuzz            every fuzzer for FUZZ_SECONDS (default 300) each
#   make fuzz-shorts     the short runs, two at a time (mk/test.mk): a step
#                        of `make test`
#
# Each fuzzer's short run, in `make test`, and where it is (its long run,
# fuzz-NAME, is a step of `make fuzz`):
#   fuzz-short          the scene loader, builder and evaluation (mk/scene.mk, 30 s)
#   fuzz-import-short   the glTF, URDF and table readers (mk/import.mk, 6, 6, 3 s)
#   fuzz-dfmoco-short   DFMoco's line reader (mk/dfmoco.mk, 3 s)
#   fuzz-rpc-short      strand serve's JSON-RPC decoder (mk/serve.mk, 6 s)
#   fuzz-board-short    the lockstep's datagrams and pmc's answers (mk/boards.mk, 3 s)

.PHONY: fuzz

# libFuzzer and the sanitizers' runtimes are in libclang-rt-14-dev, which
# clang only recommends (mk/deps.sh installs without recommends)
DEB_FUZZ := clang libclang-rt-14-dev
$(BUILD)/.deps-fuzz: mk/deps.sh $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_FUZZ) && touch $@
deps: $(BUILD)/.deps-fuzz

FUZZ_SECONDS ?= 300
# A fuzzer sees the project from its roots, as the tests do (the layers are
# the main build's to enforce).
FUZZ_CFLAGS  := -std=gnu11 -g -O1 -ffp-contract=off \
                -fsanitize=fuzzer,address,undefined,float-cast-overflow -fno-sanitize-recover=all \
                -iquote . -iquote firmware

# $(call fuzz_run,NAME,SEED,MAX_LEN,SECONDS): $(FUZZ_DIR)/fuzz_NAME for
# SECONDS on a scratch copy of the seed corpus SEED (libFuzzer writes what
# it finds to its first directory: the seed stays what the sources say);
# its log is $(FUZZ_DIR)/fuzz-NAME.log, an input that failed
# $(FUZZ_DIR)/crashes/NAME-*. One PASS line, or the log's tail and FAIL.
define fuzz_run
	$(Q)rm -rf $(FUZZ_DIR)/corpus-$(1) && mkdir -p $(FUZZ_DIR)/corpus-$(1) $(FUZZ_DIR)/crashes && \
	cp $(2)/* $(FUZZ_DIR)/corpus-$(1)/ && \
	$(FUZZ_DIR)/fuzz_$(1) -max_total_time=$(4) -max_len=$(3) -timeout=10 -rss_limit_mb=2048 \
		-print_final_stats=1 -artifact_prefix=$(FUZZ_DIR)/crashes/$(1)- \
		$(FUZZ_DIR)/corpus-$(1) >$(FUZZ_DIR)/fuzz-$(1).log 2>&1 || \
		{ tail -n 40 $(FUZZ_DIR)/fuzz-$(1).log; \
		  echo "FAIL fuzz $(1): see $(FUZZ_DIR)/fuzz-$(1).log"; exit 1; }
	$(Q)echo "PASS fuzz $(1) $$(grep -h -o 'stat::number_of_executed_units: *[0-9]*' \
		$(FUZZ_DIR)/fuzz-$(1).log | grep -o '[0-9]*$$') inputs in $(4) s, no crash," \
		"leak or sanitizer report"
endef
