# mk/ltc.mk - external clocks: LTC timecode through libltc (decoder for the
# chase, encoder for the simulated source) and libasound for capture
# (hal/ltc/, sim/sim_ltc.c), and linuxptp for several boards in lockstep
# (firmware/play/board*.c: ptp4l's management answers through pmc).
#
# Sound exists only in the VM (this machine's kernel has no sound at all):
# the ALSA path is tested there on snd-aloop (mk/vm.mk), the rest in the
# unit tests against the simulated capture on the virtual clock.

DEB_BUILD += libltc-dev libasound2-dev
DEB_TEST  += linuxptp iproute2

FW_LIBS += -lltc -lasound

# ---- LTC for real, in the VM (mk/vm.mk, tests/vm/t_ltc_*.sh) -----------------
# snd-aloop: what is played into hw:Loopback,0,0 comes out of hw:Loopback,1,0
# sample for sample, and its "PCM Rate Shift 100000" control runs the cable's
# clock off ours. aplay plays the LTC tests/vm/ltcgen.c makes with libltc's
# encoder, amixer sets the shift; libasound finds hw:CARD,DEV through its
# configuration (alsa.conf and the cards' and pcm's files).
DEB_VM      += alsa-utils libasound2-data
VM_MODULES  += kernel/sound/soundcore.ko kernel/sound/core/snd.ko \
               kernel/sound/core/snd-timer.ko kernel/sound/core/snd-pcm.ko \
               kernel/sound/drivers/snd-aloop.ko
VM_HOST_BINS += /usr/bin/aplay /usr/bin/amixer
VM_BINS     += $(BUILD)/vm/ltcgen
VM_FILES    += /usr/share/alsa/alsa.conf=/usr/share/alsa/alsa.conf \
               /usr/share/alsa/cards=/usr/share/alsa/cards /usr/share/alsa/pcm=/usr/share/alsa/pcm \
               /usr/share/alsa/ctl=/usr/share/alsa/ctl

$(BUILD)/vm/ltcgen: tests/vm/ltcgen.c | $(BUILD)/.deps-build
	@mkdir -p $(@D)
	$(Q)$(CC) -std=gnu11 -O2 $(WARN) -Werror $< -lltc -lm -o $@

# ---- make bench-ltc, bench-ltc-vm (part of make bench) ---------------------------
# bench-ltc: the chase against the simulated capture on the virtual clock
# (bench/chase_bench.c): lock time, trigger phase error p50/p99, the rate
# after 10 s, at the card's clock 0, +-100 and +-1000 ppm off. Built like a
# test (the tests' chase runner, tests/chaseutil.c; sanitized: the figures
# are the virtual clock's, not the machine's speed).
# bench-ltc-vm: tests/vm/t_ltc_chase.sh through snd-aloop with the loopback's
# rate shift at 0, +-100 and +-1000 ppm, one boot each: strand's rate, the
# pulses' rate by the kernel's timestamps, the lock.
.PHONY: bench-ltc bench-ltc-vm
bench: bench-ltc bench-ltc-vm

$(BUILD)/san/bench/chase_bench.o: bench/chase_bench.c | $(BUILD)/.deps-test
	@mkdir -p $(@D)
	$(Q)$(CC) $(TEST_CFLAGS) $(DEPFLAGS) -c $< -o $@
$(BUILD)/bench/chase_bench: $(BUILD)/san/bench/chase_bench.o $(TEST_COMMON_OBJ) \
		$(BUILD)/san/libfw.a $(BUILD)/san/libmotion.a | $(GPIOD_LIB)
	@mkdir -p $(@D)
	$(Q)$(CC) $(TEST_CFLAGS) $(filter %.o %.a,$^) $(TEST_LIBS) -o $@

bench-ltc: $(BUILD)/bench/chase_bench
	$(Q)$<

# shift -> ppm: 100000 / shift - 1 (99900: +1001, 100010: -100)
LTC_VM_SHIFTS := 100000 99990 100010 99900 100100
bench-ltc-vm: $(BUILD)/vm/initrd.cpio.gz
	$(Q)echo "bench-ltc-vm: LTC through snd-aloop under qemu (TCG), 148 frames each; rates in ppm" \
		"(strand's estimate; the trigger pulses' by gpiomon); the shift's ppm is 1e5/shift - 1"
	$(Q)for s in $(LTC_VM_SHIFTS); do \
		VM_ONLY=t_ltc_chase VM_APPEND="strand.ltc_shift=$$s" sh tests/vm/run.sh \
			$(VM_KDIR)/vmlinux $< $(BUILD)/bench-ltc-vm >$(BUILD)/bench-ltc-vm.log 2>&1 || \
			grep '^FAIL' $(BUILD)/bench-ltc-vm.log; \
		grep -h '^BENCH ltc_vm_\|^BENCH gpio_edge_rate' $(BUILD)/bench-ltc-vm/console.log.txt | \
			sed 's/^BENCH //' | tr '\n' ' ' | sed 's/^/BENCH ltc_vm /; s/$$/\n/'; \
	done
