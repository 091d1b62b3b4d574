# mk/play.mk - the play loop's parts outside firmware/: the HAL (hal/) and
# the simulated rig (sim/). They build like firmware/ and go into the same
# archive for the tests and into the program.

HALSIM_SRC := $(wildcard hal/*.c sim/*.c)
HALSIM_HDR := $(wildcard hal/*.h sim/*.h)
HALSIM_OBJ := $(HALSIM_SRC:%.c=$(BUILD)/%.o)
HALSIM_SAN_OBJ := $(HALSIM_SRC:%.c=$(BUILD)/san/%.o)

TEST_CFLAGS += -Ihal -Isim

$(BUILD)/hal/%.o: hal/%.c $(MOTION_HDR) $(HALSIM_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) $(OPT) -g -c $< -o $@
$(BUILD)/sim/%.o: sim/%.c $(MOTION_HDR) $(HALSIM_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) $(OPT) -g -c $< -o $@
$(BUILD)/san/hal/%.o: hal/%.c $(MOTION_HDR) $(HALSIM_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) -g -O1 $(SAN) -c $< -o $@
$(BUILD)/san/sim/%.o: sim/%.c $(MOTION_HDR) $(HALSIM_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) -g -O1 $(SAN) -c $< -o $@

# firmware/ and the tests include these headers too
$(FW_OBJ) $(FW_LIB_SAN_OBJ) $(TEST_COMMON_OBJ) $(TEST_BIN:$(BUILD)/tests/%=$(BUILD)/san/tests/%.o): \
	$(HALSIM_HDR)

$(BUILD)/san/libfw.a: $(HALSIM_SAN_OBJ)
$(BUILD)/strand: $(HALSIM_OBJ)

# ---- the player until the strand command's dispatcher is on main --------------
# build/strand-play: `play` and `journal` with scenes built in code
# (tools/strand_play.c); replaced by `strand play` once the loader lands.
PLAY_TOOL_OBJ = $(filter-out $(BUILD)/firmware/main.o,$(FW_OBJ)) $(HALSIM_OBJ)

$(BUILD)/tools/%.o: tools/%.c $(MOTION_HDR) $(FW_HDR) $(HALSIM_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) -Itests $(OPT) -g -c $< -o $@
$(BUILD)/tools/synth.o: tests/synth.c tests/synth.h $(MOTION_HDR) $(FW_HDR) | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) -Itests $(OPT) -g -c $< -o $@

$(BUILD)/strand-play: $(BUILD)/tools/strand_play.o $(BUILD)/tools/synth.o $(PLAY_TOOL_OBJ) \
		$(BUILD)/libmotion.a
	$(Q)$(CC) $^ $(FW_LIBS) -o $@

# make run: a scene played on the simulated rig in real time, with its
# status line.
RUN_SCENE ?= synth:robot_arm
.PHONY: run
run: $(BUILD)/strand-play
	$(BUILD)/strand-play play $(RUN_SCENE) --sim --journal $(BUILD)/run.journal $(RUN_ARGS)
