# mk/play.mk - make run: the robot arm played on the simulated rig in real
# time, with its status line (RUN_SCENE and RUN_ARGS change what and how).
RUN_SCENE ?= examples/robot_arm.yaml
.PHONY: run
run: $(BUILD)/strand
	$(BUILD)/strand play $(RUN_SCENE) --sim --journal $(BUILD)/run.journal $(RUN_ARGS)

# strand serve's page is built into the program (firmware/serve/page.c).
$(BUILD)/firmware/serve/page.o $(BUILD)/san/firmware/serve/page.o: firmware/serve/page.html

# ---- strand serve against real peers ----------------------------------------------
# curl, python3-websockets and headless Chromium driven by python3-selenium
# (tests/serve/test_serve.py); SERVE_BROWSER=0 leaves the browser out.
DEB_SERVE := curl python3-websockets python3-selenium chromium chromium-driver
$(BUILD)/.deps-serve: mk/deps.sh $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_SERVE) && touch $@
.PHONY: check-serve
deps: $(BUILD)/.deps-serve
check-serve: $(BUILD)/strand $(BUILD)/strand-simdrive | $(BUILD)/.deps-serve
	$(Q)/usr/bin/python3 tests/serve/test_serve.py $(BUILD)/strand $(BUILD)/serve-test
EXTRA_TEST_STEPS += check-serve
