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
FUZZ_BOARD_SRC := tests/fuzz/fuzz_board.c firmware/lockstep/ls_msg.c firmware/lockstep/ls_ptp.c \
                  hal/clock.c

$(FUZZ_DIR)/fuzz_board: $(FUZZ_BOARD_SRC) $(wildcard firmware/lockstep/*.h) | $(BUILD)/.deps-fuzz
	@mkdir -p $(@D)
	$(Q)clang $(FUZZ_CFLAGS) $(FUZZ_BOARD_SRC) -o $@

$(FUZZ_DIR)/seed-board: $(BUILD)/tests/test_lockstep
	$(Q)rm -rf $@ && $< --write-corpus $@

fuzz-board: $(FUZZ_DIR)/fuzz_board $(FUZZ_DIR)/seed-board
	$(call fuzz_run,board,$(FUZZ_DIR)/seed-board,1024,$(FUZZ_SECONDS))

fuzz-board-short: $(FUZZ_DIR)/fuzz_board $(FUZZ_DIR)/seed-board
	$(call fuzz_run,board,$(FUZZ_DIR)/seed-board,1024,$(FUZZ_BOARD_SECONDS))

fuzz: fuzz-board

# make bench-boards (part of make bench): the lockstep case alone, three
# boards playing 10 s (250 frames): the skew between the same frame's
# trigger on the three boards (tests/boards/run.sh --bench).
.PHONY: bench-boards
bench: bench-boards
bench-boards: $(BUILD)/strand $(BUILD)/strand-simdrive
	$(Q)sh tests/boards/run.sh $(BUILD)/strand $(BUILD)/strand-simdrive --bench

TEST_PREBUILD += $(FUZZ_DIR)/fuzz_board
