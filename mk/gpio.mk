# mk/gpio.mk - the GPIO backend's libgpiod side (hal/gpio/gpio.h,
# hal/gpio/gpio_line.h).
#
# hal/gpio/*.c (the HAL backend) build with every library folder. What
# talks to libgpiod is in hal/gpio/gpiod/, in an archive of its own,
# $(GPIOD_LIB): the implementation of gpio_line.h for the installed
# library's API, and the messages both implementations share.
#
# libgpiod's API changed at 2.0 (Debian 12 has 1.6.3). HAVE_GPIOD_V2 is
# decided once, by mk/gpiod-api.sh from pkg-config's version of the
# library, when the archive is built: it names the one file to compile,
# hal/gpio/gpiod/gpio_line_v1.c or gpio_line_v2.c. No source file tests a
# version. (`make gpiod-api` says which.)
#
# tests/hal/test_gpio.c runs the backend over a fake chip (tests/fake/), linked
# ahead of the archive; the real chip is tested in the VM (mk/vm.mk).

# the program links libgpiod: one of DEB_BUILD, so that a fresh machine's
# `make run` names every package it lacks at once
DEB_BUILD += libgpiod-dev
GPIOD_LIB := $(BUILD)/hal/libgpioline.a
GPIOD_SRC := hal/gpio/gpiod/gpio_line_v1.c hal/gpio/gpiod/gpio_line_v2.c
GPIOD_HDR := hal/gpio/gpio_line.h
GPIOD_VIEW := -iquote $(VIEWS)/hal-gpio-gpiod

.PHONY: gpiod-api

gpiod-api: | $(BUILD)/.deps-build
	$(Q)echo "libgpiod $$(pkg-config --modversion libgpiod): $$(sh mk/gpiod-api.sh --have)," \
		"compiling $$(sh mk/gpiod-api.sh)"

$(BUILD)/hal/gpio/gpiod/gpio_line_api.o: $(GPIOD_SRC) $(GPIOD_HDR) mk/gpiod-api.sh | \
		$(BUILD)/.deps-build $(VIEWS)/.stamp
	@mkdir -p $(@D)
	$(Q)src=$$(sh mk/gpiod-api.sh) && \
		$(CC) $(FW_CFLAGS) $(GPIOD_VIEW) $(OPT) -g $$(pkg-config --cflags libgpiod) -c $$src -o $@
$(BUILD)/hal/gpio/gpiod/gpio_line_msg.o: hal/gpio/gpiod/gpio_line_msg.c $(GPIOD_HDR) | \
		$(BUILD)/.deps-build $(VIEWS)/.stamp
	@mkdir -p $(@D)
	$(Q)$(CC) $(FW_CFLAGS) $(GPIOD_VIEW) $(OPT) -g -c $< -o $@
$(GPIOD_LIB): $(BUILD)/hal/gpio/gpiod/gpio_line_api.o $(BUILD)/hal/gpio/gpiod/gpio_line_msg.o
	$(Q)rm -f $@ && ar rcs $@ $^

# Everything that links the firmware links the archive and libgpiod: the
# program, the tests (their archive of firmware objects holds the HAL
# backend) and the fuzzer. '=': pkg-config is asked when a link runs, after
# mk/deps.sh installed the library.
FW_LIBS += $(GPIOD_LIB) $(shell pkg-config --libs libgpiod 2>/dev/null || echo -lgpiod)
$(BUILD)/strand $(BUILD)/strand-simdrive: $(GPIOD_LIB)
$(TEST_BIN): | $(GPIOD_LIB)
$(FUZZ_DIR)/fuzz_load: | $(GPIOD_LIB)

# test_gpio, test_play_gpio and test_rt_plan (a run with a GPIO input
# thread): the fake chip, ahead of the archive in the link, and a sysfs
# tree of their own for chips that sleep.
GPIO_FAKE_TESTS := test_gpio test_play_gpio test_rt_plan
$(addprefix $(BUILD)/tests/,$(GPIO_FAKE_TESTS)): $(BUILD)/san/tests/fake/gpio_line_fake.o \
	$(BUILD)/san/tests/fake/sysfs_tree.o

# make bench-gpio (part of make bench): the trigger's edge jitter measured
# in the test VM: tests/vm/t_gpio_trigger.sh over the scene ten times (760
# frames, 30 s), gpiomon's kernel timestamps against each tick's due time.
# Under qemu's software emulation (TCG) the guest's CPU is a host thread
# the host preempts: these figures bound what the harness sees, not what a
# board does (README "GPIO").
.PHONY: bench-gpio
bench: bench-gpio
bench-gpio: $(BUILD)/vm/initrd.cpio.gz
	$(Q)VM_ONLY=t_gpio_trigger VM_APPEND="strand.bench_passes=10 strand.max_late_us=100000" \
		sh tests/vm/run.sh $(VM_KDIR)/vmlinux $< \
		$(BUILD)/bench-gpio >$(BUILD)/bench-gpio.log 2>&1 || \
		{ cat $(BUILD)/bench-gpio.log; exit 1; }
	$(Q)echo "bench-gpio: trigger edges in the VM ($$(sed -n 's/^vm: booting [^ ]* (\([A-Z]*\)).*/\1/p' \
		$(BUILD)/bench-gpio.log)), 250 Hz tick, 20 ms pulses; late = edge - due"
	$(Q)grep -h '^BENCH gpio_' $(BUILD)/bench-gpio/console.log.txt
