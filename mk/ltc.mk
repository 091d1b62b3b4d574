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
