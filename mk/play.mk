# mk/play.mk - make run: the robot arm played on the simulated rig in real
# time, with its status line (RUN_SCENE and RUN_ARGS change what and how).
RUN_SCENE ?= examples/robot_arm.yaml
.PHONY: run
run: $(BUILD)/strand
	$(BUILD)/strand play $(RUN_SCENE) --sim --journal $(BUILD)/run.journal $(RUN_ARGS)

# strand serve's page is built into the program (firmware/serve/page.c).
$(BUILD)/firmware/serve/page.o $(BUILD)/san/firmware/serve/page.o: firmware/serve/page.html
