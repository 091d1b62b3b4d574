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

# make run: the robot arm played on the simulated rig in real time, with
# its status line (RUN_SCENE and RUN_ARGS change what and how).
RUN_SCENE ?= examples/robot_arm.yaml
.PHONY: run
run: $(BUILD)/strand
	$(BUILD)/strand play $(RUN_SCENE) --sim --journal $(BUILD)/run.journal $(RUN_ARGS)
