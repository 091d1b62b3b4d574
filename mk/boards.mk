# mk/boards.mk - several boards, one scene (firmware/lockstep/, README
# "Several boards, one scene").
#
#   make check-boards      three strands in network namespaces joined by a
#                          bridge, ptp4l between them in software-timestamp
#                          mode: the lockstep's skew, each refusal, a board
#                          killed, an e-stop and a device fault crossing
#                          boards (tests/boards/run.sh, ~10 s; a step of
#                          make test). Needs root; elsewhere one SKIP line
#                          says why (never under CI).
#   make fuzz-board-short  libFuzzer on the datagrams and pmc's answers, for
#                          FUZZ_BOARD_SECONDS (3; make fuzz: FUZZ_SECONDS)
#
# linuxptp and iproute2 are DEB_TEST's (mk/ltc.mk).

.PHONY: check-boards fuzz-board fuzz-board-short

EXTRA_TEST_STEPS += check-boards fuzz-board-short

check-boards: $(BUILD)/strand $(BUILD)/strand-simdrive | $(BUILD)/.deps-test
	$(Q)sh tests/boards/run.sh $(BUILD)/strand $(BUILD)/strand-simdrive

FUZZ_BOARD_SECONDS ?= 3
FUZZ_BOARD_DIR := $(BUILD)/fuzz
FUZZ_BOARD_SRC := tests/fuzz/fuzz_board.c firmware/lockstep/ls_msg.c firmware/lockstep/ls_ptp.c \
                  hal/clock.c

$(FUZZ_BOARD_DIR)/fuzz_board: $(FUZZ_BOARD_SRC) $(wildcard firmware/lockstep/*.h) | $(BUILD)/.deps-fuzz
	@mkdir -p $(@D)
	$(Q)clang $(FUZZ_CFLAGS) $(FUZZ_BOARD_SRC) -o $@

$(FUZZ_BOARD_DIR)/seed-board: $(BUILD)/tests/test_lockstep
	$(Q)rm -rf $@ && $< --write-corpus $@

define run_fuzz_board
	$(Q)rm -rf $(FUZZ_BOARD_DIR)/corpus-board && mkdir -p $(FUZZ_BOARD_DIR)/corpus-board $(FUZZ_BOARD_DIR)/crashes && \
	cp $(FUZZ_BOARD_DIR)/seed-board/* $(FUZZ_BOARD_DIR)/corpus-board/ && \
	$(FUZZ_BOARD_DIR)/fuzz_board -max_total_time=$(1) -max_len=1024 -timeout=10 -rss_limit_mb=2048 \
		-print_final_stats=1 -artifact_prefix=$(FUZZ_BOARD_DIR)/crashes/ \
		$(FUZZ_BOARD_DIR)/corpus-board > $(FUZZ_BOARD_DIR)/fuzz-board.log 2>&1 || \
		{ tail -n 40 $(FUZZ_BOARD_DIR)/fuzz-board.log; echo "FAIL fuzz board: see $(FUZZ_BOARD_DIR)/fuzz-board.log"; exit 1; }
	$(Q)echo "PASS fuzz board $$(grep -h -o 'stat::number_of_executed_units: *[0-9]*' $(FUZZ_BOARD_DIR)/fuzz-board.log | \
		grep -o '[0-9]*$$') inputs in $(1) s, no crash, leak or sanitizer report"
endef

fuzz-board: $(FUZZ_BOARD_DIR)/fuzz_board $(FUZZ_BOARD_DIR)/seed-board
	$(call run_fuzz_board,$(FUZZ_SECONDS))

fuzz-board-short: $(FUZZ_BOARD_DIR)/fuzz_board $(FUZZ_BOARD_DIR)/seed-board
	$(call run_fuzz_board,$(FUZZ_BOARD_SECONDS))

fuzz: fuzz-board

# make bench-boards (part of make bench): the lockstep case alone, three
# boards playing 10 s (250 frames): the skew between the same frame's
# trigger on the three boards (tests/boards/run.sh --bench).
.PHONY: bench-boards
bench: bench-boards
bench-boards: $(BUILD)/strand $(BUILD)/strand-simdrive
	$(Q)sh tests/boards/run.sh $(BUILD)/strand $(BUILD)/strand-simdrive --bench

TEST_PREBUILD += $(FUZZ_BOARD_DIR)/fuzz_board
