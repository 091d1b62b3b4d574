# mk/dmx.mk - lights over DMX512 (hal/dmx/, firmware/rig/drv_dmx.c) against
# real peers: Debian's olad, through its E1.31 and Art-Net inputs and
# ola-python, and tshark's dissectors, inside a network namespace the test
# makes (tests/dmx/dmx-ola.sh says why and how it is confined).
#
#   make check-dmx   the test (a step of make test); needs root for the
#                    namespace: skipped, saying why, where it cannot run,
#                    never under CI

.PHONY: check-dmx

DEB_DMX := ola ola-python tshark iproute2 util-linux procps
$(BUILD)/.deps-dmx: mk/deps.sh $(BUILD)/.deps-build
	$(Q)sh mk/deps.sh $(DEB_DMX) && touch $@
deps: $(BUILD)/.deps-dmx

check-dmx: $(BUILD)/strand
	$(Q)why=""; [ "$$(id -u)" -eq 0 ] || why="not root (the test makes a network namespace)"; \
	if [ -z "$$why" ]; then \
		$(MAKE) --no-print-directory $(BUILD)/.deps-dmx && \
		sh tests/dmx/dmx-ola.sh $(BUILD)/strand $(BUILD)/dmx-test; \
	elif [ -n "$$CI" ]; then echo "FAIL check-dmx cannot run under CI: $$why"; exit 1; \
	else echo "SKIP check-dmx: $$why"; fi

EXTRA_TEST_STEPS += check-dmx
