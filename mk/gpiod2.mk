# mk/gpiod2.mk - libgpiod 2, run for real: a second strand, build/strand-gpiod2,
# whose GPIO lines go through hal/gpio/gpiod/gpio_line_v2.c and Debian 13's
# libgpiod 2.x, linked statically; the VM runs every GPIO test against it as
# well as against build/strand (libgpiod 1.6, Debian 12's), mk/vm.mk.
#
# Debian 12 has no libgpiod 2. Debian 13's libgpiod-dev is fetched from
# Debian's archive with apt-get download through a sources list and an apt
# state of its own under $(GPIOD2_DIR) (tests/vm/fetch-gpiod2.sh): never
# installed, unpacked with dpkg -x; its libgpiod.a links against Debian
# 12's C library. Everything else in strand-gpiod2 is the objects of
# build/strand.
#
#   make strand-gpiod2   the second strand (`strand-gpiod2 --version` names
#                        the library)

GPIOD2_DIR := $(BUILD)/gpiod2
GPIOD2_LIB := $(GPIOD2_DIR)/libgpioline.a

.PHONY: strand-gpiod2
strand-gpiod2: $(BUILD)/strand-gpiod2

$(GPIOD2_DIR)/.done: tests/vm/fetch-gpiod2.sh | $(BUILD)/.deps-vm
	$(Q)sh tests/vm/fetch-gpiod2.sh $(GPIOD2_DIR)

$(GPIOD2_DIR)/gpio_line_v2.o: hal/gpio/gpiod/gpio_line_v2.c $(GPIOD_HDR) $(GPIOD2_DIR)/.done | \
		$(VIEWS)/.stamp
	$(Q)$(CC) $(FW_CFLAGS) $(GPIOD_VIEW) $(OPT) -g -I$(GPIOD2_DIR)/root/usr/include -c $< -o $@
$(GPIOD2_LIB): $(GPIOD2_DIR)/gpio_line_v2.o $(BUILD)/hal/gpio/gpiod/gpio_line_msg.o
	$(Q)rm -f $@ && ar rcs $@ $^

# build/strand's link with the v2 archive and libgpiod.a in place of the
# v1 archive and -lgpiod.
$(BUILD)/strand-gpiod2: $(CLI_OBJ) $(LIB_OBJ) $(BUILD)/libmotion.a $(GPIOD2_LIB)
	$(Q)$(CC) $(CLI_OBJ) $(LIB_OBJ) $(BUILD)/libmotion.a \
		$(patsubst -lgpiod,$(GPIOD2_DIR)/libgpiod.a,$(patsubst $(GPIOD_LIB),$(GPIOD2_LIB),$(FW_LIBS))) \
		-o $@

# The VM: the second strand as /gpiod2/bin/strand (the libraries it needs
# are build/strand's, copied for it), and every GPIO test run again with it
# first on PATH (tests/vm/init.sh; lib.sh checks `strand --version`): the
# trigger, the e-stop, step mode, a held line, genlock. Not t_gpio_sleep:
# whether a chip sleeps is read from sysfs, the same code on either API.
VM_FILES += /gpiod2/bin/strand=$(BUILD)/strand-gpiod2
VM_AGAIN += $(addsuffix @gpiod2,t_gpio_busy t_gpio_estop t_gpio_genlock t_gpio_step t_gpio_trigger)
DEB_VM   += debian-archive-keyring

# built with everything else before make test's steps run
TEST_PREBUILD += $(BUILD)/strand-gpiod2 $(BUILD)/vm/ltcgen
