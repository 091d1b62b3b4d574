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
